//! Fig. 10 of the paper: E_eff/E_R against q0 d for the fractal spectra.
//! `cargo run --release --example fig10 [OUT_DIR]` (default target/figures).

#[path = "common/plot.rs"]
mod plot;

use plotters::style::BLUE;

fn main() {
    plot::run(
        coatcheck::figures::fig10,
        121,
        &[BLUE],
        plot::Legend::UpperRight,
    );
}
