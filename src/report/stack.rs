//! The report of a layer-stack check ([`crate::check::stack`]): JSON and a human table, and
//! the one-row CSV of the batch's shape ([`super::batch`]); the levers of a failing stack
//! ([`crate::check::stack_levers`]) follow the verdict as for a film.
//!
//! JSON: the top-level keys of a film's report (`check.schema.json`) for the top surface and
//! the contact (`area_fraction`, `sigma_rms_top_pa`, `mean_contact_pressure_pa`, …), with
//! `thickness_m` the thickness of the layer `criteria.thickness_of` names and the film's
//! interface keys (`sigma_rms_interface_pa`, `tau_rms_interface_pa`, `tau_peak_pa`,
//! `sigma_peak_interface_pa`) those of the bottom interface (on the substrate); then
//! `interfaces`, top first: `name` (the layer above it), `depth_m`, `sigma_rms_pa`,
//! `tau_rms_pa`, `tau_peak_pa`, `sigma_peak_pa` (each with `_err`), `bond_strength_pa`,
//! `bond_exceedance`; each check names where it applies (`at`: a layer, or `substrate`); the
//! scene echo lists the layers (`scene.layers`) and `thickness_of`.
//!
//! Under the vector shear rule (sliding friction, or asked for) the report carries, as a film's,
//! `shear_tail` and `friction`, and every interface the film's sliding keys
//! `mean_interface_shear_pa`, `tau_x_rms_interface_pa`, `tau_y_rms_interface_pa` and
//! `tau_peak_static_pa` (each with `_err`; the top level those of the bottom interface);
//! `tau_peak_pa` and `bond_exceedance` are then the vector's and `sigma_rms_pa` includes the
//! friction-driven part. The table says which rule the peaks follow and lists the shear vector
//! at every interface. (A stack's normal–tangential coupling, the film's `friction_coupling`,
//! is not evaluated.)

use super::check::{
    check_cells, check_json, put, put_files, put_head, put_min_thickness, put_sliding, scene_csv,
};
use super::{Format, batch, margin_cell, modulus, mpa, sig, table, um, utilisation_cell, wrap};
use crate::check::ShearTail;
use crate::check::levers::Lever;
use crate::check::stack::{InterfaceEvaluation, StackOutcome};
use crate::error::Error;
use crate::pipeline::Judged;
use crate::prec::Estimate;
use crate::scene::Scene;
use serde_json::{Map, Value, json};

/// The report of a judged layer stack (its outcome `o`): the table or JSON, with the per-file
/// verdicts when the scene lists several roughness files; CSV is the batch's one row
/// ([`batch::records_csv`]).
pub fn scene(j: &Judged, o: &StackOutcome, format: Format) -> Result<String, Error> {
    let scene = &j.scene;
    Ok(match format {
        Format::Table => {
            let mut t = format!("{}{}", batch::files_table(j), human(scene, o, &j.levers));
            if let Some(x) = &j.stack_exact {
                t += &format!("\n{}", super::verify_stack::check_table(x, o));
                t += &format!("boundary of the exact solve: {}\n", x.boundary.describe());
            }
            if let Some(r) = &j.stack_robust {
                t += &format!(
                    "\n{}",
                    super::stack_robust::table_text(r, &scene.stack_design(), o)
                );
            }
            t
        }
        Format::Json => {
            // JSON shows NaN as null: the table of the same numbers is checked instead.
            super::finite_only(&human(scene, o, &j.levers))?;
            let mut v = json(scene, o, &j.levers);
            if let Some(x) = &j.stack_exact {
                super::finite_only(&super::verify_stack::check_table(x, o))?;
                v["verify"] = super::verify_stack::check_json(x, o);
                v["exact"] = super::verify_stack::exact_json(x, o);
                v["verify"]["boundary"] = x.boundary.json();
                v["verdict_with_verify"] = json!(if j.pass() { "pass" } else { "fail" });
            }
            if let Some(r) = &j.stack_robust {
                v["robust"] = super::stack_robust::json_value(r, &scene.stack_design(), o);
                v["verdict_with_robust"] = json!(if j.pass() { "pass" } else { "fail" });
            }
            put_files(&mut v, j);
            format!("{v:#}\n")
        }
        Format::Csv => scene_csv(j)?,
    })
}

/// The JSON object (module docs).
pub fn json(scene: &Scene, o: &StackOutcome, levers: &[Lever]) -> Value {
    let c = &o.contact.top;
    let bottom = o.interfaces.last().expect("a stack has an interface");
    let design = scene.stack_design();
    let mut m = Map::new();
    let thickness = design.layers[design.thickness_of].thickness;
    put_head(&mut m, o.pass, thickness, scene.pressure);
    put(&mut m, "area_fraction", Some(c.area_fraction));
    put(
        &mut m,
        "mean_contact_pressure_pa",
        Some(o.mean_contact_pressure),
    );
    put(&mut m, "sigma_rms_top_pa", c.sigma_rms_top);
    put(&mut m, "sigma_rms_interface_pa", Some(bottom.sigma_rms));
    put(&mut m, "tau_rms_interface_pa", Some(bottom.tau_rms));
    put(&mut m, "tau_peak_pa", Some(bottom.tau_peak));
    put(&mut m, "sigma_peak_interface_pa", Some(bottom.sigma_peak));
    put(&mut m, "e_eff_over_e_film", c.e_eff_over_e_film);
    if let Some(s) = &bottom.sliding {
        m.insert("shear_tail".into(), json!(o.shear_tail.name()));
        m.insert("friction".into(), json!(s.friction));
        put_interface_sliding(&mut m, bottom);
    }
    put_min_thickness(&mut m, o.min_thickness.as_ref());
    m.insert(
        "governing_check".into(),
        json!(o.governing().map(|c| c.result.kind.name())),
    );
    let interfaces: Vec<Value> = o
        .interfaces
        .iter()
        .map(|i| {
            let mut v = Map::new();
            v.insert("name".into(), json!(i.name));
            v.insert("depth_m".into(), json!(i.depth));
            put(&mut v, "sigma_rms_pa", Some(i.sigma_rms));
            put(&mut v, "tau_rms_pa", Some(i.tau_rms));
            put(&mut v, "tau_peak_pa", Some(i.tau_peak));
            put(&mut v, "sigma_peak_pa", Some(i.sigma_peak));
            v.insert("bond_strength_pa".into(), json!(i.bond_strength));
            v.insert("bond_exceedance".into(), json!(i.bond_exceedance));
            put_interface_sliding(&mut v, i);
            Value::Object(v)
        })
        .collect();
    m.insert("interfaces".into(), Value::Array(interfaces));
    let checks: Vec<Value> = o
        .checks
        .iter()
        .map(|c| {
            let mut m = check_json(&c.result);
            m.insert("at".into(), json!(c.at));
            Value::Object(m)
        })
        .collect();
    m.insert("checks".into(), Value::Array(checks));
    m.insert("low_octave_share".into(), json!(c.low_octave_share));
    m.insert("h_rms_m".into(), json!(o.h_rms));
    m.insert("rms_slope".into(), json!(o.rms_slope));
    m.insert("levers".into(), json!(levers));
    m.insert("warnings".into(), json!(o.warnings));
    m.insert(
        "scene".into(),
        json!({
            "roughness": scene.roughness,
            "film": scene.film,
            "substrate": scene.substrate,
            "bond": scene.bond,
            "overrides": scene.overrides,
            "layers": scene.layers,
            "thickness_of": design.layers[design.thickness_of].name,
            "criteria": scene.criteria,
            "rtol": scene.settings.rtol,
        }),
    );
    Value::Object(m)
}

/// The film's sliding keys of an interface under the vector rule (none otherwise).
fn put_interface_sliding(m: &mut Map<String, Value>, i: &InterfaceEvaluation) {
    if let Some(s) = &i.sliding {
        put_sliding(m, s, i.tau_peak_static);
    }
}

/// The rule of the peaks and, under the vector rule, the shear vector at every interface
/// (empty for the paper's rule).
fn sliding_table(scene: &Scene, o: &StackOutcome) -> String {
    if o.shear_tail != ShearTail::Vector {
        return String::new();
    }
    let mut out = wrap(&format!(
        "tau_peak and P(|tau| > bond) by the vector rule: |tau| of (mu·p0 + X, Y) at exceedance \
         epsilon, mu = {} (uncoupled approximation: the pressure is that of frictionless \
         contact; sigma_rms includes the friction-driven part)",
        scene.friction
    ));
    out.push('\n');
    let mut t = table(&[
        "interface below",
        "mean shear μ·p0 [MPa]",
        "τ_x,rms [MPa]",
        "τ_y,rms [MPa]",
        "τ_peak static [MPa]",
    ]);
    for i in &o.interfaces {
        let Some(s) = &i.sliding else { continue };
        t.add_row([
            i.name.clone(),
            mpa(s.mean.value),
            pm_mpa(&s.tau_x_rms),
            pm_mpa(&s.tau_y_rms),
            i.tau_peak_static.as_ref().map_or("-".into(), pm_mpa),
        ]);
    }
    out + &format!("{t}\n")
}

/// An estimate in MPa with its error ("0.2216 ± 2.4e-11").
fn pm_mpa(e: &Estimate) -> String {
    format!("{} ± {}", mpa(e.value), sig(e.err * 1e-6, 2))
}

/// The human report: the layers, the contact, every interface, the checks, the verdict; in the
/// units of every table (MPa, µm) and at most [`super::WIDTH`] columns.
pub fn human(scene: &Scene, o: &StackOutcome, levers: &[Lever]) -> String {
    let c = &o.contact.top;
    let mut out = String::new();
    let mut layers = table(&["layer", "E", "ν", "thickness", "bond to below"]);
    for l in &scene.stack_design().layers {
        layers.add_row([
            l.name.clone(),
            modulus(l.material.youngs),
            format!("{}", l.material.poisson),
            format!("{} µm", um(l.thickness)),
            format!("{} MPa", mpa(l.bond_strength)),
        ]);
    }
    out += &format!("{layers}\n");
    out += &wrap(&format!(
        "substrate: {} (E = {}, ν = {}), p0 = {} MPa",
        scene.substrate.name,
        modulus(scene.substrate.elastic.youngs),
        scene.substrate.elastic.poisson,
        mpa(scene.pressure)
    ));
    out.push('\n');
    let mut t = table(&["result", "value", "error estimate"]);
    let est = |e: &Estimate, unit: &str, scale: f64| {
        [
            format!("{}{unit}", sig(e.value * scale, 4)),
            format!("{}{unit}", sig(e.err * scale, 3)),
        ]
    };
    let [v, e] = est(&c.area_fraction, "", 1.0);
    t.add_row(["A/A0 (real contact area fraction)".into(), v, e]);
    let [v, e] = est(&o.mean_contact_pressure, " MPa", 1e-6);
    t.add_row(["mean pressure in real contact p0·A0/A".into(), v, e]);
    if let Some(s) = &c.sigma_rms_top {
        let [v, e] = est(s, " MPa", 1e-6);
        t.add_row(["sigma_rms top surface".into(), v, e]);
    }
    t.add_row([
        "h_rms of the spectrum used".into(),
        format!("{} µm", um(o.h_rms)),
        String::new(),
    ]);
    t.add_row([
        "rms slope of the spectrum used".into(),
        sig(o.rms_slope, 4),
        String::new(),
    ]);
    out += &format!("{t}\n");
    let mut t = table(&[
        "interface below",
        "depth",
        "σ_rms [MPa]",
        "τ_rms [MPa]",
        "τ_peak [MPa]",
        "σ_peak [MPa]",
        "P(|τ| > bond)",
    ]);
    for i in &o.interfaces {
        t.add_row([
            i.name.clone(),
            format!("{} µm", um(i.depth)),
            pm_mpa(&i.sigma_rms),
            pm_mpa(&i.tau_rms),
            pm_mpa(&i.tau_peak),
            pm_mpa(&i.sigma_peak),
            format!("{:.2e}", i.bond_exceedance),
        ]);
    }
    out += &format!("{t}\n");
    out += &sliding_table(scene, o);
    let mut k = table(&[
        "check",
        "at",
        "value",
        "limit",
        "utilisation",
        "margin",
        "result",
    ]);
    for c in &o.checks {
        let ch = &c.result;
        let (v, l) = check_cells(ch);
        k.add_row([
            ch.kind.name().to_string(),
            c.at.clone(),
            v,
            l,
            utilisation_cell(ch.margin),
            margin_cell(ch.margin),
            if ch.pass { "PASS" } else { "FAIL" }.into(),
        ]);
    }
    out += &format!("{k}\n");
    let governing = o.governing();
    out += &format!(
        "verdict: {}{}\n",
        if o.pass { "PASS" } else { "FAIL" },
        governing
            .map(|c| format!(
                " (governing check: {} at {}, utilisation {})",
                c.result.kind.name(),
                c.at,
                utilisation_cell(c.result.margin)
            ))
            .unwrap_or_default()
    );
    out += &super::check::levers_and_warnings(levers, &o.warnings);
    out
}
