//! The arguments of `coatcheck check`: every flag, and the scene keys they override.

use coatcheck::report::Format;
use std::path::PathBuf;

const AFTER_HELP: &str = "\
Exit codes:
  0  every enabled check passes at the given thickness
  1  a check fails (the report says which)
  2  bad input (file, value, unit, material, scene) or a numerical failure; nothing is written

Flags override the scene file's keys of the same name (roughness.*, film.*, substrate.*, bond.*,
load.pressure, criteria.*, numerics.rtol). Values accept units: 10um, \"0.1 MPa\", 200GPa, \"1e5 1/m\".
Checks: bond-shear (peak interface shear vs bond strength), substrate-yield (mean real-contact
pressure and peak interface normal stress vs yield), min-thickness (smallest film thickness
above which every check passes at every thickness).

Example: coatcheck check examples/paper-rubber-on-steel.toml --thickness 5um --format json

Batch: several scene files, or a directory of *.toml scenes, are judged in parallel and
summarised in one table (failures first) or one record per scene (--format json|csv). Flags
apply to every scene. Exit code 0 when every scene passes, 1 when any fails, 2 when any could
not be evaluated (the others are still run and reported). --junit FILE writes a JUnit XML
report (a test case per scene and check) for CI systems.

Example: coatcheck check examples/specs/ --junit coatcheck-junit.xml";

/// Arguments of `coatcheck check`.
#[derive(clap::Args, Debug)]
#[command(after_help = AFTER_HELP)]
pub struct CheckArgs {
    /// Scene file (TOML); flags override its values.
    pub scene: Option<PathBuf>,
    /// More scene files or directories of *.toml scenes: a batch run with a summary table.
    #[arg(value_name = "MORE_SCENES")]
    pub more_scenes: Vec<PathBuf>,
    /// Measured PSD file (columns q [1/m], C [m^4]); relative to the working directory.
    #[arg(long, allow_hyphen_values = true)]
    pub psd: Option<String>,
    /// Measured heights (line scans or a height map, as `coatcheck psd` reads them); the PSD is
    /// computed with the `coatcheck psd` defaults.
    #[arg(long, allow_hyphen_values = true)]
    pub profile: Option<String>,
    /// Roughness model: self-affine (eq. 2) or gaussian (eq. 5).
    #[arg(long)]
    pub model: Option<String>,
    /// Hurst exponent H of the self-affine model.
    #[arg(long, allow_hyphen_values = true)]
    pub hurst: Option<String>,
    /// Lowest wavenumber q0 of the model (or centre of the Gaussian band), e.g. "1e5 1/m".
    #[arg(long, allow_hyphen_values = true)]
    pub q0: Option<String>,
    /// Short-wavelength cut-off q1 of the self-affine model.
    #[arg(long, allow_hyphen_values = true)]
    pub q1: Option<String>,
    /// Roll-off wavenumber q_r of the self-affine model (flat below it).
    #[arg(long, allow_hyphen_values = true)]
    pub roll_off: Option<String>,
    /// Width Q of the Gaussian band.
    #[arg(long, allow_hyphen_values = true)]
    pub width: Option<String>,
    /// Scale the spectrum to this rms slope.
    #[arg(long, allow_hyphen_values = true)]
    pub rms_slope: Option<String>,
    /// Scale the spectrum to this rms height, e.g. 1um.
    #[arg(long, allow_hyphen_values = true)]
    pub rms_height: Option<String>,
    /// Use measured data only above this wavenumber.
    #[arg(long, allow_hyphen_values = true)]
    pub q_min: Option<String>,
    /// Use measured data only below this wavenumber.
    #[arg(long, allow_hyphen_values = true)]
    pub q_max: Option<String>,
    /// PSD file: column of q (1-based number or header name; default: detected from the header).
    #[arg(long)]
    pub q_col: Option<String>,
    /// PSD file: column of C.
    #[arg(long)]
    pub c_col: Option<String>,
    /// PSD file: unit of q (e.g. 1/um), overriding the header's.
    #[arg(long)]
    pub q_unit: Option<String>,
    /// PSD file: unit of C (e.g. um^4 for a 2D PSD, nm^3 for a 1D PSD), overriding the header's.
    #[arg(long)]
    pub c_unit: Option<String>,
    /// PSD file: 2d (C in m^4) or 1d (C1D in m^3 from line scans, converted exactly by the
    /// inverse Abel transform); default from the unit of C, else 2d.
    #[arg(long)]
    pub psd_kind: Option<String>,
    /// Film material (name from `coatcheck materials`).
    #[arg(long)]
    pub film: Option<String>,
    /// Film Young's modulus (instead of a material name).
    #[arg(long, allow_hyphen_values = true)]
    pub film_youngs_modulus: Option<String>,
    /// Film Poisson ratio (with --film-youngs-modulus).
    #[arg(long, allow_hyphen_values = true)]
    pub film_poisson_ratio: Option<String>,
    /// Film thickness d, e.g. 10um.
    #[arg(long, allow_hyphen_values = true)]
    pub thickness: Option<String>,
    /// Substrate material (name from `coatcheck materials`).
    #[arg(long)]
    pub substrate: Option<String>,
    /// Substrate Young's modulus (instead of a material name).
    #[arg(long, allow_hyphen_values = true)]
    pub substrate_youngs_modulus: Option<String>,
    /// Substrate Poisson ratio (with --substrate-youngs-modulus).
    #[arg(long, allow_hyphen_values = true)]
    pub substrate_poisson_ratio: Option<String>,
    /// Substrate yield strength (overrides the material's).
    #[arg(long, allow_hyphen_values = true)]
    pub yield_strength: Option<String>,
    /// Bond (name from `coatcheck materials`).
    #[arg(long)]
    pub bond: Option<String>,
    /// Bond shear strength (instead of a bond name).
    #[arg(long, allow_hyphen_values = true)]
    pub shear_strength: Option<String>,
    /// Nominal pressure p0, e.g. "0.1 MPa".
    #[arg(long, allow_hyphen_values = true)]
    pub pressure: Option<String>,
    /// Exceedance probability that defines a peak value (default 1e-6).
    #[arg(long, allow_hyphen_values = true)]
    pub epsilon: Option<String>,
    /// Safety factor: limits are strengths divided by it (default 1).
    #[arg(long, allow_hyphen_values = true)]
    pub safety_factor: Option<String>,
    /// Checks to run, comma-separated (default: bond-shear,substrate-yield,min-thickness).
    #[arg(long)]
    pub checks: Option<String>,
    /// Relative tolerance of the contact integrals (default 1e-8).
    #[arg(long, allow_hyphen_values = true)]
    pub rtol: Option<String>,
    /// Output format.
    #[arg(long, value_enum, default_value = "table")]
    pub format: Format,
    /// Write the report to this file (atomically) instead of standard output.
    #[arg(long)]
    pub output: Option<PathBuf>,
    /// Directory of extra material files (*.toml) that add to or override the bundled library.
    #[arg(long)]
    pub materials: Option<PathBuf>,
    /// Print the results over log-spaced thicknesses FROM:TO:N (e.g. 1um:1mm:25) instead of
    /// one check; exit code 0 unless the input is bad.
    #[arg(long, value_name = "FROM:TO:N")]
    pub sweep_thickness: Option<String>,
    /// Also solve the contact exactly on the scene's height map (roughness.profile) with
    /// boundary elements and judge the checks on the solved fields; the design then passes only
    /// if both pass.
    #[arg(long, conflicts_with = "sweep_thickness")]
    pub verify: bool,
    /// Also write a JUnit XML report (a test case per scene and check), atomically.
    #[arg(long, value_name = "FILE")]
    pub junit: Option<PathBuf>,
    /// Also write the results (one row per scene, or per thickness of a sweep) as Parquet,
    /// atomically; needs a build with the cargo feature `parquet`.
    #[arg(long, value_name = "FILE")]
    pub parquet: Option<PathBuf>,
}

impl CheckArgs {
    pub fn overrides(&self) -> Vec<(&'static str, String)> {
        let all: [(&'static str, &Option<String>); 32] = [
            ("roughness.psd", &self.psd),
            ("roughness.profile", &self.profile),
            ("roughness.model", &self.model),
            ("roughness.hurst", &self.hurst),
            ("roughness.q0", &self.q0),
            ("roughness.q1", &self.q1),
            ("roughness.roll_off", &self.roll_off),
            ("roughness.width", &self.width),
            ("roughness.rms_slope", &self.rms_slope),
            ("roughness.rms_height", &self.rms_height),
            ("roughness.q_min", &self.q_min),
            ("roughness.q_max", &self.q_max),
            ("roughness.q_col", &self.q_col),
            ("roughness.c_col", &self.c_col),
            ("roughness.q_unit", &self.q_unit),
            ("roughness.c_unit", &self.c_unit),
            ("roughness.psd_kind", &self.psd_kind),
            ("film.material", &self.film),
            ("film.youngs_modulus", &self.film_youngs_modulus),
            ("film.poisson_ratio", &self.film_poisson_ratio),
            ("film.thickness", &self.thickness),
            ("substrate.material", &self.substrate),
            ("substrate.youngs_modulus", &self.substrate_youngs_modulus),
            ("substrate.poisson_ratio", &self.substrate_poisson_ratio),
            ("substrate.yield_strength", &self.yield_strength),
            ("bond.material", &self.bond),
            ("bond.shear_strength", &self.shear_strength),
            ("load.pressure", &self.pressure),
            ("criteria.epsilon", &self.epsilon),
            ("criteria.safety_factor", &self.safety_factor),
            ("criteria.checks", &self.checks),
            ("numerics.rtol", &self.rtol),
        ];
        all.into_iter()
            .filter_map(|(k, v)| v.clone().map(|v| (k, v)))
            .collect()
    }
}
