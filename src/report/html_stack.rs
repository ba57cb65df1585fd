//! The HTML report's section of a layer stack ([`super::html`]): the checks with where they
//! apply, what alone would make a failing stack pass, the layers with their sources, the
//! results on the top surface and the contact, every interface's stresses, the spectrum plot,
//! the warnings and the uncertainty (with `--robust`: the materials' ranges, the robust verdict
//! and each check at its worst corner).

use super::check::{check_cells, scene_rows};
use super::html::{Section, lever_text, spectrum_plot};
use super::{margin_cell, modulus, mpa, sig, um, utilisation_cell};
use crate::Error;
use crate::check::stack::{StackDesign, StackOutcome};
use crate::pipeline::Judged;
use crate::prec::Estimate;
use crate::scene::Scene;

/// An estimate in MPa with its error ("0.2216 ± 2.4e-11 MPa").
fn pm_mpa(e: &Estimate) -> String {
    format!("{} ± {} MPa", mpa(e.value), sig(e.err * 1e-6, 2))
}

/// The inputs table of a stack's scene: the scene's rows without the film's (the top layer's
/// in a stack: the layers' rows replace them), a row per layer, `thickness_of` and the sources.
fn inputs(scene: &Scene, design: &StackDesign) -> Vec<(String, String)> {
    let mut inputs: Vec<(String, String)> = scene_rows(scene)
        .into_iter()
        .filter(|(k, _)| !matches!(k.as_str(), "film" | "film thickness" | "bond"))
        .collect();
    for (l, s) in design.layers.iter().zip(&scene.layers) {
        inputs.push((
            format!("layer '{}'", l.name),
            format!(
                "{}: E = {}, nu = {}, thickness {} µm; bond to below: {} ({} MPa)",
                s.material.name,
                modulus(l.material.youngs),
                l.material.poisson,
                um(l.thickness),
                s.bond.name,
                mpa(l.bond_strength)
            ),
        ));
    }
    inputs.push((
        "thickness_of".into(),
        format!(
            "layer '{}' (min-thickness varies it, the others fixed)",
            design.layers[design.thickness_of].name
        ),
    ));
    for s in &scene.layers {
        inputs.push((
            format!("source of {}", s.material.name),
            s.material.source.clone(),
        ));
        inputs.push((format!("source of {}", s.bond.name), s.bond.source.clone()));
    }
    inputs.push((
        format!("source of {}", scene.substrate.name),
        scene.substrate.source.clone(),
    ));
    inputs.dedup();
    inputs
}

/// The section of one judged stack `o` (its scene and levers in `j`).
pub fn section(title: &str, j: &Judged, o: &StackOutcome) -> Result<Section, Error> {
    let scene = &j.scene;
    let design = scene.stack_design();
    let (spectrum, _) = scene.roughness.spectrum()?;
    let checks = o
        .checks
        .iter()
        .map(|c| {
            let (v, l) = check_cells(&c.result);
            [
                format!("{} at {}", c.result.kind.name(), c.at),
                v,
                l,
                utilisation_cell(c.result.margin),
                margin_cell(c.result.margin),
                if c.result.pass { "PASS" } else { "FAIL" }.into(),
            ]
        })
        .collect();
    let headline = match o.governing() {
        Some(c) => format!(
            "governing check: {} at {}{}",
            c.result.kind.name(),
            c.at,
            c.result
                .margin
                .map(|m| format!(" (utilisation {:.1} %)", 100.0 * (1.0 - m)))
                .unwrap_or_default()
        ),
        None => "no check enabled".into(),
    };
    let headline = match &j.stack_robust {
        Some(r) => format!(
            "{headline}; robust (worst corner of the materials' ranges): {}",
            if r.pass { "PASS" } else { "FAIL" }
        ),
        None => headline,
    };
    let inputs = inputs(scene, &design);
    let c = &o.contact.top;
    let mut results = vec![
        ("A/A0 (real contact area fraction)".into(), {
            let a = c.area_fraction;
            format!("{} ± {}", sig(a.value, 4), sig(a.err, 2))
        }),
        (
            "mean pressure in real contact p0·A0/A".into(),
            pm_mpa(&o.mean_contact_pressure),
        ),
    ];
    if let Some(s) = &c.sigma_rms_top {
        results.push(("sigma_rms top surface".into(), pm_mpa(s)));
    }
    results.push((
        "h_rms of the spectrum used".into(),
        format!("{} µm", um(o.h_rms)),
    ));
    results.push(("rms slope of the spectrum used".into(), sig(o.rms_slope, 4)));
    let interfaces = o
        .interfaces
        .iter()
        .map(|i| {
            // The units are in the table's header.
            let pm = |e: &Estimate| format!("{} ± {}", mpa(e.value), sig(e.err * 1e-6, 2));
            [
                i.name.clone(),
                um(i.depth),
                pm(&i.sigma_rms),
                pm(&i.tau_rms),
                pm(&i.tau_peak),
                pm(&i.sigma_peak),
                format!("{:.2e}", i.bond_exceedance),
            ]
        })
        .collect();
    let depth: f64 = design.layers.iter().map(|l| l.thickness).sum();
    let (lo, _) = spectrum.support();
    let mut uncertainty = vec![
        format!(
            "Numerical: each result above carries its estimated numerical error (relative \
             tolerance {}).",
            sig(scene.settings.rtol, 4)
        ),
        format!(
            "Model: {} of the contact stress variance comes from the lowest octave of the \
             spectrum (q_L z = {} at the bottom interface). Above 0.5 a few long waves carry the \
             contact, where Persson's theory under-estimates the contact area, and its contact \
             pressures are then conservative.",
            sig(c.low_octave_share, 4),
            sig(lo * depth, 4)
        ),
        "Materials: the moduli and strengths are the library's values (sources above); their \
         spread is not propagated."
            .into(),
    ];
    if let Some(r) = &j.stack_robust {
        uncertainty.pop();
        uncertainty.extend(super::stack_robust::sentences(r, &design, o));
    }
    Ok(Section {
        title: title.to_string(),
        pass: j.pass(),
        headline,
        checks,
        levers: j.levers.iter().map(lever_text).collect(),
        inputs,
        results,
        interfaces,
        exact: Vec::new(),
        plots: vec![spectrum_plot(&spectrum)?],
        warnings: j.warnings.clone(),
        uncertainty,
    })
}
