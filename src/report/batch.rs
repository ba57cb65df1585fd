//! Output of a batch: one flat record per scene (JSON, CSV and Parquet share its columns), the
//! summary table with failures first, and the per-file table of a scene with several roughness
//! files.

use super::sig;
use crate::batch::{SceneRun, Totals};
use crate::check::CheckKind;
use crate::error::Error;
use crate::pipeline::{Judged, governing_margin};
use comfy_table::{Table, presets::UTF8_FULL_CONDENSED};
use serde::Serialize;

/// One check of a scene in a record.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckRecord {
    pub name: &'static str,
    /// Pa for stresses, m for min-thickness.
    pub value: f64,
    pub value_err: f64,
    pub limit: Option<f64>,
    pub margin: Option<f64>,
    pub pass: bool,
}

/// One scene of a batch as a flat record (JSON, CSV, Parquet). SI units.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Record {
    pub scene: String,
    /// `pass`, `fail` or `error`.
    pub verdict: &'static str,
    pub governing_check: Option<&'static str>,
    /// Margin of the governing check (unused fraction of its limit; < 0 fails).
    pub margin: Option<f64>,
    pub thickness_m: Option<f64>,
    pub min_thickness_m: Option<f64>,
    pub min_thickness_err_m: Option<f64>,
    pub area_fraction: Option<f64>,
    pub mean_contact_pressure_pa: Option<f64>,
    pub tau_peak_pa: Option<f64>,
    pub sigma_peak_interface_pa: Option<f64>,
    /// The worst roughness file when the scene lists several.
    pub worst_file: Option<String>,
    /// How many roughness files the scene was judged on (0 when it could not be evaluated).
    pub files: usize,
    pub checks: Vec<CheckRecord>,
    pub warnings: Vec<String>,
    /// Why the scene could not be evaluated.
    pub error: Option<String>,
    pub seconds: f64,
}

impl Record {
    pub fn of(run: &SceneRun) -> Self {
        let mut r = Record {
            scene: run.file.display().to_string(),
            verdict: run.verdict(),
            seconds: run.seconds,
            ..Record::default()
        };
        match &run.result {
            Err(e) => r.error = Some(e.to_string()),
            Ok(j) => {
                let o = &j.outcome;
                let ev = &o.evaluation;
                r.governing_check = o.governing.map(CheckKind::name);
                r.margin = governing_margin(o);
                r.thickness_m = Some(o.thickness);
                let dmin = o.min_thickness.as_ref().and_then(|m| m.thickness);
                r.min_thickness_m = dmin.map(|d| d.value);
                r.min_thickness_err_m = dmin.map(|d| d.err);
                r.area_fraction = Some(ev.contact.area_fraction.value);
                r.mean_contact_pressure_pa = Some(ev.mean_contact_pressure.value);
                r.tau_peak_pa = ev.tau_peak.map(|e| e.value);
                r.sigma_peak_interface_pa = ev.sigma_peak_interface.map(|e| e.value);
                r.worst_file = j.worst_file().map(|p| p.display().to_string());
                r.files = j.files.len().max(1);
                r.checks = o
                    .checks
                    .iter()
                    .map(|c| CheckRecord {
                        name: c.kind.name(),
                        value: c.value.value,
                        value_err: c.value.err,
                        limit: c.limit,
                        margin: c.margin,
                        pass: c.pass,
                    })
                    .collect();
                r.warnings = j.warnings.clone();
            }
        }
        r
    }

    /// The margin of one check, if it ran.
    pub fn check_margin(&self, kind: CheckKind) -> Option<f64> {
        self.checks
            .iter()
            .find(|c| c.name == kind.name())
            .and_then(|c| c.margin)
    }
}

/// A cell of the flat (CSV, Parquet) form of a record.
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    Text(Option<String>),
    Number(Option<f64>),
    Count(u64),
}

/// The flat columns of a record: name and getter (CSV and Parquet share them).
pub type Column = (&'static str, fn(&Record) -> Cell);

pub const COLUMNS: &[Column] = &[
    ("scene", |r| Cell::Text(Some(r.scene.clone()))),
    ("verdict", |r| Cell::Text(Some(r.verdict.into()))),
    ("governing_check", |r| {
        Cell::Text(r.governing_check.map(Into::into))
    }),
    ("margin", |r| Cell::Number(r.margin)),
    ("thickness_m", |r| Cell::Number(r.thickness_m)),
    ("min_thickness_m", |r| Cell::Number(r.min_thickness_m)),
    ("min_thickness_err_m", |r| {
        Cell::Number(r.min_thickness_err_m)
    }),
    ("area_fraction", |r| Cell::Number(r.area_fraction)),
    ("mean_contact_pressure_pa", |r| {
        Cell::Number(r.mean_contact_pressure_pa)
    }),
    ("tau_peak_pa", |r| Cell::Number(r.tau_peak_pa)),
    ("sigma_peak_interface_pa", |r| {
        Cell::Number(r.sigma_peak_interface_pa)
    }),
    ("bond_shear_margin", |r| {
        Cell::Number(r.check_margin(CheckKind::BondShear))
    }),
    ("substrate_yield_margin", |r| {
        Cell::Number(r.check_margin(CheckKind::SubstrateYield))
    }),
    ("min_thickness_margin", |r| {
        Cell::Number(r.check_margin(CheckKind::MinThickness))
    }),
    ("worst_file", |r| Cell::Text(r.worst_file.clone())),
    ("files", |r| Cell::Count(r.files as u64)),
    ("warnings", |r| {
        Cell::Text((!r.warnings.is_empty()).then(|| r.warnings.join(" | ")))
    }),
    ("error", |r| Cell::Text(r.error.clone())),
    ("seconds", |r| Cell::Number(Some(r.seconds))),
];

/// The batch as JSON: `{"scenes": [records], "totals": {...}}`.
pub fn json(runs: &[SceneRun]) -> String {
    let records: Vec<Record> = runs.iter().map(Record::of).collect();
    let v = serde_json::json!({ "scenes": records, "totals": Totals::of(runs) });
    format!("{v:#}\n")
}

/// The batch as CSV: a header and one row per scene ([`COLUMNS`]).
pub fn csv(runs: &[SceneRun]) -> Result<String, Error> {
    let ser = |e: csv::Error| Error::Numerical {
        what: "CSV output",
        detail: e.to_string(),
    };
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(COLUMNS.iter().map(|(name, _)| *name))
        .map_err(ser)?;
    for run in runs {
        let r = Record::of(run);
        w.write_record(COLUMNS.iter().map(|(_, get)| match get(&r) {
            Cell::Text(t) => t.unwrap_or_default(),
            Cell::Number(x) => x.map(|x| format!("{x:e}")).unwrap_or_default(),
            Cell::Count(n) => n.to_string(),
        }))
        .map_err(ser)?;
    }
    let bytes = w.into_inner().map_err(|e| Error::Numerical {
        what: "CSV output",
        detail: e.to_string(),
    })?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// The summary table: scene, verdict, governing check, margin, d_min, warnings (failures first),
/// then the errors and warnings in full, then the totals.
pub fn summary(runs: &[SceneRun], seconds: f64) -> String {
    let mut t = Table::new();
    t.load_preset(UTF8_FULL_CONDENSED);
    t.set_header([
        "scene",
        "verdict",
        "governing check",
        "margin",
        "d_min",
        "warnings",
    ]);
    let mut notes = String::new();
    for run in runs {
        let mut scene = run.file.display().to_string();
        let verdict = run.verdict().to_uppercase();
        match &run.result {
            Err(e) => {
                t.add_row([
                    scene,
                    verdict,
                    "-".into(),
                    "-".into(),
                    "-".into(),
                    "-".into(),
                ]);
                notes += &format!("error: {e}\n");
            }
            Ok(j) => {
                if let Some(f) = j.worst_file() {
                    let name = f.file_name().map_or(f.as_os_str(), |n| n);
                    scene += &format!("\n(worst of {}: {})", j.files.len(), name.display());
                }
                let o = &j.outcome;
                let margin = governing_margin(o)
                    .map(|m| format!("{:+.1} %", 100.0 * m))
                    .unwrap_or_else(|| "-".into());
                let dmin = match &o.min_thickness {
                    None => "-".into(),
                    Some(m) => match m.thickness {
                        None => "none passes".into(),
                        Some(d) if m.all_pass_to_floor => {
                            format!("<= {} um", sig(d.value * 1e6, 4))
                        }
                        Some(d) => format!("{} um", sig(d.value * 1e6, 4)),
                    },
                };
                t.add_row([
                    scene,
                    verdict,
                    o.governing.map_or("-", CheckKind::name).into(),
                    margin,
                    dmin,
                    j.warnings.len().to_string(),
                ]);
                for w in &j.warnings {
                    notes += &format!("warning: {}: {w}\n", run.file.display());
                }
            }
        }
    }
    let n = Totals::of(runs);
    format!(
        "{t}\n{notes}{} scenes: {} passed, {} failed, {} could not be evaluated ({:.2} s)\n",
        n.scenes, n.pass, n.fail, n.error, seconds
    )
}

/// The verdict of every roughness file of a scene that lists several (empty otherwise).
pub fn files_table(j: &Judged) -> String {
    if j.files.len() < 2 {
        return String::new();
    }
    let mut t = Table::new();
    t.load_preset(UTF8_FULL_CONDENSED);
    t.set_header(["roughness file", "verdict", "governing check", "margin"]);
    for f in &j.files {
        t.add_row([
            f.path.display().to_string(),
            if f.pass { "PASS" } else { "FAIL" }.into(),
            f.governing.map_or("-", CheckKind::name).into(),
            f.margin
                .map(|m| format!("{:+.1} %", 100.0 * m))
                .unwrap_or_else(|| "-".into()),
        ]);
    }
    let worst = j
        .worst_file()
        .map_or(String::new(), |p| p.display().to_string());
    format!("{t}\nworst file: {worst} (its full report follows)\n")
}

/// The batch in a format: the summary table, JSON or CSV.
pub fn report(runs: &[SceneRun], seconds: f64, format: super::Format) -> Result<String, Error> {
    Ok(match format {
        super::Format::Table => summary(runs, seconds),
        super::Format::Json => {
            // JSON shows NaN as null: the CSV of the same numbers is checked instead.
            super::finite_only(&csv(runs)?)?;
            json(runs)
        }
        super::Format::Csv => csv(runs)?,
    })
}
