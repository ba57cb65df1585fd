//! The thickness sweep (the paper's Fig. 7 as a table): one row per thickness, as a table, JSON
//! or CSV. Under sliding friction the sliding columns ([`SLIDING`]) follow, so that the static
//! and the sliding peak shear stand side by side.

use super::{Format, mpa, sig, table, um};
use crate::check::Evaluation;
use crate::error::Error;
use serde_json::{Map, Value, json};

/// The sweep columns: (header, unit scale to SI, getter).
pub type Getter = fn(&Evaluation) -> Option<f64>;
pub const SWEEP: &[(&str, &str, Getter)] = &[
    ("A/A0", "area_fraction", |e| {
        Some(e.contact.area_fraction.value)
    }),
    ("E_eff/E_film", "e_eff_over_e_film", |e| {
        e.contact.e_eff_over_e_film.map(|x| x.value)
    }),
    ("p_mean [MPa]", "mean_contact_pressure_pa", |e| {
        Some(e.mean_contact_pressure.value)
    }),
    ("sigma_rms top [MPa]", "sigma_rms_top_pa", |e| {
        e.contact.sigma_rms_top.map(|x| x.value)
    }),
    ("sigma_rms int [MPa]", "sigma_rms_interface_pa", |e| {
        e.contact.sigma_rms_interface.map(|x| x.value)
    }),
    ("sigma_peak int [MPa]", "sigma_peak_interface_pa", |e| {
        e.sigma_peak_interface.map(|x| x.value)
    }),
    ("tau_rms [MPa]", "tau_rms_interface_pa", |e| {
        e.contact.tau_rms_interface.map(|x| x.value)
    }),
    ("tau_peak [MPa]", "tau_peak_pa", |e| {
        e.tau_peak.map(|x| x.value)
    }),
];

/// The columns added under sliding friction (`tau_peak` is then the vector rule's peak).
pub const SLIDING: &[(&str, &str, Getter)] = &[
    ("tau_peak static [MPa]", "tau_peak_static_pa", |e| {
        e.tau_peak_static.map(|x| x.value)
    }),
    ("tau_x_rms [MPa]", "tau_x_rms_interface_pa", |e| {
        e.sliding.map(|s| s.tau_x_rms.value)
    }),
    ("tau_y_rms [MPa]", "tau_y_rms_interface_pa", |e| {
        e.sliding.map(|s| s.tau_y_rms.value)
    }),
];

/// The friction of a sweep under sliding (`None` when static).
fn friction(rows: &[Evaluation]) -> Option<f64> {
    rows.iter()
        .find_map(|e| e.sliding.map(|s| s.friction))
        .filter(|&mu| mu > 0.0)
}

/// The thickness sweep in the chosen format.
pub fn sweep(rows: &[Evaluation], format: Format) -> Result<String, Error> {
    let pressure_col = |h: &str| h.contains("MPa");
    let mu = friction(rows);
    let extra: &[(&str, &str, Getter)] = if mu.is_some() { SLIDING } else { &[] };
    let cols: Vec<&(&str, &str, Getter)> = SWEEP.iter().chain(extra).collect();
    match format {
        Format::Table => {
            let mut head = vec!["d [um]"];
            head.extend(cols.iter().map(|(h, _, _)| *h));
            head.push("checks");
            let mut t = table(&head);
            for ev in rows {
                let mut cells = vec![um(ev.contact.thickness)];
                for (h, _, get) in &cols {
                    cells.push(match get(ev) {
                        Some(x) if pressure_col(h) => mpa(x),
                        Some(x) => sig(x, 4),
                        None => "-".into(),
                    });
                }
                cells.push(
                    ev.checks
                        .iter()
                        .map(|c| {
                            format!("{} {}", c.kind.name(), if c.pass { "PASS" } else { "FAIL" })
                        })
                        .collect::<Vec<_>>()
                        .join(", "),
                );
                t.add_row(cells);
            }
            let note = mu
                .map(|mu| {
                    format!(
                        "sliding with friction mu = {mu}: tau_peak is |tau| of the shear vector \
                         (mu p0 + X, Y) (vector rule); tau_peak static is the paper's half-normal \
                         rule on the static shear; sigma columns include the friction-driven part\n"
                    )
                })
                .unwrap_or_default();
            Ok(format!("{t}\n{note}"))
        }
        Format::Json => {
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
            Ok(format!("{:#}\n", json!({ "sweep": list })))
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
