//! The exact contact under sliding friction (not in the paper, which treats static contact;
//! notes.md, "Sliding friction"): the friction traction μ·p(x) along x is applied to the solved
//! pressure field p of the frictionless contact (uncoupled approximation: the friction does not
//! change the contact, [`crate::contact::friction_coupling`] says how large the neglected term
//! is), and its interface stresses ([`crate::bem::sliding::friction_fields`], kernels g_t, f_t,
//! h) are added to the static ones (f, g of eq. B7).
//!
//! The interface shear is then a vector field τ = (τ_x, τ_y) whose mean is (μ·p0, 0) (the q = 0
//! mode of the friction passes the film unchanged) and whose fluctuations have their own rms
//! along x and y; the normal stress gains a friction-driven part of mean zero. Persson's
//! counterparts are [`crate::contact::SlidingShear`] and the vector tail of [`crate::tail`]:
//! [`compare_sliding`] sets them side by side for `coatcheck verify --friction`, and
//! [`SlidingVerification`] carries the exact numbers (with the half-resolution error estimate of
//! [`super::verify`]) into `check --verify`.

use super::{CheckRow, Comparison, Row, area_fraction_error, comparison_rows, map_spectrum, solve};
use crate::bem::free;
use crate::bem::sliding::{FrictionFields, friction_fields_with};
use crate::bem::{BemSettings, BemSolution, Boundary, FieldStats, InterfaceFields, Surface};
use crate::check::Evaluation;
use crate::contact::{Contact, Engine, Request, SlidingShear, friction_coupling};
use crate::error::Error;
use crate::layer::Stack;
use crate::prec::{EPS, Estimate, Settings, Termination};
use crate::tail::ShearVector;
use crate::topography::HeightMap;
use rayon::prelude::*;
use serde::Serialize;

/// The |τ| quantiles reported under sliding beside Persson's vector rule.
pub const SLIDING_QUANTILES: [f64; 3] = [0.5, 0.99, 0.999];

/// The interface shear vector field of one solve under sliding, summarised.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExactSliding {
    /// The friction coefficient μ.
    pub friction: f64,
    /// Mean of τ_x and of τ_y over the interface (Pa); (μ·p0, 0) up to rounding.
    pub mean: [f64; 2],
    /// Rms deviation of τ_x and of τ_y about their means (Pa).
    pub tau_x_rms: f64,
    pub tau_y_rms: f64,
    /// Rms deviation of the interface normal stress, friction-driven part included (Pa).
    pub sigma_rms_interface: f64,
    /// Rms of |τ| of the static (pressure-driven) shear alone (Pa): Persson's τ_rms (eq. B9).
    pub static_tau_rms: f64,
}

impl ExactSliding {
    /// The sliding summary of the total fields `total` (`static_tau_rms` from the static ones).
    fn of(friction: f64, total: &InterfaceFields, static_tau_rms: f64) -> Self {
        let x = FieldStats::of(&total.shear_x);
        let y = FieldStats::of(&total.shear_y);
        Self {
            friction,
            mean: [x.mean, y.mean],
            tau_x_rms: x.rms_dev,
            tau_y_rms: y.rms_dev,
            sigma_rms_interface: total.normal_stats.rms_dev,
            static_tau_rms,
        }
    }
}

/// The interface fields under the friction traction μ·p along x: the static fields plus the
/// friction-driven ones, with their statistics, and the sliding summary. `None` for μ = 0 (the
/// static fields are then the answer).
pub fn with_friction(
    solution: &BemSolution,
    stack: &Stack,
    fields: &InterfaceFields,
    mu: f64,
) -> Result<Option<(InterfaceFields, ExactSliding)>, Error> {
    if mu == 0.0 {
        return Ok(None);
    }
    let (layers, d) = (stack.layers, stack.thickness);
    let kernels = |q: f64| {
        let t = layers.tangential(q * d);
        [t.g_t, t.f_t, t.h]
    };
    with_friction_kernels(solution, fields, mu, kernels).map(Some)
}

/// [`with_friction`] at an interface whose tangential kernels at wavenumber q > 0 (1/m) are
/// `kernels(q) = [g_t, f_t, h]` ([`friction_fields_with`]), with the static fields `fields` of
/// the same interface, for any μ ≥ 0.
pub fn with_friction_kernels<K>(
    solution: &BemSolution,
    fields: &InterfaceFields,
    mu: f64,
    kernels: K,
) -> Result<(InterfaceFields, ExactSliding), Error>
where
    K: Fn(f64) -> [f64; 3] + Sync,
{
    let f = match solution.boundary {
        Boundary::Periodic => friction_fields_with(
            &solution.pressure,
            (solution.nx, solution.ny),
            (solution.dx, solution.dy),
            mu,
            kernels,
        )?,
        // The zero-padded pressure on the doubled grid, as the static fields (`bem::free`).
        Boundary::Free => {
            let nx = solution.nx;
            let f = friction_fields_with(
                &free::padded(&solution.pressure, nx),
                (2 * nx, 2 * solution.ny),
                (solution.dx, solution.dy),
                mu,
                kernels,
            )?;
            FrictionFields {
                shear_x: free::cropped(&f.shear_x, nx),
                shear_y: free::cropped(&f.shear_y, nx),
                normal: free::cropped(&f.normal, nx),
            }
        }
    };
    let add =
        |a: &[f64], b: &[f64]| -> Vec<f64> { a.par_iter().zip(b).map(|(a, b)| a + b).collect() };
    let normal = add(&fields.normal, &f.normal);
    let shear_x = add(&fields.shear_x, &f.shear_x);
    let shear_y = add(&fields.shear_y, &f.shear_y);
    let magnitude: Vec<f64> = shear_x
        .par_iter()
        .zip(&shear_y)
        .map(|(x, y)| x.hypot(*y))
        .collect();
    let total = InterfaceFields {
        normal_stats: FieldStats::of(&normal),
        shear_stats: FieldStats::of(&magnitude),
        normal,
        shear_x,
        shear_y,
    };
    let summary = ExactSliding::of(mu, &total, fields.shear_stats.rms);
    Ok((total, summary))
}

/// The exact sliding numbers of `check --verify`, each with the half-resolution error estimate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SlidingVerification {
    pub friction: f64,
    /// Mean τ_x and τ_y (Pa).
    pub mean_x: Estimate,
    pub mean_y: Estimate,
    /// Rms deviation of τ_x and τ_y (Pa).
    pub tau_x_rms: Estimate,
    pub tau_y_rms: Estimate,
    /// |τ| at [`SLIDING_QUANTILES`], then its maximum (Pa).
    pub quantiles: [Estimate; 3],
    pub max: Estimate,
}

impl SlidingVerification {
    /// From the full-resolution solve (`fine`, with its |τ| statistics) and, when made, the
    /// half-resolution one: the error is their difference, as in [`super::verify`].
    pub(crate) fn of(
        fine: (&ExactSliding, &FieldStats),
        coarse: Option<(&ExactSliding, &FieldStats)>,
    ) -> Self {
        let est = |get: &dyn Fn(&ExactSliding, &FieldStats) -> f64| {
            let v = get(fine.0, fine.1);
            Estimate {
                value: v,
                err: coarse.map_or(f64::NAN, |(s, t)| (v - get(s, t)).abs()),
                status: Termination::Converged,
            }
        };
        let q = |p: f64| move |_: &ExactSliding, t: &FieldStats| t.quantile(p).unwrap_or(f64::NAN);
        Self {
            friction: fine.0.friction,
            mean_x: est(&|s, _| s.mean[0]),
            mean_y: est(&|s, _| s.mean[1]),
            tau_x_rms: est(&|s, _| s.tau_x_rms),
            tau_y_rms: est(&|s, _| s.tau_y_rms),
            quantiles: SLIDING_QUANTILES.map(|p| est(&q(p))),
            max: est(&|_, t| t.max),
        }
    }
}

/// Persson's |τ| quantile at probability `prob` (0 < prob < 1) for the shear vector of `s`: the
/// vector's peak at ε = 1 − prob ([`ShearVector::peak`]) above the median, the root of
/// P(|τ| > t) = 1 − prob by bisection at and below it. The rms errors enter as in the check's
/// peak: their largest relative error times the level (it is homogeneous of degree 1 and
/// increasing in both rms).
pub fn vector_quantile(s: &SlidingShear, prob: f64) -> Result<Estimate, Error> {
    let v = ShearVector::new(s.mean.value, s.tau_x_rms.value, s.tau_y_rms.value)?;
    let eps = 1.0 - prob;
    let mut q = if eps < 0.5 {
        v.peak(eps)?
    } else {
        let (mut lo, mut hi) = (0.0, v.peak(0.25)?.value);
        while hi - lo > 4.0 * EPS * hi {
            let mid = 0.5 * (lo + hi);
            if v.exceedance(mid).value > eps {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Estimate::new(0.5 * (lo + hi), 4.0 * EPS * hi, Termination::Converged)
    };
    let rel = s.tau_x_rms.rel_err().max(s.tau_y_rms.rel_err());
    q.err += rel * q.value;
    Ok(q)
}

/// `coatcheck verify --friction μ`: the exact contact on a height map with the friction traction
/// applied, beside Persson's sliding estimate from the map's spectrum.
#[derive(Debug, Clone)]
pub struct SlidingComparison {
    /// The comparison with the total (static + friction) interface fields and Persson's sliding
    /// contact (σ_rms(d) with the friction-driven part); its rows are the sliding rows.
    pub comparison: Comparison,
    pub exact: ExactSliding,
    /// Persson's shear vector, with the coupling over the map's wavenumbers.
    pub persson: SlidingShear,
}

/// Solve the contact on `map` at `p0`, apply the friction μ > 0 and compare with Persson's
/// sliding estimate (contact integrals to `settings`; bond strength optional).
pub fn compare_sliding(
    map: &HeightMap,
    stack: &Stack,
    (p0, mu): (f64, f64),
    bem: &BemSettings,
    settings: Settings,
    bond: Option<f64>,
) -> Result<SlidingComparison, Error> {
    let surface = Surface::from_height_map(map)?;
    let started = std::time::Instant::now();
    let (solution, fields) = solve(&surface, stack, p0, bem)?;
    let Some((total, exact)) = with_friction(&solution, stack, &fields, mu)? else {
        return Err(Error::invalid(
            "friction coefficient",
            mu,
            "a value > 0 (without friction use compare)",
        ));
    };
    let seconds = started.elapsed().as_secs_f64();
    let engine = Engine::new(&map_spectrum(map)?, settings);
    let (theory, shear) = engine.evaluate_sliding(stack, p0, mu, Request::all())?;
    let mut persson = shear.ok_or_else(|| Error::Numerical {
        what: "Persson's sliding estimate",
        detail: "no interface shear was computed".into(),
    })?;
    persson.coupling = Some(friction_coupling(
        stack,
        mu,
        (surface.q_low(), surface_q_high(&surface)),
    ));
    let above_bond = bond.map(|b| total.shear_fraction_above(b));
    let rows = sliding_rows(
        (&solution, &fields, &total),
        (&theory, &persson),
        &exact,
        bond.zip(above_bond),
    )?;
    let (area_fraction, area_fraction_half, area_fraction_quarter) =
        area_fraction_error(&surface, stack, p0, bem, solution.area_fraction)?;
    Ok(SlidingComparison {
        comparison: Comparison {
            area_fraction,
            area_fraction_half,
            area_fraction_quarter,
            surface,
            solution,
            fields: total,
            persson: theory,
            above_bond,
            rows,
            seconds,
        },
        exact,
        persson,
    })
}

/// The largest wavenumber of the map's spectrum: the Nyquist limit of its finer axis.
fn surface_q_high(s: &Surface) -> f64 {
    std::f64::consts::PI / s.dx.min(s.dy)
}

/// The rows of `verify --friction`: the static rows of A/A0, the top and contact pressures and
/// σ_rms(d) (friction part included on both sides), then the shear vector: the static τ_rms,
/// the mean and the rms of each component, |τ| quantiles against the vector rule, its maximum,
/// and the bond exceedance.
fn sliding_rows(
    (sol, fields, total): (&BemSolution, &InterfaceFields, &InterfaceFields),
    (theory, shear): (&Contact, &SlidingShear),
    exact: &ExactSliding,
    bond: Option<(f64, f64)>,
) -> Result<Vec<Row>, Error> {
    let mut rows = comparison_rows(sol, total, theory, None, None);
    rows.retain(|r| !r.name.contains("tau"));
    vector_rows(
        &mut rows,
        (theory.tau_rms_interface, fields.shear_stats.rms),
        (total, exact),
        shear,
        bond,
    )?;
    Ok(rows)
}

/// The shear vector's rows of one interface under sliding, appended to `rows`: the static τ_rms
/// (Persson's, the exact field's), the mean and the rms of each component, the |τ| quantiles
/// of the total fields `total` against the vector rule, their maximum, and the bond exceedance
/// (`bond`: the strength and the exact fraction above it).
pub(crate) fn vector_rows(
    rows: &mut Vec<Row>,
    (static_persson, static_exact): (Option<Estimate>, f64),
    (total, exact): (&InterfaceFields, &ExactSliding),
    shear: &SlidingShear,
    bond: Option<(f64, f64)>,
) -> Result<(), Error> {
    rows.push(Row::new(
        "tau_rms interface (pressure-driven)",
        "Pa",
        static_persson,
        static_exact,
    ));
    rows.push(Row::new(
        "mean tau_x interface",
        "Pa",
        Some(shear.mean),
        exact.mean[0],
    ));
    rows.push(Row::new(
        "mean tau_y interface",
        "Pa",
        Some(Estimate::exact(0.0)),
        exact.mean[1],
    ));
    rows.push(Row::new(
        "tau_x rms interface",
        "Pa",
        Some(shear.tau_x_rms),
        exact.tau_x_rms,
    ));
    rows.push(Row::new(
        "tau_y rms interface",
        "Pa",
        Some(shear.tau_y_rms),
        exact.tau_y_rms,
    ));
    for q in &total.shear_stats.quantiles {
        rows.push(Row::new(
            format!("interface |tau| q{}", q.prob),
            "Pa",
            Some(vector_quantile(shear, q.prob)?),
            q.value,
        ));
    }
    rows.push(Row::new(
        "interface |tau| max",
        "Pa",
        None,
        total.shear_stats.max,
    ));
    if let Some((b, f)) = bond {
        let v = ShearVector::new(
            shear.mean.value,
            shear.tau_x_rms.value,
            shear.tau_y_rms.value,
        )?;
        rows.push(Row::new(
            "area fraction |tau| > bond",
            "",
            Some(v.exceedance(b)),
            f,
        ));
    }
    Ok(())
}

/// The sliding rows of `check --verify`: the shear vector's mean and rms and the |τ| quantiles
/// and maximum, beside Persson's (the vector rule's quantiles, from the evaluation's shear).
pub(super) fn check_rows(ev: &Evaluation, s: &SlidingVerification) -> Vec<CheckRow> {
    let shear = ev.sliding.as_ref();
    let row = |name, key, persson, exact| CheckRow {
        name,
        key,
        persson,
        exact,
    };
    let quantile = |p: f64| shear.and_then(|sh| vector_quantile(sh, p).ok());
    let [q50, q99, q999] = s.quantiles;
    vec![
        row(
            "mean tau_x interface",
            "mean_interface_shear_pa",
            shear.map(|sh| sh.mean),
            s.mean_x,
        ),
        row(
            "mean tau_y interface",
            "mean_interface_shear_y_pa",
            shear.map(|_| Estimate::exact(0.0)),
            s.mean_y,
        ),
        row(
            "tau_x rms interface",
            "tau_x_rms_interface_pa",
            shear.map(|sh| sh.tau_x_rms),
            s.tau_x_rms,
        ),
        row(
            "tau_y rms interface",
            "tau_y_rms_interface_pa",
            shear.map(|sh| sh.tau_y_rms),
            s.tau_y_rms,
        ),
        row("|tau| q0.5", "tau_abs_q50_pa", quantile(0.5), q50),
        row("|tau| q0.99", "tau_abs_q99_pa", quantile(0.99), q99),
        row("|tau| q0.999", "tau_abs_q999_pa", quantile(0.999), q999),
        row("|tau| max", "tau_abs_max_pa", None, s.max),
    ]
}
