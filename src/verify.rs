//! The design check on the measured surface itself: the exact contact of the scene's film,
//! substrate and load on a height map (boundary elements, [`crate::bem`]), with the criteria of
//! [`crate::check`] applied to the solved fields instead of Persson's Gaussian distributions
//! (paper Appendix B; notes.md for the definitions).
//!
//! # Criteria on a field
//! - bond-shear: the level that |τ(x, d)| exceeds on a fraction ε of the interface, against
//!   τ_bond / SF.
//! - substrate-yield: the larger of the mean real-contact pressure p0·A0/A and the level that the
//!   interface normal stress σ_n(x, d) (compression positive) exceeds on a fraction ε, against
//!   σ_Y / SF.
//!
//! On a map of N pixels "a fraction ε" is counted in pixels: the ε-level is the nearest-rank
//! (1 − ε) quantile of the field. When ε < 1/N the map cannot resolve events that rare; the
//! ε-level is then the field's maximum and is flagged `resolved = false` (it is the level
//! exceeded on no pixel of the map, which is all the map can say).
//!
//! # Error estimate
//! The solver's own tolerance bounds only part of the error; the larger part is the grid. Each
//! number is therefore also computed on the map sampled at every second pixel (both directions,
//! the same surface at half the resolution), and the difference of the two solutions is
//! reported as the error of the full-resolution value (A/A0 converges at first order in the
//! pixel size, see `examples/bench_bem.rs`, so the difference over-estimates the error of the
//! finer grid). Maps with fewer than 32 pixels along a side get no half-resolution solve and a
//! NaN error. The map is one period of a periodic surface, as `coatcheck verify` treats it.
//! The minimum thickness is not verified (it would need a solve per thickness).

use crate::bem::{self, BemSettings, Convergence, Surface};
use crate::check::{CheckKind, Design};
use crate::error::Error;
use crate::layer::Stack;
use crate::prec::{Estimate, Termination};
use serde::Serialize;

/// Smallest side (pixels) for which a half-resolution solve is made.
const MIN_SIDE_FOR_HALF: usize = 32;

/// The level a field exceeds on a fraction ε of the map.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Level {
    pub value: Estimate,
    /// False when ε < 1/N: the value is then the field's maximum.
    pub resolved: bool,
}

/// One check judged on the exact fields.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ExactCheck {
    pub kind: CheckKind,
    /// The checked level (Pa).
    pub value: Estimate,
    pub limit: f64,
    /// 1 − value/limit (≥ 0 passes).
    pub margin: f64,
    pub pass: bool,
    /// Whether the ε-level is resolved by the map (see [`Level`]).
    pub resolved: bool,
}

/// The exact contact of a design on a height map, summarised for the checks.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verification {
    pub nx: usize,
    pub ny: usize,
    /// q_L·d with q_L = 2π / (longer side of the map).
    pub q_low_d: f64,
    pub area_fraction: Estimate,
    /// p0·A0/A (Pa).
    pub mean_contact_pressure: Estimate,
    /// Rms of p − p0 at z = 0 (Pa).
    pub sigma_rms_top: Estimate,
    /// Rms deviation of σ_n at z = d (Pa).
    pub sigma_rms_interface: Estimate,
    /// Rms of |τ| at z = d (Pa).
    pub tau_rms_interface: Estimate,
    /// ε-level of |τ| at z = d.
    pub tau_peak: Level,
    /// ε-level of σ_n at z = d.
    pub sigma_peak_interface: Level,
    /// Fraction of the interface where |τ| > τ_bond (the strength, not the limit).
    pub bond_exceedance: Estimate,
    /// The enabled stress checks.
    pub checks: Vec<ExactCheck>,
    pub pass: bool,
    /// The full-resolution solve.
    pub convergence: Convergence,
    /// Wall time of both solves (s).
    pub seconds: f64,
}

/// The numbers of one solve.
struct Solved {
    area: f64,
    area_tol: f64,
    mean_pressure: f64,
    sigma_top: f64,
    sigma_int: f64,
    tau_rms: f64,
    tau_level: f64,
    sigma_level: f64,
    bond_fraction: f64,
    resolved: bool,
    convergence: Convergence,
}

/// The nearest-rank (1 − ε) quantile of `values` (reordered) and whether ε ≥ 1/N.
fn level(values: &mut [f64], eps: f64) -> (f64, bool) {
    let n = values.len();
    let nf = n as f64;
    let rank = (((1.0 - eps) * nf).ceil() as usize).clamp(1, n);
    let (_, v, _) = values.select_nth_unstable_by(rank - 1, f64::total_cmp);
    (*v, eps * nf >= 1.0)
}

fn solve_one(
    surface: &Surface,
    stack: &Stack,
    design: &Design,
    settings: &BemSettings,
) -> Result<Solved, Error> {
    let p0 = design.pressure;
    let sol = bem::solve(surface, stack, p0, settings)?;
    let c = &sol.convergence;
    if c.status != Termination::Converged {
        return Err(Error::Numerical {
            what: "exact contact (boundary elements)",
            detail: format!(
                "{}x{} grid: no convergence in {} iterations (rms gap in contact {:.3e} m, \
                 penetration {:.3e} m, tolerance {:.3e} m)",
                surface.nx,
                surface.ny,
                c.iterations,
                c.gap_rms_in_contact,
                c.max_penetration,
                c.tolerance
            ),
        });
    }
    let fields = bem::interface_fields(&sol, stack)?;
    let eps = design.criteria.epsilon;
    let mut tau: Vec<f64> = (0..fields.shear_x.len())
        .map(|i| fields.shear_magnitude(i))
        .collect();
    let (tau_level, resolved) = level(&mut tau, eps);
    let mut normal = fields.normal.clone();
    let (sigma_level, _) = level(&mut normal, eps);
    Ok(Solved {
        area: sol.area_fraction.value,
        area_tol: sol.area_fraction.err,
        mean_pressure: p0 / sol.area_fraction.value,
        sigma_top: sol.sigma_rms_top,
        sigma_int: fields.normal_stats.rms_dev,
        tau_rms: fields.shear_stats.rms,
        tau_level,
        sigma_level,
        bond_fraction: fields.shear_fraction_above(design.bond_strength),
        resolved,
        convergence: sol.convergence,
    })
}

/// The surface sampled at every second pixel (same period, half the resolution).
fn half(surface: &Surface) -> Option<Result<Surface, Error>> {
    // A map with an odd side would lose its period; small maps have too few pixels to halve.
    let (nx, ny) = (surface.nx / 2, surface.ny / 2);
    if !surface.nx.is_multiple_of(2)
        || !surface.ny.is_multiple_of(2)
        || 2 * nx.min(ny) < MIN_SIDE_FOR_HALF
    {
        return None;
    }
    let heights = (0..ny)
        .flat_map(|iy| (0..nx).map(move |ix| (2 * iy, 2 * ix)))
        .map(|(iy, ix)| surface.heights[iy * surface.nx + ix])
        .collect();
    Some(Surface::new(
        heights,
        nx,
        ny,
        2.0 * surface.dx,
        2.0 * surface.dy,
    ))
}

/// Solve the design at `thickness` on `surface` and judge the enabled stress checks.
pub fn verify(
    surface: &Surface,
    design: &Design,
    thickness: f64,
    settings: &BemSettings,
) -> Result<Verification, Error> {
    let started = std::time::Instant::now();
    let stack = Stack::new(design.layers, thickness)?;
    let fine = solve_one(surface, &stack, design, settings)?;
    let coarse = half(surface)
        .map(|s| solve_one(&s?, &stack, design, settings))
        .transpose()?;
    let est = |f: fn(&Solved) -> f64, floor: f64| {
        let v = f(&fine);
        let err = coarse.as_ref().map_or(f64::NAN, |c| (v - f(c)).abs());
        Estimate {
            value: v,
            err: err.max(floor),
            status: Termination::Converged,
        }
    };
    let area_fraction = est(|s| s.area, fine.area_tol);
    let mean_contact_pressure = est(|s| s.mean_pressure, 0.0);
    let tau_peak = Level {
        value: est(|s| s.tau_level, 0.0),
        resolved: fine.resolved,
    };
    let sigma_peak_interface = Level {
        value: est(|s| s.sigma_level, 0.0),
        resolved: fine.resolved,
    };
    let sf = design.criteria.safety_factor;
    let on = design.criteria.checks;
    let mut checks = Vec::new();
    let mut judge = |kind, value: Estimate, limit: f64, resolved| {
        checks.push(ExactCheck {
            kind,
            value,
            limit,
            margin: 1.0 - value.value / limit,
            pass: value.value <= limit,
            resolved,
        });
    };
    if on.bond_shear {
        judge(
            CheckKind::BondShear,
            tau_peak.value,
            design.bond_strength / sf,
            tau_peak.resolved,
        );
    }
    if on.substrate_yield
        && let Some(y) = design.yield_strength
    {
        let (value, resolved) = if sigma_peak_interface.value.value >= mean_contact_pressure.value {
            (sigma_peak_interface.value, sigma_peak_interface.resolved)
        } else {
            (mean_contact_pressure, true)
        };
        judge(CheckKind::SubstrateYield, value, y / sf, resolved);
    }
    let pass = checks.iter().all(|c| c.pass);
    Ok(Verification {
        nx: surface.nx,
        ny: surface.ny,
        q_low_d: surface.q_low() * thickness,
        area_fraction,
        mean_contact_pressure,
        sigma_rms_top: est(|s| s.sigma_top, 0.0),
        sigma_rms_interface: est(|s| s.sigma_int, 0.0),
        tau_rms_interface: est(|s| s.tau_rms, 0.0),
        tau_peak,
        sigma_peak_interface,
        bond_exceedance: est(|s| s.bond_fraction, 0.0),
        checks,
        pass,
        convergence: fine.convergence,
        seconds: started.elapsed().as_secs_f64(),
    })
}

#[cfg(test)]
mod tests {
    use super::level;

    #[test]
    fn level_is_the_nearest_rank_quantile_or_the_maximum() {
        let mut v: Vec<f64> = (1..=1000).rev().map(f64::from).collect();
        // ε = 0.01 of 1000 samples: 10 samples lie above the level 990.
        assert_eq!(level(&mut v, 0.01), (990.0, true));
        // ε = 1e-6 < 1/N: the maximum, flagged unresolved.
        assert_eq!(level(&mut v, 1e-6), (1000.0, false));
        // ε = 1/N exactly is resolved: the level is exceeded on exactly one sample.
        assert_eq!(level(&mut v, 1e-3), (999.0, true));
    }
}
