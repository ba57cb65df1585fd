//! The exact contact on a layer stack under sliding friction (not in the paper; notes.md,
//! "Sliding friction" and "Layer stacks"): the film's uncoupled approximation
//! ([`crate::verify::sliding`]) at every interface k. The traction μ·p(x) along x on the solved
//! frictionless pressure p passes to interface k through the stack's tangential kernels g_t,k,
//! f_t,k and h_k ([`crate::layer::stack::Stack::tangential`]) by the FFT of
//! [`crate::bem::sliding::friction_fields_with`], and the result is added to the static fields
//! of f_k, g_k. Each interface's shear is then a vector field with mean (μ·p0, 0) (g_t,k = h_k = 1
//! at q = 0) and its own x and y fluctuations, and its normal stress gains a friction-driven
//! part of mean zero.
//!
//! [`compare_sliding`] sets every interface beside Persson's sliding values on the stack
//! ([`crate::contact::Engine::evaluate_stack_sliding`]) for `coatcheck verify --layer
//! --friction`. The normal–tangential coupling that the approximation neglects is not computed
//! for a stack (the stack's kernels give the interfaces' stresses, not the top's normal
//! displacement under a tangential load); the report says so.

use super::{InterfaceComparison, StackComparison, top_rows};
use crate::bem::{BemSettings, BemSolution, InterfaceFields, Surface};
use crate::contact::{Engine, Request, SlidingShear};
use crate::error::Error;
use crate::layer::stack::{InterfaceShear, MAX_LAYERS, Stack};
use crate::prec::Settings;
use crate::topography::HeightMap;
use crate::verify::sliding::{ExactSliding, vector_rows, with_friction_kernels};
use crate::verify::{Row, exact_only, map_spectrum};

/// The tangential kernels [g_t,k, f_t,k, h_k] of interface `k` of `stack` at wavenumber q
/// (1/m), as [`crate::bem::sliding::friction_fields_with`] takes them.
pub fn interface_kernels(stack: &Stack, k: usize) -> impl Fn(f64) -> [f64; 3] + Sync + '_ {
    let n = stack.layers().len();
    move |q| {
        let mut out = [InterfaceShear::default(); MAX_LAYERS];
        stack.tangential_into(q, &mut out[..n]);
        let t = out[k];
        [t.g_t, t.f_t, t.h]
    }
}

/// Every interface's fields under the friction traction μ·p along x (top first): the static
/// fields `fields` plus the friction-driven ones, with the sliding summary; for μ = 0 the static
/// fields themselves and no summary.
pub fn with_friction(
    solution: &BemSolution,
    stack: &Stack,
    fields: Vec<InterfaceFields>,
    mu: f64,
) -> Result<Vec<(InterfaceFields, Option<ExactSliding>)>, Error> {
    if mu == 0.0 {
        return Ok(fields.into_iter().map(|f| (f, None)).collect());
    }
    Ok(friction_totals(solution, stack, &fields, mu)?
        .into_iter()
        .map(|(total, summary)| (total, Some(summary)))
        .collect())
}

/// Every interface's total fields under the friction traction μ·p along x (top first): the
/// static `fields` plus the friction-driven ones, with the sliding summary.
fn friction_totals(
    solution: &BemSolution,
    stack: &Stack,
    fields: &[InterfaceFields],
    mu: f64,
) -> Result<Vec<(InterfaceFields, ExactSliding)>, Error> {
    fields
        .iter()
        .enumerate()
        .map(|(k, f)| with_friction_kernels(solution, f, mu, interface_kernels(stack, k)))
        .collect()
}

/// `coatcheck verify --layer … --friction μ`: the exact contact on a height map with the friction
/// traction applied, beside Persson's sliding values on the stack from the map's spectrum.
#[derive(Debug, Clone)]
pub struct StackSlidingComparison {
    /// The comparison with the total (static + friction) fields at every interface and
    /// Persson's sliding contact (σ_rms(z_k) with the friction-driven part); its interface rows
    /// are the sliding rows.
    pub comparison: StackComparison,
    /// The static fields at every interface (top first).
    pub static_fields: Vec<InterfaceFields>,
    /// Every interface's exact shear vector, top first.
    pub exact: Vec<ExactSliding>,
    /// Every interface's Persson shear vector, top first.
    pub persson: Vec<SlidingShear>,
}

/// Solve the contact on `map` at `p0`, apply the friction μ > 0 and compare every interface
/// with Persson's sliding estimate on the stack (contact integrals to `settings`; `bond` the
/// shear strength every interface is measured against).
pub fn compare_sliding(
    map: &HeightMap,
    stack: &Stack,
    (p0, mu): (f64, f64),
    bem: &BemSettings,
    settings: Settings,
    bond: Option<f64>,
) -> Result<StackSlidingComparison, Error> {
    if !(mu.is_finite() && mu > 0.0) {
        return Err(Error::invalid(
            "friction coefficient",
            mu,
            "a finite value > 0 (without friction use compare)",
        ));
    }
    let surface = Surface::from_height_map(map)?;
    let started = std::time::Instant::now();
    let (solution, static_fields) = super::solve(&surface, stack, p0, bem)?;
    let sliding = friction_totals(&solution, stack, &static_fields, mu)?;
    let seconds = started.elapsed().as_secs_f64();
    let (theory, shears) = Engine::new(&map_spectrum(map)?, settings).evaluate_stack_sliding(
        stack,
        p0,
        mu,
        Request::all(),
    )?;
    let persson = shears.ok_or_else(|| Error::Numerical {
        what: "Persson's sliding estimate on the stack",
        detail: "no interface shear was computed".into(),
    })?;
    let rows = top_rows(&solution, &theory);
    let mut fields = Vec::with_capacity(sliding.len());
    let mut exact = Vec::with_capacity(sliding.len());
    let mut interfaces = Vec::with_capacity(sliding.len());
    for (k, (total, summary)) in sliding.into_iter().enumerate() {
        let ic = &theory.interfaces[k];
        let above_bond = bond.map(|b| total.shear_fraction_above(b));
        let mut r = vec![Row::new(
            "sigma_rms interface",
            "Pa",
            ic.sigma_rms,
            total.normal_stats.rms_dev,
        )];
        exact_only(&mut r, "interface sigma_n", &total.normal_stats);
        vector_rows(
            &mut r,
            (ic.tau_rms, static_fields[k].shear_stats.rms),
            (&total, &summary),
            &persson[k],
            bond.zip(above_bond),
        )?;
        interfaces.push(InterfaceComparison {
            depth: ic.depth,
            above_bond,
            rows: r,
        });
        fields.push(total);
        exact.push(summary);
    }
    Ok(StackSlidingComparison {
        comparison: StackComparison {
            surface,
            solution,
            fields,
            persson: theory,
            rows,
            interfaces,
            seconds,
        },
        static_fields,
        exact,
        persson,
    })
}
