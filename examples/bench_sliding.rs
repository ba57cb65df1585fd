//! Benchmark of the check under sliding friction against the static one: the median time of a
//! full check with d_min (engine set-up, evaluation, checks, d_min search) on the paper's scene
//! (examples/paper-rubber-on-steel.toml) and on the 1000-point measured PSD
//! (examples/measured-rolloff.toml), static (μ = 0, the paper's rule) and sliding (μ = 0.5, the
//! vector rule), with the ratio of the medians and the engine evaluations of the d_min search.
//!
//! Run: `cargo run --release --example bench_sliding`

#[path = "common/timing.rs"]
mod timing;

use coatcheck::check::Checker;
use coatcheck::material::Library;
use coatcheck::scene::Scene;
use std::path::PathBuf;

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let lib = Library::builtin().unwrap();
    println!(
        "| scene | static: median, evaluations | sliding mu = 0.5: median, evaluations | ratio |"
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
        let run = |design: &coatcheck::check::Design| {
            let mut evals = 0;
            let t = timing::median_us(41, || {
                let c = Checker::new(&spectrum, design.clone(), scene.settings).unwrap();
                let out = c.run(d).unwrap();
                evals = out.min_thickness.as_ref().unwrap().evaluations;
            });
            (t, evals)
        };
        let (ts, es) = run(&stat);
        let (tf, ef) = run(&sliding);
        println!(
            "| {name} | {:.2} ms, {es} | {:.2} ms, {ef} | {:.2} |",
            ts / 1e3,
            tf / 1e3,
            tf / ts
        );
    }
}
