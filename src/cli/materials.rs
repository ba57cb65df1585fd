//! `coatcheck materials`: list the materials library.

use coatcheck::Error;
use coatcheck::material::Library;
use coatcheck::report::materials;
use std::path::PathBuf;

/// `--format` of `materials`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum MaterialsFormat {
    Table,
    Json,
}

/// Arguments of `coatcheck materials`.
#[derive(clap::Args, Debug)]
pub struct MaterialsArgs {
    /// Directory of extra material files (*.toml) that add to or override the bundled library.
    #[arg(long)]
    pub materials: Option<PathBuf>,
    /// Output format.
    #[arg(long, value_enum, default_value = "table")]
    pub format: MaterialsFormat,
}

/// Print the library (exit code 0).
pub fn run(args: MaterialsArgs) -> Result<i32, Error> {
    let lib = Library::with_dir(args.materials.as_deref())?;
    let text = match args.format {
        MaterialsFormat::Table => materials::table(&lib)?,
        MaterialsFormat::Json => materials::json(&lib)?,
    };
    coatcheck::report::stdout(&text)?;
    Ok(0)
}
