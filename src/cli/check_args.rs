//! The arguments of `coatcheck check`: its own flags, and one flag per scene key (built from
//! the scene's key table) whose values override the scene file's.

use super::OutputFormat;
use clap::builder::ValueParser;
use clap::{Arg, ArgAction, ArgMatches, Command, FromArgMatches};
use coatcheck::scene::{Key, Value};
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
    /// Flags for the scene keys (`--psd`, `--thickness`, ...), from the scene's key table.
    #[command(flatten)]
    pub keys: SceneFlags,
    /// Output format.
    #[arg(long, value_enum, default_value = "table")]
    pub format: OutputFormat,
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
    /// boundary elements and judge the checks on the solved fields, the minimum thickness
    /// included; a scene given by a spectrum is solved on random-phase realisations of it. The
    /// design then passes only if both pass.
    #[arg(long, conflicts_with = "sweep_thickness")]
    pub verify: bool,
    /// With --verify on a scene without a height map: the number of random-phase realisations
    /// of its spectrum (fixed seeds 1..K), 2 to 256.
    #[arg(long, value_name = "K", requires = "verify", default_value_t = coatcheck::exact::realisations::DEFAULT_REALISATIONS)]
    pub realisations: usize,
    /// With --verify on a scene without a height map: the largest side of the realisations'
    /// grid in pixels, a power of two from 32 to 4096 (a solve holds about 120 n² bytes).
    #[arg(long, value_name = "N", requires = "verify", default_value_t = coatcheck::exact::realisations::DEFAULT_MAX_SIDE)]
    pub realisation_grid: usize,
    /// With --verify: the boundary of the exact solve on the height map (auto, periodic or
    /// free; see `coatcheck verify --help`). Realisations are periodic unless free is given.
    #[arg(long, value_enum, requires = "verify", default_value = "auto")]
    pub boundary: super::verify::BoundaryArg,
    /// Also write the qualification report as one self-contained HTML page (verdict, checks,
    /// what would make a failing design pass, inputs with sources, plots, warnings,
    /// uncertainty), atomically; a batch gets a summary and a section per scene.
    #[arg(long, value_name = "FILE.html", conflicts_with = "sweep_thickness")]
    pub report: Option<PathBuf>,
    /// Also write a JUnit XML report (a test case per scene and check), atomically.
    #[arg(long, value_name = "FILE")]
    pub junit: Option<PathBuf>,
    /// Also write the results (one row per scene, or per thickness of a sweep) as Parquet,
    /// atomically; needs a build with the cargo feature `parquet`.
    #[arg(long, value_name = "FILE")]
    pub parquet: Option<PathBuf>,
}

impl CheckArgs {
    /// The scene keys given as flags, `(key name, text)`, in table order.
    pub fn overrides(&self) -> Vec<(&'static str, String)> {
        self.keys
            .0
            .iter()
            .map(|(k, v)| (k.name(), v.clone()))
            .collect()
    }
}

/// The values of the scene-key flags given, in table order. One flag per row of
/// [`coatcheck::scene::KEYS`]: `--flag <FLAG>` with the row's help; numbers and file names may
/// start with `-` (a negative number is then rejected naming its key).
#[derive(Debug)]
pub struct SceneFlags(Vec<(Key, String)>);

/// The flag's name without dashes: also its argument id.
fn long(key: Key) -> &'static str {
    key.flag().trim_start_matches("--")
}

fn arg(key: Key) -> Arg {
    let spec = key.spec();
    let arg = Arg::new(long(key));
    // A switch's flag alone means yes; `=` keeps the next argument (a scene file) its own.
    let arg = match spec.value {
        Value::Switch => arg
            .num_args(0..=1)
            .require_equals(true)
            .default_missing_value("true"),
        _ => arg,
    };
    arg.long(long(key))
        .value_name(long(key).to_uppercase().replace('-', "_"))
        .help(spec.help)
        .action(ArgAction::Set)
        .value_parser(ValueParser::string())
        .allow_hyphen_values(matches!(
            spec.value,
            Value::Files | Value::Quantity(..) | Value::Span(_)
        ))
}

impl clap::Args for SceneFlags {
    fn augment_args(cmd: Command) -> Command {
        cmd.args(Key::ALL.iter().map(|&k| arg(k)))
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

impl FromArgMatches for SceneFlags {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        Ok(SceneFlags(
            Key::ALL
                .iter()
                .filter_map(|&k| m.get_one::<String>(long(k)).map(|v| (k, v.clone())))
                .collect(),
        ))
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        for &k in Key::ALL {
            if let Some(v) = m.get_one::<String>(long(k)) {
                self.0.retain(|(key, _)| *key != k);
                self.0.push((k, v.clone()));
            }
        }
        self.0.sort_by_key(|(k, _)| *k as usize);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::{CommandFactory, Parser};
    use coatcheck::scene::KEYS;

    #[derive(Parser)]
    struct Check {
        #[command(flatten)]
        args: CheckArgs,
    }

    fn parse(argv: &[&str]) -> CheckArgs {
        Check::try_parse_from(std::iter::once("check").chain(argv.iter().copied()))
            .unwrap()
            .args
    }

    #[test]
    fn every_scene_key_has_its_flag_with_its_help() {
        Check::command().debug_assert();
        let help = Check::command().render_help().to_string();
        for spec in KEYS {
            let value = spec.flag[2..].to_uppercase().replace('-', "_");
            let switch = spec.value == Value::Switch;
            let shown = if switch {
                format!("{}[=<{value}>]", spec.flag)
            } else {
                format!("{} <{value}>", spec.flag)
            };
            assert!(help.contains(&shown), "{}", spec.flag);
            assert!(help.contains(spec.help), "{}", spec.help);
            let args = if switch {
                // Alone it means yes, and the next argument stays the scene.
                let alone = parse(&[spec.flag, "scene.toml"]);
                assert_eq!(alone.overrides(), vec![(spec.name, "true".to_string())]);
                assert_eq!(alone.scene, Some(PathBuf::from("scene.toml")));
                parse(&[&format!("{}=x", spec.flag)])
            } else {
                parse(&[spec.flag, "x"])
            };
            assert_eq!(args.overrides(), vec![(spec.name, "x".to_string())]);
        }
    }

    #[test]
    fn overrides_keep_table_order_and_hyphens_where_numbers_go() {
        let args = parse(&[
            "s.toml",
            "--pressure",
            "1MPa",
            "--thickness",
            "-1um",
            "--film",
            "nbr",
            "--format",
            "json",
        ]);
        assert_eq!(
            args.overrides(),
            vec![
                ("film.material", "nbr".to_string()),
                ("film.thickness", "-1um".to_string()),
                ("load.pressure", "1MPa".to_string()),
            ]
        );
        assert!(args.scene.is_some() && args.more_scenes.is_empty());
        // A name never starts with '-': `--film -x` is a missing value, not a name.
        assert!(Check::try_parse_from(["check", "--film", "-x"]).is_err());
    }

    #[test]
    fn an_update_replaces_only_the_flags_it_gives() {
        let mut args = parse(&["--thickness", "1um", "--film", "nbr"]);
        let m = Check::command()
            .try_get_matches_from(["check", "--thickness", "2um", "--bond", "epoxy"])
            .unwrap();
        args.update_from_arg_matches(&m).unwrap();
        assert_eq!(
            args.overrides(),
            vec![
                ("film.material", "nbr".to_string()),
                ("film.thickness", "2um".to_string()),
                ("bond.material", "epoxy".to_string()),
            ]
        );
    }
}
