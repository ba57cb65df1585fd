//! `coatcheck materials`: the library as a table for people or JSON for machines (SI units,
//! `_pa` for stresses and moduli), each entry with its source.

use super::{modulus, mpa, table as new_table};
use crate::Error;
use crate::material::{Entry, Library};
use serde_json::{Value, json};

/// The library as a table (moduli in engineering units, strengths in MPa).
pub fn table(lib: &Library) -> Result<String, Error> {
    let mut t = new_table(&["name", "kind", "E", "nu", "strength", "source"]);
    let mpa = |x: f64| format!("{} MPa", mpa(x));
    for e in lib.entries()? {
        t.add_row(match e {
            Entry::Material(m) => vec![
                m.name.clone(),
                m.kind.to_string(),
                modulus(m.elastic.youngs),
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
    Ok(format!("{t}\n"))
}

/// The library as JSON: `materials` (films and substrates) and `bonds`, in library order.
pub fn json(lib: &Library) -> Result<String, Error> {
    let (mut materials, mut bonds) = (Vec::new(), Vec::new());
    for e in lib.entries()? {
        match e {
            Entry::Material(m) => materials.push(json!({
                "name": m.name,
                "kind": m.kind.to_string(),
                "youngs_modulus_pa": m.elastic.youngs,
                "poisson_ratio": m.elastic.poisson,
                "yield_strength_pa": m.yield_strength,
                "source": m.source,
            })),
            Entry::Bond(b) => bonds.push(json!({
                "name": b.name,
                "shear_strength_pa": b.shear_strength,
                "source": b.source,
            })),
        }
    }
    let v: Value = json!({
        "schema_version": super::SCHEMA_VERSION,
        "coatcheck_version": env!("CARGO_PKG_VERSION"),
        "materials": materials,
        "bonds": bonds,
    });
    Ok(format!("{v:#}\n"))
}
