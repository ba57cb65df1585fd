//! The generator of the exact/Persson ratio table that the low-octave warning quotes
//! ([`crate::check::regime`]): on a height map, for each q_L·d of [`Q_LOW_D`], one exact solve
//! of [`design`] (A/A0 and the ε-levels of the interface |τ| and σ_n, as [`super::verify`]
//! computes them) and Persson's evaluation on the map's own spectrum (as [`super::persson`]),
//! and their ratios. `examples/regime_table.rs` runs it on the bundled map and
//! writes the table.

use super::{map_spectrum, solve_one};
use crate::bem::{BemSettings, Surface};
use crate::check::regime::RegimeRow;
use crate::check::{Checker, Checks, Criteria, Design};
use crate::error::Error;
use crate::layer::{Bilayer, Elastic, Stack};
use crate::prec::Settings;
use crate::topography::HeightMap;

/// The q_L·d of the table's rows.
pub const Q_LOW_D: [f64; 10] = [0.03, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0, 2.0, 3.0];

/// The exceedance of the compared peaks: resolved on a 128 × 128 map (16 pixels above it).
pub const EPSILON: f64 = 1e-3;

/// The design of the table: natural rubber (2 MPa, ν 0.5) on steel (200 GPa, ν 0.3) at
/// p0 = 0.1 MPa, the peaks at [`EPSILON`]; the strengths do not enter the ratios.
pub fn design() -> Result<Design, Error> {
    Ok(Design {
        layers: Bilayer::new(Elastic::new(2e6, 0.5)?, Elastic::new(200e9, 0.3)?),
        pressure: 0.1e6,
        yield_strength: Some(250e6),
        bond_strength: 10e6,
        friction: 0.0,
        criteria: Criteria {
            shear_tail: None,
            epsilon: EPSILON,
            safety_factor: 1.0,
            checks: Checks {
                bond_shear: true,
                substrate_yield: true,
                min_thickness: false,
            },
        },
    })
}

/// The ratios at `q_low_d` on `map` (one period of a periodic surface).
pub fn row(map: &HeightMap, q_low_d: f64, bem: &BemSettings) -> Result<RegimeRow, Error> {
    let surface = Surface::from_height_map(map)?;
    let design = design()?;
    let thickness = q_low_d / surface.q_low();
    let stack = Stack::new(design.layers, thickness)?;
    let exact = solve_one(&surface, &stack, &design, bem, None)?;
    let persson = Checker::new(&map_spectrum(map)?, design.clone(), Settings::default())?
        .evaluate(thickness)?;
    let missing = |what: &str| Error::Numerical {
        what: "exact/Persson ratio table",
        detail: format!("Persson's {what} was not evaluated at q_L d = {q_low_d}"),
    };
    let tau = persson.tau_peak.ok_or_else(|| missing("tau peak"))?;
    let sigma = persson
        .sigma_peak_interface
        .ok_or_else(|| missing("sigma peak"))?;
    Ok(RegimeRow {
        q_low_d,
        area_ratio: exact.area / persson.contact.area_fraction.value,
        tau_peak_ratio: exact.tau_level / tau.value,
        sigma_peak_ratio: exact.sigma_level / sigma.value,
    })
}

/// One table line of `r` (nine significant digits).
pub fn line(r: &RegimeRow) -> String {
    format!(
        "{},{:.9e},{:.9e},{:.9e}",
        r.q_low_d, r.area_ratio, r.tau_peak_ratio, r.sigma_peak_ratio
    )
}
