//! Benchmark of batch runs (`coatcheck check DIR`): throughput in scenes per second of
//! `batch::run_all` (loading, reading PSDs, full checks with d_min, in parallel) on 1 and on all
//! threads, and of the whole command when the release binary exists. The batch is 48 scenes:
//! 16 copies each of the paper's model scene, the 1000-point measured PSD scene and the failing
//! waviness scene, at thicknesses spread over a decade (so the d_min searches differ).
//!
//! Run: `cargo build --release && cargo run --release --example bench_batch`

use coatcheck::batch::run_all;
use coatcheck::material::Library;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

/// Median of at least 5 runs (more while under about 5 s in all).
fn time(mut f: impl FnMut()) -> Duration {
    let t = Instant::now();
    f();
    let one = t.elapsed().as_secs_f64();
    let reps = ((5.0 / one) as usize).clamp(5, 50);
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

/// Write the batch into `dir`; PSD paths point back into examples/.
fn write_batch(dir: &Path, examples: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for (name, thickness_um) in [
        ("paper-rubber-on-steel.toml", 10.0),
        ("measured-rolloff.toml", 200.0),
        ("waviness-thin-film.toml", 5.0),
    ] {
        let text = std::fs::read_to_string(examples.join(name)).unwrap();
        let text = text.replace(
            "psd = \"measured-rolloff.csv\"",
            &format!(
                "psd = \"{}\"",
                examples.join("measured-rolloff.csv").display()
            ),
        );
        for i in 0..16 {
            let d = thickness_um * 10f64.powf(i as f64 / 15.0 - 0.5);
            let scene = text
                .lines()
                .map(|l| {
                    if l.trim_start().starts_with("thickness =") {
                        format!("thickness = \"{d} um\"")
                    } else {
                        l.to_string()
                    }
                })
                .collect::<Vec<_>>()
                .join("\n");
            let path = dir.join(format!("{i:02}-{name}"));
            std::fs::write(&path, scene).unwrap();
            files.push(path);
        }
    }
    files
}

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let dir = tempfile::tempdir().unwrap();
    let files = write_batch(dir.path(), &root.join("examples"));
    let n = files.len();
    let lib = Library::builtin().unwrap();
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());

    let mut rows: Vec<(String, Duration)> = Vec::new();
    let mut verdicts = (0, 0, 0);
    for threads in [1, cores] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let t = time(|| {
            let runs = pool.install(|| run_all(&files, &[], &lib, &|| {}));
            let count = |v: &str| runs.iter().filter(|r| r.verdict() == v).count();
            verdicts = (count("pass"), count("fail"), count("error"));
        });
        rows.push((format!("in-process run_all, {threads} thread(s)"), t));
    }
    // By kind of scene, 1 thread: where the time goes.
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    for kind in [
        "paper-rubber-on-steel",
        "measured-rolloff",
        "waviness-thin-film",
    ] {
        let some: Vec<PathBuf> = files
            .iter()
            .filter(|f| f.to_string_lossy().contains(kind))
            .cloned()
            .collect();
        let t = time(|| {
            one.install(|| run_all(&some, &[], &lib, &|| {}));
        });
        let per = t / some.len() as u32;
        rows.push((format!("  {kind} only, 1 thread (per scene)"), per));
    }
    let bin = root.join("target/release/coatcheck");
    if bin.exists() {
        let t = time(|| {
            let o = std::process::Command::new(&bin)
                .args(["check", dir.path().to_str().unwrap(), "--format", "json"])
                .output()
                .unwrap();
            assert!(matches!(o.status.code(), Some(0 | 1)));
        });
        rows.push((format!("whole command, {cores} thread(s)"), t));
    }
    println!(
        "batch of {n} scenes ({} pass, {} fail, {} error), {cores} cores",
        verdicts.0, verdicts.1, verdicts.2
    );
    println!("{:<48} {:>12} {:>14}", "", "median", "scenes/s");
    for (name, t) in rows {
        // Rows "(per scene)" are one scene's time; the others the whole batch's.
        let scenes = if name.ends_with("(per scene)") { 1 } else { n };
        println!(
            "{name:<48} {:>9.1} ms {:>14.1}",
            t.as_secs_f64() * 1e3,
            scenes as f64 / t.as_secs_f64()
        );
    }
}
