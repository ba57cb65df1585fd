//! The report of a layer-stack check ([`crate::check::stack`]): JSON and a human table.
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

use crate::check::CheckKind;
use crate::check::stack::StackOutcome;
use crate::prec::Estimate;
use crate::scene::Scene;
use comfy_table::{Table, presets::UTF8_FULL};
use serde_json::{Map, Value, json};

fn put(m: &mut Map<String, Value>, key: &str, e: Option<Estimate>) {
    m.insert(key.into(), json!(e.map(|e| e.value)));
    m.insert(format!("{key}_err"), json!(e.map(|e| e.err)));
}

/// The JSON object (module docs).
pub fn json(scene: &Scene, o: &StackOutcome) -> Value {
    let c = &o.contact.top;
    let bottom = o.interfaces.last().expect("a stack has an interface");
    let design = scene.stack_design();
    let mut m = Map::new();
    m.insert("schema_version".into(), json!(super::SCHEMA_VERSION));
    m.insert("coatcheck_version".into(), json!(env!("CARGO_PKG_VERSION")));
    m.insert(
        "verdict".into(),
        json!(if o.pass { "pass" } else { "fail" }),
    );
    m.insert(
        "thickness_m".into(),
        json!(design.layers[design.thickness_of].thickness),
    );
    m.insert("pressure_pa".into(), json!(scene.pressure));
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
    let (dmin, dmin_gov) = match &o.min_thickness {
        Some(mt) => (mt.thickness, mt.governing),
        None => (None, None),
    };
    put(&mut m, "min_thickness_m", dmin);
    m.insert(
        "min_thickness_governing_check".into(),
        json!(dmin_gov.map(CheckKind::name)),
    );
    let governing = o
        .checks
        .iter()
        .min_by(|a, b| {
            let ma = a.result.margin.unwrap_or(f64::NEG_INFINITY);
            let mb = b.result.margin.unwrap_or(f64::NEG_INFINITY);
            ma.total_cmp(&mb)
        })
        .map(|c| c.result.kind.name());
    m.insert("governing_check".into(), json!(governing));
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
            Value::Object(v)
        })
        .collect();
    m.insert("interfaces".into(), Value::Array(interfaces));
    let checks: Vec<Value> = o
        .checks
        .iter()
        .map(|c| {
            let ch = &c.result;
            json!({
                "name": ch.kind.name(),
                "at": c.at,
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
    m.insert("warnings".into(), json!(o.warnings));
    m.insert(
        "scene".into(),
        json!({
            "roughness": scene.roughness,
            "film": scene.film,
            "substrate": scene.substrate,
            "bond": scene.bond,
            "layers": scene.layers,
            "thickness_of": design.layers[design.thickness_of].name,
            "criteria": scene.criteria,
            "rtol": scene.settings.rtol,
        }),
    );
    Value::Object(m)
}

fn pm(e: &Estimate) -> String {
    format!("{:.6e} ± {:.1e}", e.value, e.err)
}

/// The human report: the contact, every interface, the checks.
pub fn human(scene: &Scene, o: &StackOutcome) -> String {
    let c = &o.contact.top;
    let mut out = String::new();
    let mut layers = Table::new();
    layers.load_preset(UTF8_FULL).set_header([
        "layer",
        "E",
        "ν",
        "thickness (m)",
        "bond to below (Pa)",
    ]);
    for l in &scene.stack_design().layers {
        layers.add_row([
            l.name.clone(),
            format!("{:.4e} Pa", l.material.youngs),
            format!("{}", l.material.poisson),
            format!("{:.4e}", l.thickness),
            format!("{:.4e}", l.bond_strength),
        ]);
    }
    out += &format!(
        "{layers}\nsubstrate: {} (E = {:.4e} Pa, ν = {}), p0 = {:.4e} Pa\n\n",
        scene.substrate.name,
        scene.substrate.elastic.youngs,
        scene.substrate.elastic.poisson,
        scene.pressure
    );
    out += &format!("A/A0               {}\n", pm(&c.area_fraction));
    out += &format!("p0·A0/A (Pa)       {}\n", pm(&o.mean_contact_pressure));
    if let Some(s) = &c.sigma_rms_top {
        out += &format!("σ_rms top (Pa)     {}\n", pm(s));
    }
    let mut t = Table::new();
    t.load_preset(UTF8_FULL).set_header([
        "interface below",
        "depth (m)",
        "σ_rms (Pa)",
        "τ_rms (Pa)",
        "τ_peak (Pa)",
        "σ_peak (Pa)",
        "P(|τ| > bond)",
    ]);
    for i in &o.interfaces {
        t.add_row([
            i.name.clone(),
            format!("{:.4e}", i.depth),
            pm(&i.sigma_rms),
            pm(&i.tau_rms),
            pm(&i.tau_peak),
            pm(&i.sigma_peak),
            format!("{:.3e}", i.bond_exceedance),
        ]);
    }
    out += &format!("{t}\n");
    let mut k = Table::new();
    k.load_preset(UTF8_FULL)
        .set_header(["check", "at", "value", "limit", "margin", "pass"]);
    for c in &o.checks {
        let ch = &c.result;
        k.add_row([
            ch.kind.name().to_string(),
            c.at.clone(),
            pm(&ch.value),
            ch.limit.map_or("none".into(), |l| format!("{l:.4e}")),
            ch.margin.map_or("-".into(), |m| format!("{m:.3}")),
            if ch.pass { "pass" } else { "FAIL" }.into(),
        ]);
    }
    out += &format!("{k}\n");
    for w in &o.warnings {
        out += &format!("warning: {w}\n");
    }
    out += &format!("verdict: {}\n", if o.pass { "PASS" } else { "FAIL" });
    out
}
