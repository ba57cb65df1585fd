//! Fig. 14 of the paper: the interface kernels f(qd) (red) and g(qd) (blue) against q for d = 10 µm.
//! `cargo run --release --example fig14 [OUT_DIR]` (default target/figures).

#[path = "common/plot.rs"]
mod plot;

use plotters::style::{BLUE, RED};

fn main() {
    plot::run(
        coatcheck::figures::fig14,
        301,
        &[RED, BLUE],
        plot::Legend::UpperRight,
    );
}
