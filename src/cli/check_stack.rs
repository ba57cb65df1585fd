//! `coatcheck check` on a scene with `[[layer]]` tables: the stack's checks
//! ([`coatcheck::check::stack`]) reported as a table or JSON ([`coatcheck::report::stack`]);
//! with `--verify` also the exact contact on the scene's height map judged at every interface
//! ([`coatcheck::verify_stack`], [`coatcheck::report::verify_stack`]).

use super::OutputFormat;
use super::check_args::CheckArgs;
use coatcheck::Error;
use coatcheck::bem::BemSettings;
use coatcheck::check::stack::StackChecker;
use coatcheck::scene::Scene;
use coatcheck::topography::plausible::periodic_warning;
use coatcheck::{pipeline, report, verify_stack};

/// The options a stack check does not take (yet), by flag.
fn refuse(args: &CheckArgs, scene: &Scene) -> Result<(), Error> {
    let given = [
        ("--sweep-thickness", args.sweep_thickness.is_some()),
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
    ];
    match given.iter().find(|(_, on)| *on) {
        Some((what, _)) => Err(Error::Value {
            origin: what.to_string(),
            msg: "not available for a layer stack ([[layer]] tables): its check reports as a \
                  table or JSON (with --verify on a height map), on one roughness file"
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
    let mut outcome = checker.run()?;
    let exact = if args.verify {
        let (map, surface, mismatch) = pipeline::scene_map(scene)?;
        outcome.warnings.extend(periodic_warning(&map, mismatch));
        let v = verify_stack::verify(&surface, checker.design(), &BemSettings::default())?;
        Some((map, v))
    } else {
        None
    };
    let pass = outcome.pass && exact.as_ref().is_none_or(|(_, v)| v.pass);
    let text = match args.format {
        OutputFormat::Json => {
            let mut v = report::stack::json(scene, &outcome);
            if let (Some((map, x)), Some(o)) = (&exact, v.as_object_mut()) {
                // JSON shows NaN as null: the table of the same numbers is checked instead.
                report::finite_only(&report::verify_stack::check_table(map, &outcome, x))?;
                o.insert(
                    "verify".into(),
                    report::verify_stack::check_json(map, &outcome, x),
                );
                o.insert(
                    "verdict_with_verify".into(),
                    if pass { "pass" } else { "fail" }.into(),
                );
            }
            format!(
                "{}\n",
                serde_json::to_string_pretty(&v).expect("plain values serialise")
            )
        }
        _ => {
            let mut t = report::stack::human(scene, &outcome);
            if let Some((map, x)) = &exact {
                t += &format!("\n{}", report::verify_stack::check_table(map, &outcome, x));
            }
            t
        }
    };
    match &args.output {
        Some(path) => report::write_file(path, &text)?,
        None => report::stdout(&text)?,
    }
    Ok(if pass { 0 } else { 1 })
}
