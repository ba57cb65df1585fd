//! Benchmark of `coatcheck check` on the 1000-point measured PSD (examples/measured-rolloff.*):
//! the median time of a full check with d_min in-process, of the bond-shear check alone, and of
//! the whole command (process start, reading, output) when the release binary exists.
//!
//! Run: `cargo build --release && cargo run --release --example bench_check`

use coatcheck::check::{Checker, Checks};
use coatcheck::material::Library;
use coatcheck::scene::Scene;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

/// Median of `reps` runs (fewer when one run is slow: at most about 3 s per row, at least 5).
fn time(reps: usize, mut f: impl FnMut()) -> Duration {
    let t = Instant::now();
    f();
    let one = t.elapsed().as_secs_f64();
    let reps = reps.min((3.0 / one) as usize).max(5);
    median(
        (0..reps)
            .map(|_| {
                let t = Instant::now();
                f();
                t.elapsed()
            })
            .collect(),
    )
}

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let scene_path = root.join("examples/measured-rolloff.toml");
    let lib = Library::builtin().unwrap();
    let scene = Scene::load(Some(&scene_path), &[], &lib).unwrap();
    let (spectrum, _) = scene.roughness.spectrum().unwrap();
    let d = scene.thickness.unwrap();
    let reps = 200;

    let mut rows: Vec<(String, Duration)> = Vec::new();
    let mut evals = 0;
    rows.push((
        "full check + d_min (engine set-up, evaluation, checks, d_min)".into(),
        time(reps, || {
            let c = Checker::new(&spectrum, scene.design(), scene.settings).unwrap();
            let out = c.run(d).unwrap();
            evals = out.min_thickness.as_ref().unwrap().evaluations;
        }),
    ));
    rows.push((
        "full check + d_min, including reading scene and PSD".into(),
        time(reps, || {
            let s = Scene::load(Some(&scene_path), &[], &lib).unwrap();
            let (sp, _) = s.roughness.spectrum().unwrap();
            let c = Checker::new(&sp, s.design(), s.settings).unwrap();
            c.run(d).unwrap();
        }),
    ));
    let mut bond_only = scene.design();
    bond_only.criteria.checks = Checks {
        bond_shear: true,
        substrate_yield: false,
        min_thickness: false,
    };
    rows.push((
        "bond-shear only (--checks bond-shear)".into(),
        time(reps, || {
            let c = Checker::new(&spectrum, bond_only.clone(), scene.settings).unwrap();
            c.run(d).unwrap();
        }),
    ));
    let c = Checker::new(&spectrum, scene.design(), scene.settings).unwrap();
    rows.push((
        "one evaluation (all quantities, engine set up)".into(),
        time(reps, || {
            c.evaluate(d).unwrap();
        }),
    ));
    rows.push((
        "d_min search alone, new checker (its engine's grid built)".into(),
        time(reps, || {
            let c = Checker::new(&spectrum, scene.design(), scene.settings).unwrap();
            c.min_thickness().unwrap();
        }),
    ));
    rows.push((
        "d_min search alone (engine set up)".into(),
        time(reps, || {
            c.min_thickness().unwrap();
        }),
    ));

    let bin = root.join("target/release/coatcheck");
    if Path::new(&bin).exists() {
        for (label, extra) in [
            ("whole command, full check + d_min", vec![]),
            (
                "whole command, --checks bond-shear",
                vec!["--checks", "bond-shear"],
            ),
        ] {
            rows.push((
                label.into(),
                time(50, || {
                    let o = std::process::Command::new(&bin)
                        .arg("check")
                        .arg(&scene_path)
                        .args(&extra)
                        .output()
                        .unwrap();
                    assert!(o.status.code().is_some_and(|c| c <= 1));
                }),
            ));
        }
    } else {
        println!("(no target/release/coatcheck: run `cargo build --release` to time the command)");
    }
    println!(
        "1000-point measured PSD, median of up to {reps} repetitions; d_min used {evals} engine evaluations"
    );
    println!("{:<64} {:>12}", "what", "median");
    for (label, t) in rows {
        println!("{label:<64} {:>9.3} ms", t.as_secs_f64() * 1e3);
    }
}
