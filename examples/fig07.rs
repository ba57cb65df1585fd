//! Fig. 7 of the paper: rms widths of the top (red) and interface normal (blue) and shear (green) stress distributions against the film thickness; fractal q0 = 1e5 1/m.
//! `cargo run --release --example fig07 [OUT_DIR]` (default target/figures).

#[path = "common/plot.rs"]
mod plot;

use plotters::style::{BLUE, GREEN, RED};

fn main() {
    plot::run(
        coatcheck::figures::fig07,
        121,
        &[RED, BLUE, GREEN],
        plot::Legend::UpperRight,
    );
}
