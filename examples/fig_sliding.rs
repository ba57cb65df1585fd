//! Not in the paper: the peak interface shear |τ| (exceedance 1e-6, vector rule) against the
//! film thickness under sliding friction μ = 0 (blue), 0.5 (green), 1 (red), with the bond
//! strength (black); fractal q0 = 1e5 1/m, p0 = 0.1 MPa (Fig. 7's setting).
//! `cargo run --release --example fig_sliding [OUT_DIR]` (default target/figures).

#[path = "common/plot.rs"]
mod plot;

use plotters::style::{BLACK, BLUE, GREEN, RED};

fn main() {
    plot::run(
        coatcheck::figures::sliding,
        121,
        &[BLUE, GREEN, RED, BLACK],
        plot::Legend::UpperRight,
    );
}
