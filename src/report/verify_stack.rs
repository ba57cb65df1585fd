//! Output of the exact solver on a layer stack ([`crate::verify_stack`]): `coatcheck verify
//! --layer` (tables, JSON, CSV, the fields at every interface) and the exact section of `check
//! --verify` on a `[[layer]]` scene (tables in MPa with 4 significant digits, JSON).
//!
//! JSON of `verify --layer` (`verify.schema.json`): the film's keys with `thickness_m` the
//! depth of the bottom interface and the film's interface keys (`interface_normal_pa`,
//! `interface_shear_abs_pa`, `shear_fraction_above_bond`) those of the bottom interface, as the
//! stack check does; `comparison` the top surface's rows then the bottom interface's; `layers`
//! (top first) and `interfaces`, each with `name`, `depth_m`, its field statistics and its own
//! `comparison`. With `--friction` every interface also carries the film's `sliding` object and
//! the top-level `sliding` is the bottom interface's.
//!
//! The `check --verify` section (`check.schema.json`, `verify`): the film's keys for the top
//! surface and the contact, `interfaces` like the check's (`name`, `depth_m`, `sigma_rms_pa`,
//! `tau_rms_pa`, `tau_peak_pa`, `sigma_peak_pa`, `bond_exceedance`, each with `_err` and
//! `persson_` beside it, then `bond_strength_pa`, `sigma_max_pa`, `tau_max_pa`, the field
//! statistics and `peaks_resolved`; under sliding friction a `sliding` object with the shear
//! vector's keys), the checks with `at`, the solver and the exact verdict.

use super::verify::{
    check_head, exact_check_json, fields_csv, min_thickness_json, min_thickness_line,
    put_exact_row, put_row, row_cells, show, sliding_json, solver_json, stats_json, surface_json,
};
use super::{margin_cell, modulus, mpa, sig, table, um, utilisation_cell, wrap};
use crate::bem::{BemSolution, InterfaceFields, Surface};
use crate::check::CheckKind;
use crate::check::stack::StackOutcome;
use crate::contact::SlidingShear;
use crate::error::Error;
use crate::layer::stack::Stack;
use crate::pipeline::StackExact;
use crate::prec::Estimate;
use crate::verify::Row;
use crate::verify::boundary::BoundaryDecision;
use crate::verify::sliding::{
    ExactSliding, SLIDING_QUANTILES, SlidingVerification, vector_quantile,
};
use crate::verify_stack::{StackComparison, StackVerification};
use serde_json::{Map, Value, json};
use std::path::Path;

/// What `coatcheck verify --layer` was asked: the map file, the stack, the layers' names (top
/// first), the load and the bond strength every interface is measured against.
pub struct StackVerifyInputs<'a> {
    pub map: &'a Path,
    pub stack: &'a Stack,
    pub names: &'a [String],
    pub p0: f64,
    pub bond: Option<f64>,
    /// The boundary of the solve.
    pub boundary: BoundaryDecision,
}

/// Stresses in MPa, the rest as they are.
fn scaled(r: &Row, x: f64) -> f64 {
    if r.unit == "Pa" { x * 1e-6 } else { x }
}

fn rows_table(t: &mut comfy_table::Table, at: &str, rows: &[Row]) {
    for r in rows {
        t.add_row(vec![
            at.to_string(),
            r.name.clone(),
            if r.unit == "Pa" { "MPa" } else { r.unit }.to_string(),
            r.persson.map_or("-".into(), |p| sig(scaled(r, p.value), 4)),
            r.persson.map_or("-".into(), |p| sig(scaled(r, p.err), 2)),
            sig(scaled(r, r.exact), 4),
            r.ratio().map_or("-".into(), |v| sig(v, 3)),
        ]);
    }
}

/// `coatcheck verify --layer`'s tables: the scene and the layers, then Persson beside the
/// exact contact at the top and at every interface.
pub fn verify_table(i: &StackVerifyInputs, c: &StackComparison) -> String {
    let (s, sol) = (&c.surface, &c.solution);
    let mut scene = table(&["scene", "value"]);
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
        format!("{} µm, {}", um(sol.h_rms), sig(s.rms_slope(), 4)),
    ]);
    for ((l, name), ic) in i.stack.layers().iter().zip(i.names).zip(&c.interfaces) {
        scene.add_row(vec![
            name.clone(),
            format!(
                "E = {}, nu = {}, {} µm (interface at {} µm, q_L z = {})",
                modulus(l.material.youngs),
                l.material.poisson,
                um(l.thickness),
                um(ic.depth),
                sig(s.q_low() * ic.depth, 4)
            ),
        ]);
    }
    let sub = i.stack.substrate();
    scene.add_row(vec![
        "substrate".into(),
        format!("E = {}, nu = {}", modulus(sub.youngs), sub.poisson),
    ]);
    scene.add_row(vec!["pressure p0".into(), format!("{} MPa", mpa(i.p0))]);
    scene.add_row(vec!["boundary".into(), i.boundary.describe()]);
    let v = &sol.convergence;
    scene.add_row(vec![
        "solver".into(),
        format!(
            "{:?} after {} iterations in {:.2} s (rms gap in contact {:.2e} µm, penetration \
             {:.2e} µm, tolerance {:.2e} µm)",
            v.status,
            v.iterations,
            c.seconds,
            v.gap_rms_in_contact * 1e6,
            v.max_penetration * 1e6,
            v.tolerance * 1e6
        ),
    ]);
    let mut t = table(&[
        "at",
        "quantity",
        "unit",
        "Persson",
        "Persson err",
        "exact (BEM)",
        "exact/Persson",
    ]);
    rows_table(&mut t, "top", &c.rows);
    for (name, ic) in i.names.iter().zip(&c.interfaces) {
        rows_table(&mut t, name, &ic.rows);
    }
    format!(
        "{scene}\n{t}\n{}\n",
        wrap(&format!(
            "at: the top surface, or the interface below the named layer. A/A0 counts pixels in \
             contact (±{:.1e} from the solver tolerance); refine the map to see the \
             discretisation error. Quantiles: contact pressure over the contact area, interface \
             stresses over the whole interface.",
            sol.area_fraction.err
        ))
    )
}

fn rows_json(rows: &[Row]) -> Vec<Value> {
    rows.iter()
        .map(|r| {
            json!({
                "quantity": r.name, "unit": r.unit,
                "persson": r.persson.map(|p| p.value),
                "persson_err": r.persson.map(|p| p.err),
                "exact": r.exact, "ratio": r.ratio(),
            })
        })
        .collect()
}

/// `coatcheck verify --layer`'s JSON object (module docs).
pub fn verify_json(i: &StackVerifyInputs, c: &StackComparison) -> Value {
    let (surface, sol, theory) = (&c.surface, &c.solution, &c.persson);
    let bottom = c.interfaces.last().expect("a stack has an interface");
    let bottom_fields = c.fields.last().expect("a stack has an interface");
    let z = bottom.depth;
    let mut comparison = rows_json(&c.rows);
    comparison.extend(rows_json(&bottom.rows));
    let layers: Vec<Value> = i
        .stack
        .layers()
        .iter()
        .zip(i.names)
        .map(|(l, name)| {
            json!({
                "name": name, "youngs_modulus_pa": l.material.youngs,
                "poisson_ratio": l.material.poisson, "thickness_m": l.thickness,
            })
        })
        .collect();
    let interfaces: Vec<Value> = c
        .interfaces
        .iter()
        .zip(&c.fields)
        .zip(i.names)
        .map(|((ic, f), name)| {
            json!({
                "name": name, "depth_m": ic.depth, "q_low_z": surface.q_low() * ic.depth,
                "normal_pa": stats_json(&f.normal_stats),
                "shear_abs_pa": stats_json(&f.shear_stats),
                "shear_fraction_above_bond": ic.above_bond,
                "comparison": rows_json(&ic.rows),
            })
        })
        .collect();
    json!({
        "schema_version": super::SCHEMA_VERSION,
        "coatcheck_version": env!("CARGO_PKG_VERSION"),
        "map": i.map.display().to_string(),
        "nx": surface.nx, "ny": surface.ny, "dx_m": surface.dx, "dy_m": surface.dy,
        "h_rms_m": sol.h_rms, "rms_slope": surface.rms_slope(), "q_low_per_m": surface.q_low(),
        "q_low_d": surface.q_low() * z,
        "thickness_m": z, "pressure_pa": i.p0,
        "solver": solver_json(&sol.convergence, c.seconds),
        "boundary": i.boundary.json(),
        "area_fraction": sol.area_fraction.value,
        "area_fraction_err": sol.area_fraction.err,
        "persson_area_fraction": theory.top.area_fraction.value,
        "persson_area_fraction_err": theory.top.area_fraction.err,
        "sigma_rms_top_pa": sol.sigma_rms_top,
        "contact_pressure_pa": stats_json(&sol.contact_pressure),
        "interface_normal_pa": stats_json(&bottom_fields.normal_stats),
        "interface_shear_abs_pa": stats_json(&bottom_fields.shear_stats),
        "bond_strength_pa": i.bond,
        "shear_fraction_above_bond": bottom.above_bond,
        "comparison": comparison,
        "layers": layers,
        "interfaces": interfaces,
    })
}

/// `coatcheck verify --layer --friction μ`'s note below the tables.
pub fn sliding_note(mu: f64) -> String {
    let mut out = wrap(&format!(
        "sliding friction mu = {mu}: the traction mu p(x) along x is applied to the solved \
         frictionless pressure (uncoupled approximation: the friction does not change the \
         contact; the normal-tangential coupling it neglects is not computed for a stack). At \
         every interface the fields, sigma_rms interface and |tau| include the friction-driven \
         part (the stack's kernels g_t, f_t, h of that interface); Persson's |tau| quantiles are \
         those of the vector (mu p0 + X, Y), X and Y independent Gaussians with that interface's \
         tau_x and tau_y rms."
    ));
    out.push('\n');
    out
}

/// `coatcheck verify --layer --friction`'s JSON: every interface's `sliding` object (the
/// film's, with `friction_coupling` null) and the bottom interface's as the top-level one, added
/// to the object of [`verify_json`].
pub fn add_sliding_json(v: &mut Value, exact: &[ExactSliding], persson: &[SlidingShear]) {
    let all: Vec<Value> = exact
        .iter()
        .zip(persson)
        .map(|(e, p)| sliding_json(e, p))
        .collect();
    if let Some(items) = v["interfaces"].as_array_mut() {
        for (item, s) in items.iter_mut().zip(&all) {
            item["sliding"] = s.clone();
        }
    }
    if let Some(bottom) = all.last() {
        v["sliding"] = bottom.clone();
    }
}

/// A CSV cell: the number in full precision, empty when there is none.
fn cell(x: Option<f64>) -> String {
    x.map_or(String::new(), |x| format!("{x:e}"))
}

/// `coatcheck verify --layer --format csv`: one row per compared quantity, `at` (`top` or the
/// layer above the interface), `depth_m`, then the columns of the comparison (SI units).
pub fn verify_csv(i: &StackVerifyInputs, c: &StackComparison) -> String {
    let mut out = String::from("at,depth_m,quantity,unit,persson,persson_err,exact,ratio\n");
    let mut put = |at: &str, depth: f64, rows: &[Row]| {
        for r in rows {
            out += &format!(
                "{},{depth:e},{},{},{},{},{:e},{}\n",
                at.replace([',', '"', '\n'], " "),
                r.name,
                r.unit,
                cell(r.persson.map(|p| p.value)),
                cell(r.persson.map(|p| p.err)),
                r.exact,
                cell(r.ratio())
            );
        }
    };
    put("top", 0.0, &c.rows);
    for (name, ic) in i.names.iter().zip(&c.interfaces) {
        put(name, ic.depth, &ic.rows);
    }
    out
}

/// The fields of a solve on a stack as CSV: x, y, height, pressure, gap, then at every interface
/// k (top first) σ_n, τ_x, τ_y, |τ| (`sigma_n_1_pa,tau_x_1_pa,tau_y_1_pa,tau_abs_1_pa, …`).
pub fn write_fields(
    path: &Path,
    s: &Surface,
    sol: &BemSolution,
    fields: &[InterfaceFields],
) -> Result<(), Error> {
    fields_csv(path, s, sol, fields, |k| {
        format!(",sigma_n_{k}_pa,tau_x_{k}_pa,tau_y_{k}_pa,tau_abs_{k}_pa")
    })
}

/// One quantity of `check --verify` on a stack: its name, report key, Persson's value and the
/// exact one.
type CheckRow = (&'static str, &'static str, Option<Estimate>, Estimate);

/// The top surface's quantities, Persson's beside the exact ones.
fn top_rows(o: &StackOutcome, v: &StackVerification) -> Vec<CheckRow> {
    let c = &o.contact.top;
    vec![
        (
            "A/A0",
            "area_fraction",
            Some(c.area_fraction),
            v.area_fraction,
        ),
        (
            "mean contact pressure",
            "mean_contact_pressure_pa",
            Some(o.mean_contact_pressure),
            v.mean_contact_pressure,
        ),
        (
            "sigma_rms top",
            "sigma_rms_top_pa",
            c.sigma_rms_top,
            v.sigma_rms_top,
        ),
    ]
}

/// Interface k's quantities, Persson's beside the exact ones.
fn interface_rows(o: &StackOutcome, v: &StackVerification, k: usize) -> Vec<CheckRow> {
    let (p, e) = (&o.interfaces[k], &v.interfaces[k]);
    vec![
        ("sigma_rms", "sigma_rms_pa", Some(p.sigma_rms), e.sigma_rms),
        ("tau_rms", "tau_rms_pa", Some(p.tau_rms), e.tau_rms),
        (
            "tau_peak",
            "tau_peak_pa",
            Some(p.tau_peak),
            e.tau_peak.value,
        ),
        (
            "sigma_peak",
            "sigma_peak_pa",
            Some(p.sigma_peak),
            e.sigma_peak.value,
        ),
        (
            "P(|tau| > bond strength)",
            "bond_exceedance",
            Some(Estimate::exact(p.bond_exceedance)),
            e.bond_exceedance,
        ),
    ]
}

/// Interface k's shear vector under sliding friction: the exact values beside Persson's
/// (`persson`, interface k's shear vector from the stack checker under sliding; his |τ|
/// quantiles by the vector rule, [`vector_quantile`], which cannot fail where the checker's own
/// vector peak of the same shear succeeded).
fn sliding_rows(s: &SlidingVerification, persson: Option<&SlidingShear>) -> Vec<CheckRow> {
    let [q50, q99, q999] = s.quantiles;
    let [p50, p99, p999] = SLIDING_QUANTILES;
    let quantile = |prob: f64| persson.and_then(|p| vector_quantile(p, prob).ok());
    vec![
        (
            "mean tau_x",
            "mean_interface_shear_pa",
            persson.map(|p| p.mean),
            s.mean_x,
        ),
        (
            "mean tau_y",
            "mean_interface_shear_y_pa",
            persson.map(|_| Estimate::exact(0.0)),
            s.mean_y,
        ),
        (
            "tau_x rms",
            "tau_x_rms_interface_pa",
            persson.map(|p| p.tau_x_rms),
            s.tau_x_rms,
        ),
        (
            "tau_y rms",
            "tau_y_rms_interface_pa",
            persson.map(|p| p.tau_y_rms),
            s.tau_y_rms,
        ),
        ("|tau| q0.5", "tau_abs_q50_pa", quantile(p50), q50),
        ("|tau| q0.99", "tau_abs_q99_pa", quantile(p99), q99),
        ("|tau| q0.999", "tau_abs_q999_pa", quantile(p999), q999),
        ("|tau| max", "tau_abs_max_pa", None, s.max),
    ]
}

/// The JSON object of interface k's sliding rows (`key`, `key_err`, `persson_key`), with the
/// friction and the approximation.
fn sliding_object(
    s: &SlidingVerification,
    persson: Option<&SlidingShear>,
    put: impl Fn(&mut Map<String, Value>, Vec<CheckRow>),
) -> Value {
    let mut m = Map::new();
    m.insert("friction".into(), json!(s.friction));
    m.insert("approximation".into(), json!("uncoupled"));
    put(&mut m, sliding_rows(s, persson));
    Value::Object(m)
}

/// The spread over the realisations of a number by its report key.
type Spread<'a> = dyn Fn(&str) -> Option<f64> + 'a;

/// The rows of one place (`top` or an interface), with the spread over the realisations
/// (`spread(key)`) when there are realisations.
fn add_rows(
    t: &mut comfy_table::Table,
    at: &str,
    rows: Vec<CheckRow>,
    spread: Option<&Spread<'_>>,
) {
    for (name, key, p, e) in rows {
        t.add_row(row_cells(Some(at), name, key, p, e, spread.map(|s| s(key))));
    }
}

/// The heading of the `check --verify` section: the map, or the realisations and their grid.
fn heading(x: &StackExact) -> String {
    let v = &x.verification;
    let solves = x
        .min_thickness
        .as_ref()
        .map(|m| format!(", {} more for the minimum thickness", m.solves))
        .unwrap_or_default();
    match &x.realisations {
        None => format!(
            "exact check on the height map {} ({} x {} pixels, q_L z = {} at the bottom \
             interface; boundary elements with the stack's kernels, {} iterations{solves}; error \
             = difference to the same map at half resolution)",
            x.map.display(),
            v.nx,
            v.ny,
            sig(v.q_low_z, 3),
            v.convergence.iterations
        ),
        Some(r) => format!(
            "exact check on {} random-phase realisations of the scene's spectrum ({}; seeds \
             {}..{}; {} x {} pixels of {} µm, q_L z = {} at the bottom interface, modes up to {} \
             1/m; boundary elements with the stack's kernels{solves}): each exact number is the \
             mean over the realisations, spread = standard error of that mean, error = mean \
             difference to the same surfaces at half resolution; the grid leaves out {} of the \
             slope variance",
            r.count,
            x.map.display(),
            r.seeds[0],
            r.seeds[r.seeds.len() - 1],
            v.nx,
            v.ny,
            um(r.grid.dx),
            sig(v.q_low_z, 3),
            sig(r.grid.q_nyquist, 4),
            sig(r.grid.unresolved_slope_share, 3)
        ),
    }
}

/// The `check --verify` section of a stack as tables (MPa, µm, 4 significant digits): Persson
/// beside the exact numbers at the top and at every interface, the exact checks, both minimum
/// thicknesses of the layer `criteria.thickness_of` and the exact verdict.
pub fn check_table(x: &StackExact, o: &StackOutcome) -> String {
    let v = &x.verification;
    let r = x.realisations.as_ref();
    let mut out = wrap(&heading(x));
    out.push('\n');
    let mut head = vec!["at", "quantity", "Persson", "exact (BEM)", "error estimate"];
    if r.is_some() {
        head.push("spread");
    }
    head.push("exact/Persson");
    let mut t = table(&head);
    let top = r.map(|r| move |key: &str| r.top_spread(key));
    add_rows(
        &mut t,
        "top",
        top_rows(o, v),
        top.as_ref().map(|f| f as &Spread<'_>),
    );
    for (k, i) in v.interfaces.iter().enumerate() {
        let at = r.map(|r| move |key: &str| r.interface_spread(k, key));
        let mut rows = interface_rows(o, v, k);
        let persson = o.interfaces[k].sliding.as_ref();
        rows.extend(
            i.sliding
                .as_ref()
                .map(|s| sliding_rows(s, persson))
                .unwrap_or_default(),
        );
        add_rows(&mut t, &i.name, rows, at.as_ref().map(|f| f as &Spread<'_>));
    }
    out += &format!("{t}\n");
    if let Some(s) = v.interfaces.first().and_then(|i| i.sliding.as_ref()) {
        out += &wrap(&format!(
            "sliding friction mu = {}: at every interface the exact fields add the traction mu \
             p(x) along x on the solved frictionless pressure through that interface's kernels \
             g_t, f_t, h (uncoupled approximation); the exact levels, sigma_rms and P(|tau| > \
             bond strength) are of the total fields, tau_rms is the pressure-driven shear's.",
            s.friction
        ));
        out.push('\n');
    }
    let mut c = table(&[
        "check (exact)",
        "at",
        "value",
        "limit",
        "utilisation",
        "margin",
        "result",
    ]);
    for sc in &v.checks {
        let ch = &sc.check;
        let mut result = if ch.pass { "PASS" } else { "FAIL" }.to_string();
        if !ch.resolved {
            result += " (map maximum)";
        }
        let (value, limit) = if ch.kind == CheckKind::MinThickness {
            let limit = if ch.limit.is_infinite() {
                "none passes".into()
            } else {
                format!(">= {} µm", um(ch.limit))
            };
            (format!("{} µm", um(ch.value.value)), limit)
        } else {
            (
                show("_pa", ch.value.value),
                format!("<= {}", show("_pa", ch.limit)),
            )
        };
        c.add_row(vec![
            ch.kind.name().to_string(),
            sc.at.clone(),
            value,
            limit,
            utilisation_cell(Some(ch.margin)),
            margin_cell(Some(ch.margin)),
            result,
        ]);
    }
    out += &format!("{c}\n");
    if let Some(m) = &x.min_thickness {
        let what = format!(
            "minimum thickness of layer '{}' (the others fixed)",
            thickness_of(o)
        );
        out += &wrap(&min_thickness_line(
            &what,
            o.min_thickness.as_ref(),
            m,
            r.map(|r| r.min_thickness_spread),
        ));
        out.push('\n');
    }
    let min_by = if x.min_thickness.is_some() {
        "the exact minimum thickness included"
    } else {
        "min-thickness is judged by Persson's theory only"
    };
    out += &wrap(&format!(
        "exact verdict: {}; with --verify the stack passes only if both Persson's and the exact \
         checks pass ({min_by}; map maximum: epsilon < 1/pixels, the level is the field's \
         maximum)",
        if v.pass { "PASS" } else { "FAIL" }
    ));
    out.push('\n');
    out
}

/// The name of the layer whose minimum thickness the check searched (the layer its
/// min-thickness check is at).
fn thickness_of(o: &StackOutcome) -> &str {
    o.checks
        .iter()
        .find(|c| c.result.kind == CheckKind::MinThickness)
        .map_or("", |c| c.at.as_str())
}

fn put_rows(m: &mut Map<String, Value>, rows: Vec<CheckRow>) {
    for (_, key, p, e) in rows {
        put_row(m, key, p, e);
    }
}

/// The exact checks with where each applies.
fn checks_json(v: &StackVerification) -> Value {
    let checks: Vec<Value> = v
        .checks
        .iter()
        .map(|sc| {
            let mut c = exact_check_json(&sc.check);
            c["at"] = json!(sc.at);
            c
        })
        .collect();
    Value::Array(checks)
}

/// The `check --verify` section of a stack as a JSON value (module docs).
pub fn check_json(x: &StackExact, o: &StackOutcome) -> Value {
    let v = &x.verification;
    let mut m = Map::new();
    check_head(&mut m, &x.map, v.nx, v.ny, v.q_low_z);
    put_rows(&mut m, top_rows(o, v));
    let interfaces: Vec<Value> = v
        .interfaces
        .iter()
        .enumerate()
        .map(|(k, i)| {
            let mut e = Map::new();
            e.insert("name".into(), json!(i.name));
            e.insert("depth_m".into(), json!(i.depth));
            put_rows(&mut e, interface_rows(o, v, k));
            e.insert("bond_strength_pa".into(), json!(i.bond_strength));
            e.insert("sigma_max_pa".into(), json!(i.normal.max));
            e.insert("tau_max_pa".into(), json!(i.shear.max));
            e.insert("normal_pa".into(), stats_json(&i.normal));
            e.insert("shear_abs_pa".into(), stats_json(&i.shear));
            e.insert("peaks_resolved".into(), json!(i.tau_peak.resolved));
            if let Some(sl) = &i.sliding {
                e.insert(
                    "sliding".into(),
                    sliding_object(sl, o.interfaces[k].sliding.as_ref(), put_rows),
                );
            }
            Value::Object(e)
        })
        .collect();
    m.insert("interfaces".into(), Value::Array(interfaces));
    m.insert("checks".into(), checks_json(v));
    m.insert("solver".into(), solver_json(&v.convergence, v.seconds));
    m.insert(
        "verdict".into(),
        json!(if v.pass { "pass" } else { "fail" }),
    );
    Value::Object(m)
}

/// The exact numbers of `rows` with their errors, their spread over the realisations
/// (`_spread`, null on a map) and their ratio to Persson's (`_ratio`).
fn put_exact_rows(
    m: &mut Map<String, Value>,
    rows: Vec<CheckRow>,
    spread: impl Fn(&str) -> Option<f64>,
) {
    for (_, key, p, e) in rows {
        put_exact_row(m, key, p, e, spread(key));
    }
}

/// The exact result of a stack as a JSON value (`exact`, the film's keys of
/// [`super::verify::exact_json`] for the top surface and the contact): its verdict, the surface
/// (the map or the realisations), the exact d_min of the layer `thickness_of` with its error
/// (bracket plus grid, each also apart) beside Persson's, A/A0, then `interfaces` (top first,
/// each with `name`, `depth_m` and the stress levels with `_err`, `_spread` and `_ratio`), and
/// the exact checks with `at`.
pub fn exact_json(x: &StackExact, o: &StackOutcome) -> Value {
    let v = &x.verification;
    let r = x.realisations.as_ref();
    let mut m = Map::new();
    m.insert(
        "verdict".into(),
        json!(if v.pass { "pass" } else { "fail" }),
    );
    let surface = r.map(|r| (r.count, r.grid.unresolved_slope_share));
    surface_json(&mut m, &x.map, v.nx, v.ny, surface);
    m.insert("thickness_of".into(), json!(thickness_of(o)));
    min_thickness_json(
        &mut m,
        x.min_thickness.as_ref(),
        r.map(|r| r.min_thickness_spread),
        o.min_thickness.as_ref(),
    );
    put_exact_rows(&mut m, top_rows(o, v), |key| {
        r.and_then(|r| r.top_spread(key))
    });
    let interfaces: Vec<Value> = v
        .interfaces
        .iter()
        .enumerate()
        .map(|(k, i)| {
            let mut e = Map::new();
            e.insert("name".into(), json!(i.name));
            e.insert("depth_m".into(), json!(i.depth));
            put_exact_rows(&mut e, interface_rows(o, v, k), |key| {
                r.and_then(|r| r.interface_spread(k, key))
            });
            if let Some(sl) = &i.sliding {
                let sliding = sliding_object(sl, o.interfaces[k].sliding.as_ref(), |m, rows| {
                    put_exact_rows(m, rows, |key| r.and_then(|r| r.interface_spread(k, key)))
                });
                e.insert("sliding".into(), sliding);
            }
            Value::Object(e)
        })
        .collect();
    m.insert("interfaces".into(), Value::Array(interfaces));
    m.insert("checks".into(), checks_json(v));
    Value::Object(m)
}
