//! The exact contact on a layer stack: the boundary-element solve of [`super`] with the stack's
//! surface compliance u_z(q)/p(q) = 2 S(q)/(q E1*) (S of the whole stack normalised by the TOP
//! layer's E1*, `layer::stack`), and the fields at every interface k from the transfer functions
//! f_k(q), g_k(q) (notes.md, "Layer stacks").

use super::free::{Solid, solve_free};
use super::{
    BemSettings, BemSolution, Boundary, InterfaceFields, Surface, interface_fields_with,
    solve_compliance_from, solve_with_compliance,
};
use crate::error::Error;
use crate::layer::stack::{MAX_LAYERS, Stack};

/// S and (f_k, g_k) at every interface at q, without allocating.
fn response(stack: &Stack, q: f64) -> (f64, [(f64, f64); MAX_LAYERS]) {
    let mut out = [(0.0, 0.0); MAX_LAYERS];
    let s = stack.response_into(q, &mut out[..stack.layers().len()]);
    (s, out)
}

/// Solve the contact of a rigid flat with the layer stack whose top has the heights of
/// `surface`, at nominal pressure `p0` (Pa).
pub fn solve_stack(
    surface: &Surface,
    stack: &Stack,
    p0: f64,
    settings: &BemSettings,
) -> Result<BemSolution, Error> {
    let e1 = stack.layers()[0].material.e_star();
    if settings.boundary == Boundary::Free {
        let layers = stack.layers();
        let s = |q: f64| response(stack, q).0;
        let solid = Solid::Layered {
            e_star: e1,
            s: &s,
            thinnest: layers
                .iter()
                .map(|l| l.thickness)
                .filter(|&t| t > 0.0)
                .fold(f64::INFINITY, f64::min),
            total: layers.iter().map(|l| l.thickness).sum(),
        };
        return solve_free(surface, &solid, p0, settings, None);
    }
    solve_with_compliance(
        surface,
        |q| 2.0 * response(stack, q).0 / (q * e1),
        p0,
        settings,
    )
}

/// [`solve_stack`] warm-started from the pressure field `start` (Pa, one value per pixel, e.g.
/// the solution of a neighbouring thickness), as [`super::solve_from`] does for a film: the same
/// converged contact, in fewer iterations.
pub fn solve_stack_from(
    surface: &Surface,
    stack: &Stack,
    p0: f64,
    settings: &BemSettings,
    start: &[f64],
) -> Result<BemSolution, Error> {
    let e1 = stack.layers()[0].material.e_star();
    solve_compliance_from(
        surface,
        |q| 2.0 * response(stack, q).0 / (q * e1),
        p0,
        settings,
        Some(start),
    )
}

/// The normal and shear stress fields at every interface of the stack (top first) of a solved
/// contact.
pub fn stack_interface_fields(
    solution: &BemSolution,
    stack: &Stack,
) -> Result<Vec<InterfaceFields>, Error> {
    (0..stack.layers().len())
        .map(|k| interface_fields_with(solution, |q| response(stack, q).1[k]))
        .collect()
}
