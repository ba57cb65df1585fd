//! The thickness sweep of a layer stack (`check --sweep-thickness` on a `[[layer]]` scene): the
//! layer `criteria.thickness_of` names at each thickness, the others fixed; one row per
//! thickness as a table, JSON or CSV.
//!
//! JSON: the film sweep's document (`sweep.schema.json`) with `thickness_of` at the top; each
//! item's film keys hold the top surface, the contact and the bottom interface (on the
//! substrate), as in the stack check's JSON, its `checks` say where they apply (`at`), and
//! `interfaces` lists every interface, top first (`name`, `depth_m`, `sigma_rms_pa`,
//! `tau_rms_pa`, `tau_peak_pa`, `sigma_peak_pa`). CSV: `thickness_m`, the film sweep's columns,
//! then `interface<k>_sigma_rms_pa`, `_tau_rms_pa`, `_tau_peak_pa`, `_sigma_peak_pa` for each
//! interface k (1 the top layer's).

use super::{Format, mpa, sig, table, um, wrap};
use crate::check::CheckKind;
use crate::check::stack::{InterfaceEvaluation, StackRow};
use crate::error::Error;
use serde_json::{Map, Value, json};

/// A sweep column: (JSON and CSV key, getter in SI).
type Getter = fn(&StackRow) -> Option<f64>;

/// The bottom interface (on the substrate).
fn bottom(r: &StackRow) -> &InterfaceEvaluation {
    r.interfaces.last().expect("a stack has an interface")
}

/// The film sweep's columns, in its order ([`super::SWEEP`]).
const COLUMNS: &[(&str, Getter)] = &[
    ("area_fraction", |r| Some(r.contact.top.area_fraction.value)),
    ("e_eff_over_e_film", |r| {
        r.contact.top.e_eff_over_e_film.map(|x| x.value)
    }),
    ("mean_contact_pressure_pa", |r| {
        Some(r.mean_contact_pressure.value)
    }),
    ("sigma_rms_top_pa", |r| {
        r.contact.top.sigma_rms_top.map(|x| x.value)
    }),
    ("sigma_rms_interface_pa", |r| {
        Some(bottom(r).sigma_rms.value)
    }),
    ("sigma_peak_interface_pa", |r| {
        Some(bottom(r).sigma_peak.value)
    }),
    ("tau_rms_interface_pa", |r| Some(bottom(r).tau_rms.value)),
    ("tau_peak_pa", |r| Some(bottom(r).tau_peak.value)),
];

/// Each interface's columns: (key after `interface<k>_`, getter in SI).
type InterfaceGetter = fn(&InterfaceEvaluation) -> f64;
const INTERFACE: &[(&str, InterfaceGetter)] = &[
    ("sigma_rms_pa", |i| i.sigma_rms.value),
    ("tau_rms_pa", |i| i.tau_rms.value),
    ("tau_peak_pa", |i| i.tau_peak.value),
    ("sigma_peak_pa", |i| i.sigma_peak.value),
];

/// The checks failing in a row, short ("bond at primer", "yield").
fn failing(r: &StackRow) -> String {
    let f: Vec<String> = r
        .checks
        .iter()
        .filter(|c| !c.result.pass)
        .map(|c| match c.result.kind {
            CheckKind::BondShear => format!("bond at {}", c.at),
            CheckKind::SubstrateYield => "yield".into(),
            CheckKind::MinThickness => "d_min".into(),
        })
        .collect();
    if f.is_empty() {
        "-".into()
    } else {
        f.join(", ")
    }
}

/// The table: the varied layer's thickness, A/A0, the mean pressure in contact, τ_peak at
/// every interface, σ_peak on the substrate, and the failing checks.
fn human(rows: &[StackRow], thickness_of: &str, (h_rms, rms_slope): (f64, f64)) -> String {
    let names: Vec<String> = rows
        .first()
        .map(|r| r.interfaces.iter().map(|i| i.name.clone()).collect())
        .unwrap_or_default();
    let mut head = vec!["d".to_string(), "A/A0".into(), "p_mean".into()];
    head.extend(names.iter().map(|n| format!("τ_peak {n}")));
    head.push("σ_peak sub".into());
    head.push("fails".into());
    let mut t = table(&head.iter().map(String::as_str).collect::<Vec<_>>());
    for r in rows {
        let mut cells = vec![
            um(r.thickness),
            sig(r.contact.top.area_fraction.value, 4),
            mpa(r.mean_contact_pressure.value),
        ];
        cells.extend(r.interfaces.iter().map(|i| mpa(i.tau_peak.value)));
        cells.push(mpa(bottom(r).sigma_peak.value));
        cells.push(failing(r));
        t.add_row(cells);
    }
    let caption = format!(
        "spectrum used: h_rms = {} µm, rms slope = {}. d: the thickness of layer '{thickness_of}' \
         in µm (the other layers fixed), stresses in MPa; τ_peak at the interface below each \
         layer, σ_peak on the substrate; fails: the checks failing at that thickness (bond: \
         bond-shear, yield: substrate-yield)",
        um(h_rms),
        sig(rms_slope, 4)
    );
    format!("{}\n{t}\n", wrap(&caption))
}

fn json_doc(rows: &[StackRow], thickness_of: &str, (h_rms, rms_slope): (f64, f64)) -> String {
    let list: Vec<Value> = rows
        .iter()
        .map(|r| {
            let mut m = Map::new();
            m.insert("thickness_m".into(), json!(r.thickness));
            for (key, get) in COLUMNS {
                m.insert((*key).into(), json!(get(r)));
            }
            let checks: Vec<Value> = r
                .checks
                .iter()
                .map(|c| {
                    json!({"name": c.result.kind.name(), "at": c.at, "value": c.result.value.value,
                           "limit": c.result.limit, "pass": c.result.pass})
                })
                .collect();
            m.insert("checks".into(), Value::Array(checks));
            let interfaces: Vec<Value> = r
                .interfaces
                .iter()
                .map(|i| {
                    let mut v = Map::new();
                    v.insert("name".into(), json!(i.name));
                    v.insert("depth_m".into(), json!(i.depth));
                    for (key, get) in INTERFACE {
                        v.insert((*key).into(), json!(get(i)));
                    }
                    Value::Object(v)
                })
                .collect();
            m.insert("interfaces".into(), Value::Array(interfaces));
            Value::Object(m)
        })
        .collect();
    format!(
        "{:#}\n",
        json!({
            "schema_version": super::SCHEMA_VERSION,
            "coatcheck_version": env!("CARGO_PKG_VERSION"),
            "h_rms_m": h_rms,
            "rms_slope": rms_slope,
            "thickness_of": thickness_of,
            "sweep": list,
        })
    )
}

fn csv(rows: &[StackRow]) -> Result<String, Error> {
    let ser = |e: csv::Error| Error::Numerical {
        what: "CSV output",
        detail: e.to_string(),
    };
    let n = rows.first().map_or(0, |r| r.interfaces.len());
    let mut w = csv::Writer::from_writer(Vec::new());
    let mut head = vec!["thickness_m".to_string()];
    head.extend(COLUMNS.iter().map(|(k, _)| k.to_string()));
    for k in 1..=n {
        head.extend(
            INTERFACE
                .iter()
                .map(|(key, _)| format!("interface{k}_{key}")),
        );
    }
    w.write_record(&head).map_err(ser)?;
    let num = |x: f64| format!("{x:e}");
    for r in rows {
        let mut cells = vec![num(r.thickness)];
        cells.extend(
            COLUMNS
                .iter()
                .map(|(_, get)| get(r).map(num).unwrap_or_default()),
        );
        for i in &r.interfaces {
            cells.extend(INTERFACE.iter().map(|(_, get)| num(get(i))));
        }
        w.write_record(&cells).map_err(ser)?;
    }
    let bytes = w.into_inner().map_err(|e| Error::Numerical {
        what: "CSV output",
        detail: e.to_string(),
    })?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// The stack's thickness sweep in the chosen format, with the varied layer's name and the
/// h_rms (m) and rms slope of the spectrum used.
pub fn sweep(
    rows: &[StackRow],
    thickness_of: &str,
    roughness: (f64, f64),
    format: Format,
) -> Result<String, Error> {
    // Every format is checked for non-finite numbers on its CSV (JSON would show null).
    let table_csv = csv(rows)?;
    super::finite_only(&table_csv)?;
    Ok(match format {
        Format::Table => human(rows, thickness_of, roughness),
        Format::Json => json_doc(rows, thickness_of, roughness),
        Format::Csv => table_csv,
    })
}
