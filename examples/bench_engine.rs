//! Benchmark: one contact evaluation (all quantities at one thickness) on a 1000-point
//! tabulated PSD, and the area alone; medians over repeated runs, with the number of kernel
//! evaluations (S⁻² at every node, and f, g where the interface integrals need them). The
//! Engine (d-independent grid) is built once, as in a thickness sweep.
//!
//! Run: `cargo run --release --example bench_engine`

use coatcheck::contact::{Engine, Request};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::Settings;
use std::hint::black_box;

#[path = "common/timing.rs"]
mod timing;
use timing::median_us;

#[path = "../tests/it/fixtures.rs"]
mod fixtures;
use fixtures::measured_like;

fn main() {
    let spectrum = measured_like(1000);
    let pair = Bilayer::new(
        Elastic::new(1e6, 0.5).expect("valid"),
        Elastic::new(2e11, 0.3).expect("valid"),
    );
    println!(
        "{:>8} {:>10} {:>16} {:>12} {:>10} {:>10} {:>12}",
        "rtol", "d [um]", "request", "median [us]", "S evals", "f,g evals", "max rel err"
    );
    for rtol in [1e-6, 1e-8] {
        let engine = Engine::new(&spectrum, Settings { rtol });
        for d in [1e-6, 20e-6, 200e-6] {
            let stack = Stack::new(pair, d).expect("valid");
            for (name, req) in [
                ("area", Request::default()),
                ("all", Request::all()),
                (
                    "tau only",
                    Request {
                        tau_interface: true,
                        ..Default::default()
                    },
                ),
            ] {
                let c = engine.evaluate(&stack, 1e5, req).expect("evaluates");
                let worst = [
                    Some(c.area_fraction),
                    c.sigma_rms_top,
                    c.sigma_rms_interface,
                    c.tau_rms_interface,
                ]
                .into_iter()
                .flatten()
                .map(|e| e.rel_err())
                .fold(0.0, f64::max);
                let t = median_us(201, || {
                    black_box(
                        engine
                            .evaluate(black_box(&stack), 1e5, req)
                            .expect("evaluates"),
                    );
                });
                println!(
                    "{rtol:>8.0e} {:>10.1} {name:>16} {t:>12.1} {:>10} {:>10} {worst:>12.1e}",
                    d * 1e6,
                    c.kernel_evaluations,
                    c.interface_kernel_evaluations
                );
            }
        }
    }
    let t = median_us(51, || {
        black_box(
            Engine::new(black_box(&spectrum), Settings::default())
                .evaluate(
                    &Stack::new(pair, 20e-6).expect("valid"),
                    1e5,
                    Request::all(),
                )
                .expect("evaluates"),
        );
    });
    println!("engine construction + one full evaluation (rtol 1e-8, d = 20 um): {t:.1} us");
}
