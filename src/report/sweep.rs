//! The thickness sweep (the paper's Fig. 7 as a table): one row per thickness, as a table, JSON
//! or CSV. Under sliding friction the sliding columns ([`SLIDING`]) follow, so that the static
//! and the sliding peak shear stand side by side.

use super::{Format, mpa, sig, table, um};
use crate::check::{CheckKind, Evaluation};
use crate::error::Error;
use serde_json::{Map, Value, json};

/// The sweep columns: (table header, JSON and CSV key, getter in SI).
pub type Getter = fn(&Evaluation) -> Option<f64>;
pub const SWEEP: &[(&str, &str, Getter)] = &[
    ("A/A0", "area_fraction", |e| {
        Some(e.contact.area_fraction.value)
    }),
    ("E_eff/ E_film", "e_eff_over_e_film", |e| {
        e.contact.e_eff_over_e_film.map(|x| x.value)
    }),
    ("p_mean", "mean_contact_pressure_pa", |e| {
        Some(e.mean_contact_pressure.value)
    }),
    ("σ_rms top", "sigma_rms_top_pa", |e| {
        e.contact.sigma_rms_top.map(|x| x.value)
    }),
    ("σ_rms int", "sigma_rms_interface_pa", |e| {
        e.contact.sigma_rms_interface.map(|x| x.value)
    }),
    ("σ_peak int", "sigma_peak_interface_pa", |e| {
        e.sigma_peak_interface.map(|x| x.value)
    }),
    ("τ_rms int", "tau_rms_interface_pa", |e| {
        e.contact.tau_rms_interface.map(|x| x.value)
    }),
    ("τ_peak int", "tau_peak_pa", |e| {
        e.tau_peak.map(|x| x.value)
    }),
];

/// The columns added under sliding friction (`tau_peak` is then the vector rule's peak).
pub const SLIDING: &[(&str, &str, Getter)] = &[
    ("τ_peak st", "tau_peak_static_pa", |e| {
        e.tau_peak_static.map(|x| x.value)
    }),
    ("τ_x rms", "tau_x_rms_interface_pa", |e| {
        e.sliding.map(|s| s.tau_x_rms.value)
    }),
    ("τ_y rms", "tau_y_rms_interface_pa", |e| {
        e.sliding.map(|s| s.tau_y_rms.value)
    }),
];

/// The friction of a sweep under sliding (`None` when static).
fn friction(rows: &[Evaluation]) -> Option<f64> {
    rows.iter()
        .find_map(|e| e.sliding.map(|s| s.friction))
        .filter(|&mu| mu > 0.0)
}

/// The thickness sweep in the chosen format, with the h_rms (m) and rms slope of the spectrum
/// used (`roughness`; in the table's caption and the JSON's top level).
pub fn sweep(
    rows: &[Evaluation],
    (h_rms, rms_slope): (f64, f64),
    format: Format,
) -> Result<String, Error> {
    let mu = friction(rows);
    let extra: &[(&str, &str, Getter)] = if mu.is_some() { SLIDING } else { &[] };
    let cols: Vec<&(&str, &str, Getter)> = SWEEP.iter().chain(extra).collect();
    match format {
        Format::Table => {
            // Short headers (a unit line above) so that the table fits the width; σ_rms of the
            // top surface, nearly constant in d, is in JSON and CSV only.
            let shown: Vec<_> = cols
                .iter()
                .filter(|(_, k, _)| *k != "sigma_rms_top_pa")
                .collect();
            let mut head = vec!["d"];
            head.extend(shown.iter().map(|(h, _, _)| *h));
            head.push("fails");
            let mut t = table(&head);
            for ev in rows {
                let mut cells = vec![um(ev.contact.thickness)];
                for (_, key, get) in &shown {
                    cells.push(match get(ev) {
                        Some(x) if key.ends_with("_pa") => mpa(x),
                        Some(x) => sig(x, 4),
                        None => "-".into(),
                    });
                }
                let failing: Vec<_> = ev
                    .checks
                    .iter()
                    .filter(|c| !c.pass)
                    .map(|c| match c.kind {
                        CheckKind::BondShear => "bond",
                        CheckKind::SubstrateYield => "yield",
                        CheckKind::MinThickness => "d_min",
                    })
                    .collect();
                cells.push(if failing.is_empty() {
                    "-".into()
                } else {
                    failing.join(", ")
                });
                t.add_row(cells);
            }
            let mut caption = format!(
                "spectrum used: h_rms = {} µm, rms slope = {}. d in µm, stresses in MPa; fails: \
                 the checks failing at that thickness (bond: bond-shear, yield: substrate-yield)",
                um(h_rms),
                sig(rms_slope, 4)
            );
            if let Some(mu) = mu {
                caption += &format!(
                    "; sliding with friction mu = {mu}: τ_peak int is |tau| of the shear vector \
                     (mu p0 + X, Y) (vector rule), τ_peak st the paper's half-normal rule on the \
                     static shear; σ columns include the friction-driven part"
                );
            }
            Ok(format!("{}\n{t}\n", super::wrap(&caption)))
        }
        Format::Json => {
            // JSON shows NaN as null: the CSV of the same numbers is checked instead.
            super::finite_only(&sweep(rows, (h_rms, rms_slope), Format::Csv)?)?;
            let list: Vec<Value> = rows
                .iter()
                .map(|ev| {
                    let mut m = Map::new();
                    m.insert("thickness_m".into(), json!(ev.contact.thickness));
                    for (_, key, get) in &cols {
                        m.insert((*key).into(), json!(get(ev)));
                    }
                    let checks: Vec<Value> = ev
                        .checks
                        .iter()
                        .map(|c| json!({"name": c.kind.name(), "value": c.value.value, "limit": c.limit, "pass": c.pass}))
                        .collect();
                    m.insert("checks".into(), Value::Array(checks));
                    Value::Object(m)
                })
                .collect();
            Ok(format!(
                "{:#}\n",
                json!({
                    "schema_version": super::SCHEMA_VERSION,
                    "coatcheck_version": env!("CARGO_PKG_VERSION"),
                    "h_rms_m": h_rms,
                    "rms_slope": rms_slope,
                    "sweep": list,
                })
            ))
        }
        Format::Csv => {
            let mut w = csv::Writer::from_writer(Vec::new());
            let ser = |e: csv::Error| Error::Numerical {
                what: "CSV output",
                detail: e.to_string(),
            };
            let mut head = vec!["thickness_m".to_string()];
            head.extend(cols.iter().map(|(_, k, _)| k.to_string()));
            w.write_record(&head).map_err(ser)?;
            for ev in rows {
                let mut cells = vec![format!("{:e}", ev.contact.thickness)];
                for (_, _, get) in &cols {
                    cells.push(get(ev).map(|x| format!("{x:e}")).unwrap_or_default());
                }
                w.write_record(&cells).map_err(ser)?;
            }
            let bytes = w.into_inner().map_err(|e| Error::Numerical {
                what: "CSV output",
                detail: e.to_string(),
            })?;
            Ok(String::from_utf8_lossy(&bytes).into_owned())
        }
    }
}
