//! `coatcheck synth`: a synthetic self-affine surface (fixed seed) as a height-map CSV, or some
//! of its rows as line scans.

use coatcheck::Error;
use coatcheck::scene::Key;
use coatcheck::topography::Profile;
use coatcheck::topography::io::{write_height_map, write_profile};
use coatcheck::topography::synth::{Amplitude, SynthSpec, self_affine_map};
use coatcheck::units::{Dim, parse_quantity};
use std::path::PathBuf;

/// Generate a periodic self-affine surface with random phases and a known PSD:
/// C = C0 below q0, C0 (q/q0)^(−2(1+H)) up to q1, 0 above.
#[derive(Debug, clap::Args)]
pub struct SynthArgs {
    /// Pixels per side, 4 to 8192.
    #[arg(long, default_value_t = 256)]
    pub n: usize,
    /// Pixel size (e.g. 1um).
    #[arg(long)]
    pub pixel_size: String,
    /// Hurst exponent, 0 < H <= 1.
    #[arg(long, default_value_t = 0.8)]
    pub hurst: f64,
    /// Roll-off wavenumber (e.g. 1e5 1/m, or 0.1 1/um).
    #[arg(long)]
    pub q0: String,
    /// Short-wavelength cut-off wavenumber.
    #[arg(long)]
    pub q1: String,
    /// rms height (e.g. 1um); or give --rms-slope.
    #[arg(
        long,
        allow_hyphen_values = true,
        conflicts_with = "rms_slope",
        required_unless_present = "rms_slope"
    )]
    pub rms_height: Option<String>,
    /// rms slope.
    #[arg(long, allow_hyphen_values = true)]
    pub rms_slope: Option<String>,
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Write K rows, spread evenly over the map, as line scans (`x, z1..zK`) instead of the map.
    #[arg(long)]
    pub line_scans: Option<usize>,
    /// Output CSV file (written atomically).
    #[arg(long, short)]
    pub output: PathBuf,
}

fn quantity(flag: &'static str, s: &str, dim: Dim, expected: &'static str) -> Result<f64, Error> {
    parse_quantity(s, dim).map_err(|e| Error::invalid(flag, format!("'{s}' ({e})"), expected))
}

/// Run `coatcheck synth`; returns the exit code (0) or an error (exit code 2).
pub fn run(a: SynthArgs) -> Result<i32, Error> {
    let amplitude = match (&a.rms_height, &a.rms_slope) {
        (Some(h), _) => Amplitude::RmsHeight(Key::RmsHeight.parse_flag("--rms-height", h)?),
        (None, Some(x)) => Amplitude::RmsSlope(Key::RmsSlope.parse_flag("--rms-slope", x)?),
        (None, None) => {
            return Err(Error::invalid(
                "amplitude",
                "none",
                "--rms-height or --rms-slope",
            ));
        }
    };
    let spec = SynthSpec {
        n: a.n,
        dx: quantity(
            "--pixel-size",
            &a.pixel_size,
            Dim::Length(1),
            "a length such as 1um",
        )?,
        hurst: a.hurst,
        q0: Key::Q0.parse_flag("--q0", &a.q0)?,
        q1: Key::Q1.parse_flag("--q1", &a.q1)?,
        amplitude,
        seed: a.seed,
    };
    let map = self_affine_map(&spec)?;
    let note = format!(
        "synth: self-affine, H = {}, q0 = {:e} 1/m, q1 = {:e} 1/m, C0 = {:e} m^4, seed = {}",
        spec.hurst,
        spec.q0,
        spec.q1,
        spec.c0(),
        spec.seed
    );
    let what = match a.line_scans {
        Some(k) => {
            if k == 0 || k > map.ny {
                return Err(Error::invalid(
                    "--line-scans",
                    k,
                    "between 1 and the number of rows n",
                ));
            }
            let p = Profile {
                dx: map.dx,
                // Rows spread evenly over the map, so that the scans are nearly independent.
                scans: (0..k).map(|j| map.row(j * map.ny / k).to_vec()).collect(),
                periodic: true,
            };
            coatcheck::report::write_with(&a.output, |w| {
                write_profile(w, &p, std::slice::from_ref(&note))
            })?;
            format!("{k} line scans of {} points, rows of", map.nx)
        }
        None => {
            coatcheck::report::write_with(&a.output, |w| {
                write_height_map(w, &map, std::slice::from_ref(&note))
            })?;
            "the height map".to_string()
        }
    };
    let um = coatcheck::report::um;
    coatcheck::report::stdout(&format!(
        "{}\n{}\n",
        coatcheck::report::wrap(&format!(
            "wrote {what} a {} x {} map of {} µm pixels (rms height {} µm) to {}",
            map.nx,
            map.ny,
            um(map.dx),
            um(map.rms()),
            a.output.display()
        )),
        coatcheck::report::wrap(&note)
    ))?;
    Ok(0)
}
