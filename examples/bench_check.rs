//! Benchmark of `coatcheck check` on the 1000-point measured PSD (examples/measured-rolloff.*):
//! the median time of a full check with d_min in-process, of the bond-shear check alone, of the
//! steps around the engine (scene and materials, PSD file, report), and of the whole command
//! (process start, reading, output) beside the process floor (`coatcheck --version`) and
//! `coatcheck materials`, when the release binary exists next to this example's target dir.
//!
//! Run: `cargo build --release && cargo run --release --example bench_check`

use coatcheck::check::{Checker, Checks};
use coatcheck::material::Library;
use coatcheck::report;
use coatcheck::scene::Scene;
use std::path::PathBuf;
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

    rows.push((
        "scene file and its materials (fresh library)".into(),
        time(reps, || {
            let lib = Library::builtin().unwrap();
            Scene::load(Some(&scene_path), &[], &lib).unwrap();
        }),
    ));
    rows.push((
        "PSD file to spectrum (read, validate, rms slope)".into(),
        time(reps, || {
            scene.roughness.spectrum().unwrap();
        }),
    ));
    let outcome = c.run(d).unwrap();
    rows.push((
        "report: tables".into(),
        time(reps, || {
            report::human(&scene, &outcome, &[]);
        }),
    ));
    rows.push((
        "report: JSON".into(),
        time(reps, || {
            report::json(&scene, &outcome, &[]).to_string();
        }),
    ));

    // The release binary of the same target dir: <target>/release/examples/bench_check.
    let bin = std::env::current_exe()
        .ok()
        .and_then(|e| Some(e.parent()?.parent()?.join("coatcheck")))
        .filter(|b| b.exists());
    if let Some(bin) = bin {
        for (label, args) in [
            (
                "process floor: coatcheck --version",
                vec!["--version".to_string()],
            ),
            (
                "coatcheck materials (library listing)",
                vec!["materials".into()],
            ),
            (
                "whole command, full check + d_min",
                vec!["check".into(), scene_path.display().to_string()],
            ),
            (
                "whole command, --checks bond-shear",
                vec![
                    "check".into(),
                    scene_path.display().to_string(),
                    "--checks".into(),
                    "bond-shear".into(),
                ],
            ),
        ] {
            rows.push((
                label.into(),
                time(50, || {
                    let o = std::process::Command::new(&bin)
                        .args(&args)
                        .output()
                        .unwrap();
                    assert!(o.status.code().is_some_and(|c| c <= 1));
                }),
            ));
        }
    } else {
        println!("(no release coatcheck binary: run `cargo build --release` to time the command)");
    }
    println!(
        "1000-point measured PSD, median of up to {reps} repetitions; d_min used {evals} engine evaluations"
    );
    println!("{:<64} {:>12}", "what", "median");
    for (label, t) in rows {
        println!("{label:<64} {:>9.3} ms", t.as_secs_f64() * 1e3);
    }
}
