//! `coatcheck materials`: the library as a table for people or JSON for machines (SI units,
//! `_pa` for stresses and moduli), each entry with its source, and the ranges of its values
//! with theirs (`check --robust`).

use super::{modulus, mpa, table as new_table};
use crate::Error;
use crate::material::{Entry, Library, Ranges, Span};
use serde_json::{Value, json};

/// "4.000 MPa to 8.000 MPa", or "-" without a range.
fn span_text(span: Option<Span>, f: impl Fn(f64) -> String) -> String {
    span.map_or("-".into(), |s| format!("{} to {}", f(s.min), f(s.max)))
}

/// The library as a table (moduli in engineering units, strengths in MPa), then the ranges
/// of the entries that have them, with their sources.
pub fn table(lib: &Library) -> Result<String, Error> {
    let mut t = new_table(&["name", "kind", "E", "nu", "strength", "source"]);
    let mut r = new_table(&[
        "name",
        "E range",
        "nu range",
        "strength range",
        "range source",
    ]);
    let mpa = |x: f64| format!("{} MPa", mpa(x));
    let nu = |x: f64| x.to_string();
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
        let (name, ranges): (&str, &Ranges) = match e {
            Entry::Material(m) => (&m.name, &m.ranges),
            Entry::Bond(b) => (&b.name, &b.ranges),
        };
        if let Some(source) = &ranges.source {
            r.add_row(vec![
                name.to_string(),
                span_text(ranges.youngs_modulus, modulus),
                span_text(ranges.poisson_ratio, nu),
                span_text(ranges.strength, mpa),
                source.clone(),
            ]);
        }
    }
    Ok(format!(
        "{t}\n\nRanges (check --robust judges a design at their worst corner; the others have \
         nominal values only):\n{r}\n"
    ))
}

/// `[min, max]` or null.
fn span_json(s: Option<Span>) -> Value {
    json!(s.map(|s| [s.min, s.max]))
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
                "youngs_modulus_range_pa": span_json(m.ranges.youngs_modulus),
                "poisson_ratio_range": span_json(m.ranges.poisson_ratio),
                "yield_strength_range_pa": span_json(m.ranges.strength),
                "range_source": m.ranges.source,
            })),
            Entry::Bond(b) => bonds.push(json!({
                "name": b.name,
                "shear_strength_pa": b.shear_strength,
                "source": b.source,
                "shear_strength_range_pa": span_json(b.ranges.strength),
                "range_source": b.ranges.source,
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
