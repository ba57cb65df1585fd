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
        Some(path) => report::write_file(path, &text)?,
        None => report::stdout(&text)?,
    }
    Ok(code)
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
        report::write_file(path, &coatcheck::junit::report(runs)?)?;
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
        Some(path) => report::write_file(path, &text)?,
        None => report::stdout(&text)?,
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
        Some(path) => report::write_file(path, &text)?,
        None => report::stdout(&text)?,
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
