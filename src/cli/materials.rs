//! `coatcheck materials`: list the materials library.

use coatcheck::Error;
use coatcheck::material::{Entry, Library};
use coatcheck::report::sig;
use comfy_table::{ContentArrangement, Table, presets::UTF8_FULL_CONDENSED};
use std::path::PathBuf;

/// Arguments of `coatcheck materials`.
#[derive(clap::Args, Debug)]
pub struct MaterialsArgs {
    /// Directory of extra material files (*.toml) that add to or override the bundled library.
    #[arg(long)]
    pub materials: Option<PathBuf>,
}

/// Print the library as a table (exit code 0).
pub fn run(args: MaterialsArgs) -> Result<i32, Error> {
    let lib = Library::with_dir(args.materials.as_deref())?;
    let mut t = Table::new();
    t.load_preset(UTF8_FULL_CONDENSED)
        .set_content_arrangement(ContentArrangement::Dynamic)
        .set_width(120)
        .set_header(["name", "kind", "E [MPa]", "nu", "strength [MPa]", "source"]);
    let mpa = |x: f64| sig(x * 1e-6, 4);
    for e in lib.entries()? {
        t.add_row(match e {
            Entry::Material(m) => vec![
                m.name.clone(),
                m.kind.to_string(),
                mpa(m.elastic.youngs),
                m.elastic.poisson.to_string(),
                m.yield_strength
                    .map(|y| format!("yield {}", mpa(y)))
                    .unwrap_or_else(|| "-".into()),
                m.source.clone(),
            ],
            Entry::Bond(b) => vec![
                b.name.clone(),
                "bond".into(),
                "-".into(),
                "-".into(),
                format!("shear {}", mpa(b.shear_strength)),
                b.source.clone(),
            ],
        });
    }
    coatcheck::report::stdout(&format!("{t}\n"))?;
    Ok(0)
}
