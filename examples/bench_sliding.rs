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
use std::time::Instant;

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
        let mut times: Vec<(f64, f64)> = Vec::with_capacity(REPS);
        let (mut es, mut ef) = (0, 0);
        for i in 0..WARM_UP + REPS {
            let (ts, e) = timed_check(&spectrum, &stat, scene.settings, d);
            es = e;
            let (tf, e) = timed_check(&spectrum, &sliding, scene.settings, d);
            ef = e;
            if i >= WARM_UP {
                times.push((ts, tf));
            }
        }
        let median = |mut v: Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let ts = median(times.iter().map(|t| t.0).collect());
        let tf = median(times.iter().map(|t| t.1).collect());
        println!(
            "| {name} | {:.2} ms, {es} | {:.2} ms, {ef} | {:.2} |",
            ts / 1e3,
            tf / 1e3,
            tf / ts
        );
    }
}

/// The wall time (µs) of one full check of `design` at thickness `d`, from the checker's
/// set-up, and the engine evaluations of its d_min search.
fn timed_check(
    spectrum: &Spectrum,
    design: &Design,
    settings: coatcheck::prec::Settings,
    d: f64,
) -> (f64, usize) {
    let t = Instant::now();
    let c = Checker::new(spectrum, design.clone(), settings).unwrap();
    let out = c.run(d).unwrap();
    let us = t.elapsed().as_secs_f64() * 1e6;
    (us, out.min_thickness.unwrap().evaluations)
}
