//! The report of one judged scene: human tables, one JSON object, or CSV.
//!
//! The JSON object carries `verdict`, `area_fraction`, `mean_contact_pressure_pa`,
//! `sigma_rms_top_pa`, `sigma_rms_interface_pa`, `tau_rms_interface_pa`, `tau_peak_pa`,
//! `sigma_peak_interface_pa`, `e_eff_over_e_film`, `min_thickness_m`, `governing_check`,
//! `checks` and `levers` (what alone would make a failing design pass), each numeric result with
//! a sibling `<key>_err` (its numerical error estimate), plus the inputs and warnings. Under the
//! vector shear rule (sliding friction, or asked for) it also carries `shear_tail`, `friction`,
//! `mean_interface_shear_pa`, `tau_x_rms_interface_pa`, `tau_y_rms_interface_pa` (each with
//! `_err`), `tau_peak_static_pa` (the paper's rule on the static shear, with `_err`) and
//! `friction_coupling`; `tau_peak_pa` is then the vector's peak and `sigma_rms_interface_pa`
//! includes the friction-driven part.

use super::{
    Format, batch, margin_cell, modulus, mpa, sig, table, um, utilisation_cell, verify, wrap,
};
use crate::check::levers::Lever;
use crate::check::{CheckKind, CheckResult, Outcome};
use crate::contact::SlidingShear;
use crate::error::Error;
use crate::pipeline::Judged;
use crate::prec::Estimate;
use crate::scene::{RoughnessSource, Scale, Scene};
use serde_json::{Map, Value, json};

fn opt(e: Option<Estimate>, f: impl Fn(f64) -> String) -> (String, String) {
    match e {
        Some(e) => (f(e.value), f(e.err)),
        None => ("-".into(), "-".into()),
    }
}

/// The scene's inputs as (quantity, value) rows in human units.
pub(crate) fn scene_rows(scene: &Scene) -> Vec<(String, String)> {
    let mut rows = Vec::new();
    let r = &scene.roughness;
    match &r.source {
        RoughnessSource::Measured { path } => {
            rows.push(("roughness".into(), format!("PSD file {}", path.display())))
        }
        RoughnessSource::Profile { path } => rows.push((
            "roughness".into(),
            format!("heights {} (PSD by coatcheck psd)", path.display()),
        )),
        RoughnessSource::SelfAffine {
            hurst,
            q0,
            q1,
            roll_off,
        } => {
            let ro = roll_off
                .map(|q| format!(", roll-off q_r = {} 1/m", sig(q, 4)))
                .unwrap_or_default();
            rows.push((
                "roughness".into(),
                format!(
                    "self-affine H = {}, q0 = {} 1/m, q1 = {} 1/m{ro}",
                    sig(*hurst, 4),
                    sig(*q0, 4),
                    sig(*q1, 4)
                ),
            ));
        }
        RoughnessSource::Gaussian { q0, width } => rows.push((
            "roughness".into(),
            format!(
                "Gaussian band q0 = {} 1/m, width Q = {} 1/m",
                sig(*q0, 4),
                sig(*width, 4)
            ),
        )),
    }
    match r.scale {
        Some(Scale::RmsSlope(x)) => rows.push(("rms slope".into(), sig(x, 4))),
        Some(Scale::RmsHeight(h)) => rows.push(("rms height".into(), format!("{} µm", um(h)))),
        None => {}
    }
    if let Some(q) = r.q_min {
        rows.push(("q_min".into(), format!("{} 1/m", sig(q, 4))));
    }
    if let Some(q) = r.q_max {
        rows.push(("q_max".into(), format!("{} 1/m", sig(q, 4))));
    }
    let f = &scene.film;
    rows.push((
        "film".into(),
        format!(
            "{}: E = {}, nu = {}",
            f.name,
            modulus(f.elastic.youngs),
            f.elastic.poisson
        ),
    ));
    if let Some(d) = scene.thickness {
        rows.push(("film thickness".into(), format!("{} µm", um(d))));
    }
    let s = &scene.substrate;
    let y = s
        .yield_strength
        .map(|y| format!(", yield = {} MPa", mpa(y)))
        .unwrap_or_default();
    rows.push((
        "substrate".into(),
        format!(
            "{}: E = {}, nu = {}{y}",
            s.name,
            modulus(s.elastic.youngs),
            s.elastic.poisson
        ),
    ));
    rows.push((
        "bond".into(),
        format!(
            "{}: shear strength = {} MPa",
            scene.bond.name,
            mpa(scene.bond.shear_strength)
        ),
    ));
    rows.push((
        "nominal pressure p0".into(),
        format!("{} MPa", mpa(scene.pressure)),
    ));
    for o in &scene.overrides {
        let show = |x: f64| match o.unit {
            "Pa" if o.key.ends_with("youngs_modulus") => modulus(x),
            "Pa" => format!("{} MPa", mpa(x)),
            _ => sig(x, 4),
        };
        rows.push((
            "override".into(),
            format!(
                "{} = {} (library {}: {})",
                o.key,
                show(o.value),
                o.material,
                o.library_value.map_or("none".into(), show)
            ),
        ));
    }
    if scene.friction > 0.0 {
        rows.push((
            "sliding friction mu".into(),
            format!("{} (traction mu p along x)", scene.friction),
        ));
    }
    let c = &scene.criteria;
    let tail = match c.shear_tail {
        Some(t) => format!(", shear tail: {}", t.name()),
        None => String::new(),
    };
    rows.push((
        "criteria".into(),
        format!(
            "epsilon = {:e}, safety factor = {}, checks: {}{tail}",
            c.epsilon,
            c.safety_factor,
            enabled_names(scene).join(", ")
        ),
    ));
    rows
}

fn enabled_names(scene: &Scene) -> Vec<&'static str> {
    let c = scene.criteria.checks;
    [
        (c.bond_shear, CheckKind::BondShear),
        (c.substrate_yield, CheckKind::SubstrateYield),
        (c.min_thickness, CheckKind::MinThickness),
    ]
    .into_iter()
    .filter(|(on, _)| *on)
    .map(|(_, k)| k.name())
    .collect()
}

/// Value and limit of a check in human units.
pub(crate) fn check_cells(c: &CheckResult) -> (String, String) {
    let f = |x: f64| match c.kind {
        CheckKind::MinThickness => format!("{} µm", um(x)),
        _ => format!("{} MPa", mpa(x)),
    };
    let limit = match (c.kind, c.limit) {
        (CheckKind::MinThickness, Some(l)) => format!(">= {}", f(l)),
        (_, Some(l)) => format!("<= {}", f(l)),
        (_, None) => "none passes".into(),
    };
    (f(c.value.value), limit)
}

/// The results at the design thickness as (quantity, value, error estimate), as the table
/// shows them.
pub(crate) fn result_rows(outcome: &Outcome) -> Vec<[String; 3]> {
    let ev = &outcome.evaluation;
    let c = &ev.contact;
    let mut rows = Vec::new();
    let mut row = |name: &str, e: Option<Estimate>, f: &dyn Fn(f64) -> String| {
        let (v, err) = opt(e, f);
        rows.push([name.to_string(), v, err]);
    };
    let plain = |x: f64| sig(x, 4);
    let mpa_unit = |x: f64| format!("{} MPa", mpa(x));
    // A stress whose value or error in MPa would leave f64's normal range (a thick film's
    // interface stress, or the subnormal error of one that flushed to 0) in Pa, where both keep
    // their digits.
    let pa_unit = |x: f64| match x {
        0.0 => "0 Pa".to_string(),
        _ => format!("{x:.3e} Pa"),
    };
    let tiny = |x: f64| x != 0.0 && (x * 1e-6).abs() < f64::MIN_POSITIVE;
    let stress = |e: Option<Estimate>| -> &dyn Fn(f64) -> String {
        match e {
            Some(e) if tiny(e.value) || tiny(e.err) => &pa_unit,
            _ => &mpa_unit,
        }
    };
    row(
        "A/A0 (real contact area fraction)",
        Some(c.area_fraction),
        &plain,
    );
    row("E_eff/E_film", c.e_eff_over_e_film, &plain);
    row(
        "mean pressure in real contact p0·A0/A",
        Some(ev.mean_contact_pressure),
        &mpa_unit,
    );
    let friction = ev.sliding.map_or(0.0, |s| s.friction);
    row("sigma_rms top surface", c.sigma_rms_top, &mpa_unit);
    row(
        if friction > 0.0 {
            "sigma_rms interface (with the friction-driven part)"
        } else {
            "sigma_rms interface"
        },
        c.sigma_rms_interface,
        stress(c.sigma_rms_interface),
    );
    row(
        "sigma_peak interface (exceedance epsilon)",
        ev.sigma_peak_interface,
        &mpa_unit,
    );
    row(
        "tau_rms interface",
        c.tau_rms_interface,
        stress(c.tau_rms_interface),
    );
    match &ev.sliding {
        Some(s) => {
            row(
                "mean interface shear mu·p0 (along x)",
                Some(s.mean),
                &mpa_unit,
            );
            row(
                "tau_x rms interface (fluctuation along x)",
                Some(s.tau_x_rms),
                stress(Some(s.tau_x_rms)),
            );
            row(
                "tau_y rms interface (fluctuation along y)",
                Some(s.tau_y_rms),
                stress(Some(s.tau_y_rms)),
            );
            row(
                "tau_peak interface (vector rule: |tau| of (mu·p0 + X, Y), exceedance epsilon)",
                ev.tau_peak,
                stress(ev.tau_peak),
            );
            row(
                "tau_peak static (paper's half-normal rule)",
                ev.tau_peak_static,
                stress(ev.tau_peak_static),
            );
        }
        None => row(
            "tau_peak interface (exceedance epsilon)",
            ev.tau_peak,
            stress(ev.tau_peak),
        ),
    }
    rows.push([
        "h_rms of the spectrum used".into(),
        format!("{} µm", um(outcome.h_rms)),
        String::new(),
    ]);
    rows.push([
        "rms slope of the spectrum used".into(),
        sig(outcome.rms_slope, 4),
        String::new(),
    ]);
    rows.push([
        "share of G(q1) from the lowest octave".into(),
        sig(c.low_octave_share, 3),
        String::new(),
    ]);
    if let Some(p) = ev.bond_exceedance {
        rows.push(["P(|tau| > bond strength)".into(), sig(p, 3), String::new()]);
    }
    if let Some(k) = ev
        .sliding
        .and_then(|s| s.coupling)
        .filter(|_| friction > 0.0)
    {
        rows.push([
            "coupling neglected (uncoupled approximation): max mu|c|/S".into(),
            sig(k, 3),
            String::new(),
        ]);
    }
    if let Some(p) = ev.yield_exceedance {
        rows.push([
            "P(sigma_interface > yield strength)".into(),
            sig(p, 3),
            String::new(),
        ]);
    }
    rows
}

/// The checks as (check, value, limit, utilisation, margin, result), as the table shows them.
pub(crate) fn check_rows(outcome: &Outcome) -> Vec<[String; 6]> {
    let mean = outcome.evaluation.mean_contact_pressure.value;
    check_rows_of(outcome.checks.iter(), Some(mean))
}

/// Rows of [`check_rows`] for any checks; with the mean contact pressure, substrate-yield's
/// value says which level it is.
pub(crate) fn check_rows_of<'a>(
    checks: impl Iterator<Item = &'a CheckResult>,
    mean_contact_pressure: Option<f64>,
) -> Vec<[String; 6]> {
    checks
        .map(|ch| {
            let (mut v, l) = check_cells(ch);
            if ch.kind == CheckKind::SubstrateYield
                && let Some(mean) = mean_contact_pressure
            {
                v += if ch.value.value == mean {
                    " (mean contact pressure)"
                } else {
                    " (interface peak)"
                };
            }
            [
                ch.kind.name().to_string(),
                v,
                l,
                utilisation_cell(ch.margin),
                margin_cell(ch.margin),
                if ch.pass { "PASS" } else { "FAIL" }.into(),
            ]
        })
        .collect()
}

/// The default output: scene, results, checks, d_min, the verdict, what would make a failing
/// design pass, warnings.
pub fn human(scene: &Scene, outcome: &Outcome, levers: &[Lever]) -> String {
    let mut out = String::new();
    let mut t = table(&["scene", "value"]);
    for (k, v) in scene_rows(scene) {
        t.add_row(vec![k, v]);
    }
    out += &format!("{t}\n");
    let mut t = table(&["result", "value", "error estimate"]);
    for r in result_rows(outcome) {
        t.add_row(r.to_vec());
    }
    out += &format!("{t}\n");
    let mut t = table(&["check", "value", "limit", "utilisation", "margin", "result"]);
    for r in check_rows(outcome) {
        t.add_row(r.to_vec());
    }
    out += &format!("{t}\n");

    // The check that binds at d_min: not the verdict's governing check, so worded apart from it.
    let set_by = |g: Option<CheckKind>| format!("set by {}", g.map_or("-", CheckKind::name));
    if let Some(m) = &outcome.min_thickness {
        out += &match (m.thickness, m.governing) {
            (None, g) => format!("minimum thickness: no thickness passes ({})\n", set_by(g)),
            (Some(d), _) if m.all_pass_to_floor => format!(
                "minimum thickness: every thickness down to {} µm passes\n",
                um(d.value)
            ),
            (Some(d), g) => format!(
                "minimum thickness: {} µm ± {} µm ({})\n",
                um(d.value),
                sig(d.err * 1e6, 2),
                set_by(g)
            ),
        };
    }
    let gov = outcome
        .governing
        .and_then(|g| outcome.checks.iter().find(|c| c.kind == g));
    out += &format!(
        "verdict: {}{}\n",
        if outcome.pass { "PASS" } else { "FAIL" },
        gov.map(|c| format!(
            " (governing check: {}, utilisation {})",
            c.kind.name(),
            utilisation_cell(c.margin)
        ))
        .unwrap_or_default()
    );
    out += &levers_and_warnings(levers, &outcome.warnings);
    out
}

/// The lines under a verdict: what alone would make a failing design pass, then the warnings
/// (a film's and a layer stack's table alike).
pub(super) fn levers_and_warnings(levers: &[Lever], warnings: &[String]) -> String {
    let mut out = String::new();
    if !levers.is_empty() {
        out += "what alone would make it pass:\n";
        for l in levers {
            out += &wrap(&format!("  - {}", super::html::lever_text(l)));
            out.push('\n');
        }
    }
    for w in warnings {
        out += &wrap(&format!("warning: {w}"));
        out.push('\n');
    }
    out
}

/// The report of one judged scene: the check's tables, JSON or CSV, with the per-file verdicts
/// when the scene lists several roughness files, and the exact section of `check --verify`.
/// CSV is the batch's shape, one row ([`batch::records_csv`]).
pub fn scene(j: &Judged, format: Format) -> Result<String, Error> {
    let outcome = match &j.outcome {
        crate::pipeline::Verdict::Film(o) => o,
        crate::pipeline::Verdict::Stack(o) => return super::stack::scene(j, o, format),
    };
    let scene = &j.scene;
    let verdict = if j.pass() { "pass" } else { "fail" };
    Ok(match format {
        Format::Table => {
            let mut t = format!(
                "{}{}",
                batch::files_table(j),
                human(scene, outcome, &j.levers)
            );
            if let Some(x) = &j.exact {
                t += &format!("\n{}", verify::check_table(x, outcome));
            }
            if let Some(r) = &j.robust {
                t += &format!(
                    "\n{}",
                    super::robust::table_text(r, &scene.design(), outcome)
                );
            }
            t
        }
        Format::Json => {
            // JSON shows NaN as null: the table of the same numbers is checked instead.
            super::finite_only(&human(scene, outcome, &j.levers))?;
            let mut v = json(scene, outcome, &j.levers);
            put_files(&mut v, j);
            if let (Some(x), Some(o)) = (&j.exact, v.as_object_mut()) {
                o.insert("verify".into(), verify::check_json(x, outcome));
                o.insert("exact".into(), verify::exact_json(x, outcome));
                o.insert("verdict_with_verify".into(), verdict.into());
            }
            if let (Some(r), Some(o)) = (&j.robust, v.as_object_mut()) {
                let robust = super::robust::json_value(r, &scene.design(), outcome);
                o.insert("robust".into(), robust);
                o.insert("verdict_with_robust".into(), verdict.into());
            }
            format!("{v:#}\n")
        }
        Format::Csv => scene_csv(j)?,
    })
}

/// The per-file keys of a judged scene's JSON (a film's or a stack's) when its scene lists
/// several roughness files: `worst_file`, `files` and the warnings of all of them.
pub(super) fn put_files(v: &mut Value, j: &Judged) {
    if !j.files.is_empty() {
        let worst = j.worst_file().map(|p| p.display().to_string());
        v["worst_file"] = json!(worst);
        v["files"] = json!(j.files);
        v["warnings"] = json!(j.warnings);
    }
}

/// The CSV of a judged scene (a film's or a stack's): the batch's one row.
pub(super) fn scene_csv(j: &Judged) -> Result<String, Error> {
    let file = j.scene.file.clone().unwrap_or_else(|| "scene".into());
    batch::records_csv(&[batch::Record::judged(&file, j, 0.0)])
}

/// `key` and `key_err`: an estimate's value and error (null when absent).
pub(crate) fn put(m: &mut Map<String, Value>, key: &str, e: Option<Estimate>) {
    m.insert(key.into(), json!(e.map(|e| e.value)));
    m.insert(format!("{key}_err"), json!(e.map(|e| e.err)));
}

/// One check as JSON: name, value (with `_err`) and its unit, limit, utilisation, margin, pass.
pub(crate) fn check_json(ch: &CheckResult) -> Map<String, Value> {
    let unit = if ch.kind == CheckKind::MinThickness {
        "m"
    } else {
        "Pa"
    };
    let mut m = Map::new();
    m.insert("name".into(), json!(ch.kind.name()));
    m.insert("value".into(), json!(ch.value.value));
    m.insert("value_err".into(), json!(ch.value.err));
    m.insert("unit".into(), json!(unit));
    m.insert("limit".into(), json!(ch.limit));
    m.insert("utilisation".into(), json!(ch.margin.map(|m| 1.0 - m)));
    m.insert("margin".into(), json!(ch.margin));
    m.insert("pass".into(), json!(ch.pass));
    m
}

/// `min_thickness_m` (with `_err`) and `min_thickness_governing_check`.
pub(crate) fn put_min_thickness(
    m: &mut Map<String, Value>,
    min: Option<&crate::check::MinThickness>,
) {
    put(m, "min_thickness_m", min.and_then(|mt| mt.thickness));
    m.insert(
        "min_thickness_governing_check".into(),
        json!(min.and_then(|mt| mt.governing).map(CheckKind::name)),
    );
}

/// The keys a report's JSON (a film's or a stack's) starts with: the versions, the verdict, the
/// thickness (a stack's of the layer `criteria.thickness_of`) and the pressure.
pub(super) fn put_head(m: &mut Map<String, Value>, pass: bool, thickness: f64, pressure: f64) {
    m.insert("schema_version".into(), json!(super::SCHEMA_VERSION));
    m.insert("coatcheck_version".into(), json!(env!("CARGO_PKG_VERSION")));
    m.insert("verdict".into(), json!(if pass { "pass" } else { "fail" }));
    m.insert("thickness_m".into(), json!(thickness));
    m.insert("pressure_pa".into(), json!(pressure));
}

/// The sliding keys of an interface under the vector rule (a film's, a stack's at each
/// interface and at the top level its bottom interface's): the mean shear, the rms of τ_x and
/// τ_y and the paper's rule's peak of the static shear, each with `_err`.
pub(super) fn put_sliding(
    m: &mut Map<String, Value>,
    s: &SlidingShear,
    tau_peak_static: Option<Estimate>,
) {
    put(m, "mean_interface_shear_pa", Some(s.mean));
    put(m, "tau_x_rms_interface_pa", Some(s.tau_x_rms));
    put(m, "tau_y_rms_interface_pa", Some(s.tau_y_rms));
    put(m, "tau_peak_static_pa", tau_peak_static);
}

/// The JSON object (see the module docs for the keys).
pub fn json(scene: &Scene, outcome: &Outcome, levers: &[Lever]) -> Value {
    let ev = &outcome.evaluation;
    let c = &ev.contact;
    let mut m = Map::new();
    put_head(&mut m, outcome.pass, outcome.thickness, scene.pressure);
    put(&mut m, "area_fraction", Some(c.area_fraction));
    put(
        &mut m,
        "mean_contact_pressure_pa",
        Some(ev.mean_contact_pressure),
    );
    put(&mut m, "sigma_rms_top_pa", c.sigma_rms_top);
    put(&mut m, "sigma_rms_interface_pa", c.sigma_rms_interface);
    put(&mut m, "tau_rms_interface_pa", c.tau_rms_interface);
    put(&mut m, "tau_peak_pa", ev.tau_peak);
    put(&mut m, "sigma_peak_interface_pa", ev.sigma_peak_interface);
    put(&mut m, "e_eff_over_e_film", c.e_eff_over_e_film);
    if let Some(s) = &ev.sliding {
        m.insert("shear_tail".into(), json!(ev.shear_tail.name()));
        m.insert("friction".into(), json!(s.friction));
        put_sliding(&mut m, s, ev.tau_peak_static);
        m.insert("friction_coupling".into(), json!(s.coupling));
    }
    m.insert("bond_exceedance".into(), json!(ev.bond_exceedance));
    m.insert("yield_exceedance".into(), json!(ev.yield_exceedance));
    put_min_thickness(&mut m, outcome.min_thickness.as_ref());
    m.insert(
        "governing_check".into(),
        json!(outcome.governing.map(CheckKind::name)),
    );
    let checks: Vec<Value> = outcome
        .checks
        .iter()
        .map(|ch| Value::Object(check_json(ch)))
        .collect();
    m.insert("checks".into(), Value::Array(checks));
    m.insert("levers".into(), json!(levers));
    m.insert("low_octave_share".into(), json!(c.low_octave_share));
    m.insert("h_rms_m".into(), json!(outcome.h_rms));
    m.insert("rms_slope".into(), json!(outcome.rms_slope));
    m.insert("warnings".into(), json!(outcome.warnings));
    m.insert(
        "scene".into(),
        json!({
            "roughness": scene.roughness,
            "film": scene.film,
            "substrate": scene.substrate,
            "bond": scene.bond,
            "criteria": scene.criteria,
            "rtol": scene.settings.rtol,
            "overrides": scene.overrides,
        }),
    );
    Value::Object(m)
}
