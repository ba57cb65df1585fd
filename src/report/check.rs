//! The report of one judged scene: human tables, one JSON object, or CSV.
//!
//! The JSON object carries `verdict`, `area_fraction`, `mean_contact_pressure_pa`,
//! `sigma_rms_top_pa`, `sigma_rms_interface_pa`, `tau_rms_interface_pa`, `tau_peak_pa`,
//! `sigma_peak_interface_pa`, `e_eff_over_e_film`, `min_thickness_m`, `governing_check` and
//! `checks`, each numeric result with a sibling `<key>_err` (its numerical error estimate), plus
//! the inputs and warnings. Under the vector shear rule (sliding friction, or asked for) it also
//! carries `shear_tail`, `friction`, `mean_interface_shear_pa`, `tau_x_rms_interface_pa`,
//! `tau_y_rms_interface_pa` (each with `_err`), `tau_peak_static_pa` (the paper's rule on the
//! static shear, with `_err`) and `friction_coupling`; `tau_peak_pa` is then the vector's peak and
//! `sigma_rms_interface_pa` includes the friction-driven part.

use super::{Format, batch, modulus, mpa, sig, table, um, verify};
use crate::check::{CheckKind, CheckResult, Outcome};
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
        Some(Scale::RmsHeight(h)) => rows.push(("rms height".into(), format!("{} um", um(h)))),
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
        rows.push(("film thickness".into(), format!("{} um", um(d))));
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
fn check_cells(c: &CheckResult) -> (String, String) {
    let f = |x: f64| match c.kind {
        CheckKind::MinThickness => format!("{} um", um(x)),
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
        &mpa_unit,
    );
    row(
        "sigma_peak interface (exceedance epsilon)",
        ev.sigma_peak_interface,
        &mpa_unit,
    );
    row("tau_rms interface", c.tau_rms_interface, &mpa_unit);
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
                &mpa_unit,
            );
            row(
                "tau_y rms interface (fluctuation along y)",
                Some(s.tau_y_rms),
                &mpa_unit,
            );
            row(
                "tau_peak interface (vector rule: |tau| of (mu·p0 + X, Y), exceedance epsilon)",
                ev.tau_peak,
                &mpa_unit,
            );
            row(
                "tau_peak static (paper's half-normal rule)",
                ev.tau_peak_static,
                &mpa_unit,
            );
        }
        None => row(
            "tau_peak interface (exceedance epsilon)",
            ev.tau_peak,
            &mpa_unit,
        ),
    }
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

/// The checks as (check, value, limit, margin, result), as the table shows them.
pub(crate) fn check_rows(outcome: &Outcome) -> Vec<[String; 5]> {
    let ev = &outcome.evaluation;
    outcome
        .checks
        .iter()
        .map(|ch| {
            let (mut v, l) = check_cells(ch);
            if ch.kind == CheckKind::SubstrateYield {
                v += if ch.value.value == ev.mean_contact_pressure.value {
                    " (mean contact pressure)"
                } else {
                    " (interface peak)"
                };
            }
            let margin = ch
                .margin
                .map(|m| format!("{:+.1} %", 100.0 * m))
                .unwrap_or_else(|| "-".into());
            [
                ch.kind.name().to_string(),
                v,
                l,
                margin,
                if ch.pass { "PASS" } else { "FAIL" }.into(),
            ]
        })
        .collect()
}

/// The default output: scene, results, checks, d_min, warnings.
pub fn human(scene: &Scene, outcome: &Outcome) -> String {
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
    let mut t = table(&["check", "value", "limit", "margin", "result"]);
    for r in check_rows(outcome) {
        t.add_row(r.to_vec());
    }
    out += &format!("{t}\n");

    if let Some(m) = &outcome.min_thickness {
        out += &match (m.thickness, m.governing) {
            (None, g) => format!(
                "minimum thickness: no thickness passes (governed by {})\n",
                g.map(CheckKind::name).unwrap_or("-")
            ),
            (Some(d), _) if m.all_pass_to_floor => format!(
                "minimum thickness: every thickness down to {} um passes\n",
                um(d.value)
            ),
            (Some(d), g) => format!(
                "minimum thickness: {} um ± {} um (governed by {})\n",
                um(d.value),
                sig(d.err * 1e6, 2),
                g.map(CheckKind::name).unwrap_or("-")
            ),
        };
    }
    out += &format!(
        "verdict: {}{}\n",
        if outcome.pass { "PASS" } else { "FAIL" },
        outcome
            .governing
            .map(|g| format!(" (governing check: {})", g.name()))
            .unwrap_or_default()
    );
    for w in &outcome.warnings {
        out += &format!("warning: {w}\n");
    }
    out
}

/// The report of one judged scene: the check's tables, JSON or CSV, with the per-file verdicts
/// when the scene lists several roughness files, and the exact section of `check --verify`.
pub fn scene(j: &Judged, format: Format) -> Result<String, Error> {
    let (scene, outcome) = (&j.scene, &j.outcome);
    let ev = &outcome.evaluation;
    let verdict = if j.pass() { "pass" } else { "fail" };
    let several = !j.files.is_empty();
    Ok(match format {
        Format::Table => {
            let mut t = format!("{}{}", batch::files_table(j), human(scene, outcome));
            if let Some(x) = &j.exact {
                t += &format!("\n{}", verify::check_table(&x.map, ev, &x.verification));
            }
            t
        }
        Format::Json => {
            // JSON shows NaN as null: the table of the same numbers is checked instead.
            super::finite_only(&human(scene, outcome))?;
            let mut v = json(scene, outcome);
            if several {
                let worst = j.worst_file().map(|p| p.display().to_string());
                v["worst_file"] = json!(worst);
                v["files"] = json!(j.files);
                v["warnings"] = json!(j.warnings);
            }
            if let (Some(x), Some(o)) = (&j.exact, v.as_object_mut()) {
                o.insert(
                    "verify".into(),
                    verify::check_json(&x.map, ev, &x.verification),
                );
                o.insert("verdict_with_verify".into(), verdict.into());
            }
            format!("{v:#}\n")
        }
        Format::Csv => {
            let mut c = csv(scene, outcome)?;
            if several {
                let worst = j.worst_file().map(|p| p.display().to_string());
                c += &format!("worst_file,{},,\n", worst.unwrap_or_default());
            }
            if let Some(x) = &j.exact {
                c += &verify::check_csv(ev, &x.verification);
                c += &format!("verdict_with_verify,{verdict},,\n");
            }
            c
        }
    })
}

fn put(m: &mut Map<String, Value>, key: &str, e: Option<Estimate>) {
    m.insert(key.into(), json!(e.map(|e| e.value)));
    m.insert(format!("{key}_err"), json!(e.map(|e| e.err)));
}

/// The JSON object (see the module docs for the keys).
pub fn json(scene: &Scene, outcome: &Outcome) -> Value {
    let ev = &outcome.evaluation;
    let c = &ev.contact;
    let mut m = Map::new();
    m.insert("schema_version".into(), json!(super::SCHEMA_VERSION));
    m.insert("coatcheck_version".into(), json!(env!("CARGO_PKG_VERSION")));
    m.insert(
        "verdict".into(),
        json!(if outcome.pass { "pass" } else { "fail" }),
    );
    m.insert("thickness_m".into(), json!(outcome.thickness));
    m.insert("pressure_pa".into(), json!(scene.pressure));
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
        put(&mut m, "mean_interface_shear_pa", Some(s.mean));
        put(&mut m, "tau_x_rms_interface_pa", Some(s.tau_x_rms));
        put(&mut m, "tau_y_rms_interface_pa", Some(s.tau_y_rms));
        put(&mut m, "tau_peak_static_pa", ev.tau_peak_static);
        m.insert("friction_coupling".into(), json!(s.coupling));
    }
    m.insert("bond_exceedance".into(), json!(ev.bond_exceedance));
    m.insert("yield_exceedance".into(), json!(ev.yield_exceedance));
    let (dmin, dmin_gov) = match &outcome.min_thickness {
        Some(mt) => (mt.thickness, mt.governing),
        None => (None, None),
    };
    put(&mut m, "min_thickness_m", dmin);
    m.insert(
        "min_thickness_governing_check".into(),
        json!(dmin_gov.map(CheckKind::name)),
    );
    m.insert(
        "governing_check".into(),
        json!(outcome.governing.map(CheckKind::name)),
    );
    let checks: Vec<Value> = outcome
        .checks
        .iter()
        .map(|ch| {
            json!({
                "name": ch.kind.name(),
                "value": ch.value.value,
                "value_err": ch.value.err,
                "unit": if ch.kind == CheckKind::MinThickness { "m" } else { "Pa" },
                "limit": ch.limit,
                "utilisation": ch.margin.map(|m| 1.0 - m),
                "margin": ch.margin,
                "pass": ch.pass,
            })
        })
        .collect();
    m.insert("checks".into(), Value::Array(checks));
    m.insert("low_octave_share".into(), json!(c.low_octave_share));
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
        }),
    );
    Value::Object(m)
}

/// CSV: one row per result, `quantity,value,err,unit`, then the checks.
pub fn csv(scene: &Scene, outcome: &Outcome) -> Result<String, Error> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let ser = |e: csv::Error| Error::Numerical {
        what: "CSV output",
        detail: e.to_string(),
    };
    w.write_record(["quantity", "value", "err", "unit"])
        .map_err(ser)?;
    let ev = &outcome.evaluation;
    let c = &ev.contact;
    let num = |x: Option<f64>| x.map(|x| format!("{x:e}")).unwrap_or_default();
    let mut rows: Vec<(&str, Option<Estimate>, &str)> = vec![
        ("area_fraction", Some(c.area_fraction), "1"),
        (
            "mean_contact_pressure",
            Some(ev.mean_contact_pressure),
            "Pa",
        ),
        ("sigma_rms_top", c.sigma_rms_top, "Pa"),
        ("sigma_rms_interface", c.sigma_rms_interface, "Pa"),
        ("tau_rms_interface", c.tau_rms_interface, "Pa"),
        ("tau_peak", ev.tau_peak, "Pa"),
        ("sigma_peak_interface", ev.sigma_peak_interface, "Pa"),
        ("e_eff_over_e_film", c.e_eff_over_e_film, "1"),
        (
            "min_thickness",
            outcome.min_thickness.as_ref().and_then(|m| m.thickness),
            "m",
        ),
    ];
    if let Some(s) = &ev.sliding {
        rows.extend([
            ("mean_interface_shear", Some(s.mean), "Pa"),
            ("tau_x_rms_interface", Some(s.tau_x_rms), "Pa"),
            ("tau_y_rms_interface", Some(s.tau_y_rms), "Pa"),
            ("tau_peak_static", ev.tau_peak_static, "Pa"),
        ]);
    }
    w.write_record(["thickness", &format!("{:e}", outcome.thickness), "", "m"])
        .map_err(ser)?;
    w.write_record(["pressure", &format!("{:e}", scene.pressure), "", "Pa"])
        .map_err(ser)?;
    for (k, e, unit) in rows {
        w.write_record([k, &num(e.map(|e| e.value)), &num(e.map(|e| e.err)), unit])
            .map_err(ser)?;
    }
    for ch in &outcome.checks {
        let unit = if ch.kind == CheckKind::MinThickness {
            "m"
        } else {
            "Pa"
        };
        w.write_record([
            &format!("check:{}", ch.kind.name()),
            &format!("{:e}", ch.value.value),
            &format!("{:e}", ch.value.err),
            unit,
        ])
        .map_err(ser)?;
        w.write_record([
            &format!("limit:{}", ch.kind.name()),
            &num(ch.limit),
            "",
            unit,
        ])
        .map_err(ser)?;
        w.write_record([
            format!("pass:{}", ch.kind.name()).as_str(),
            if ch.pass { "1" } else { "0" },
            "",
            "",
        ])
        .map_err(ser)?;
    }
    w.write_record([
        "verdict",
        if outcome.pass { "pass" } else { "fail" },
        "",
        "",
    ])
    .map_err(ser)?;
    let bytes = w.into_inner().map_err(|e| Error::Numerical {
        what: "CSV output",
        detail: e.to_string(),
    })?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}
