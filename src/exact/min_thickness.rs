//! The minimum film thickness on a surface by the exact solver: the search of
//! [`crate::check::min_thickness`] (scan down from q_L·d = 10, the narrow-band guard at sampled
//! maxima, ITP refinement of the pass/fail crossing; safe for a utilisation that is not
//! monotone in d) with one boundary-element solve per thickness, each warm-started from the
//! solved pressure of the nearest thickness (in ln d) solved before ([`crate::bem::solve_from`]).
//! The search runs from coarse to fine ([`super::levels`]): in full on the map at a quarter of
//! the resolution (every fourth pixel; on a map under 512 pixels a side, whose quarter would
//! have fewer than [`super::levels::MIN_COARSE_SIDE`], at half the resolution), then on the
//! finer copies only near the coarser crossing, inheriting the coarser scan where the levels
//! agree (else in full there too).
//!
//! The utilisation at d is the largest value/limit of the enabled exact stress checks
//! ([`crate::verify`]: the ε-levels of the solved fields and the mean contact pressure). The
//! error of d_min has two parts:
//! - the bracket: the search stops when its bracket is [`crate::check::D_MIN_RTOL`] wide, or
//!   (on a finer level) when its half-width is at most a quarter of its distance to the coarser
//!   d_min, a lower bound of the grid part; d_min is the geometric midpoint, the distance to the
//!   bracket's upper end (plus the shift by the solver tolerance's share of A/A0) its error
//!   ([`crate::check::search_min_thickness`]);
//! - the grid: the difference to the d_min of the map at half the resolution (every second
//!   pixel, as [`crate::verify`] estimates the error of every exact number). NaN for maps with
//!   fewer than 32 pixels a side (no half-resolution map); infinite when one resolution finds a
//!   passing thickness and the other none.
//!
//! The reported error is their sum.

use super::levels::{MIN_COARSE_SIDE, Solver, search_levels};
use crate::bem::{BemSettings, Surface};
use crate::check::{CheckKind, Design, MinThickness, Utilisation};
use crate::error::Error;
use crate::layer::Stack;
use crate::prec::Estimate;
use crate::verify::{ExactCheck, Level, exact_checks, half, solve_one};

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

/// The exact utilisation at one thickness on a surface, warm-started from a pressure field:
/// the utilisation, the solved pressure and the solver's iterations.
pub(crate) type Solve<'a> =
    dyn FnMut(&Surface, f64, Option<&[f64]>) -> Result<(Utilisation, Vec<f64>, usize), Error> + 'a;

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

/// [`min_thickness`] with the exact utilisation at (surface, thickness, warm start) given by
/// `solve` (a film's, or a stack's with one layer varied): the searches from coarse to fine
/// ([`super::levels`]) on the map at a quarter and at half the resolution and on the map.
pub(crate) fn min_thickness_with(
    surface: &Surface,
    solve: &mut Solve<'_>,
) -> Result<ExactMinThickness, Error> {
    let halved = half(surface).transpose()?;
    let quarter = halved
        .as_ref()
        .filter(|h| h.nx.min(h.ny) >= 2 * MIN_COARSE_SIDE)
        .and_then(half)
        .transpose()?;
    let levels: Vec<&Surface> = [quarter.as_ref(), halved.as_ref(), Some(surface)]
        .into_iter()
        .flatten()
        .collect();
    let mut solver = Solver::new(solve);
    let mut searches = search_levels(&levels, &mut solver)?;
    let fine = searches.pop().expect("the map itself is a level");
    let grid_err = match searches.pop() {
        None => f64::NAN,
        Some(c) => match (fine.thickness, c.thickness) {
            (Some(a), Some(b)) => (a.value - b.value).abs(),
            (None, None) => 0.0,
            _ => f64::INFINITY,
        },
    };
    Ok(ExactMinThickness {
        search: fine,
        grid_err,
        solves: solver.solves,
        iterations: solver.iterations,
    })
}
