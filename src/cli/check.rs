//! `coatcheck check`: judge one coating design (scene file and/or flags).

use coatcheck::Error;
use coatcheck::batch::{self, Judged, SceneRun};
use coatcheck::bem::BemSettings;
use coatcheck::check::{Checker, Outcome, log_space};
use coatcheck::material::Library;
use coatcheck::report::{self, Format};
use coatcheck::scene::Scene;
use coatcheck::units::{Dim, parse_quantity};
use coatcheck::verify::verify;
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
    fn overrides(&self) -> Vec<(&'static str, String)> {
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

/// `FROM:TO:N` with lengths in any unit.
fn parse_sweep(text: &str) -> Result<(f64, f64, usize), Error> {
    let bad = |why: &str| Error::Value {
        origin: "--sweep-thickness".into(),
        msg: format!(
            "'{text}': {why} (expected FROM:TO:N with thicknesses > 0 and N >= 1, e.g. 1um:1mm:25)"
        ),
    };
    let parts: Vec<&str> = text.split(':').collect();
    let [a, b, n] = parts[..] else {
        return Err(bad("expected three fields"));
    };
    let len = |s: &str| {
        parse_quantity(s, Dim::Length(1))
            .map_err(|e| bad(&e.to_string()))
            .and_then(|x| {
                if x.is_finite() && x > 0.0 {
                    Ok(x)
                } else {
                    Err(bad("thicknesses must be > 0"))
                }
            })
    };
    let n: usize = n
        .trim()
        .parse()
        .map_err(|_| bad("N is not a whole number"))?;
    if n == 0 || n > 100_000 {
        return Err(bad("N out of range"));
    }
    Ok((len(a)?, len(b)?, n))
}

/// Run the check; the exit code is 0 (pass) or 1 (fail).
pub fn run(args: CheckArgs) -> Result<i32, Error> {
    if args.parquet.is_some() && !coatcheck::parquet::AVAILABLE {
        return Err(coatcheck::parquet::unavailable());
    }
    if is_batch(&args) {
        return run_batch(&args);
    }
    let library = Library::with_dir(args.materials.as_deref())?;
    let sweep = args
        .sweep_thickness
        .as_deref()
        .map(parse_sweep)
        .transpose()?;
    let scene = Scene::load(args.scene.as_deref(), &args.overrides(), &library)?;
    if let Some(w) = scene.version_warning() {
        eprintln!("coatcheck: warning: {w}");
    }
    if !scene.roughness.more_files.is_empty() {
        return run_files(&args, &scene, sweep.is_some());
    }
    let (spectrum, read_warnings) = scene.roughness.spectrum()?;
    for w in &read_warnings {
        eprintln!("coatcheck: warning: {w}");
    }
    let checker = Checker::new(&spectrum, scene.design(), scene.settings)?;
    let (text, code) = if let Some((from, to, n)) = sweep {
        let rows = checker.sweep(&log_space(from, to, n))?;
        if let Some(path) = &args.parquet {
            coatcheck::parquet::write_sweep(path, &rows)?;
        }
        (report::sweep(&rows, args.format)?, 0)
    } else {
        let thickness = scene.thickness.ok_or_else(|| Error::Value {
            origin: scene
                .file
                .as_ref()
                .map_or("scene".into(), |p| p.display().to_string()),
            msg: "film.thickness is missing; give the film thickness (thickness = \"10 um\" under [film], or --thickness 10um)".into(),
        })?;
        let outcome = checker.run(thickness)?;
        write_single_extras(&args, &scene, &outcome)?;
        let exact = if args.verify {
            let (map, surface) = super::verify::scene_map(&scene)?;
            let v = verify(
                &surface,
                checker.design(),
                thickness,
                &BemSettings::default(),
            )?;
            Some((map, v))
        } else {
            None
        };
        let pass = outcome.pass && exact.as_ref().is_none_or(|(_, v)| v.pass);
        let ev = &outcome.evaluation;
        let text = match args.format {
            Format::Table => {
                let mut t = report::human(&scene, &outcome);
                if let Some((map, v)) = &exact {
                    t += &format!("\n{}", super::verify::check_table(map, ev, v));
                }
                t
            }
            Format::Json => {
                let mut j = report::json(&scene, &outcome);
                if let (Some((map, v)), Some(o)) = (&exact, j.as_object_mut()) {
                    o.insert("verify".into(), super::verify::check_json(map, ev, v));
                    o.insert(
                        "verdict_with_verify".into(),
                        (if pass { "pass" } else { "fail" }).into(),
                    );
                }
                format!("{j:#}\n")
            }
            Format::Csv => {
                let mut c = report::csv(&scene, &outcome)?;
                if let Some((_, v)) = &exact {
                    c += &super::verify::check_csv(ev, v);
                    c += &format!(
                        "verdict_with_verify,{},,\n",
                        if pass { "pass" } else { "fail" }
                    );
                }
                c
            }
        };
        (text, if pass { 0 } else { 1 })
    };
    match &args.output {
        Some(path) => report::write_atomic(path, &text)?,
        None => emit(&text),
    }
    Ok(code)
}

/// Print to standard output; a closed pipe (e.g. `| head`) is not an error.
pub fn emit(text: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(text.as_bytes()).and_then(|()| out.flush());
}

/// Several scenes, or a directory: a batch.
fn is_batch(args: &CheckArgs) -> bool {
    !args.more_scenes.is_empty() || args.scene.as_ref().is_some_and(|p| p.is_dir())
}

/// `--junit` and `--parquet` for one scene: a batch of one.
fn write_single_extras(args: &CheckArgs, scene: &Scene, outcome: &Outcome) -> Result<(), Error> {
    if args.junit.is_none() && args.parquet.is_none() {
        return Ok(());
    }
    let run = SceneRun {
        file: scene.file.clone().unwrap_or_else(|| PathBuf::from("scene")),
        seconds: 0.0,
        result: Ok(Judged {
            scene: scene.clone(),
            outcome: outcome.clone(),
            files: Vec::new(),
            warnings: outcome.warnings.clone(),
        }),
    };
    write_batch_extras(args, std::slice::from_ref(&run))
}

fn write_batch_extras(args: &CheckArgs, runs: &[SceneRun]) -> Result<(), Error> {
    if let Some(path) = &args.junit {
        report::write_atomic(path, &coatcheck::junit::report(runs)?)?;
    }
    if let Some(path) = &args.parquet {
        coatcheck::parquet::write_batch(path, runs)?;
    }
    Ok(())
}

/// One scene that lists several roughness files: the detailed report of the worst file, after
/// a table of every file's verdict.
fn run_files(args: &CheckArgs, scene: &Scene, sweep: bool) -> Result<i32, Error> {
    if args.verify {
        return Err(Error::Value {
            origin: "--verify".into(),
            msg: "runs on one height map; this scene lists several (give one with --profile)"
                .into(),
        });
    }
    if sweep {
        return Err(Error::Value {
            origin: "--sweep-thickness".into(),
            msg: format!(
                "a sweep runs on one roughness file; this scene lists {} (give one with --psd or --profile)",
                1 + scene.roughness.more_files.len()
            ),
        });
    }
    let start = std::time::Instant::now();
    let judged = batch::judge(scene)?;
    let run = SceneRun {
        file: scene.file.clone().unwrap_or_else(|| PathBuf::from("scene")),
        seconds: start.elapsed().as_secs_f64(),
        result: Ok(judged),
    };
    let Ok(j) = &run.result else {
        unreachable!("judged above")
    };
    let worst = j.worst_file().map(|p| p.display().to_string());
    let text = match args.format {
        Format::Table => format!(
            "{}{}",
            batch::files_table(j),
            report::human(&j.scene, &j.outcome)
        ),
        Format::Json => {
            let mut v = report::json(&j.scene, &j.outcome);
            v["worst_file"] = serde_json::json!(worst);
            v["files"] = serde_json::json!(j.files);
            v["warnings"] = serde_json::json!(j.warnings);
            format!("{v:#}\n")
        }
        Format::Csv => {
            let mut text = report::csv(&j.scene, &j.outcome)?;
            text += &format!("worst_file,{},,\n", worst.unwrap_or_default());
            text
        }
    };
    write_batch_extras(args, std::slice::from_ref(&run))?;
    match &args.output {
        Some(path) => report::write_atomic(path, &text)?,
        None => emit(&text),
    }
    Ok(if j.outcome.pass { 0 } else { 1 })
}

/// Several scenes or a directory: judged in parallel, one summary (failures first), exit code
/// 0 all pass, 1 any fails, 2 any could not be evaluated.
fn run_batch(args: &CheckArgs) -> Result<i32, Error> {
    for (given, flag) in [
        (args.sweep_thickness.is_some(), "--sweep-thickness"),
        (args.verify, "--verify"),
    ] {
        if given {
            return Err(Error::Value {
                origin: flag.into(),
                msg: "runs on one scene; give one scene file".into(),
            });
        }
    }
    let library = Library::with_dir(args.materials.as_deref())?;
    let inputs: Vec<PathBuf> = args
        .scene
        .iter()
        .chain(&args.more_scenes)
        .cloned()
        .collect();
    let files = batch::scene_files(&inputs)?;
    let start = std::time::Instant::now();
    let progress = progress_bar(files.len());
    let runs = batch::run_all(&files, &args.overrides(), &library, &|| progress.inc(1));
    progress.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    let text = match args.format {
        Format::Table => batch::summary(&runs, seconds),
        Format::Json => batch::json(&runs),
        Format::Csv => batch::csv(&runs)?,
    };
    // The table lists the errors; other formats and files get them on standard error.
    if args.format != Format::Table || args.output.is_some() {
        for run in &runs {
            if let Err(e) = &run.result {
                eprintln!("coatcheck: {e}");
            }
        }
    }
    write_batch_extras(args, &runs)?;
    match &args.output {
        Some(path) => report::write_atomic(path, &text)?,
        None => emit(&text),
    }
    Ok(batch::Totals::of(&runs).exit_code())
}

/// A progress bar on standard error for batches of more than a few scenes; hidden when
/// standard error is not a terminal (CI logs, pipes).
fn progress_bar(n: usize) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if n < 4 || !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(n as u64);
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} scenes ({eta} left)",
    ) {
        bar.set_style(style);
    }
    bar
}
