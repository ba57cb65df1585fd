//! Benchmark of the boundary-element contact solver (`coatcheck::bem`):
//! `cargo run --release --example bench_bem [-- --quick] [-- --sizes 2048,4096] [-- --runs 1]
//! [-- --seed 2]`.
//!
//! 1. Solve times (median of runs) of a converged solve on self-affine surfaces at A/A0 ≈ 0.05,
//!    512² and 1024² (issue 6 targets: ≤ 1 s and ≤ 5 s on 2 cores), for a homogeneous rubber
//!    half-space (identical film and substrate) and a rubber film on steel at q_L·d = 1.
//! 2. Grid convergence: one band-limited surface (the 1024² map subsampled to 256² and 512²)
//!    with a rubber film on steel at q_L·d = 0.3 and 1: A/A0, τ_rms and the |τ| quantiles.
//!
//! `RAYON_NUM_THREADS` sets the threads (default: all cores). Wall times are medians; the CPU
//! column (all threads) tells what the solve costs when the machine is shared.

use coatcheck::bem::{self, BemSettings, Surface};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::topography::synth::{Amplitude, SynthSpec, self_affine_map};
use std::f64::consts::PI;
use std::time::Instant;

const L: f64 = 1e-3;
const XI: f64 = 0.1;

fn surface(n: usize, q1_over_ql: f64, seed: u64) -> Surface {
    let q_l = 2.0 * PI / L;
    let map = self_affine_map(&SynthSpec {
        n,
        dx: L / n as f64,
        hurst: 0.8,
        q0: q_l,
        q1: q1_over_ql * q_l,
        amplitude: Amplitude::RmsSlope(XI),
        seed,
    })
    .expect("valid synth spec");
    Surface::from_height_map(&map).expect("valid map")
}

fn subsample(s: &Surface, n: usize) -> Surface {
    let step = s.nx / n;
    let mut h = Vec::with_capacity(n * n);
    for iy in 0..n {
        for ix in 0..n {
            h.push(s.heights[iy * step * s.nx + ix * step]);
        }
    }
    Surface::new(h, n, n, s.dx * step as f64, s.dy * step as f64).expect("valid map")
}

/// CPU seconds used by this process so far, all threads (utime + stime of /proc/self/stat, in
/// clock ticks of 1/100 s); `None` where /proc is not available.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let rubber = Elastic::new(1e6, 0.5).expect("valid");
    let steel = Elastic::new(2e11, 0.3).expect("valid");
    let e0 = rubber.e_star();
    let settings = BemSettings::default();
    println!(
        "threads: {}, gap tolerance {:e} h_rms",
        rayon::current_num_threads(),
        settings.gap_tol
    );
    println!("\n# solve times (median of runs), H = 0.8, q1 = n/8 q_L, xi = {XI}");
    println!(
        "{:>6} {:>22} {:>5} {:>9} {:>6} {:>9} {:>11} {:>13} {:>11} {:>11}",
        "n",
        "solid",
        "runs",
        "A/A0",
        "iter",
        "restarts",
        "solve (s)",
        "solve cpu (s)",
        "fields (s)",
        "status"
    );
    let args: Vec<String> = std::env::args().collect();
    let sizes: Vec<usize> = match args.iter().position(|a| a == "--sizes") {
        Some(i) => args
            .get(i + 1)
            .expect("--sizes needs a list, e.g. 2048,4096")
            .split(',')
            .map(|v| v.parse().expect("sizes are integers"))
            .collect(),
        None if quick => vec![256, 512],
        None => vec![512, 1024, 2048],
    };
    let only_sizes = args.iter().any(|a| a == "--sizes");
    let runs_arg: Option<usize> = args.iter().position(|a| a == "--runs").map(|i| {
        args.get(i + 1)
            .and_then(|v| v.parse().ok())
            .expect("--runs needs a count")
    });
    // The surface's random phases (1 unless asked: the figures in the README are for seed 1).
    let seed: u64 = args.iter().position(|a| a == "--seed").map_or(1, |i| {
        args.get(i + 1)
            .and_then(|v| v.parse().ok())
            .expect("--seed needs an integer")
    });
    for &n in &sizes {
        let s = surface(n, n as f64 / 8.0, seed);
        let q_l = s.q_low();
        for (name, layers, d, p_over) in [
            (
                "rubber half-space",
                Bilayer::new(rubber, rubber),
                1.0 / q_l,
                0.025,
            ),
            (
                "rubber on steel qLd=1",
                Bilayer::new(rubber, steel),
                1.0 / q_l,
                0.035,
            ),
        ] {
            let stack = Stack::new(layers, d).expect("valid");
            let p0 = p_over * e0 * XI;
            let runs = runs_arg.unwrap_or(if n >= 2048 { 3 } else { 5 });
            let (mut ts, mut tc, mut tf) = (Vec::new(), Vec::new(), Vec::new());
            let mut last = None;
            for _ in 0..runs {
                // The previous run's fields are freed first, so that the peak memory is a solve's.
                drop(last.take());
                let (t, c) = (Instant::now(), cpu_seconds());
                let sol = bem::solve(&s, &stack, p0, &settings).expect("solve");
                ts.push(t.elapsed().as_secs_f64());
                if let (Some(c0), Some(c1)) = (c, cpu_seconds()) {
                    tc.push(c1 - c0);
                }
                let t = Instant::now();
                let f = bem::interface_fields(&sol, &stack).expect("fields");
                tf.push(t.elapsed().as_secs_f64());
                last = Some((sol, f));
            }
            let (sol, _) = last.expect("at least one run");
            let cpu = if tc.is_empty() { f64::NAN } else { median(tc) };
            println!(
                "{:>6} {:>22} {:>5} {:>9.5} {:>6} {:>9} {:>11.3} {:>13.2} {:>11.3} {:>11?}",
                n,
                name,
                runs,
                sol.area_fraction.value,
                sol.convergence.iterations,
                sol.convergence.restarts,
                median(ts),
                cpu,
                median(tf),
                sol.convergence.status
            );
        }
    }

    if only_sizes {
        return;
    }
    let fine = if quick { 512 } else { 1024 };
    println!(
        "\n# grid convergence: one surface (q1 = 32 q_L, H = 0.8, xi = {XI}) on refined grids, \
         rubber on steel, p0 = 0.3 E0* xi"
    );
    println!(
        "{:>6} {:>6} {:>9} {:>11} {:>11} {:>11} {:>11} {:>11} {:>11}",
        "qLd",
        "n",
        "A/A0",
        "tau_rms",
        "|tau|q0.5",
        "|tau|q0.9",
        "|tau|q0.99",
        "|tau|q0.999",
        "|tau|max"
    );
    let base = surface(fine, 32.0, 2);
    for qld in [0.3, 1.0] {
        let mut n = fine / 4;
        while n <= fine {
            let s = if n == fine {
                base.clone()
            } else {
                subsample(&base, n)
            };
            let stack = Stack::new(Bilayer::new(rubber, steel), qld / s.q_low()).expect("valid");
            let sol = bem::solve(&s, &stack, 0.3 * e0 * XI, &settings).expect("solve");
            let f = bem::interface_fields(&sol, &stack).expect("fields");
            let q = |p| f.shear_stats.quantile(p).expect("reported quantile");
            println!(
                "{:>6} {:>6} {:>9.5} {:>11.4e} {:>11.4e} {:>11.4e} {:>11.4e} {:>11.4e} {:>11.4e}",
                qld,
                n,
                sol.area_fraction.value,
                f.shear_stats.rms,
                q(0.5),
                q(0.9),
                q(0.99),
                q(0.999),
                f.shear_stats.max
            );
            n *= 2;
        }
    }
}
