//! `coatcheck check`: judge one coating design (scene file and/or flags).

use coatcheck::Error;
use coatcheck::batch::{self, SceneRun};
use coatcheck::bem::BemSettings;
use coatcheck::check::log_space;
use coatcheck::exact::ExactOptions;
use coatcheck::material::Library;
use coatcheck::pipeline;
use coatcheck::report::{self, Format};
use coatcheck::scene::{Key, Scene};
use std::path::PathBuf;

pub use super::check_args::CheckArgs;

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
    // Each end within film.thickness's range, as a scene's thickness.
    let len = |s: &str| Key::Thickness.parse_flag("--sweep-thickness", s);
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
    if args.parquet.is_some() && !report::parquet::AVAILABLE {
        return Err(report::parquet::unavailable());
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
    if scene.is_stack() {
        super::check_stack::refuse(&args)?;
    }
    let several = !scene.roughness.more_files.is_empty();
    let (text, code) = match sweep {
        Some(range) => (run_sweep(&args, &scene, range)?, 0),
        None => {
            let exact = args.verify.then(|| exact_options(&args)).transpose()?;
            let started = std::time::Instant::now();
            let judged =
                pipeline::judge_exact(&scene, exact.as_ref()).map_err(|e| match &scene.file {
                    Some(file) => coatcheck::batch::naming(file, e),
                    None => e,
                })?;
            let run = SceneRun {
                file: scene.file.clone().unwrap_or_else(|| PathBuf::from("scene")),
                seconds: if several {
                    started.elapsed().as_secs_f64()
                } else {
                    0.0
                },
                result: Ok(judged),
            };
            write_extras(&args, std::slice::from_ref(&run))?;
            let Ok(j) = &run.result else {
                unreachable!("judged above")
            };
            (
                report::scene(j, Format::from(args.format))?,
                if j.pass() { 0 } else { 1 },
            )
        }
    };
    output(&args, &text)?;
    Ok(code)
}

/// The exact check's options from `--realisations` and `--realisation-grid`.
fn exact_options(args: &CheckArgs) -> Result<ExactOptions, Error> {
    use coatcheck::exact::realisations::{MAX_REALISATIONS, MAX_SIDE, MIN_SIDE};
    if !(2..=MAX_REALISATIONS).contains(&args.realisations) {
        return Err(Error::invalid(
            "--realisations",
            args.realisations,
            "2 <= K <= 256",
        ));
    }
    let n = args.realisation_grid;
    if !(n.is_power_of_two() && (MIN_SIDE..=MAX_SIDE).contains(&n)) {
        return Err(Error::invalid(
            "--realisation-grid",
            n,
            "a power of two from 32 to 4096",
        ));
    }
    Ok(ExactOptions {
        bem: BemSettings::default(),
        realisations: args.realisations,
        max_side: n,
        boundary: args.boundary.into(),
    })
}

/// The thickness sweep of a scene with one roughness file.
fn run_sweep(
    args: &CheckArgs,
    scene: &Scene,
    (from, to, n): (f64, f64, usize),
) -> Result<String, Error> {
    if !scene.roughness.more_files.is_empty() {
        return Err(Error::Value {
            origin: "--sweep-thickness".into(),
            msg: format!(
                "a sweep runs on one roughness file; this scene lists {} (give one with --psd or --profile)",
                1 + scene.roughness.more_files.len()
            ),
        });
    }
    if scene.robust {
        return Err(Error::Value {
            origin: "--sweep-thickness".into(),
            msg: "--robust (criteria.robust) judges the design at its thickness; run it without \
                  the sweep"
                .into(),
        });
    }
    if scene.is_stack() {
        return super::check_stack::sweep(args, scene, &log_space(from, to, n));
    }
    let (checker, read_warnings) = pipeline::checker(scene)?;
    for w in &read_warnings {
        eprintln!("coatcheck: warning: {w}");
    }
    let rows = checker.sweep(&log_space(from, to, n))?;
    if let Some(path) = &args.parquet {
        report::parquet::write_sweep(path, &rows)?;
    }
    report::sweep(&rows, checker.roughness(), Format::from(args.format))
}

/// The report to `--output` or standard output.
fn output(args: &CheckArgs, text: &str) -> Result<(), Error> {
    match &args.output {
        Some(path) => report::write_file(path, text),
        None => report::stdout(text),
    }
}

/// Several scenes, or a directory: a batch.
fn is_batch(args: &CheckArgs) -> bool {
    !args.more_scenes.is_empty() || args.scene.as_ref().is_some_and(|p| p.is_dir())
}

/// `--junit` and `--parquet` (one scene is a batch of one).
fn write_extras(args: &CheckArgs, runs: &[SceneRun]) -> Result<(), Error> {
    if let Some(path) = &args.junit {
        report::write_file(path, &report::junit::report(runs)?)?;
    }
    if let Some(path) = &args.parquet {
        report::parquet::write_batch(path, runs)?;
    }
    if let Some(path) = &args.report {
        let meta = report::html::Meta {
            version: env!("CARGO_PKG_VERSION").into(),
            date: report::html::utc_date(),
            command_line: std::env::args().collect::<Vec<_>>().join(" "),
        };
        report::write_file(path, &report::html::page(runs, &meta)?)?;
    }
    Ok(())
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
    let text = report::batch::report(&runs, seconds, Format::from(args.format))?;
    // The table lists the errors; other formats and files get them on standard error.
    if Format::from(args.format) != Format::Table || args.output.is_some() {
        for run in &runs {
            if let Err(e) = &run.result {
                eprintln!("coatcheck: {e}");
            }
        }
    }
    write_extras(args, &runs)?;
    output(args, &text)?;
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
