//! Benchmark of the exact minimum thickness (`coatcheck::exact::min_thickness`, the d_min of
//! `check --verify` on a film scene with a height map):
//! `cargo run --release --example bench_exact_dmin [-- --sizes 512,1024] [-- --runs 3]`.
//!
//! The scene is the bundled height-map example's (natural rubber 2 MPa, ν 0.4998, on carbon
//! steel 200 GPa, ν 0.29, yield 250 MPa; epoxy bond 10 MPa; 0.1 MPa; ε = 1e-4; bond-shear,
//! substrate-yield and min-thickness checks) on a synthetic self-affine map like the bundled one
//! (H = 0.8, h_rms 0.5 µm, roll-off 2e5 1/m, cut-off 3e6 1/m, 0.5 µm pixels), n × n pixels. The
//! search runs from coarse to fine on the map at a quarter and at half the resolution and on the
//! map (the half-resolution d_min gives the grid error), as `check --verify` does; `solves`
//! counts all levels, `on map` those on the map itself.
//!
//! `RAYON_NUM_THREADS` sets the threads (default: all cores). Wall times are medians; the CPU
//! column (all threads) tells what the search costs when the machine is shared.

use coatcheck::bem::{BemSettings, Surface};
use coatcheck::check::{Checks, Criteria, Design};
use coatcheck::exact::min_thickness::min_thickness;
use coatcheck::layer::{Bilayer, Elastic};
use coatcheck::topography::synth::{Amplitude, SynthSpec, self_affine_map};
use std::time::Instant;

fn surface(n: usize) -> Surface {
    let spec = SynthSpec {
        n,
        dx: 0.5e-6,
        hurst: 0.8,
        q0: 2.0e5,
        q1: 3.0e6,
        amplitude: Amplitude::RmsHeight(0.5e-6),
        seed: 1,
    };
    Surface::from_height_map(&self_affine_map(&spec).expect("valid synth spec")).expect("valid")
}

fn design() -> Design {
    Design {
        layers: Bilayer::new(
            Elastic::new(2e6, 0.4998).expect("valid"),
            Elastic::new(200e9, 0.29).expect("valid"),
        ),
        pressure: 0.1e6,
        yield_strength: Some(250e6),
        bond_strength: 10e6,
        friction: 0.0,
        criteria: Criteria {
            shear_tail: None,
            epsilon: 1e-4,
            safety_factor: 1.0,
            checks: Checks::all(),
        },
    }
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

fn arg<T: std::str::FromStr>(name: &str) -> Option<Vec<T>> {
    let args: Vec<String> = std::env::args().collect();
    let i = args.iter().position(|a| a == name)?;
    Some(
        args.get(i + 1)
            .unwrap_or_else(|| panic!("{name} needs a value"))
            .split(',')
            .map(|v| {
                v.parse()
                    .unwrap_or_else(|_| panic!("{name}: {v} is not a number"))
            })
            .collect(),
    )
}

fn main() {
    let sizes = arg::<usize>("--sizes").unwrap_or_else(|| vec![256, 512, 1024]);
    let runs = arg::<usize>("--runs").map_or(3, |r| r[0]);
    let settings = BemSettings::default();
    let design = design();
    println!(
        "threads: {}, gap tolerance {:e} h_rms",
        rayon::current_num_threads(),
        settings.gap_tol
    );
    println!(
        "{:>6} {:>5} {:>12} {:>11} {:>11} {:>7} {:>7} {:>6} {:>9} {:>11}",
        "n",
        "runs",
        "d_min (m)",
        "bracket",
        "grid err",
        "solves",
        "on map",
        "iter",
        "wall (s)",
        "cpu (s)"
    );
    for n in sizes {
        let s = surface(n);
        let (mut ts, mut tc, mut last) = (Vec::new(), Vec::new(), None);
        for _ in 0..runs {
            let (t, c) = (Instant::now(), cpu_seconds());
            let m = min_thickness(&s, &design, &settings).expect("search");
            ts.push(t.elapsed().as_secs_f64());
            if let (Some(c0), Some(c1)) = (c, cpu_seconds()) {
                tc.push(c1 - c0);
            }
            last = Some(m);
        }
        let m = last.expect("at least one run");
        let d = m.search.thickness;
        println!(
            "{:>6} {:>5} {:>12.5e} {:>11.3e} {:>11.3e} {:>7} {:>7} {:>6} {:>9.3} {:>11.2}",
            n,
            runs,
            d.map_or(f64::NAN, |d| d.value),
            d.map_or(f64::NAN, |d| d.err),
            m.grid_err,
            m.solves,
            m.search.evaluations,
            m.iterations,
            median(ts),
            if tc.is_empty() { f64::NAN } else { median(tc) },
        );
    }
}
