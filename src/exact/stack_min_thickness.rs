//! The minimum thickness of one layer of a stack (`criteria.thickness_of`, the others fixed) by
//! the exact solver: the search of [`super::min_thickness`] (the scan, the narrow-band guard and
//! the ITP refinement of [`crate::check::min_thickness`], each solve warm-started from the
//! nearest thickness solved before, from coarse to fine as [`super::levels`] says; the error
//! the bracket's plus the difference to the d_min of the map at half the resolution), with one
//! boundary-element solve of the stack ([`crate::verify_stack`]) per thickness.
//!
//! The utilisation at d is the largest value/limit of the enabled exact stress checks of the
//! stack: bond-shear at every interface against its own bond, substrate-yield at the bottom (the
//! ε-levels of the solved fields and the mean contact pressure), as [`crate::verify_stack`]
//! judges them; under sliding friction on the total fields (static plus friction-driven). The scan range is the film's (q_L·d from 10 down, the bulk bound 50/q_L); why it
//! holds for a layer below the top is argued in [`crate::check::stack`].

use super::min_thickness::{ExactMinThickness, min_thickness_with, utilisation};
use crate::bem::{BemSettings, Surface};
use crate::check::Utilisation;
use crate::check::stack::StackDesign;
use crate::error::Error;
use crate::prec::Estimate;
use crate::verify::ExactCheck;
use crate::verify_stack::{
    InterfaceExact, StackExactCheck, design_stack, interface, judge, solve_one,
};

/// `design` with the layer `thickness_of` at thickness `d`.
pub fn at_thickness(design: &StackDesign, d: f64) -> StackDesign {
    let mut x = design.clone();
    x.layers[design.thickness_of].thickness = d;
    x
}

/// The exact utilisation of the stack design with the layer `thickness_of` at `thickness` on
/// `surface` under the sliding friction `mu` (0: static contact), warm-started from `start`,
/// with the solved pressure and the solver's iterations.
pub fn exact_utilisation(
    surface: &Surface,
    (design, mu): (&StackDesign, f64),
    settings: &BemSettings,
    thickness: f64,
    start: Option<&[f64]>,
) -> Result<(Utilisation, Vec<f64>, usize), Error> {
    let design = at_thickness(design, thickness);
    let stack = design_stack(&design)?;
    let s = solve_one(surface, &stack, (&design, mu), settings, start)?;
    let depths = stack.depths();
    let interfaces: Vec<InterfaceExact> = s
        .interfaces
        .into_iter()
        .enumerate()
        .map(|(k, f)| interface(&design, k, depths[k], f, (None, None)))
        .collect();
    let checks: Vec<ExactCheck> = judge(&design, &interfaces, Estimate::exact(s.mean_pressure))
        .into_iter()
        .map(|c| c.check)
        .collect();
    let u = utilisation(&checks, s.area, s.area_tol);
    Ok((u, s.pressure, s.convergence.iterations))
}

/// The exact minimum thickness of the layer `thickness_of` on `surface` under the sliding
/// friction `mu` (0: static contact), with its bracket and grid errors (module docs).
pub fn min_thickness(
    surface: &Surface,
    design: &StackDesign,
    mu: f64,
    settings: &BemSettings,
) -> Result<ExactMinThickness, Error> {
    min_thickness_with(surface, &mut |s, d, start| {
        exact_utilisation(s, (design, mu), settings, d, start)
    })
}

/// The min-thickness check of the stack design at its own thickness of the layer
/// `thickness_of`, named after that layer.
pub fn check(design: &StackDesign, m: &ExactMinThickness) -> StackExactCheck {
    let layer = &design.layers[design.thickness_of];
    StackExactCheck {
        at: layer.name.clone(),
        check: m.check(layer.thickness),
    }
}
