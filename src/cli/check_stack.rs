//! `coatcheck check` on a scene with `[[layer]]` tables: the stack's checks
//! ([`coatcheck::check::stack`]) reported as a table or JSON ([`coatcheck::report::stack`]).

use super::OutputFormat;
use super::check_args::CheckArgs;
use coatcheck::Error;
use coatcheck::check::stack::StackChecker;
use coatcheck::report;
use coatcheck::scene::Scene;

/// The options a stack check does not take (yet), by flag.
fn refuse(args: &CheckArgs, scene: &Scene) -> Result<(), Error> {
    let given = [
        ("--sweep-thickness", args.sweep_thickness.is_some()),
        ("--verify", args.verify),
        ("--report", args.report.is_some()),
        ("--junit", args.junit.is_some()),
        ("--parquet", args.parquet.is_some()),
        ("--format csv", args.format == OutputFormat::Csv),
        (
            "several roughness files",
            !scene.roughness.more_files.is_empty(),
        ),
        ("load.friction (sliding)", scene.friction > 0.0),
        ("criteria.shear_tail", scene.criteria.shear_tail.is_some()),
        ("--robust (criteria.robust)", scene.robust),
    ];
    match given.iter().find(|(_, on)| *on) {
        Some((what, _)) => Err(Error::Value {
            origin: what.to_string(),
            msg: "not available for a layer stack ([[layer]] tables): its check reports as a \
                  table or JSON, on one roughness file"
                .into(),
        }),
        None => Ok(()),
    }
}

/// Judge the stack; the exit code is 0 (pass) or 1 (fail).
pub fn run(args: &CheckArgs, scene: &Scene) -> Result<i32, Error> {
    refuse(args, scene)?;
    let (spectrum, warnings) = scene.roughness.spectrum()?;
    for w in &warnings {
        eprintln!("coatcheck: warning: {w}");
    }
    let checker = StackChecker::new(&spectrum, scene.stack_design(), scene.settings)?;
    let outcome = checker.run()?;
    let text = match args.format {
        OutputFormat::Json => format!(
            "{}\n",
            serde_json::to_string_pretty(&report::stack::json(scene, &outcome))
                .expect("plain values serialise")
        ),
        _ => report::stack::human(scene, &outcome),
    };
    match &args.output {
        Some(path) => report::write_file(path, &text)?,
        None => report::stdout(&text)?,
    }
    Ok(if outcome.pass { 0 } else { 1 })
}
