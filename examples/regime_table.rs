//! The exact/Persson ratio table that `check`'s low-octave warning quotes
//! (`coatcheck::check::regime`): the exact solver against Persson's theory on the bundled
//! height map over q_L·d (`coatcheck::verify::regime`).
//!
//! `cargo run --release --example regime_table > src/check/regime.csv`

use coatcheck::bem::BemSettings;
use coatcheck::topography::io::{MapOptions, read_height_map};
use coatcheck::verify::regime::{EPSILON, Q_LOW_D, line, row};
use std::path::Path;

fn main() -> Result<(), coatcheck::error::Error> {
    let path = Path::new("examples/data/height-map.csv");
    let opts = MapOptions {
        periodic: Some(true),
        ..MapOptions::default()
    };
    let map = read_height_map(path, &opts)?;
    println!(
        "# exact/Persson on {} ({} x {}, one period): natural rubber 2 MPa, nu 0.5 on steel \
         200 GPa, nu 0.3, p0 = 0.1 MPa; peaks at epsilon = {EPSILON:e}",
        path.display(),
        map.nx,
        map.ny
    );
    println!("# regenerate: cargo run --release --example regime_table > src/check/regime.csv");
    println!("q_low_d,area_ratio,tau_peak_ratio,sigma_peak_ratio");
    for q_low_d in Q_LOW_D {
        println!("{}", line(&row(&map, q_low_d, &BemSettings::default())?));
    }
    Ok(())
}
