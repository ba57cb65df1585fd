//! Benchmark: only what a scene needs is computed (issue 5).
//!
//! 1. One evaluation on the 1000-point measured PSD (examples/measured-rolloff.csv) per request:
//!    the contact area alone, the area with the top-surface stress (a closed form in G(q1)), the
//!    interface shear alone, and everything. Printed: median time, layer-kernel evaluations in
//!    all, and how many of them evaluated the interface kernels f, g (0 unless asked for).
//! 2. A thickness sweep of 25 thicknesses: one engine reused for every thickness (what
//!    `check --sweep-thickness` and the d_min search do) against a new engine per thickness.
//!
//! Run: `cargo run --release --example bench_needs`

use coatcheck::contact::{Engine, Request};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::Settings;
use coatcheck::psd::Spectrum;
use coatcheck::psd::read::{ReadOptions, read_spectrum};
use std::hint::black_box;

#[path = "common/timing.rs"]
mod timing;
use std::path::PathBuf;
use timing::median_us;

fn main() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/measured-rolloff.csv");
    let (table, _) = read_spectrum(&path, &ReadOptions::default()).expect("bundled PSD");
    let spectrum = Spectrum::Tabulated(table);
    let pair = Bilayer::new(
        Elastic::new(2e6, 0.4998).expect("valid"),
        Elastic::new(2e11, 0.29).expect("valid"),
    );
    let stack = Stack::new(pair, 20e-6).expect("valid");
    let engine = Engine::new(&spectrum, Settings::default());
    let none = Request::default();
    println!("one evaluation, 1000-point PSD, d = 20 um, rtol 1e-8 (median of 301)");
    println!(
        "{:<28} {:>12} {:>18} {:>22}",
        "request", "median [us]", "kernel evaluations", "of which f, g (interface)"
    );
    for (name, req) in [
        ("contact area only", none),
        (
            "area + sigma_rms top",
            Request {
                sigma_top: true,
                ..none
            },
        ),
        (
            "tau_rms interface only",
            Request {
                tau_interface: true,
                ..none
            },
        ),
        ("everything", Request::all()),
    ] {
        let c = engine.evaluate(&stack, 1e5, req).expect("evaluates");
        let t = median_us(301, || {
            black_box(
                engine
                    .evaluate(black_box(&stack), 1e5, req)
                    .expect("evaluates"),
            );
        });
        println!(
            "{name:<28} {t:>12.1} {:>18} {:>22}",
            c.kernel_evaluations, c.interface_kernel_evaluations
        );
    }

    let thicknesses: Vec<f64> = (0..25).map(|i| 1e-7 * 10f64.powf(i as f64 / 6.0)).collect();
    let reused = median_us(21, || {
        let engine = Engine::new(&spectrum, Settings::default());
        for &d in &thicknesses {
            let s = Stack::new(pair, d).expect("valid");
            black_box(engine.evaluate(&s, 1e5, Request::all()).expect("evaluates"));
        }
    });
    let fresh = median_us(21, || {
        for &d in &thicknesses {
            let engine = Engine::new(&spectrum, Settings::default());
            let s = Stack::new(pair, d).expect("valid");
            black_box(engine.evaluate(&s, 1e5, Request::all()).expect("evaluates"));
        }
    });
    println!();
    println!("thickness sweep, 25 thicknesses 0.1 um .. 1 mm, everything (median of 21, one core)");
    println!("{:<44} {:>12}", "", "median [ms]");
    println!(
        "{:<44} {:>12.2}",
        "one engine for all thicknesses",
        reused * 1e-3
    );
    println!(
        "{:<44} {:>12.2}",
        "a new engine per thickness",
        fresh * 1e-3
    );
    println!("ratio {:.2}", fresh / reused);
}
