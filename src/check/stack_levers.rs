//! What to change when a layer stack fails ([`super::stack`]): the levers of a film
//! ([`super::levers`]) on the stack, each alone (everything else as given) making every stress
//! check pass at the design's thicknesses:
//!
//! - thickness: the layer `thickness_of` at least its d_min (the others fixed);
//! - strength: at each interface whose bond-shear fails, that bond's shear strength ≥
//!   τ_peak·SF there; the substrate's yield strength ≥ (the governing stress)·SF;
//! - load: the largest nominal pressure p ≤ p0 at which every stress check passes;
//! - roughness: the largest rms height of the lowest octave [q_L, 2 q_L] of the spectrum at
//!   which every stress check passes.
//!
//! The last two are searched as for a film ([`super::levers`]: a log grid from the design
//! value down, then bisection), each step one new [`StackChecker`] and one evaluation.

use super::CheckKind;
use super::levers::{Lever, load_levers};
use super::stack::{StackChecker, StackDesign, StackOutcome};
use crate::Error;
use crate::prec::Settings;
use crate::psd::Spectrum;

fn stress_checks_pass(
    spectrum: &Spectrum,
    design: &StackDesign,
    settings: Settings,
) -> Result<bool, Error> {
    StackChecker::new(spectrum, design.clone(), settings)?.stress_checks_pass()
}

/// The levers for a failing stack (empty when every check passes).
pub fn stack_levers(
    spectrum: &Spectrum,
    design: &StackDesign,
    settings: Settings,
    outcome: &StackOutcome,
) -> Result<Vec<Lever>, Error> {
    let mut out = Vec::new();
    if outcome.pass {
        return Ok(out);
    }
    let varied = &design.layers[design.thickness_of];
    if let Some(m) = outcome.min_thickness.as_ref().and_then(|m| m.thickness)
        && m.value > varied.thickness
    {
        out.push(Lever {
            name: "thickness",
            relation: ">=",
            value: Some(m.value),
            current: varied.thickness,
            unit: "m",
            at: Some(varied.name.clone()),
        });
    }
    let failing: Vec<_> = outcome
        .checks
        .iter()
        .filter(|c| !c.result.pass && c.result.kind != CheckKind::MinThickness)
        .collect();
    if failing.is_empty() {
        return Ok(out);
    }
    let sf = design.criteria.safety_factor;
    for c in &failing {
        let (name, current, at) = match c.result.kind {
            CheckKind::BondShear => {
                let layer = design
                    .layers
                    .iter()
                    .find(|l| l.name == c.at)
                    .expect("a bond-shear check is at a layer");
                ("bond_strength", layer.bond_strength, Some(c.at.clone()))
            }
            CheckKind::SubstrateYield => match design.yield_strength {
                Some(y) => ("yield_strength", y, None),
                None => continue,
            },
            CheckKind::MinThickness => continue,
        };
        out.push(Lever {
            name,
            relation: ">=",
            value: Some(c.result.value.value * sf),
            current,
            unit: "Pa",
            at,
        });
    }
    let set_pressure = |at: &mut StackDesign, p| at.pressure = p;
    let passes = |s: &Spectrum, at: &StackDesign| stress_checks_pass(s, at, settings);
    out.extend(load_levers(
        spectrum,
        design,
        design.pressure,
        set_pressure,
        passes,
    )?);
    Ok(out)
}
