//! Output of `coatcheck verify` (the side-by-side table of Persson's estimate and the exact
//! contact, its JSON object, the fields as CSV) and of the exact section of `check --verify`
//! (tables in MPa with 4 significant digits like the check's report, JSON, CSV rows).

use super::{margin_cell, modulus, mpa, sig, table, um, utilisation_cell, wrap};
use crate::bem::{BemSolution, Convergence, FieldStats, InterfaceFields, Surface};
use crate::check::{CheckKind, MinThickness, Outcome};
use crate::contact::SlidingShear;
use crate::error::Error;
use crate::exact::min_thickness::ExactMinThickness;
use crate::layer::Stack;
use crate::pipeline::Exact;
use crate::prec::Estimate;
use crate::verify::boundary::BoundaryDecision;
use crate::verify::sliding::ExactSliding;
use crate::verify::{Comparison, ExactCheck, check_rows};
use serde_json::{Map, Value, json};
use std::io::Write;
use std::path::Path;

/// What `coatcheck verify` was asked: the map file, the layered solid and the load.
pub struct VerifyInputs<'a> {
    pub map: &'a Path,
    pub stack: &'a Stack,
    pub p0: f64,
    pub bond: Option<f64>,
    /// The boundary of the solve.
    pub boundary: BoundaryDecision,
}

pub(super) fn stats_json(s: &FieldStats) -> Value {
    json!({
        "mean": s.mean,
        "rms": s.rms,
        "rms_dev": s.rms_dev,
        "max": s.max,
        "quantiles": s.quantiles.iter().map(|q| json!({"p": q.prob, "value": q.value})).collect::<Vec<_>>(),
    })
}

/// `coatcheck verify`'s tables: the scene, then Persson beside the exact contact.
pub fn verify_table(i: &VerifyInputs, c: &Comparison) -> String {
    let (s, sol, stack, p0) = (&c.surface, &c.solution, i.stack, i.p0);
    let (xi, seconds, rows) = (s.rms_slope(), c.seconds, &c.rows);
    let (area_fraction, area_half) = (c.area_fraction, c.area_fraction_half);
    let area_quarter = c
        .area_fraction_quarter
        .map(|q| format!(", a quarter {}", sig(q, 4)))
        .unwrap_or_default();
    let mut scene = table(&["scene", "value"]);
    let l = stack.layers;
    scene.add_row(vec![
        "height map".into(),
        format!(
            "{} ({} x {}, pixel {} x {} µm)",
            i.map.display(),
            s.nx,
            s.ny,
            um(s.dx),
            um(s.dy)
        ),
    ]);
    scene.add_row(vec![
        "h_rms, rms slope".into(),
        format!("{} µm, {}", um(sol.h_rms), sig(xi, 4)),
    ]);
    scene.add_row(vec![
        "film".into(),
        format!("E = {}, nu = {}", modulus(l.film.youngs), l.film.poisson),
    ]);
    scene.add_row(vec![
        "substrate".into(),
        format!(
            "E = {}, nu = {}",
            modulus(l.substrate.youngs),
            l.substrate.poisson
        ),
    ]);
    scene.add_row(vec![
        "thickness d, q_L d".into(),
        format!(
            "{} µm, {}",
            um(stack.thickness),
            sig(s.q_low() * stack.thickness, 4)
        ),
    ]);
    scene.add_row(vec!["pressure p0".into(), format!("{} MPa", mpa(p0))]);
    scene.add_row(vec!["boundary".into(), i.boundary.describe()]);
    let c = &sol.convergence;
    scene.add_row(vec![
        "solver".into(),
        format!(
            "{:?} after {} iterations in {seconds:.2} s (rms gap in contact {:.2e} µm, \
             penetration {:.2e} µm, tolerance {:.2e} µm)",
            c.status,
            c.iterations,
            c.gap_rms_in_contact * 1e6,
            c.max_penetration * 1e6,
            c.tolerance * 1e6
        ),
    ]);
    let mut t = table(&[
        "quantity",
        "unit",
        "Persson",
        "Persson err",
        "exact (BEM)",
        "exact/Persson",
    ]);
    // Stresses in MPa like every table; the rest as they are.
    let scale = |unit: &str| if unit == "Pa" { 1e-6 } else { 1.0 };
    for r in rows {
        let k = scale(r.unit);
        t.add_row(vec![
            r.name.clone(),
            if r.unit == "Pa" { "MPa" } else { r.unit }.to_string(),
            r.persson.map_or("-".into(), |p| sig(p.value * k, 4)),
            r.persson.map_or("-".into(), |p| sig(p.err * k, 2)),
            sig(r.exact * k, 4),
            r.ratio().map_or("-".into(), |v| sig(v, 3)),
        ]);
    }
    let area = match area_half {
        Some(h) => format!(
            "A/A0 counts pixels in contact: {} ± {} (the solver tolerance's ±{:.1e} plus the \
             grid error from the same map at half resolution, A/A0 = {}{area_quarter})",
            sig(area_fraction.value, 4),
            sig(area_fraction.err, 2),
            sol.area_fraction.err,
            sig(h, 4)
        ),
        None => format!(
            "A/A0 counts pixels in contact (±{:.1e} from the solver tolerance; the map is too \
             small to halve: refine it to see the discretisation error)",
            sol.area_fraction.err
        ),
    };
    format!(
        "{scene}\n{t}\n{}\n",
        wrap(&format!(
            "{area}. Quantiles: contact pressure over the contact area, interface stresses over \
             the whole interface."
        ))
    )
}

/// The note under `verify --friction`'s tables: the uncoupled approximation and the vector rule.
pub fn sliding_note(e: &ExactSliding, p: &SlidingShear) -> String {
    let mut out = wrap(&format!(
        "sliding friction mu = {}: the traction mu p(x) along x is applied to the solved \
         frictionless pressure (uncoupled approximation: the friction does not change the \
         contact; max mu |c|/S over the map's wavenumbers = {}). The interface fields, sigma_rms \
         interface and |tau| include the friction-driven part; Persson's |tau| quantiles are \
         those of the vector (mu p0 + X, Y), X and Y independent Gaussians with the tau_x and \
         tau_y rms.",
        e.friction,
        p.coupling.map_or("-".into(), |c| sig(c, 3))
    ));
    out.push('\n');
    out
}

/// `verify --friction`'s `sliding` object: the friction, the coupling the approximation
/// neglects, and the shear vector's mean and rms, exact beside Persson's (Pa).
pub fn sliding_json(e: &ExactSliding, p: &SlidingShear) -> Value {
    json!({
        "friction": e.friction,
        "approximation": "uncoupled",
        "friction_coupling": p.coupling,
        "mean_interface_shear_pa": e.mean,
        "persson_mean_interface_shear_pa": p.mean.value,
        "tau_x_rms_interface_pa": e.tau_x_rms,
        "persson_tau_x_rms_interface_pa": p.tau_x_rms.value,
        "persson_tau_x_rms_interface_pa_err": p.tau_x_rms.err,
        "tau_y_rms_interface_pa": e.tau_y_rms,
        "persson_tau_y_rms_interface_pa": p.tau_y_rms.value,
        "persson_tau_y_rms_interface_pa_err": p.tau_y_rms.err,
        "sigma_rms_interface_pa": e.sigma_rms_interface,
        "tau_rms_static_pa": e.static_tau_rms,
    })
}

/// The boundary-element solver's convergence (lengths in m), as `verify` and `check --verify`
/// write it.
pub(super) fn solver_json(c: &Convergence, seconds: f64) -> Value {
    json!({
        "iterations": c.iterations,
        "restarts": c.restarts,
        "gap_rms_in_contact_m": c.gap_rms_in_contact,
        "max_penetration_m": c.max_penetration,
        "tolerance_m": c.tolerance,
        "load_error": c.load_error,
        "status": c.status,
        "seconds": seconds,
    })
}

/// `coatcheck verify`'s JSON object.
pub fn verify_json(i: &VerifyInputs, c: &Comparison) -> Value {
    let (surface, sol, fields, theory) = (&c.surface, &c.solution, &c.fields, &c.persson);
    let (d, p0, bond, above, rows) = (i.stack.thickness, i.p0, i.bond, c.above_bond, &c.rows);
    let (xi, seconds) = (surface.rms_slope(), c.seconds);
    json!({
        "schema_version": super::SCHEMA_VERSION,
        "coatcheck_version": env!("CARGO_PKG_VERSION"),
        "map": i.map.display().to_string(),
        "nx": surface.nx, "ny": surface.ny, "dx_m": surface.dx, "dy_m": surface.dy,
        "h_rms_m": sol.h_rms, "rms_slope": xi, "q_low_per_m": surface.q_low(),
        "q_low_d": surface.q_low() * d,
        "thickness_m": d, "pressure_pa": p0,
        "solver": solver_json(&sol.convergence, seconds),
        "boundary": i.boundary.json(),
        "area_fraction": sol.area_fraction.value,
        "area_fraction_err": c.area_fraction.err,
        "area_fraction_half_resolution": c.area_fraction_half,
        "area_fraction_quarter_resolution": c.area_fraction_quarter,
        "persson_area_fraction": theory.area_fraction.value,
        "persson_area_fraction_err": theory.area_fraction.err,
        "sigma_rms_top_pa": sol.sigma_rms_top,
        "contact_pressure_pa": stats_json(&sol.contact_pressure),
        "interface_normal_pa": stats_json(&fields.normal_stats),
        "interface_shear_abs_pa": stats_json(&fields.shear_stats),
        "bond_strength_pa": bond,
        "shear_fraction_above_bond": above,
        "comparison": rows.iter().map(|r| json!({
            "quantity": r.name, "unit": r.unit,
            "persson": r.persson.map(|p| p.value),
            "persson_err": r.persson.map(|p| p.err),
            "exact": r.exact, "ratio": r.ratio(),
        })).collect::<Vec<_>>(),
    })
}

/// The fields of a solve as CSV: x, y, height, pressure, gap, interface σ_n, τ_x, τ_y, |τ|.
pub fn write_fields(
    path: &Path,
    s: &Surface,
    sol: &BemSolution,
    f: &InterfaceFields,
) -> Result<(), Error> {
    fields_csv(path, s, sol, std::slice::from_ref(f), |_| {
        ",sigma_n_interface_pa,tau_x_pa,tau_y_pa,tau_abs_pa".into()
    })
}

/// The fields of a solve as CSV (a film's or a stack's): x, y, height, pressure, gap, then σ_n,
/// τ_x, τ_y, |τ| at every interface of `fields`, whose header columns are `columns(k)` for
/// the k-th (from 1).
pub(super) fn fields_csv(
    path: &Path,
    s: &Surface,
    sol: &BemSolution,
    fields: &[InterfaceFields],
    columns: impl Fn(usize) -> String,
) -> Result<(), Error> {
    super::write_with(path, |w: &mut dyn Write| {
        write!(w, "x_m,y_m,height_m,pressure_pa,gap_m")?;
        for k in 1..=fields.len() {
            write!(w, "{}", columns(k))?;
        }
        writeln!(w)?;
        for iy in 0..s.ny {
            for ix in 0..s.nx {
                let i = iy * s.nx + ix;
                write!(
                    w,
                    "{:e},{:e},{:e},{:e},{:e}",
                    ix as f64 * s.dx,
                    iy as f64 * s.dy,
                    s.heights[i],
                    sol.pressure[i],
                    sol.gap[i]
                )?;
                for f in fields {
                    write!(
                        w,
                        ",{:e},{:e},{:e},{:e}",
                        f.normal[i],
                        f.shear_x[i],
                        f.shear_y[i],
                        f.shear_magnitude(i)
                    )?;
                }
                writeln!(w)?;
            }
        }
        Ok(())
    })
}

/// A value of the `check --verify` section (a film's or a stack's) in human units: stresses
/// (keys ending in `_pa`) in MPa, thicknesses (`_m`) in µm, the rest as they are, 4 significant
/// digits.
pub(super) fn show(key: &str, x: f64) -> String {
    if key.ends_with("_pa") {
        format!("{} MPa", sig(x * 1e-6, 4))
    } else if key.ends_with("_m") {
        format!("{} µm", um(x))
    } else {
        sig(x, 4)
    }
}

/// The report key's unit suffix of an exact check's value and limit.
fn check_key(kind: CheckKind) -> &'static str {
    if kind == CheckKind::MinThickness {
        "_m"
    } else {
        "_pa"
    }
}

/// The heading of the `check --verify` section: the map, or the realisations and their grid.
fn heading(x: &Exact) -> String {
    let v = &x.verification;
    let solves = x
        .min_thickness
        .as_ref()
        .map(|m| format!(", {} more for the minimum thickness", m.solves))
        .unwrap_or_default();
    let boundary = x.boundary.describe();
    match &x.realisations {
        None => format!(
            "exact check on the height map {} ({} x {} pixels, q_L d = {}; boundary elements, {} \
             iterations{solves}; boundary {boundary}; error = grid error from the same map at \
             half and a quarter of the resolution)",
            x.map.display(),
            v.nx,
            v.ny,
            sig(v.q_low_d, 3),
            v.convergence.iterations
        ),
        Some(r) => format!(
            "exact check on {} random-phase realisations of the scene's spectrum ({}; seeds {}..{}; {} x \
             {} pixels of {} µm, q_L d = {}, modes up to {} 1/m; boundary elements{solves}; \
             boundary {boundary}): \
             each exact number is the mean over the realisations, spread = standard error of \
             that mean, error = mean grid error from the same surfaces at half and a quarter \
             of the resolution; the grid leaves out {} of the slope variance",
            r.count,
            x.map.display(),
            r.seeds[0],
            r.seeds[r.seeds.len() - 1],
            v.nx,
            v.ny,
            um(r.grid.dx),
            sig(v.q_low_d, 3),
            sig(r.grid.q_nyquist, 4),
            sig(r.grid.unresolved_slope_share, 3)
        ),
    }
}

/// The `check --verify` section as tables (MPa, µm, 4 significant digits, like the check's
/// report): Persson beside the exact numbers, the exact checks, both minimum thicknesses and
/// the exact verdict.
pub fn check_table(x: &Exact, outcome: &Outcome) -> String {
    let (v, ev) = (&x.verification, &outcome.evaluation);
    let spread = x.realisations.as_ref();
    let mut out = wrap(&heading(x));
    out.push('\n');
    let mut head = vec!["quantity", "Persson", "exact (BEM)", "error estimate"];
    if spread.is_some() {
        head.push("spread");
    }
    head.push("exact/Persson");
    let mut t = table(&head);
    for r in check_rows(ev, v) {
        let s = spread.map(|s| s.spread_of(r.key));
        t.add_row(row_cells(None, r.name, r.key, r.persson, r.exact, s));
    }
    out += &format!("{t}\n");
    let mut c = table(&[
        "check (exact)",
        "value",
        "limit",
        "utilisation",
        "margin",
        "result",
    ]);
    for ch in &v.checks {
        let mut result = if ch.pass { "PASS" } else { "FAIL" }.to_string();
        if !ch.resolved {
            result += " (map maximum: epsilon < 1/pixels)";
        }
        let key = check_key(ch.kind);
        let limit = match ch.kind {
            CheckKind::MinThickness if ch.limit.is_infinite() => "none passes".into(),
            CheckKind::MinThickness => format!(">= {}", show(key, ch.limit)),
            _ => format!("<= {}", show(key, ch.limit)),
        };
        c.add_row(vec![
            ch.kind.name().to_string(),
            show(key, ch.value.value),
            limit,
            utilisation_cell(Some(ch.margin)),
            margin_cell(Some(ch.margin)),
            result,
        ]);
    }
    out += &format!("{c}\n");
    if let Some(s) = &v.sliding {
        out += &wrap(&format!(
            "sliding friction mu = {}: the exact fields add the traction mu p(x) along x on the \
             solved frictionless pressure (uncoupled approximation); the exact levels, sigma_rms \
             interface and P(|tau| > bond strength) are of the total fields, tau_rms interface is \
             the pressure-driven shear's; Persson's |tau| quantiles are the vector rule's.",
            s.friction
        ));
        out.push('\n');
    }
    if let Some(m) = &x.min_thickness {
        out += &wrap(&min_thickness_line(
            "minimum thickness",
            outcome.min_thickness.as_ref(),
            m,
            spread.map(|r| r.min_thickness_spread),
        ));
        out.push('\n');
    }
    out += &wrap(&format!(
        "exact verdict: {}; with --verify the design passes only if both Persson's checks and \
         the exact ones (the exact minimum thickness included) pass",
        if v.pass { "PASS" } else { "FAIL" }
    ));
    out.push('\n');
    out
}

/// One row of a `check --verify` table (a film's or a stack's): the place `at` (a stack's),
/// the quantity, Persson's value, the exact one and its error, the spread over the realisations
/// (`spread`, `Some` when there are realisations) and exact/Persson.
pub(super) fn row_cells(
    at: Option<&str>,
    name: &str,
    key: &str,
    p: Option<Estimate>,
    e: Estimate,
    spread: Option<Option<f64>>,
) -> Vec<String> {
    let ratio = p
        .filter(|p| p.value != 0.0)
        .map_or("-".into(), |p| sig(e.value / p.value, 3));
    let mut row: Vec<String> = at.map(str::to_string).into_iter().collect();
    row.extend([
        name.to_string(),
        p.map_or("-".into(), |p| show(key, p.value)),
        show(key, e.value),
        show(key, e.err),
    ]);
    if let Some(s) = spread {
        row.push(s.map_or("-".into(), |s| show(key, s)));
    }
    row.push(ratio);
    row
}

/// One quantity of the `check --verify` JSON (a film's or a stack's): the exact value as `key`,
/// its error as `key_err` and Persson's as `persson_key`.
pub(super) fn put_row(m: &mut Map<String, Value>, key: &str, p: Option<Estimate>, e: Estimate) {
    m.insert(key.into(), json!(e.value));
    m.insert(format!("{key}_err"), json!(e.err));
    m.insert(format!("persson_{key}"), json!(p.map(|p| p.value)));
}

/// One quantity of an `exact` object (a film's or a stack's): the exact value as `key`, its
/// error as `key_err`, its spread over the realisations as `key_spread` (null on a map) and its
/// ratio to Persson's as `key_ratio`.
pub(super) fn put_exact_row(
    m: &mut Map<String, Value>,
    key: &str,
    p: Option<Estimate>,
    e: Estimate,
    spread: Option<f64>,
) {
    m.insert(key.into(), json!(e.value));
    m.insert(format!("{key}_err"), json!(e.err));
    m.insert(format!("{key}_spread"), json!(spread));
    m.insert(
        format!("{key}_ratio"),
        json!(p.filter(|p| p.value != 0.0).map(|p| e.value / p.value)),
    );
}

/// The keys a `check --verify` section (a film's or a stack's) starts with: the map, its
/// pixels and q_L d (a stack's q_L z at the bottom interface).
pub(super) fn check_head(m: &mut Map<String, Value>, map: &Path, nx: usize, ny: usize, q_low: f64) {
    m.insert("map".into(), json!(map.display().to_string()));
    m.insert("nx".into(), json!(nx));
    m.insert("ny".into(), json!(ny));
    m.insert("q_low_d".into(), json!(q_low));
}

/// The surface keys of an `exact` object (a film's or a stack's): `surface`, `source`,
/// `realisations`, `nx`, `ny` and `unresolved_slope_share`; `r` is the realisations' count and
/// unresolved slope share when there are realisations.
pub(super) fn surface_json(
    m: &mut Map<String, Value>,
    map: &Path,
    nx: usize,
    ny: usize,
    r: Option<(usize, f64)>,
) {
    m.insert(
        "surface".into(),
        json!(if r.is_some() { "realisations" } else { "map" }),
    );
    m.insert("source".into(), json!(map.display().to_string()));
    m.insert("realisations".into(), json!(r.map_or(1, |r| r.0)));
    m.insert("nx".into(), json!(nx));
    m.insert("ny".into(), json!(ny));
    m.insert("unresolved_slope_share".into(), json!(r.map(|r| r.1)));
}

/// Persson's and the exact minimum thickness side by side, with their errors, after `what`.
pub(super) fn min_thickness_line(
    what: &str,
    persson: Option<&MinThickness>,
    m: &ExactMinThickness,
    spread: Option<f64>,
) -> String {
    let persson = match persson.and_then(|p| p.thickness) {
        Some(d) => format!("{} µm ± {} µm", um(d.value), sig(d.err * 1e6, 2)),
        None => "no thickness passes".into(),
    };
    let exact = match m.thickness() {
        None => "no thickness passes".into(),
        Some(d) => {
            let bracket = m.search.thickness.map_or(f64::NAN, |b| b.err);
            let spread = spread
                .map(|s| format!(", spread ± {} µm", sig(s * 1e6, 2)))
                .unwrap_or_default();
            format!(
                "{} µm ± {} µm (bracket ± {} µm, grid ± {} µm{spread}; set by {})",
                um(d.value),
                sig(d.err * 1e6, 2),
                sig(bracket * 1e6, 2),
                sig(m.grid_err * 1e6, 2),
                m.search.governing.map_or("-", CheckKind::name)
            )
        }
    };
    format!("{what}: Persson {persson}; exact {exact}")
}

/// One exact check as JSON: name, value (with `_err`) and its unit, limit, utilisation,
/// margin, pass, and whether its ε-level is resolved by the map.
pub(super) fn exact_check_json(c: &ExactCheck) -> Value {
    let unit = if c.kind == CheckKind::MinThickness {
        "m"
    } else {
        "Pa"
    };
    json!({
        "name": c.kind.name(), "value": c.value.value, "value_err": c.value.err,
        "unit": unit, "limit": c.limit, "utilisation": 1.0 - c.margin,
        "margin": c.margin, "pass": c.pass, "resolved": c.resolved,
    })
}

/// The `check --verify` section as a JSON value (`verify`).
pub fn check_json(x: &Exact, outcome: &Outcome) -> Value {
    let (v, ev) = (&x.verification, &outcome.evaluation);
    let mut m = Map::new();
    check_head(&mut m, &x.map, v.nx, v.ny, v.q_low_d);
    for r in check_rows(ev, v) {
        put_row(&mut m, r.key, r.persson, r.exact);
    }
    m.insert("peaks_resolved".into(), json!(v.tau_peak.resolved));
    if let Some(s) = &v.sliding {
        m.insert("friction".into(), json!(s.friction));
        m.insert("approximation".into(), json!("uncoupled"));
    }
    m.insert(
        "checks".into(),
        json!(v.checks.iter().map(exact_check_json).collect::<Vec<_>>()),
    );
    m.insert("solver".into(), solver_json(&v.convergence, v.seconds));
    m.insert("boundary".into(), x.boundary.json());
    m.insert(
        "verdict".into(),
        json!(if v.pass { "pass" } else { "fail" }),
    );
    Value::Object(m)
}

/// The `min_thickness_*` keys of an `exact` object (a film's or a stack's): the exact d_min with
/// its error and parts, its spread over realisations, its ratio to Persson's d_min (of
/// `persson`), the check that sets it and the solves it took; null where the search did not
/// run.
pub(super) fn min_thickness_json(
    m: &mut Map<String, Value>,
    min: Option<&ExactMinThickness>,
    spread: Option<f64>,
    persson: Option<&MinThickness>,
) {
    let persson = persson.and_then(|p| p.thickness).map(|p| p.value);
    let d = min.and_then(ExactMinThickness::thickness);
    m.insert("min_thickness_m".into(), json!(d.map(|d| d.value)));
    m.insert("min_thickness_m_err".into(), json!(d.map(|d| d.err)));
    m.insert(
        "min_thickness_m_bracket_err".into(),
        json!(min.and_then(|m| m.search.thickness).map(|d| d.err)),
    );
    m.insert(
        "min_thickness_m_grid_err".into(),
        json!(min.map(|m| m.grid_err)),
    );
    m.insert(
        "min_thickness_m_spread".into(),
        json!(spread.filter(|_| min.is_some())),
    );
    m.insert(
        "min_thickness_m_ratio".into(),
        json!(d.zip(persson).map(|(d, p)| d.value / p)),
    );
    m.insert(
        "min_thickness_governing_check".into(),
        json!(min.and_then(|m| m.search.governing).map(CheckKind::name)),
    );
    m.insert("min_thickness_solves".into(), json!(min.map(|m| m.solves)));
}

/// The exact result as a JSON value (`exact`): its verdict, the exact d_min with its error
/// (bracket plus grid, each also apart) beside Persson's, A/A0 and the stress levels with
/// their errors, their ratio to Persson's (`_ratio`) and, over realisations, their spread
/// (`_spread`, null on a map), and the exact checks.
pub fn exact_json(x: &Exact, outcome: &Outcome) -> Value {
    let (v, ev) = (&x.verification, &outcome.evaluation);
    let r = x.realisations.as_ref();
    let mut m = Map::new();
    m.insert(
        "verdict".into(),
        json!(if v.pass { "pass" } else { "fail" }),
    );
    let surface = r.map(|r| (r.count, r.grid.unresolved_slope_share));
    surface_json(&mut m, &x.map, v.nx, v.ny, surface);
    min_thickness_json(
        &mut m,
        x.min_thickness.as_ref(),
        r.map(|r| r.min_thickness_spread),
        outcome.min_thickness.as_ref(),
    );
    for row in check_rows(ev, v) {
        let spread = r.and_then(|r| r.spread_of(row.key));
        put_exact_row(&mut m, row.key, row.persson, row.exact, spread);
    }
    m.insert(
        "checks".into(),
        json!(v.checks.iter().map(exact_check_json).collect::<Vec<_>>()),
    );
    Value::Object(m)
}
