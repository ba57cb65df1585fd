//! The design check on the measured surface itself, and the comparison of Persson's estimate
//! with the exact contact ([`compare`]): the exact contact of the scene's film,
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
//! number is therefore also computed on the map sampled at every second pixel and at every
//! fourth (both directions: the same surface at half and at a quarter of the resolution), and
//! its grid error is estimated from the three values ([`grid`]: Richardson extrapolation at the
//! observed rate, capped at first order, with a safety factor; a fixed factor on the larger
//! difference where the values do not converge). For A/A0 the estimate covered the difference
//! to a finer parent map of the same surface in every tested case (`tests/it/exact.rs`); it is
//! not a proof. Maps with fewer than 64 pixels a side get the difference to the half-resolution
//! map times 3, fewer than 32 a NaN error. The map is one period of a periodic surface, as
//! `coatcheck verify` treats it.
//! The minimum thickness on the map is searched by [`crate::exact`] (a solve per thickness).

use crate::bem::{self, BemSettings, BemSolution, Convergence, InterfaceFields, Surface};
use crate::check::{CheckKind, Design, Evaluation, criteria};
use crate::contact::{Contact, Engine, Request, tau_exceedance, tau_peak};
use crate::error::Error;
use crate::layer::Stack;
use crate::prec::{Estimate, Settings, Termination};
use crate::psd::Spectrum;
use crate::topography::HeightMap;
use crate::topography::spectrum::{PsdOptions, map_psd};
use serde::Serialize;

pub mod boundary;
pub mod grid;
pub mod regime;
pub mod sliding;

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
    /// Rms of |τ| at z = d (Pa); under sliding, of the static (pressure-driven) shear.
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
    /// Under sliding friction: the interface shear vector ([`sliding`]). The levels, σ_rms(d)
    /// and the bond exceedance above are then those of the total fields.
    pub sliding: Option<sliding::SlidingVerification>,
    /// The full-resolution solve.
    pub convergence: Convergence,
    /// Wall time of both solves (s).
    pub seconds: f64,
}

/// The numbers of one solve.
pub(crate) struct Solved {
    pub(crate) area: f64,
    pub(crate) area_tol: f64,
    pub(crate) mean_pressure: f64,
    pub(crate) sigma_top: f64,
    pub(crate) sigma_int: f64,
    pub(crate) tau_rms: f64,
    pub(crate) tau_level: f64,
    pub(crate) sigma_level: f64,
    pub(crate) bond_fraction: f64,
    pub(crate) resolved: bool,
    pub(crate) convergence: Convergence,
    /// Under sliding: the shear vector's summary and the |τ| statistics.
    pub(crate) sliding: Option<(sliding::ExactSliding, bem::FieldStats)>,
    /// The solved contact pressure (Pa), to warm-start a neighbouring solve.
    pub(crate) pressure: Vec<f64>,
}

/// The nearest-rank (1 − ε) quantile of `values` (reordered) and whether ε ≥ 1/N.
pub(crate) fn level(values: &mut [f64], eps: f64) -> (f64, bool) {
    let n = values.len();
    let nf = n as f64;
    let rank = (((1.0 - eps) * nf).ceil() as usize).clamp(1, n);
    let (_, v, _) = values.select_nth_unstable_by(rank - 1, f64::total_cmp);
    (*v, eps * nf >= 1.0)
}

/// The exact contact at nominal pressure `p0` and the interface fields under it. A solve that
/// did not converge is an error (nothing is judged on it).
pub fn solve(
    surface: &Surface,
    stack: &Stack,
    p0: f64,
    settings: &BemSettings,
) -> Result<(BemSolution, InterfaceFields), Error> {
    solve_warm(surface, stack, p0, settings, None)
}

/// [`solve`], warm-started from the pressure field `start` when given ([`bem::solve_from`]).
pub fn solve_warm(
    surface: &Surface,
    stack: &Stack,
    p0: f64,
    settings: &BemSettings,
    start: Option<&[f64]>,
) -> Result<(BemSolution, InterfaceFields), Error> {
    let sol = match start {
        Some(start) => bem::solve_from(surface, stack, p0, settings, start)?,
        None => bem::solve(surface, stack, p0, settings)?,
    };
    let sol = converged(surface, sol)?;
    let fields = bem::interface_fields(&sol, stack)?;
    Ok((sol, fields))
}

/// A solve that did not converge as an error (nothing is judged on it).
pub(crate) fn converged(surface: &Surface, sol: BemSolution) -> Result<BemSolution, Error> {
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
    Ok(sol)
}

/// One solve of `design` on `stack` (warm-started from `start` when given) and its numbers.
pub(crate) fn solve_one(
    surface: &Surface,
    stack: &Stack,
    design: &Design,
    settings: &BemSettings,
    start: Option<&[f64]>,
) -> Result<Solved, Error> {
    let p0 = design.pressure;
    let (sol, fields) = solve_warm(surface, stack, p0, settings, start)?;
    let tau_rms = fields.shear_stats.rms;
    let (fields, sliding) = match sliding::with_friction(&sol, stack, &fields, design.friction)? {
        Some((total, summary)) => {
            let stats = total.shear_stats.clone();
            (total, Some((summary, stats)))
        }
        None => (fields, None),
    };
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
        tau_rms,
        tau_level,
        sigma_level,
        bond_fraction: fields.shear_fraction_above(design.bond_strength),
        resolved,
        convergence: sol.convergence,
        sliding,
        pressure: sol.pressure,
    })
}

/// The surface sampled at every second pixel (same period, half the resolution).
pub(crate) fn half(surface: &Surface) -> Option<Result<Surface, Error>> {
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

/// `solve` on the map at half and at a quarter of the resolution, those that can be made
/// ([`half`] of the map, and of that).
pub(crate) fn coarser<T>(
    surface: &Surface,
    mut solve: impl FnMut(&Surface) -> Result<T, Error>,
) -> Result<(Option<T>, Option<T>), Error> {
    let Some(h) = half(surface) else {
        return Ok((None, None));
    };
    let h = h?;
    let quarter = half(&h).map(|q| solve(&q?)).transpose()?;
    Ok((Some(solve(&h)?), quarter))
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
    let fine = solve_one(surface, &stack, design, settings, None)?;
    let (coarse, quarter) = coarser(surface, |s| solve_one(s, &stack, design, settings, None))?;
    let est = |f: fn(&Solved) -> f64, floor: f64| {
        let v = f(&fine);
        let err = grid::grid_error(v, coarse.as_ref().map(f), quarter.as_ref().map(f));
        Estimate {
            value: v,
            err: err.max(floor),
            status: Termination::Converged,
        }
    };
    let area = |s: &Solved| s.area;
    let area_fraction = Estimate {
        err: grid::area_grid_error(
            fine.area,
            coarse.as_ref().map(area),
            quarter.as_ref().map(area),
            surface.len(),
        )
        .max(fine.area_tol),
        ..est(area, fine.area_tol)
    };
    let mean_contact_pressure = est(|s| s.mean_pressure, 0.0);
    let tau_peak = Level {
        value: est(|s| s.tau_level, 0.0),
        resolved: fine.resolved,
    };
    let sigma_peak_interface = Level {
        value: est(|s| s.sigma_level, 0.0),
        resolved: fine.resolved,
    };
    let checks = exact_checks(
        design,
        tau_peak,
        sigma_peak_interface,
        mean_contact_pressure,
    );
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
        sliding: fine.sliding.as_ref().map(|(s, t)| {
            let half = coarse.as_ref().and_then(|c| c.sliding.as_ref());
            sliding::SlidingVerification::of((s, t), half.map(|(s, t)| (s, t)))
        }),
        convergence: fine.convergence,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// The enabled stress checks judged on exact levels: bond-shear on the ε-level of |τ|,
/// substrate-yield on the larger of the ε-level of σ_n and the mean contact pressure.
pub(crate) fn exact_checks(
    design: &Design,
    tau_peak: Level,
    sigma_peak_interface: Level,
    mean_contact_pressure: Estimate,
) -> Vec<ExactCheck> {
    let sf = design.criteria.safety_factor;
    let on = design.criteria.checks;
    let mut checks = Vec::new();
    let mut judge = |kind, value: Estimate, limit: f64, resolved| {
        checks.push(ExactCheck {
            kind,
            value,
            limit,
            margin: criteria::margin(value.value, limit),
            pass: criteria::passes(value.value, limit),
            resolved,
        });
    };
    if on.bond_shear {
        judge(
            CheckKind::BondShear,
            tau_peak.value,
            criteria::limit(design.bond_strength, sf),
            tau_peak.resolved,
        );
    }
    if on.substrate_yield
        && let Some(y) = design.yield_strength
    {
        let (value, resolved) = criteria::yield_governing(
            (sigma_peak_interface.value, sigma_peak_interface.resolved),
            (mean_contact_pressure, true),
            |(e, _): &(Estimate, bool)| e.value,
        );
        judge(
            CheckKind::SubstrateYield,
            value,
            criteria::limit(y, sf),
            resolved,
        );
    }
    checks
}

/// One quantity of the Persson-vs-exact comparison.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub name: String,
    /// `Pa` or empty (dimensionless).
    pub unit: &'static str,
    /// Persson's prediction with its error, where the theory gives one.
    pub persson: Option<Estimate>,
    pub exact: f64,
}

impl Row {
    pub(crate) fn new(
        name: impl Into<String>,
        unit: &'static str,
        persson: Option<Estimate>,
        exact: f64,
    ) -> Self {
        Self {
            name: name.into(),
            unit,
            persson,
            exact,
        }
    }

    /// exact / Persson (none where Persson has no value or it is 0).
    pub fn ratio(&self) -> Option<f64> {
        self.persson
            .filter(|p| p.value != 0.0)
            .map(|p| self.exact / p.value)
    }
}

/// The exact contact on a height map beside Persson's estimate from the map's own spectrum.
#[derive(Debug, Clone)]
pub struct Comparison {
    pub surface: Surface,
    pub solution: BemSolution,
    pub fields: InterfaceFields,
    pub persson: Contact,
    /// Fraction of the interface where |τ| exceeds the bond strength, when one is given.
    pub above_bond: Option<f64>,
    pub rows: Vec<Row>,
    /// Wall time of the exact solve and its interface fields (s).
    pub seconds: f64,
    /// A/A0 with its error: the solver tolerance's share plus the grid error from the same
    /// map at half and at a quarter of the resolution ([`grid`]; the tolerance's share alone
    /// for maps with fewer than 32 pixels a side).
    pub area_fraction: Estimate,
    /// A/A0 of the half-resolution map, when it was solved.
    pub area_fraction_half: Option<f64>,
    /// A/A0 of the quarter-resolution map, when it was solved.
    pub area_fraction_quarter: Option<f64>,
}

/// The map's own spectrum (periodic, no window, all wavelengths down to the Nyquist limit, as
/// the boundary elements see them).
pub(crate) fn map_spectrum(map: &HeightMap) -> Result<Spectrum, Error> {
    let psd = map_psd(
        map,
        &PsdOptions {
            cutoff_pixels: 2.0,
            ..PsdOptions::default()
        },
    )?;
    Ok(Spectrum::Tabulated(psd.c2d))
}

/// Persson's estimate on the map's own spectrum (periodic, no window, all wavelengths down to
/// the Nyquist limit, as the boundary elements see them).
pub fn persson(
    map: &HeightMap,
    stack: &Stack,
    p0: f64,
    settings: Settings,
) -> Result<Contact, Error> {
    let engine = Engine::new(&map_spectrum(map)?, settings);
    engine.evaluate(stack, p0, Request::all())
}

/// Solve the contact on `map` (one period of a periodic surface) at nominal pressure `p0` and
/// compare it with Persson's estimate (contact integrals to `settings`).
pub fn compare(
    map: &HeightMap,
    stack: &Stack,
    p0: f64,
    bem: &BemSettings,
    settings: Settings,
    bond: Option<f64>,
) -> Result<Comparison, Error> {
    let surface = Surface::from_height_map(map)?;
    let started = std::time::Instant::now();
    let (solution, fields) = solve(&surface, stack, p0, bem)?;
    let seconds = started.elapsed().as_secs_f64();
    let theory = persson(map, stack, p0, settings)?;
    let above_bond = bond.map(|b| fields.shear_fraction_above(b));
    let rows = comparison_rows(&solution, &fields, &theory, bond, above_bond);
    let (area_fraction, area_fraction_half, area_fraction_quarter) =
        area_fraction_error(&surface, stack, p0, bem, solution.area_fraction)?;
    Ok(Comparison {
        surface,
        solution,
        fields,
        persson: theory,
        above_bond,
        rows,
        seconds,
        area_fraction,
        area_fraction_half,
        area_fraction_quarter,
    })
}

/// A/A0 of a solve on `surface` with its error: the solver tolerance's share plus the grid
/// error (see [`Comparison::area_fraction`]), and A/A0 at half and at a quarter of the
/// resolution where the map could be coarsened.
pub(crate) fn area_fraction_error(
    surface: &Surface,
    stack: &Stack,
    p0: f64,
    bem: &BemSettings,
    a: Estimate,
) -> Result<(Estimate, Option<f64>, Option<f64>), Error> {
    let (half_area, quarter_area) = coarser(surface, |s| {
        Ok(solve(s, stack, p0, bem)?.0.area_fraction.value)
    })?;
    let grid_err = match half_area {
        None => 0.0,
        Some(_) => grid::area_grid_error(a.value, half_area, quarter_area, surface.len()),
    };
    let area_fraction = Estimate {
        err: a.err + grid_err,
        ..a
    };
    Ok((area_fraction, half_area, quarter_area))
}

/// The compared quantities: Persson's rms values, and his Gaussian quantiles of |τ| and the
/// bond exceedance (errors propagated to first order from τ_rms's), against the field's.
fn comparison_rows(
    sol: &BemSolution,
    fields: &InterfaceFields,
    theory: &Contact,
    bond: Option<f64>,
    above: Option<f64>,
) -> Vec<Row> {
    let tau_rms = theory.tau_rms_interface;
    let area = theory.area_fraction;
    let mut rows = vec![
        Row::new("A/A0", "", Some(area), sol.area_fraction.value),
        Row::new(
            "sigma_rms top",
            "Pa",
            theory.sigma_rms_top,
            sol.sigma_rms_top,
        ),
        Row::new(
            "sigma_rms interface",
            "Pa",
            theory.sigma_rms_interface,
            fields.normal_stats.rms_dev,
        ),
        Row::new("tau_rms interface", "Pa", tau_rms, fields.shear_stats.rms),
        Row::new(
            "contact pressure mean",
            "Pa",
            Some(area.map(|a| sol.p0 / a, |a| sol.p0 / (a * a))),
            sol.contact_pressure.mean,
        ),
    ];
    exact_only(&mut rows, "contact pressure", &sol.contact_pressure);
    exact_only(&mut rows, "interface sigma_n", &fields.normal_stats);
    shear_rows(&mut rows, fields, tau_rms, bond, above);
    rows
}

/// Rows of a field's quantiles and maximum, which Persson's theory does not give.
pub(crate) fn exact_only(rows: &mut Vec<Row>, name: &str, s: &bem::FieldStats) {
    for q in &s.quantiles {
        rows.push(Row::new(format!("{name} q{}", q.prob), "Pa", None, q.value));
    }
    rows.push(Row::new(format!("{name} max"), "Pa", None, s.max));
}

/// The interface's |τ| rows: the field's quantiles beside Persson's Gaussian ones, its maximum,
/// and the bond exceedance (errors propagated to first order from τ_rms's).
pub(crate) fn shear_rows(
    rows: &mut Vec<Row>,
    fields: &InterfaceFields,
    tau_rms: Option<Estimate>,
    bond: Option<f64>,
    above: Option<f64>,
) {
    for q in &fields.shear_stats.quantiles {
        // Persson: |τ| half-normal with rms τ_rms, so the quantile at P is τ_peak(ε = 1 − P).
        let k = tau_peak(1.0, 1.0 - q.prob);
        let p = tau_rms.map(|t| t.map(|t| k * t, |_| k));
        rows.push(Row::new(
            format!("interface |tau| q{}", q.prob),
            "Pa",
            p,
            q.value,
        ));
    }
    rows.push(Row::new(
        "interface |tau| max",
        "Pa",
        None,
        fields.shear_stats.max,
    ));
    if let (Some(b), Some(f)) = (bond, above) {
        rows.push(Row::new(
            "area fraction |tau| > bond",
            "",
            tau_rms.map(|t| Estimate {
                value: tau_exceedance(t.value, b),
                err: (tau_exceedance(t.value + t.err, b) - tau_exceedance(t.value, b)).abs(),
                status: t.status,
            }),
            f,
        ));
    }
}

/// One quantity of `check --verify`: Persson's value beside the exact one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CheckRow {
    pub name: &'static str,
    /// Report key; stresses end in `_pa`.
    pub key: &'static str,
    pub persson: Option<Estimate>,
    pub exact: Estimate,
}

/// Persson's evaluation and the exact one side by side, for `check --verify`.
pub fn check_rows(ev: &Evaluation, v: &Verification) -> Vec<CheckRow> {
    let c = &ev.contact;
    let row = |name, key, persson, exact| CheckRow {
        name,
        key,
        persson,
        exact,
    };
    let mut rows = vec![
        row(
            "A/A0",
            "area_fraction",
            Some(c.area_fraction),
            v.area_fraction,
        ),
        row(
            "mean contact pressure",
            "mean_contact_pressure_pa",
            Some(ev.mean_contact_pressure),
            v.mean_contact_pressure,
        ),
        row(
            "sigma_rms top",
            "sigma_rms_top_pa",
            c.sigma_rms_top,
            v.sigma_rms_top,
        ),
        row(
            "sigma_rms interface",
            "sigma_rms_interface_pa",
            c.sigma_rms_interface,
            v.sigma_rms_interface,
        ),
        row(
            "tau_rms interface",
            "tau_rms_interface_pa",
            c.tau_rms_interface,
            v.tau_rms_interface,
        ),
        row("tau_peak", "tau_peak_pa", ev.tau_peak, v.tau_peak.value),
        row(
            "sigma_peak interface",
            "sigma_peak_interface_pa",
            ev.sigma_peak_interface,
            v.sigma_peak_interface.value,
        ),
        row(
            "P(|tau| > bond strength)",
            "bond_exceedance",
            ev.bond_exceedance.map(|p| Estimate {
                value: p,
                err: 0.0,
                status: Termination::Converged,
            }),
            v.bond_exceedance,
        ),
    ];
    if let Some(s) = &v.sliding {
        rows.extend(sliding::check_rows(ev, s));
    }
    rows
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
