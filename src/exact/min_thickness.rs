//! The minimum film thickness on a surface by the exact solver: the search of
//! [`crate::check::min_thickness`] (scan down from q_L·d = 10, the narrow-band guard at sampled
//! maxima, ITP refinement of the pass/fail crossing; safe for a utilisation that is not
//! monotone in d) with one boundary-element solve per thickness, each warm-started from the
//! solved pressure of the nearest thickness (in ln d) solved before ([`crate::bem::solve_from`]).
//!
//! The utilisation at d is the largest value/limit of the enabled exact stress checks
//! ([`crate::verify`]: the ε-levels of the solved fields and the mean contact pressure). The
//! error of d_min has two parts:
//! - the bracket: the search stops when its bracket is [`crate::check::D_MIN_RTOL`] wide; d_min
//!   is the geometric midpoint, the distance to the bracket's upper end (plus the shift by the
//!   solver tolerance's share of A/A0) its error ([`crate::check::search_min_thickness`]);
//! - the grid: the same search on the map at half the resolution (every second pixel, as
//!   [`crate::verify`] estimates the error of every exact number); the difference of the two
//!   d_min. NaN for maps with fewer than 32 pixels a side (no half-resolution map); infinite
//!   when one resolution finds a passing thickness and the other none.
//!
//! The reported error is their sum.

use crate::bem::{BemSettings, Surface};
use crate::check::checker::scan_range;
use crate::check::{CheckKind, Design, MinThickness, Utilisation, search_min_thickness};
use crate::error::Error;
use crate::layer::Stack;
use crate::prec::Estimate;
use crate::verify::{ExactCheck, Level, exact_checks, half, solve_one};

/// Solved pressure fields kept for warm starts (the newest; a search moves locally in ln d).
const WARM_KEEP: usize = 4;

/// The exact minimum thickness on one surface.
#[derive(Debug, Clone, PartialEq)]
pub struct ExactMinThickness {
    /// The search on the full map: d_min with its bracket error, the check that fails just
    /// below it, the scan range.
    pub search: MinThickness,
    /// |d_min − d_min at half the resolution| (m), see the module docs.
    pub grid_err: f64,
    /// Boundary-element solves of both searches.
    pub solves: usize,
    /// Solver iterations over those solves.
    pub iterations: usize,
}

impl ExactMinThickness {
    /// d_min with its error: the bracket's plus the grid's (none when no thickness passes).
    pub fn thickness(&self) -> Option<Estimate> {
        self.search.thickness.map(|d| Estimate {
            err: d.err + self.grid_err,
            ..d
        })
    }

    /// The min-thickness check of a film of `thickness`: it passes when thickness ≥ d_min
    /// (margin 1 − d_min/d); with no passing thickness the limit is infinite and it fails.
    pub fn check(&self, thickness: f64) -> ExactCheck {
        let d_min = self.search.thickness.map_or(f64::INFINITY, |d| d.value);
        ExactCheck {
            kind: CheckKind::MinThickness,
            value: Estimate::exact(thickness),
            limit: d_min,
            margin: 1.0 - d_min / thickness,
            pass: thickness >= d_min,
            resolved: true,
        }
    }
}

/// The largest value/limit of the exact stress checks at one solve, its relative error (the
/// solver tolerance's share of A/A0, which sets the mean contact pressure) and its check.
pub(crate) fn utilisation(checks: &[ExactCheck], area: f64, area_tol: f64) -> Utilisation {
    checks.iter().fold(
        Utilisation {
            value: 0.0,
            rel_err: area_tol / area,
            kind: None,
        },
        |worst, c| {
            let u = c.value.value / c.limit;
            if u > worst.value || worst.kind.is_none() {
                Utilisation {
                    value: u,
                    kind: Some(c.kind),
                    ..worst
                }
            } else {
                worst
            }
        },
    )
}

/// The exact utilisation of `design` at `thickness` on `surface`, warm-started from `start`,
/// with the solved pressure and the solver's iterations.
pub fn exact_utilisation(
    surface: &Surface,
    design: &Design,
    settings: &BemSettings,
    thickness: f64,
    start: Option<&[f64]>,
) -> Result<(Utilisation, Vec<f64>, usize), Error> {
    let stack = Stack::new(design.layers, thickness)?;
    let s = solve_one(surface, &stack, design, settings, start)?;
    let level = |value| Level {
        value: Estimate::exact(value),
        resolved: s.resolved,
    };
    let checks = exact_checks(
        design,
        level(s.tau_level),
        level(s.sigma_level),
        Estimate::exact(s.mean_pressure),
    );
    let u = utilisation(&checks, s.area, s.area_tol);
    Ok((u, s.pressure, s.convergence.iterations))
}

/// The largest wavenumber on the grid, |(π/dx, π/dy)| (1/m).
fn q_grid_max(surface: &Surface) -> f64 {
    (std::f64::consts::PI / surface.dx).hypot(std::f64::consts::PI / surface.dy)
}

/// The minimum-thickness search on one surface, each solve warm-started from the nearest
/// thickness solved before; returns the search, its solves and their iterations.
pub fn search(
    surface: &Surface,
    design: &Design,
    settings: &BemSettings,
) -> Result<(MinThickness, usize, usize), Error> {
    search_with(surface, &mut |s, d, start| {
        exact_utilisation(s, design, settings, d, start)
    })
}

/// The exact utilisation at one thickness on a surface, warm-started from a pressure field:
/// the utilisation, the solved pressure and the solver's iterations.
pub(crate) type Solve<'a> =
    dyn FnMut(&Surface, f64, Option<&[f64]>) -> Result<(Utilisation, Vec<f64>, usize), Error> + 'a;

/// The search of [`search`] with the exact utilisation at (surface, thickness, warm start)
/// given by `solve` (a film's, or a stack's with one layer varied).
pub(crate) fn search_with(
    surface: &Surface,
    solve: &mut Solve<'_>,
) -> Result<(MinThickness, usize, usize), Error> {
    let (lo, hi) = scan_range(surface.q_low(), q_grid_max(surface));
    let mut warm: Vec<(f64, Vec<f64>)> = Vec::new();
    let (mut solves, mut iterations) = (0, 0);
    let m = search_min_thickness(lo, hi, |d| {
        let x = d.ln();
        let start = warm
            .iter()
            .min_by(|a, b| (a.0 - x).abs().total_cmp(&(b.0 - x).abs()))
            .map(|(_, p)| p.as_slice());
        let (u, pressure, its) = solve(surface, d, start)?;
        solves += 1;
        iterations += its;
        if warm.len() == WARM_KEEP {
            warm.remove(0);
        }
        warm.push((x, pressure));
        Ok(u)
    })?;
    Ok((m, solves, iterations))
}

/// The exact minimum thickness on `surface` with its bracket and grid errors (module docs).
pub fn min_thickness(
    surface: &Surface,
    design: &Design,
    settings: &BemSettings,
) -> Result<ExactMinThickness, Error> {
    min_thickness_with(surface, &mut |s, d, start| {
        exact_utilisation(s, design, settings, d, start)
    })
}

/// [`min_thickness`] with the exact utilisation given by `solve` ([`search_with`]): the search
/// on the map and on the map at half the resolution.
pub(crate) fn min_thickness_with(
    surface: &Surface,
    solve: &mut Solve<'_>,
) -> Result<ExactMinThickness, Error> {
    let (fine, mut solves, mut iterations) = search_with(surface, solve)?;
    let grid_err = match half(surface) {
        None => f64::NAN,
        Some(coarse) => {
            let (c, s, i) = search_with(&coarse?, solve)?;
            solves += s;
            iterations += i;
            match (fine.thickness, c.thickness) {
                (Some(a), Some(b)) => (a.value - b.value).abs(),
                (None, None) => 0.0,
                _ => f64::INFINITY,
            }
        }
    };
    Ok(ExactMinThickness {
        search: fine,
        grid_err,
        solves,
        iterations,
    })
}
