//! Batch runs of `coatcheck check` (issue 7): many scenes judged in parallel (rayon), one
//! record per scene, a summary table with failures first, and the totals that decide the exit
//! code. No physics of its own: each scene goes through [`crate::check::Checker::run`] (paper
//! App. B, eqs. B8–B12; notes.md "Distributions and peak values", "Minimum thickness").
//!
//! A scene that lists several roughness files is judged on each ([`Scene::each_file`]) and
//! reported by its worst file: a failing file before a passing one, then the smallest margin
//! of the governing check.
//!
//! Verdicts: `pass`, `fail`, or `error` (the scene could not be evaluated: bad input or a
//! numerical failure; its message names the file and, for file contents, the line). Exit code
//! of a batch ([`Totals::exit_code`]): 0 when every scene passes, 1 when any fails, 2 when any
//! could not be evaluated (the others are still run and reported).

use crate::check::{CheckKind, Checker, Outcome};
use crate::error::Error;
use crate::material::Library;
use crate::report::sig;
use crate::scene::Scene;
use comfy_table::{Table, presets::UTF8_FULL_CONDENSED};
use rayon::prelude::*;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The scene files of a batch: each argument is a scene file or a directory, whose `*.toml`
/// files are taken in name order (not recursing). A directory without scenes is an error.
pub fn scene_files(args: &[PathBuf]) -> Result<Vec<PathBuf>, Error> {
    let mut files = Vec::new();
    for arg in args {
        if !arg.is_dir() {
            files.push(arg.clone());
            continue;
        }
        let io = |source| Error::Io {
            path: arg.clone(),
            source,
        };
        let mut found: Vec<PathBuf> = std::fs::read_dir(arg)
            .map_err(io)?
            .map(|e| e.map(|e| e.path()).map_err(io))
            .collect::<Result<Vec<_>, _>>()?
            .into_iter()
            .filter(|p| p.is_file() && p.extension().is_some_and(|x| x == "toml"))
            .collect();
        if found.is_empty() {
            return Err(Error::Value {
                origin: arg.display().to_string(),
                msg: "no scene files (*.toml) in this directory".into(),
            });
        }
        found.sort();
        files.extend(found);
    }
    Ok(files)
}

/// One roughness file of a scene judged on its own.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FileVerdict {
    pub path: PathBuf,
    pub pass: bool,
    pub governing: Option<CheckKind>,
    pub margin: Option<f64>,
}

/// A judged scene: the outcome of its worst roughness file.
#[derive(Debug, Clone, PartialEq)]
pub struct Judged {
    /// The scene, with the roughness of the worst file.
    pub scene: Scene,
    pub outcome: Outcome,
    /// Every file's verdict, in the scene's order, when the scene lists several.
    pub files: Vec<FileVerdict>,
    /// The reader's, the version pin's and the outcome's warnings.
    pub warnings: Vec<String>,
}

impl Judged {
    /// The worst file when the scene lists several.
    pub fn worst_file(&self) -> Option<&Path> {
        if self.files.len() > 1 {
            self.scene.roughness.file()
        } else {
            None
        }
    }
}

/// The margin of the governing check (`None` when it has no limit, e.g. no thickness passes).
pub fn governing_margin(outcome: &Outcome) -> Option<f64> {
    outcome
        .checks
        .iter()
        .find(|c| Some(c.kind) == outcome.governing)
        .and_then(|c| c.margin)
}

/// Sort key of a verdict: failing before passing, then the smaller margin (none = worst).
fn severity(pass: bool, margin: Option<f64>) -> (bool, f64) {
    (pass, margin.unwrap_or(f64::NEG_INFINITY))
}

/// The error for a scene without a film thickness (a batch judges the given thickness).
fn missing_thickness(scene: &Scene) -> Error {
    Error::Value {
        origin: scene
            .file
            .as_ref()
            .map_or("scene".into(), |p| p.display().to_string()),
        msg: "film.thickness is missing; give the film thickness (thickness = \"10 um\" under [film], or --thickness 10um)".into(),
    }
}

/// Judge a scene at its thickness on each of its roughness files; report the worst.
pub fn judge(scene: &Scene) -> Result<Judged, Error> {
    let thickness = scene.thickness.ok_or_else(|| missing_thickness(scene))?;
    let runs = scene
        .each_file()
        .into_par_iter()
        .map(|s| {
            let (spectrum, warnings) = s.roughness.spectrum()?;
            let checker = Checker::new(&spectrum, s.design(), s.settings)?;
            let outcome = checker.run(thickness)?;
            Ok((s, outcome, warnings))
        })
        .collect::<Result<Vec<_>, Error>>()?;
    let several = runs.len() > 1;
    let files: Vec<FileVerdict> = if several {
        runs.iter()
            .map(|(s, o, _)| FileVerdict {
                path: s
                    .roughness
                    .file()
                    .map(Path::to_path_buf)
                    .unwrap_or_default(),
                pass: o.pass,
                governing: o.governing,
                margin: governing_margin(o),
            })
            .collect()
    } else {
        Vec::new()
    };
    let mut warnings: Vec<String> = scene.version_warning().into_iter().collect();
    for (_, _, w) in &runs {
        warnings.extend(w.iter().cloned());
    }
    let (scene, outcome, _) = runs
        .into_iter()
        .min_by(|(_, a, _), (_, b, _)| {
            let (pa, ma) = severity(a.pass, governing_margin(a));
            let (pb, mb) = severity(b.pass, governing_margin(b));
            pa.cmp(&pb).then(ma.total_cmp(&mb))
        })
        .expect("a scene has at least one roughness");
    let named = |w: &String| match (several, scene.roughness.file()) {
        (true, Some(f)) => format!("{}: {w}", f.display()),
        _ => w.clone(),
    };
    warnings.extend(outcome.warnings.iter().map(named));
    Ok(Judged {
        scene,
        outcome,
        files,
        warnings,
    })
}

/// One scene of a batch: its file, how long it took, and its judgement or why it has none.
#[derive(Debug)]
pub struct SceneRun {
    pub file: PathBuf,
    pub seconds: f64,
    pub result: Result<Judged, Error>,
}

impl SceneRun {
    /// `pass`, `fail` or `error`.
    pub fn verdict(&self) -> &'static str {
        match &self.result {
            Ok(j) if j.outcome.pass => "pass",
            Ok(_) => "fail",
            Err(_) => "error",
        }
    }

    /// Summary order: failures (smallest margin first), then scenes that could not be
    /// evaluated, then passes (smallest margin first); ties by file name.
    fn order(&self) -> (u8, f64) {
        match &self.result {
            Ok(j) => {
                let m = governing_margin(&j.outcome).unwrap_or(f64::NEG_INFINITY);
                (if j.outcome.pass { 2 } else { 0 }, m)
            }
            Err(_) => (1, 0.0),
        }
    }
}

/// Load and judge one scene file with the flag overrides.
pub fn run_one(file: &Path, overrides: &[(&str, String)], library: &Library) -> SceneRun {
    let start = Instant::now();
    let result = Scene::load(Some(file), overrides, library).and_then(|s| judge(&s));
    SceneRun {
        file: file.to_path_buf(),
        seconds: start.elapsed().as_secs_f64(),
        result,
    }
}

/// Judge every scene in parallel; `done` is called after each scene (progress). The runs come
/// back in summary order ([`sort`]).
pub fn run_all(
    files: &[PathBuf],
    overrides: &[(&str, String)],
    library: &Library,
    done: &(dyn Fn() + Sync),
) -> Vec<SceneRun> {
    let mut runs: Vec<SceneRun> = files
        .par_iter()
        .map(|f| {
            let r = run_one(f, overrides, library);
            done();
            r
        })
        .collect();
    sort(&mut runs);
    runs
}

/// Failures first (smallest margin first), then errors, then passes; ties by file name.
pub fn sort(runs: &mut [SceneRun]) {
    runs.sort_by(|a, b| {
        let (ga, ma) = a.order();
        let (gb, mb) = b.order();
        ga.cmp(&gb)
            .then(ma.total_cmp(&mb))
            .then_with(|| a.file.cmp(&b.file))
    });
}

/// Counts of a batch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Totals {
    pub scenes: usize,
    pub pass: usize,
    pub fail: usize,
    pub error: usize,
}

impl Totals {
    pub fn of(runs: &[SceneRun]) -> Self {
        let count = |v: &str| runs.iter().filter(|r| r.verdict() == v).count();
        Totals {
            scenes: runs.len(),
            pass: count("pass"),
            fail: count("fail"),
            error: count("error"),
        }
    }

    /// 0 every scene passes, 1 a scene fails, 2 a scene could not be evaluated.
    pub fn exit_code(&self) -> i32 {
        if self.error > 0 {
            2
        } else if self.fail > 0 {
            1
        } else {
            0
        }
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directories_give_their_toml_files_in_name_order() {
        let dir = tempfile::tempdir().unwrap();
        for name in ["b.toml", "a.toml", "notes.md", "c.toml.bak"] {
            std::fs::write(dir.path().join(name), "").unwrap();
        }
        std::fs::create_dir(dir.path().join("sub.toml")).unwrap();
        let extra = PathBuf::from("x/given.toml");
        let files = scene_files(&[dir.path().to_path_buf(), extra.clone()]).unwrap();
        assert_eq!(
            files,
            [dir.path().join("a.toml"), dir.path().join("b.toml"), extra]
        );
        let empty = tempfile::tempdir().unwrap();
        let e = scene_files(&[empty.path().to_path_buf()]).unwrap_err();
        assert!(e.to_string().contains("no scene files"), "{e}");
    }

    #[test]
    fn exit_code_is_the_worst_verdict() {
        let t = |pass, fail, error| Totals {
            scenes: pass + fail + error,
            pass,
            fail,
            error,
        };
        assert_eq!(t(3, 0, 0).exit_code(), 0);
        assert_eq!(t(3, 1, 0).exit_code(), 1);
        assert_eq!(t(3, 1, 1).exit_code(), 2);
        assert_eq!(t(0, 0, 1).exit_code(), 2);
    }
}
