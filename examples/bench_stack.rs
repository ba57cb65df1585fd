//! Benchmark: one evaluation of the layer-stack kernels (S and every f_k, g_k at one q,
//! `layer::stack::Stack::response_into`, no allocation) for N = 1, 2 and 10 layers against the
//! one-layer kernel (`layer::Bilayer::response`). Medians over repeated sweeps of 1000 values
//! of q·z spread log-uniformly over 1e-8 … 1e4, in ns per evaluation.
//!
//! Run: `cargo run --release --example bench_stack`

use coatcheck::layer::stack::{Layer, Stack};
use coatcheck::layer::{Bilayer, Elastic};
use std::hint::black_box;

#[path = "common/timing.rs"]
mod timing;
use timing::median_us;

const POINTS: usize = 1000;

fn el(e: f64, nu: f64) -> Elastic {
    Elastic::new(e, nu).expect("valid material")
}

/// q values with q z_N (the stack's total thickness z_N) from 1e-8 to 1e4.
fn qs(total: f64) -> Vec<f64> {
    (0..POINTS)
        .map(|i| 10f64.powf(-8.0 + 12.0 * i as f64 / (POINTS - 1) as f64) / total)
        .collect()
}

fn time_stack(stack: &Stack) -> f64 {
    let total: f64 = stack.layers().iter().map(|l| l.thickness).sum();
    let qs = qs(total);
    let mut out = vec![(0.0, 0.0); stack.layers().len()];
    let us = median_us(101, || {
        for &q in &qs {
            black_box(stack.response_into(black_box(q), &mut out));
            black_box(&out);
        }
    });
    us * 1e3 / POINTS as f64
}

fn main() {
    let (rubber, epoxy, steel) = (el(1e6, 0.5), el(3e9, 0.35), el(2e11, 0.3));
    let d = 10e-6;
    let bilayer = Bilayer::new(rubber, steel);
    let qs1 = qs(d);
    let one_layer_ns = median_us(101, || {
        for &q in &qs1 {
            black_box(bilayer.response(black_box(q * d)));
        }
    }) * 1e3
        / POINTS as f64;
    let layer = |material, thickness| Layer {
        material,
        thickness,
    };
    let cases = [
        (
            "N = 1 (rubber on steel)",
            Stack::new(vec![layer(rubber, d)], steel),
        ),
        (
            "N = 2 (rubber, epoxy on steel)",
            Stack::new(vec![layer(rubber, d), layer(epoxy, d)], steel),
        ),
        (
            "N = 10 (rubber and epoxy alternating)",
            Stack::new(
                (0..10)
                    .map(|k| layer(if k % 2 == 0 { rubber } else { epoxy }, d))
                    .collect(),
                steel,
            ),
        ),
    ];
    println!("{:<40} {:>14} {:>10}", "kernel", "median [ns]", "ratio");
    println!(
        "{:<40} {:>14.1} {:>10.2}",
        "one-layer Bilayer::response", one_layer_ns, 1.0
    );
    for (name, stack) in cases {
        let ns = time_stack(&stack.expect("valid stack"));
        println!(
            "{:<40} {:>14.1} {:>10.2}",
            format!("Stack {name}"),
            ns,
            ns / one_layer_ns
        );
    }
}
