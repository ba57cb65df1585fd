//! Benchmark: a 4096 × 4096 height map, read from CSV and turned into a PSD, in bounded memory.
//!
//! `cargo run --release --example psd_large [-- N RUNS]` (defaults 4096 and 3). The map is
//! generated once by a child process (`coatcheck synth`-equivalent, seed 1) into
//! `target/psd_large_N.csv`, so that this process's peak memory (VmHWM from /proc/self/status)
//! counts only reading and processing: the heights (N² f64) plus one half spectrum
//! (N(N/2 + 1) complex f64), about 256 MiB at N = 4096.

use coatcheck::topography::io::{MapOptions, read_height_map, write_height_map};
use coatcheck::topography::spectrum::{PsdOptions, map_psd};
use coatcheck::topography::synth::{Amplitude, SynthSpec, self_affine_map};
use std::path::{Path, PathBuf};
use std::time::Instant;

fn vm_hwm_kib() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn generate(n: usize, path: &Path) {
    let dx = 1e-7;
    let ql = 2.0 * std::f64::consts::PI / (n as f64 * dx);
    let spec = SynthSpec {
        n,
        dx,
        hurst: 0.8,
        q0: 16.0 * ql,
        q1: 0.5 * n as f64 * ql,
        amplitude: Amplitude::RmsSlope(0.5),
        seed: 1,
    };
    let map = self_affine_map(&spec).expect("synth");
    coatcheck::report::write_with(path, |w| write_height_map(w, &map, &[])).expect("write");
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.get(1).map(String::as_str) == Some("--generate") {
        generate(args[2].parse().unwrap(), Path::new(&args[3]));
        return;
    }
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(4096);
    let runs: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(3);
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("target/psd_large_{n}.csv"));
    if !path.exists() {
        eprintln!("generating {} (child process) ...", path.display());
        let st = std::process::Command::new(std::env::current_exe().unwrap())
            .args(["--generate", &n.to_string(), path.to_str().unwrap()])
            .status()
            .unwrap();
        assert!(st.success());
    }
    let size = std::fs::metadata(&path).unwrap().len();
    let base = vm_hwm_kib().unwrap_or(0);
    let (mut t_read, mut t_psd) = (Vec::new(), Vec::new());
    let mut points = 0;
    for _ in 0..runs {
        let t0 = Instant::now();
        let map = read_height_map(&path, &MapOptions::default()).expect("read");
        let t1 = Instant::now();
        let p = map_psd(&map, &PsdOptions::default()).expect("psd");
        let t2 = Instant::now();
        points = p.c2d.q().len();
        t_read.push((t1 - t0).as_secs_f64());
        t_psd.push((t2 - t1).as_secs_f64());
    }
    let hwm = vm_hwm_kib().unwrap_or(0);
    let heights_mib = (n * n * 8) as f64 / 1048576.0;
    let half_mib = (n * (n / 2 + 1) * 16) as f64 / 1048576.0;
    println!(
        "| map | file | runs | read (median) | psd (median) | total | peak RSS (VmHWM) | heights + half spectrum | PSD points |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    println!(
        "| {n} x {n} | {:.0} MiB | {runs} | {:.2} s | {:.2} s | {:.2} s | {:.0} MiB (start {:.0} MiB) | {:.0} MiB | {points} |",
        size as f64 / 1048576.0,
        median(t_read.clone()),
        median(t_psd.clone()),
        median(t_read.iter().zip(&t_psd).map(|(a, b)| a + b).collect()),
        hwm as f64 / 1024.0,
        base as f64 / 1024.0,
        heights_mib + half_mib,
    );
}
