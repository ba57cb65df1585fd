//! `coatcheck verify MAP.csv`: the exact contact of a rigid flat with the film on the measured
//! height map (FFT boundary elements, `coatcheck::bem`) beside Persson's estimate from the same
//! map's power spectrum, and the interface stresses at z = d.
//!
//! Arguments to [`coatcheck::verify::compare`]; the output is [`coatcheck::report::verify`]'s.
//! With `--layer` (a layer stack, top first) the same on the stack: [`super::verify_stack`].
//! Exit codes: 0 done (and no pixel's |τ| above `--bond-strength`), 1 the bond strength is
//! exceeded somewhere, 2 bad input or a solve that did not converge (nothing is written then).

use coatcheck::Error;
use coatcheck::bem::BemSettings;
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::Settings;
use coatcheck::report::{
    self,
    verify::{VerifyInputs, sliding_json, sliding_note, verify_json, verify_table, write_fields},
};
use coatcheck::scene::Key;
use coatcheck::topography::HeightMap;
use coatcheck::topography::io::{MapOptions, read_height_map};
use coatcheck::units::{Dim, parse_quantity};
use coatcheck::verify::boundary::{BoundaryChoice, BoundaryDecision};
use coatcheck::verify::compare;
use coatcheck::verify::sliding::compare_sliding;
use std::path::PathBuf;

/// `--boundary` of `verify` and `check --verify`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum BoundaryArg {
    /// Free if the map's edges do not join (edge mismatch above 3), else periodic.
    Auto,
    /// The map is one period of a periodic surface.
    Periodic,
    /// The map is a window of a larger surface (zero-padded, Hockney).
    Free,
}

impl From<BoundaryArg> for BoundaryChoice {
    fn from(b: BoundaryArg) -> Self {
        match b {
            BoundaryArg::Auto => Self::Auto,
            BoundaryArg::Periodic => Self::Periodic,
            BoundaryArg::Free => Self::Free,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum FormatArg {
    Table,
    Json,
    /// One row per compared quantity (layer stacks, `--layer`).
    Csv,
}

/// Exact contact on a height map (treated as one period of a periodic surface), beside
/// Persson's estimate from its spectrum.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Exit codes: 0 done, 1 |tau| exceeds --bond-strength somewhere, \
                        2 bad input or a solve that did not converge."
)]
pub struct VerifyArgs {
    /// Height map: CSV matrix of heights (rows = y, columns = x), in m unless --height-unit
    /// or the file's `# coatcheck height map: ...` comment says otherwise.
    pub map: PathBuf,
    /// Film: Young's modulus and Poisson ratio, e.g. `1MPa,0.5`.
    #[arg(long, required_unless_present = "layer", conflicts_with = "layer")]
    pub film: Option<String>,
    /// A layer of a stack, top first: Young's modulus, Poisson ratio and thickness, e.g.
    /// `1MPa,0.5,10um` (repeat for every layer; instead of --film and --thickness).
    #[arg(long)]
    pub layer: Vec<String>,
    /// Substrate: Young's modulus and Poisson ratio, e.g. `200GPa,0.3`.
    #[arg(long)]
    pub substrate: String,
    /// Film thickness, e.g. `50um`.
    #[arg(long, required_unless_present = "layer", conflicts_with = "layer")]
    pub thickness: Option<String>,
    /// Nominal pressure p0, e.g. `0.1MPa`.
    #[arg(long)]
    pub pressure: String,
    /// Pixel size (x, and y unless --pixel-size-y); overrides the file's metadata.
    #[arg(long)]
    pub pixel_size: Option<String>,
    /// Pixel size along y (between rows), if different from x.
    #[arg(long)]
    pub pixel_size_y: Option<String>,
    /// Unit of the heights (m, um, nm).
    #[arg(long)]
    pub height_unit: Option<String>,
    /// Interface bond strength in shear: reports the area fraction where |τ| exceeds it (at
    /// every interface of a stack).
    #[arg(long, allow_hyphen_values = true)]
    pub bond_strength: Option<String>,
    /// Write the fields (x, y, height, pressure, gap, interface σ_n, τ_x, τ_y, |τ|) as CSV
    /// (with --friction, the interface stresses include the friction-driven part).
    #[arg(long)]
    pub fields: Option<PathBuf>,
    #[arg(long, value_enum, default_value = "table")]
    pub format: FormatArg,
    /// Solver tolerance: rms gap in contact and largest penetration, relative to h_rms
    /// (0 < gap-tol <= 1e-2).
    #[arg(long, allow_hyphen_values = true, default_value_t = BemSettings::default().gap_tol)]
    pub gap_tol: f64,
    /// Solver iteration limit (1 to 1000000).
    #[arg(long, default_value_t = BemSettings::default().max_iter)]
    pub max_iter: usize,
    /// Relative tolerance of Persson's contact integrals (default 1e-8; 1e-13 to 1e-2).
    #[arg(long)]
    pub rtol: Option<String>,
    /// Sliding friction coefficient mu: the traction mu p(x) along x is applied to the solved
    /// (frictionless) pressure, and the interface shear vector is compared with Persson's.
    #[arg(long, allow_hyphen_values = true)]
    pub friction: Option<String>,
    /// Boundary of the map in the exact solve: periodic (one period of a periodic surface),
    /// free (a window of a larger, unloaded surface; the total force is p0 times the map's
    /// area), or auto (free when the rms height step across the map's edges exceeds 3 times
    /// the rms step between neighbours).
    #[arg(long, value_enum, default_value = "auto")]
    pub boundary: BoundaryArg,
}

/// The largest `--gap-tol`: the solver's gaps and penetrations are then within 1% of h_rms; a
/// looser tolerance stops before the contact is resolved (at 1e10 it stops at once, with the
/// whole map in contact).
const GAP_TOL_MAX: f64 = 1e-2;

/// The largest `--max-iter`: each iteration costs two FFTs of the map, so a million of them is
/// hours on a large map; the default converges well within it.
const MAX_ITER: usize = 1_000_000;

pub(super) fn quantity(
    flag: &'static str,
    s: &str,
    dim: Dim,
    expected: &'static str,
) -> Result<f64, Error> {
    parse_quantity(s, dim).map_err(|e| Error::invalid(flag, format!("'{s}' ({e})"), expected))
}

/// `E,nu`: the modulus within the scene's range for `modulus`, the ratio checked by
/// [`Elastic::new`].
pub(super) fn material(flag: &'static str, s: &str, modulus: Key) -> Result<Elastic, Error> {
    const EXPECTED: &str = "E,nu with E a pressure (e.g. 1MPa,0.5)";
    let (e, nu) = s
        .split_once(',')
        .ok_or_else(|| Error::invalid(flag, format!("'{s}'"), EXPECTED))?;
    let e = modulus.parse_flag(flag, e)?;
    let nu = quantity(flag, nu, Dim::Dimensionless, EXPECTED)?;
    Elastic::new(e, nu)
}

/// What `verify` takes besides the solid: the load, the bond strength, the solver's and
/// Persson's settings, and the map.
pub(super) struct Inputs {
    pub p0: f64,
    pub bond: Option<f64>,
    pub settings: BemSettings,
    pub rtol: f64,
    /// The friction coefficient (0 without friction).
    pub mu: f64,
    pub map: HeightMap,
    /// The boundary of the solve (set in `settings`).
    pub boundary: BoundaryDecision,
}

/// The flags of [`Inputs`], checked, and the map read.
pub(super) fn inputs(a: &VerifyArgs) -> Result<Inputs, Error> {
    let p0 = Key::Pressure.parse_flag("--pressure", &a.pressure)?;
    let bond = a
        .bond_strength
        .as_deref()
        .map(|s| Key::ShearStrength.parse_flag("--bond-strength", s))
        .transpose()?;
    if !(a.gap_tol > 0.0 && a.gap_tol <= GAP_TOL_MAX) {
        return Err(Error::invalid(
            "--gap-tol",
            a.gap_tol,
            "0 < gap-tol <= 1e-2 (relative to h_rms)",
        ));
    }
    if !(1..=MAX_ITER).contains(&a.max_iter) {
        return Err(Error::invalid(
            "--max-iter",
            a.max_iter,
            "1 <= max-iter <= 1000000",
        ));
    }
    let length = |flag, s: &Option<String>| {
        s.as_deref()
            .map(|s| quantity(flag, s, Dim::Length(1), "a length (e.g. 0.5um)"))
            .transpose()
    };
    let opts = MapOptions {
        dx: length("--pixel-size", &a.pixel_size)?,
        dy: length("--pixel-size-y", &a.pixel_size_y)?,
        z_unit: a.height_unit.clone(),
        periodic: Some(true),
    };
    let rtol = a
        .rtol
        .as_deref()
        .map(|s| Key::Rtol.parse_flag("--rtol", s))
        .transpose()?
        .unwrap_or(coatcheck::prec::DEFAULT_RTOL);
    let mu = a
        .friction
        .as_deref()
        .map(|s| Key::Friction.parse_flag("--friction", s))
        .transpose()?
        .unwrap_or(0.0);
    let map = read_height_map(&a.map, &opts)?;
    let boundary = BoundaryDecision::for_map(a.boundary.into(), &map);
    let settings = BemSettings {
        gap_tol: a.gap_tol,
        max_iter: a.max_iter,
        boundary: boundary.boundary,
    };
    Ok(Inputs {
        p0,
        bond,
        settings,
        rtol,
        mu,
        map,
        boundary,
    })
}

/// Run `coatcheck verify`; returns the exit code or an error (exit code 2).
pub fn run(a: VerifyArgs) -> Result<i32, Error> {
    if !a.layer.is_empty() {
        return super::verify_stack::run(&a);
    }
    const CLAP: &str = "clap requires --film and --thickness without --layer";
    let film = material(
        "--film",
        a.film.as_deref().expect(CLAP),
        Key::FilmYoungsModulus,
    )?;
    let substrate = material("--substrate", &a.substrate, Key::SubstrateYoungsModulus)?;
    let d = Key::Thickness.parse_flag("--thickness", a.thickness.as_deref().expect(CLAP))?;
    if a.format == FormatArg::Csv {
        return Err(Error::invalid(
            "--format",
            "csv",
            "table or json (csv is written for a layer stack, --layer)",
        ));
    }
    let Inputs {
        p0,
        bond,
        settings,
        rtol,
        mu,
        map,
        boundary,
    } = inputs(&a)?;
    let stack = Stack::new(Bilayer::new(film, substrate), d)?;
    let (c, sliding) = if mu > 0.0 {
        let s = compare_sliding(&map, &stack, (p0, mu), &settings, Settings { rtol }, bond)?;
        (s.comparison, Some((s.exact, s.persson)))
    } else {
        (
            compare(&map, &stack, p0, &settings, Settings { rtol }, bond)?,
            None,
        )
    };
    if let Some(path) = &a.fields {
        write_fields(path, &c.surface, &c.solution, &c.fields)?;
    }
    let inputs = VerifyInputs {
        map: &a.map,
        stack: &stack,
        p0,
        bond,
        boundary,
    };
    let mut table = verify_table(&inputs, &c);
    if let Some(s) = &sliding {
        table += &sliding_note(&s.0, &s.1);
    }
    report::stdout(&match a.format {
        // CSV was refused above.
        FormatArg::Table | FormatArg::Csv => table,
        FormatArg::Json => {
            // JSON shows NaN as null: the table of the same numbers is checked instead.
            report::finite_only(&table)?;
            let mut v = verify_json(&inputs, &c);
            if let (Some(s), Some(o)) = (&sliding, v.as_object_mut()) {
                o.insert("sliding".into(), sliding_json(&s.0, &s.1));
            }
            format!(
                "{}\n",
                serde_json::to_string_pretty(&v).expect("a JSON value serialises")
            )
        }
    })?;
    Ok(if c.above_bond.is_some_and(|f| f > 0.0) {
        1
    } else {
        0
    })
}
