//! Fig. 6 of the paper: normal-stress distributions at the top surface (red) and the interface (blue), and the interface shear distribution (green); fractal q0 = 1e5 1/m, d = 10 µm.
//! `cargo run --release --example fig06 [OUT_DIR]` (default target/figures).

#[path = "common/plot.rs"]
mod plot;

use plotters::style::{BLUE, GREEN, RED};

fn main() {
    plot::run(
        coatcheck::figures::fig06,
        1001,
        &[RED, BLUE, GREEN],
        plot::Legend::UpperRight,
    );
}
