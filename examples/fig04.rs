//! Fig. 4 of the paper: A/A0 against q0 for the fractal (red) and Gaussian (blue) spectra,
//! d = 50 µm, with the homogeneous rubber and steel values.
//! `cargo run --release --example fig04 [OUT_DIR]` (default target/figures).

#[path = "common/plot.rs"]
mod plot;

use plotters::style::{BLACK, BLUE, RED, RGBColor};

fn main() {
    let gray = RGBColor(128, 128, 128);
    plot::run(
        coatcheck::figures::fig04,
        121,
        &[RED, BLUE, BLACK, gray],
        plot::Legend::LowerRight,
    );
}
