//! Fig. 9 of the paper: A/A0 against p0 for the fractal surfaces with q0 = 1e4 (red) and 3e3 1/m (green), d = 50 µm.
//! `cargo run --release --example fig09 [OUT_DIR]` (default target/figures).

#[path = "common/plot.rs"]
mod plot;

use plotters::style::{GREEN, RED};

fn main() {
    plot::run(
        coatcheck::figures::fig09,
        101,
        &[RED, GREEN],
        plot::Legend::LowerRight,
    );
}
