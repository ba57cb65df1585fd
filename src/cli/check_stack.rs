//! `coatcheck check` on a scene with `[[layer]]` tables: what a stack does not take (yet), and
//! its thickness sweep ([`coatcheck::check::stack::StackChecker::sweep`] reported by
//! [`coatcheck::report::stack_sweep`]); its check goes the film's way, through
//! [`coatcheck::pipeline::judge`].

use super::check_args::CheckArgs;
use coatcheck::Error;
use coatcheck::pipeline;
use coatcheck::report::{self, Format};
use coatcheck::scene::Scene;

/// The options a stack check does not take (yet), by flag.
pub fn refuse(args: &CheckArgs) -> Result<(), Error> {
    let given = [(
        "--parquet with --sweep-thickness",
        args.parquet.is_some() && args.sweep_thickness.is_some(),
    )];
    match given.iter().find(|(_, on)| *on) {
        Some((what, _)) => Err(Error::Value {
            origin: what.to_string(),
            msg: "not available for a layer stack ([[layer]] tables)".into(),
        }),
        None => Ok(()),
    }
}

/// The sweep of the layer `criteria.thickness_of` over `thicknesses`, the others fixed, on the
/// scene's one roughness file.
pub fn sweep(args: &CheckArgs, scene: &Scene, thicknesses: &[f64]) -> Result<String, Error> {
    let (checker, read_warnings) = pipeline::stack_checker(scene)?;
    for w in &read_warnings {
        eprintln!("coatcheck: warning: {w}");
    }
    let rows = checker.sweep(thicknesses)?;
    let design = checker.design();
    report::stack_sweep::sweep(
        &rows,
        &design.layers[design.thickness_of].name,
        checker.roughness(),
        Format::from(args.format),
    )
}
