//! The exact contact on a layer stack (notes.md, "Layer stacks"; paper Appendix B with the
//! stack's kernels): the boundary-element solve with the surface compliance 2 S(q)/(q E1*) of
//! the whole stack and the fields at every interface k from f_k, g_k
//! ([`crate::bem::solve_stack`], [`crate::bem::stack_interface_fields`]),
//! judged as [`crate::verify`] judges a film's fields, interface by interface:
//!
//! - bond-shear at every interface k: the level that |τ(x, z_k)| exceeds on a fraction ε of the
//!   interface, against that interface's own τ_bond,k / SF (named after the layer above it);
//! - substrate-yield at the bottom interface (the substrate's surface): the larger of p0·A0/A
//!   and the ε-level of σ_n(x, z_N), against σ_Y / SF.
//!
//! The ε-levels, their `resolved` flag and the error estimate (the grid error from the same map
//! at half and a quarter of the resolution) are those of [`crate::verify`]. Every interface also carries the
//! statistics of its fields at full resolution (σ_n and |τ|: mean, rms, quantiles, maximum).
//!
//! Under sliding friction ([`sliding`]: the traction μ·p(x) along x through every interface's
//! tangential kernels) the levels, σ_rms, the bond exceedance and the field statistics are
//! those of the total fields, τ_rms stays the pressure-driven shear's, and every interface
//! carries its shear vector.
//!
//! [`compare`] puts the exact contact beside Persson's theory on the stack
//! ([`crate::contact::StackContact`]) evaluated on the map's own spectrum, for
//! `coatcheck verify --layer`: the top surface's quantities, then every interface's.

use crate::bem::{
    BemSettings, BemSolution, Convergence, FieldStats, InterfaceFields, Surface, solve_stack,
    solve_stack_from, stack_interface_fields,
};
use crate::check::stack::StackDesign;
use crate::check::{CheckKind, criteria};
use crate::contact::{Engine, Request, StackContact};
use crate::error::Error;
use crate::layer::stack::{Layer, Stack};
use crate::prec::{Estimate, Settings, Termination};
use crate::topography::HeightMap;
use crate::verify::sliding::{ExactSliding, SlidingVerification};
use crate::verify::{
    ExactCheck, Level, Row, converged, exact_only, level, map_spectrum, shear_rows,
};
use serde::Serialize;

pub mod sliding;

/// The exact fields at one interface of a stack.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InterfaceExact {
    /// The layer above the interface.
    pub name: String,
    /// Depth z_k below the top surface (m).
    pub depth: f64,
    /// Rms deviation of σ_n at z_k (Pa).
    pub sigma_rms: Estimate,
    /// Rms of |τ| at z_k (Pa); under sliding, of the static (pressure-driven) shear.
    pub tau_rms: Estimate,
    /// ε-level of |τ| at z_k.
    pub tau_peak: Level,
    /// ε-level of σ_n at z_k.
    pub sigma_peak: Level,
    /// The bond's shear strength (Pa).
    pub bond_strength: f64,
    /// Fraction of the interface where |τ| exceeds the bond strength (not the limit).
    pub bond_exceedance: Estimate,
    /// σ_n (compression positive) over the interface at full resolution (Pa).
    pub normal: FieldStats,
    /// |τ| over the interface at full resolution (Pa).
    pub shear: FieldStats,
    /// Under sliding friction: the interface shear vector ([`sliding`]). The levels, σ_rms, the
    /// bond exceedance and the field statistics above are then those of the total fields.
    pub sliding: Option<SlidingVerification>,
}

/// One exact check with the interface it concerns (a layer's name, or `substrate`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StackExactCheck {
    pub at: String,
    pub check: ExactCheck,
}

/// The exact contact of a stack design on a height map, summarised for the checks.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StackVerification {
    pub nx: usize,
    pub ny: usize,
    /// q_L·z_N with q_L = 2π / (longer side of the map) and z_N the bottom interface's depth.
    pub q_low_z: f64,
    pub area_fraction: Estimate,
    /// p0·A0/A (Pa).
    pub mean_contact_pressure: Estimate,
    /// Rms of p − p0 at z = 0 (Pa).
    pub sigma_rms_top: Estimate,
    /// Every interface, top first.
    pub interfaces: Vec<InterfaceExact>,
    /// bond-shear at every interface, substrate-yield at the bottom (those enabled).
    pub checks: Vec<StackExactCheck>,
    pub pass: bool,
    /// The full-resolution solve.
    pub convergence: Convergence,
    /// Wall time of both solves (s).
    pub seconds: f64,
}

/// The exact contact at nominal pressure `p0` and the fields at every interface (top first). A
/// solve that did not converge is an error (nothing is judged on it).
pub fn solve(
    surface: &Surface,
    stack: &Stack,
    p0: f64,
    settings: &BemSettings,
) -> Result<(BemSolution, Vec<InterfaceFields>), Error> {
    solve_warm(surface, stack, p0, settings, None)
}

/// [`solve`], warm-started from the pressure field `start` when given
/// ([`crate::bem::solve_stack_from`]).
pub fn solve_warm(
    surface: &Surface,
    stack: &Stack,
    p0: f64,
    settings: &BemSettings,
    start: Option<&[f64]>,
) -> Result<(BemSolution, Vec<InterfaceFields>), Error> {
    let sol = match start {
        Some(start) => solve_stack_from(surface, stack, p0, settings, start)?,
        None => solve_stack(surface, stack, p0, settings)?,
    };
    let sol = converged(surface, sol)?;
    let fields = stack_interface_fields(&sol, stack)?;
    Ok((sol, fields))
}

/// The numbers of one interface of one solve.
pub(crate) struct SolvedInterface {
    sigma_rms: f64,
    tau_rms: f64,
    tau_level: f64,
    sigma_level: f64,
    bond_fraction: f64,
    resolved: bool,
    normal: FieldStats,
    shear: FieldStats,
    /// Under sliding: the shear vector's summary and the |τ| statistics.
    sliding: Option<(ExactSliding, FieldStats)>,
}

/// The numbers of one solve.
pub(crate) struct Solved {
    pub(crate) area: f64,
    pub(crate) area_tol: f64,
    pub(crate) mean_pressure: f64,
    sigma_top: f64,
    pub(crate) interfaces: Vec<SolvedInterface>,
    pub(crate) convergence: Convergence,
    /// The solved contact pressure (Pa), to warm-start a neighbouring solve.
    pub(crate) pressure: Vec<f64>,
}

/// The stack of a design at its layers' thicknesses.
pub fn design_stack(design: &StackDesign) -> Result<Stack, Error> {
    let layers = design
        .layers
        .iter()
        .map(|l| Layer {
            material: l.material,
            thickness: l.thickness,
        })
        .collect();
    Stack::new(layers, design.substrate)
}

/// One solve of `design` on `stack` (warm-started from `start` when given) and its numbers,
/// under the sliding friction `mu` (0: static contact; [`sliding`]).
pub(crate) fn solve_one(
    surface: &Surface,
    stack: &Stack,
    (design, mu): (&StackDesign, f64),
    settings: &BemSettings,
    start: Option<&[f64]>,
) -> Result<Solved, Error> {
    let p0 = design.pressure;
    let (sol, fields) = solve_warm(surface, stack, p0, settings, start)?;
    let eps = design.criteria.epsilon;
    let interfaces = sliding::with_friction(&sol, stack, fields, mu)?
        .into_iter()
        .zip(&design.layers)
        .map(|((f, summary), layer)| {
            let mut tau: Vec<f64> = (0..f.shear_x.len()).map(|i| f.shear_magnitude(i)).collect();
            let (tau_level, resolved) = level(&mut tau, eps);
            let mut normal = f.normal.clone();
            let (sigma_level, _) = level(&mut normal, eps);
            SolvedInterface {
                sigma_rms: f.normal_stats.rms_dev,
                tau_rms: summary
                    .as_ref()
                    .map_or(f.shear_stats.rms, |s| s.static_tau_rms),
                tau_level,
                sigma_level,
                bond_fraction: f.shear_fraction_above(layer.bond_strength),
                resolved,
                sliding: summary.map(|s| (s, f.shear_stats.clone())),
                normal: f.normal_stats,
                shear: f.shear_stats,
            }
        })
        .collect();
    Ok(Solved {
        area: sol.area_fraction.value,
        area_tol: sol.area_fraction.err,
        mean_pressure: p0 / sol.area_fraction.value,
        sigma_top: sol.sigma_rms_top,
        interfaces,
        convergence: sol.convergence,
        pressure: sol.pressure,
    })
}

/// A full-resolution value with the grid error from its half- and quarter-resolution values
/// ([`crate::verify::grid`]; NaN without a half-resolution solve), at least `floor`.
fn estimate(fine: f64, coarse: Option<f64>, quarter: Option<f64>, floor: f64) -> Estimate {
    let err = crate::verify::grid::grid_error(fine, coarse, quarter);
    Estimate {
        value: fine,
        err: err.max(floor),
        status: Termination::Converged,
    }
}

/// One interface's exact summary from the two solves.
pub(crate) fn interface(
    design: &StackDesign,
    k: usize,
    depth: f64,
    fine: SolvedInterface,
    (coarse, quarter): (Option<&SolvedInterface>, Option<&SolvedInterface>),
) -> InterfaceExact {
    let est =
        |f: fn(&SolvedInterface) -> f64| estimate(f(&fine), coarse.map(f), quarter.map(f), 0.0);
    let layer = &design.layers[k];
    InterfaceExact {
        name: layer.name.clone(),
        depth,
        sigma_rms: est(|s| s.sigma_rms),
        tau_rms: est(|s| s.tau_rms),
        tau_peak: Level {
            value: est(|s| s.tau_level),
            resolved: fine.resolved,
        },
        sigma_peak: Level {
            value: est(|s| s.sigma_level),
            resolved: fine.resolved,
        },
        bond_strength: layer.bond_strength,
        bond_exceedance: est(|s| s.bond_fraction),
        sliding: fine.sliding.as_ref().map(|(s, t)| {
            let half = coarse.and_then(|c| c.sliding.as_ref());
            SlidingVerification::of((s, t), half.map(|(s, t)| (s, t)))
        }),
        normal: fine.normal,
        shear: fine.shear,
    }
}

/// The enabled checks on the exact interfaces (module docs).
pub(crate) fn judge(
    design: &StackDesign,
    interfaces: &[InterfaceExact],
    mean: Estimate,
) -> Vec<StackExactCheck> {
    let sf = design.criteria.safety_factor;
    let on = design.criteria.checks;
    let check = |at: &str, kind, value: Estimate, limit: f64, resolved| StackExactCheck {
        at: at.to_string(),
        check: ExactCheck {
            kind,
            value,
            limit,
            margin: criteria::margin(value.value, limit),
            pass: criteria::passes(value.value, limit),
            resolved,
        },
    };
    let mut checks = Vec::new();
    if on.bond_shear {
        checks.extend(interfaces.iter().map(|i| {
            check(
                &i.name,
                CheckKind::BondShear,
                i.tau_peak.value,
                criteria::limit(i.bond_strength, sf),
                i.tau_peak.resolved,
            )
        }));
    }
    if on.substrate_yield
        && let (Some(y), Some(bottom)) = (design.yield_strength, interfaces.last())
    {
        let (value, resolved) = criteria::yield_governing(
            (bottom.sigma_peak.value, bottom.sigma_peak.resolved),
            (mean, true),
            |(e, _): &(Estimate, bool)| e.value,
        );
        checks.push(check(
            "substrate",
            CheckKind::SubstrateYield,
            value,
            criteria::limit(y, sf),
            resolved,
        ));
    }
    checks
}

/// Solve the stack design at its layers' thicknesses on `surface` under the sliding friction
/// `mu` (0: static contact) and judge the enabled stress checks at every interface (under
/// sliding on the total fields).
pub fn verify(
    surface: &Surface,
    design: &StackDesign,
    mu: f64,
    settings: &BemSettings,
) -> Result<StackVerification, Error> {
    let started = std::time::Instant::now();
    let stack = design_stack(design)?;
    let fine = solve_one(surface, &stack, (design, mu), settings, None)?;
    let (coarse, quarter) = crate::verify::coarser(surface, |s| {
        solve_one(s, &stack, (design, mu), settings, None)
    })?;
    let top = |f: fn(&Solved) -> f64, floor| {
        estimate(
            f(&fine),
            coarse.as_ref().map(f),
            quarter.as_ref().map(f),
            floor,
        )
    };
    let area = |s: &Solved| s.area;
    let area_fraction = Estimate {
        err: crate::verify::grid::area_grid_error(
            fine.area,
            coarse.as_ref().map(area),
            quarter.as_ref().map(area),
            surface.len(),
        )
        .max(fine.area_tol),
        ..top(area, fine.area_tol)
    };
    let mean_contact_pressure = top(|s| s.mean_pressure, 0.0);
    let sigma_rms_top = top(|s| s.sigma_top, 0.0);
    let depths = stack.depths();
    let mut coarse_interfaces = coarse.as_ref().map(|c| c.interfaces.iter());
    let mut quarter_interfaces = quarter.as_ref().map(|c| c.interfaces.iter());
    let interfaces: Vec<InterfaceExact> = fine
        .interfaces
        .into_iter()
        .enumerate()
        .map(|(k, f)| {
            let c = coarse_interfaces.as_mut().and_then(Iterator::next);
            let q = quarter_interfaces.as_mut().and_then(Iterator::next);
            interface(design, k, depths[k], f, (c, q))
        })
        .collect();
    let checks = judge(design, &interfaces, mean_contact_pressure);
    let pass = checks.iter().all(|c| c.check.pass);
    Ok(StackVerification {
        nx: surface.nx,
        ny: surface.ny,
        q_low_z: surface.q_low() * depths.last().copied().unwrap_or(0.0),
        area_fraction,
        mean_contact_pressure,
        sigma_rms_top,
        interfaces,
        checks,
        pass,
        convergence: fine.convergence,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// One interface of the Persson-vs-exact comparison.
#[derive(Debug, Clone)]
pub struct InterfaceComparison {
    /// Depth z_k (m).
    pub depth: f64,
    /// Fraction of the interface where |τ| exceeds the bond strength, when one is given.
    pub above_bond: Option<f64>,
    pub rows: Vec<Row>,
}

/// The exact contact on a height map beside Persson's theory on the stack from the map's own
/// spectrum.
#[derive(Debug, Clone)]
pub struct StackComparison {
    pub surface: Surface,
    pub solution: BemSolution,
    /// The fields at every interface, top first.
    pub fields: Vec<InterfaceFields>,
    pub persson: StackContact,
    /// The top surface's quantities.
    pub rows: Vec<Row>,
    /// Every interface's, top first.
    pub interfaces: Vec<InterfaceComparison>,
    /// Wall time of the exact solve and its interface fields (s).
    pub seconds: f64,
}

/// Persson's theory on the stack on the map's own spectrum (as [`crate::verify::persson`]).
pub fn persson(
    map: &HeightMap,
    stack: &Stack,
    p0: f64,
    settings: Settings,
) -> Result<StackContact, Error> {
    Engine::new(&map_spectrum(map)?, settings).evaluate_stack(stack, p0, Request::all())
}

/// Solve the contact on `map` (one period of a periodic surface) at nominal pressure `p0` and
/// compare it with Persson's theory on the stack; `bond` is the shear strength every interface
/// is measured against.
pub fn compare(
    map: &HeightMap,
    stack: &Stack,
    p0: f64,
    bem: &BemSettings,
    settings: Settings,
    bond: Option<f64>,
) -> Result<StackComparison, Error> {
    let surface = Surface::from_height_map(map)?;
    let started = std::time::Instant::now();
    let (solution, fields) = solve(&surface, stack, p0, bem)?;
    let seconds = started.elapsed().as_secs_f64();
    let theory = persson(map, stack, p0, settings)?;
    let rows = top_rows(&solution, &theory);
    let interfaces = fields
        .iter()
        .zip(&theory.interfaces)
        .map(|(f, ic)| {
            let above_bond = bond.map(|b| f.shear_fraction_above(b));
            InterfaceComparison {
                depth: ic.depth,
                above_bond,
                rows: interface_rows(f, ic.sigma_rms, ic.tau_rms, bond, above_bond),
            }
        })
        .collect();
    Ok(StackComparison {
        surface,
        solution,
        fields,
        persson: theory,
        rows,
        interfaces,
        seconds,
    })
}

/// The top surface's compared quantities.
fn top_rows(sol: &BemSolution, theory: &StackContact) -> Vec<Row> {
    let area = theory.top.area_fraction;
    let mut rows = vec![
        Row::new("A/A0", "", Some(area), sol.area_fraction.value),
        Row::new(
            "sigma_rms top",
            "Pa",
            theory.top.sigma_rms_top,
            sol.sigma_rms_top,
        ),
        Row::new(
            "contact pressure mean",
            "Pa",
            Some(area.map(|a| sol.p0 / a, |a| sol.p0 / (a * a))),
            sol.contact_pressure.mean,
        ),
    ];
    exact_only(&mut rows, "contact pressure", &sol.contact_pressure);
    rows
}

/// One interface's compared quantities: Persson's rms values beside the field's, the field's
/// quantiles of σ_n, and the |τ| rows of the film's comparison (`verify::shear_rows`).
fn interface_rows(
    fields: &InterfaceFields,
    sigma_rms: Option<Estimate>,
    tau_rms: Option<Estimate>,
    bond: Option<f64>,
    above: Option<f64>,
) -> Vec<Row> {
    let mut rows = vec![
        Row::new(
            "sigma_rms interface",
            "Pa",
            sigma_rms,
            fields.normal_stats.rms_dev,
        ),
        Row::new("tau_rms interface", "Pa", tau_rms, fields.shear_stats.rms),
    ];
    exact_only(&mut rows, "interface sigma_n", &fields.normal_stats);
    shear_rows(&mut rows, fields, tau_rms, bond, above);
    rows
}
