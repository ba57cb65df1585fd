//! Fig. 5 of the paper: A/A0 against q0 (fractal, d = 50 µm) for ν_R = 0.5 (red) and 0.49985 (green).
//! `cargo run --release --example fig05 [OUT_DIR]` (default target/figures).

#[path = "common/plot.rs"]
mod plot;

use plotters::style::{GREEN, RED};

fn main() {
    plot::run(
        coatcheck::figures::fig05,
        121,
        &[RED, GREEN],
        plot::Legend::LowerRight,
    );
}
