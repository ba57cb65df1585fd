//! Benchmark of the check under sliding friction against the static one: the median time of a
//! full check with d_min (engine set-up, evaluation, checks, d_min search) on the paper's scene
//! (examples/paper-rubber-on-steel.toml) and on the 1000-point measured PSD
//! (examples/measured-rolloff.toml), static (μ = 0, the paper's rule) and sliding (μ = 0.5, the
//! vector rule), with the ratio of the medians and the engine evaluations of the d_min search.
//! The static and the sliding check run in alternating pairs, so that both see the same load
//! on a shared machine.
//!
//! Run: `cargo run --release --example bench_sliding`

use coatcheck::check::{Checker, Design};
use coatcheck::material::Library;
use coatcheck::psd::Spectrum;
use coatcheck::scene::Scene;
use std::path::PathBuf;

#[path = "common/pairs.rs"]
mod pairs;

/// Timed pairs after this many warm-up pairs.
const REPS: usize = 41;
const WARM_UP: usize = 4;

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let lib = Library::builtin().unwrap();
    println!(
        "| scene | static: median, evaluations | sliding mu = 0.5: median, evaluations | ratio of medians |"
    );
    println!("|---|---|---|---|");
    for name in ["paper-rubber-on-steel", "measured-rolloff"] {
        let path = root.join(format!("examples/{name}.toml"));
        let scene = Scene::load(Some(&path), &[], &lib).unwrap();
        let (spectrum, _) = scene.roughness.spectrum().unwrap();
        let d = scene.thickness.unwrap();
        let stat = scene.design();
        let mut sliding = scene.design();
        sliding.friction = 0.5;
        let (mut es, mut ef) = (0, 0);
        let times = pairs::alternating(
            WARM_UP,
            REPS,
            || es = check(&spectrum, &stat, scene.settings, d),
            || ef = check(&spectrum, &sliding, scene.settings, d),
        );
        let ts = pairs::median(times.iter().map(|t| t.0).collect());
        let tf = pairs::median(times.iter().map(|t| t.1).collect());
        println!(
            "| {name} | {:.2} ms, {es} | {:.2} ms, {ef} | {:.2} |",
            ts / 1e3,
            tf / 1e3,
            tf / ts
        );
    }
}

/// One full check of `design` at thickness `d`, from the checker's set-up: the engine
/// evaluations of its d_min search.
fn check(
    spectrum: &Spectrum,
    design: &Design,
    settings: coatcheck::prec::Settings,
    d: f64,
) -> usize {
    let c = Checker::new(spectrum, design.clone(), settings).unwrap();
    let out = c.run(d).unwrap();
    out.min_thickness.unwrap().evaluations
}
