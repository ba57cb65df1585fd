//! Fig. 12 of the paper: E_eff/E_R for the Gaussian spectrum (q0 = 1e5 1/m, d varied) against q0 d (blue), and the Gent disc, eq. (9), against d/R (red).
//! `cargo run --release --example fig12 [OUT_DIR]` (default target/figures).

#[path = "common/plot.rs"]
mod plot;

use plotters::style::{BLUE, RED};

fn main() {
    plot::run(
        coatcheck::figures::fig12,
        101,
        &[BLUE, RED],
        plot::Legend::UpperRight,
    );
}
