//! Output of a batch: one flat record per scene (JSON, CSV and Parquet share its columns), the
//! summary table with failures first, and the per-file table of a scene with several roughness
//! files.

use super::{margin_cell, sig, table, utilisation_cell, wrap};
use crate::batch::{SceneRun, Totals};
use crate::check::CheckKind;
use crate::check::levers::Lever;
use crate::error::Error;
use crate::pipeline::{Judged, Verdict};
use crate::prec::Estimate;
use serde::Serialize;
use std::ops::Not;
use std::path::Path;

/// One check of a scene in a record (the shape of `checks[]` in the check's JSON).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckRecord {
    pub name: &'static str,
    /// Where the check applies in a layer stack: a layer (the interface below it), or
    /// `substrate` (absent for a film).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at: Option<String>,
    /// Pa for stresses, m for min-thickness ([`CheckRecord::unit`]).
    pub value: f64,
    pub value_err: f64,
    pub unit: &'static str,
    pub limit: Option<f64>,
    /// value/limit (d_min/d for the thickness): 1 − margin.
    pub utilisation: Option<f64>,
    pub margin: Option<f64>,
    pub pass: bool,
}

/// One scene as a flat record (batch JSON, and the rows of every `check --format csv` and of
/// Parquet). SI units; the keys are those of the check's JSON.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Record {
    pub scene: String,
    /// `pass`, `fail` or `error` (with `--verify`: both Persson's and the exact checks).
    pub verdict: &'static str,
    pub governing_check: Option<&'static str>,
    /// Utilisation of the governing check (value/limit; > 1 fails).
    pub utilisation: Option<f64>,
    /// Margin of the governing check (unused fraction of its limit; < 0 fails).
    pub margin: Option<f64>,
    pub thickness_m: Option<f64>,
    pub pressure_pa: Option<f64>,
    /// h_rms of the spectrum the scene was judged with, m.
    pub h_rms_m: Option<f64>,
    /// rms slope of that spectrum.
    pub rms_slope: Option<f64>,
    pub min_thickness_m: Option<f64>,
    pub min_thickness_m_err: Option<f64>,
    pub area_fraction: Option<f64>,
    pub area_fraction_err: Option<f64>,
    pub mean_contact_pressure_pa: Option<f64>,
    pub mean_contact_pressure_pa_err: Option<f64>,
    pub sigma_rms_top_pa: Option<f64>,
    pub sigma_rms_top_pa_err: Option<f64>,
    pub sigma_rms_interface_pa: Option<f64>,
    pub sigma_rms_interface_pa_err: Option<f64>,
    pub tau_rms_interface_pa: Option<f64>,
    pub tau_rms_interface_pa_err: Option<f64>,
    pub tau_peak_pa: Option<f64>,
    pub tau_peak_pa_err: Option<f64>,
    pub sigma_peak_interface_pa: Option<f64>,
    pub sigma_peak_interface_pa_err: Option<f64>,
    pub e_eff_over_e_film: Option<f64>,
    pub e_eff_over_e_film_err: Option<f64>,
    /// Sliding friction μ, under the vector shear rule.
    pub friction: Option<f64>,
    /// Under the vector shear rule: the interface shear's mean μ·p0 and the rms of its x and y
    /// fluctuations, and the paper's half-normal peak of the static shear (Pa).
    pub mean_interface_shear_pa: Option<f64>,
    pub mean_interface_shear_pa_err: Option<f64>,
    pub tau_x_rms_interface_pa: Option<f64>,
    pub tau_x_rms_interface_pa_err: Option<f64>,
    pub tau_y_rms_interface_pa: Option<f64>,
    pub tau_y_rms_interface_pa_err: Option<f64>,
    pub tau_peak_static_pa: Option<f64>,
    pub tau_peak_static_pa_err: Option<f64>,
    /// The worst roughness file when the scene lists several.
    pub worst_file: Option<String>,
    /// How many roughness files the scene was judged on (0 when it could not be evaluated).
    pub files: usize,
    pub checks: Vec<CheckRecord>,
    /// What alone would make a failing design pass.
    pub levers: Vec<Lever>,
    /// The exact check's verdict and values (`check --verify`).
    pub verify_verdict: Option<&'static str>,
    pub verify_area_fraction: Option<f64>,
    pub verify_mean_contact_pressure_pa: Option<f64>,
    pub verify_tau_peak_pa: Option<f64>,
    pub verify_sigma_peak_interface_pa: Option<f64>,
    /// The exact minimum thickness and its error (bracket plus grid).
    pub verify_min_thickness_m: Option<f64>,
    pub verify_min_thickness_m_err: Option<f64>,
    /// How many realisations of the spectrum were solved (scenes without a height map).
    pub verify_realisations: Option<usize>,
    /// The robust verdict, its governing check and margin, and the d_min range over the
    /// corners of the materials' ranges (`check --robust`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robust_verdict: Option<&'static str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robust_governing_check: Option<&'static str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robust_margin: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robust_min_thickness_m_min: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robust_min_thickness_m_max: Option<f64>,
    pub warnings: Vec<String>,
    /// A layer stack's varied layer (`criteria.thickness_of`; `thickness_m` is its thickness)
    /// and every interface, top first (absent for a film).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thickness_of: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interfaces: Option<Vec<InterfaceRecord>>,
    /// Why the scene could not be evaluated.
    pub error: Option<String>,
    pub seconds: f64,
}

/// One interface of a layer stack in a record (the shape of `interfaces[]` in the stack
/// check's JSON).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct InterfaceRecord {
    /// The layer above the interface.
    pub name: String,
    pub depth_m: f64,
    pub sigma_rms_pa: f64,
    pub sigma_rms_pa_err: f64,
    pub tau_rms_pa: f64,
    pub tau_rms_pa_err: f64,
    pub tau_peak_pa: f64,
    pub tau_peak_pa_err: f64,
    pub sigma_peak_pa: f64,
    pub sigma_peak_pa_err: f64,
    pub bond_strength_pa: f64,
    pub bond_exceedance: f64,
    /// Under the vector shear rule: the interface shear's mean μ·p0, the rms of its x and y
    /// fluctuations and the paper's half-normal peak of the static shear (Pa).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mean_interface_shear_pa: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mean_interface_shear_pa_err: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tau_x_rms_interface_pa: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tau_x_rms_interface_pa_err: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tau_y_rms_interface_pa: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tau_y_rms_interface_pa_err: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tau_peak_static_pa: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tau_peak_static_pa_err: Option<f64>,
}

impl InterfaceRecord {
    /// The record with the sliding fields of the interface `i` (under the vector rule).
    fn with_sliding(mut self, i: &crate::check::stack::InterfaceEvaluation) -> Self {
        if let Some(s) = &i.sliding {
            (
                self.mean_interface_shear_pa,
                self.mean_interface_shear_pa_err,
            ) = split(Some(s.mean));
            (self.tau_x_rms_interface_pa, self.tau_x_rms_interface_pa_err) =
                split(Some(s.tau_x_rms));
            (self.tau_y_rms_interface_pa, self.tau_y_rms_interface_pa_err) =
                split(Some(s.tau_y_rms));
            (self.tau_peak_static_pa, self.tau_peak_static_pa_err) = split(i.tau_peak_static);
        }
        self
    }
}

/// A check as a record, at `at` in a stack.
fn check_record(c: &crate::check::CheckResult, at: Option<&str>) -> CheckRecord {
    CheckRecord {
        name: c.kind.name(),
        at: at.map(Into::into),
        value: c.value.value,
        value_err: c.value.err,
        unit: if c.kind == CheckKind::MinThickness {
            "m"
        } else {
            "Pa"
        },
        limit: c.limit,
        utilisation: c.margin.map(|m| 1.0 - m),
        margin: c.margin,
        pass: c.pass,
    }
}

/// Value and error of an estimate, each `None` when the estimate is.
fn split(e: Option<Estimate>) -> (Option<f64>, Option<f64>) {
    (e.map(|e| e.value), e.map(|e| e.err))
}

impl Record {
    pub fn of(run: &SceneRun) -> Self {
        match &run.result {
            Err(e) => Record {
                scene: run.file.display().to_string(),
                verdict: run.verdict(),
                seconds: run.seconds,
                error: Some(e.to_string()),
                ..Record::default()
            },
            Ok(j) => Record::judged(&run.file, j, run.seconds),
        }
    }

    /// The record of a judged scene.
    pub fn judged(file: &Path, j: &Judged, seconds: f64) -> Self {
        let o = &j.outcome;
        let mut r = Record {
            scene: file.display().to_string(),
            verdict: if j.pass() { "pass" } else { "fail" },
            seconds,
            governing_check: o.governing().map(CheckKind::name),
            margin: o.margin(),
            utilisation: o.margin().map(|m| 1.0 - m),
            pressure_pa: Some(j.scene.pressure),
            worst_file: j.worst_file().map(|p| p.display().to_string()),
            files: j.files.len().max(1),
            levers: j.levers.clone(),
            warnings: j.warnings.clone(),
            ..Record::default()
        };
        (r.min_thickness_m, r.min_thickness_m_err) =
            split(o.min_thickness().and_then(|m| m.thickness));
        match o {
            Verdict::Film(o) => r.film(o),
            Verdict::Stack(o) => r.stack(&j.scene, o),
        }
        if let Some(x) = &j.exact {
            let v = &x.verification;
            r.verify_verdict = Some(if v.pass { "pass" } else { "fail" });
            r.verify_area_fraction = Some(v.area_fraction.value);
            r.verify_mean_contact_pressure_pa = Some(v.mean_contact_pressure.value);
            r.verify_tau_peak_pa = Some(v.tau_peak.value.value);
            r.verify_sigma_peak_interface_pa = Some(v.sigma_peak_interface.value.value);
            let d = x.min_thickness.as_ref().and_then(|m| m.thickness());
            r.verify_min_thickness_m = d.map(|d| d.value);
            r.verify_min_thickness_m_err = d.map(|d| d.err);
            r.verify_realisations = x.realisations.as_ref().map(|r| r.count);
        }
        if let Some(x) = &j.stack_exact {
            let v = &x.verification;
            r.verify_verdict = Some(if v.pass { "pass" } else { "fail" });
            r.verify_area_fraction = Some(v.area_fraction.value);
            r.verify_mean_contact_pressure_pa = Some(v.mean_contact_pressure.value);
            let d = x.min_thickness.as_ref().and_then(|m| m.thickness());
            r.verify_min_thickness_m = d.map(|d| d.value);
            r.verify_min_thickness_m_err = d.map(|d| d.err);
        }
        if let Some(x) = &j.robust {
            r.robust_verdict = Some(if x.pass { "pass" } else { "fail" });
            r.robust_governing_check = x.governing.map(CheckKind::name);
            r.robust_margin = x
                .checks
                .iter()
                .find(|c| Some(c.result.kind) == x.governing)
                .and_then(|c| c.result.margin);
            r.robust_min_thickness_m_min = x.min_thickness.and_then(|m| m.min);
            r.robust_min_thickness_m_max = x.min_thickness.and_then(|m| m.max);
        }
        if let Some(x) = &j.stack_robust {
            r.robust_verdict = Some(if x.pass { "pass" } else { "fail" });
            r.robust_governing_check = x.governing.as_ref().map(|(k, _)| k.name());
            r.robust_margin = x
                .checks
                .iter()
                .find(|c| x.governing.as_ref() == Some(&(c.check.result.kind, c.check.at.clone())))
                .and_then(|c| c.check.result.margin);
            r.robust_min_thickness_m_min = x.min_thickness.and_then(|m| m.min);
            r.robust_min_thickness_m_max = x.min_thickness.and_then(|m| m.max);
        }
        r
    }

    /// A film's results and checks.
    fn film(&mut self, o: &crate::check::Outcome) {
        let r = self;
        let ev = &o.evaluation;
        let c = &ev.contact;
        r.thickness_m = Some(o.thickness);
        r.h_rms_m = Some(o.h_rms);
        r.rms_slope = Some(o.rms_slope);
        (r.area_fraction, r.area_fraction_err) = split(Some(c.area_fraction));
        (r.mean_contact_pressure_pa, r.mean_contact_pressure_pa_err) =
            split(Some(ev.mean_contact_pressure));
        (r.sigma_rms_top_pa, r.sigma_rms_top_pa_err) = split(c.sigma_rms_top);
        (r.sigma_rms_interface_pa, r.sigma_rms_interface_pa_err) = split(c.sigma_rms_interface);
        (r.tau_rms_interface_pa, r.tau_rms_interface_pa_err) = split(c.tau_rms_interface);
        (r.tau_peak_pa, r.tau_peak_pa_err) = split(ev.tau_peak);
        (r.sigma_peak_interface_pa, r.sigma_peak_interface_pa_err) = split(ev.sigma_peak_interface);
        (r.e_eff_over_e_film, r.e_eff_over_e_film_err) = split(c.e_eff_over_e_film);
        if let Some(s) = &ev.sliding {
            r.friction = Some(s.friction);
            (r.mean_interface_shear_pa, r.mean_interface_shear_pa_err) = split(Some(s.mean));
            (r.tau_x_rms_interface_pa, r.tau_x_rms_interface_pa_err) = split(Some(s.tau_x_rms));
            (r.tau_y_rms_interface_pa, r.tau_y_rms_interface_pa_err) = split(Some(s.tau_y_rms));
            (r.tau_peak_static_pa, r.tau_peak_static_pa_err) = split(ev.tau_peak_static);
        }
        r.checks = o.checks.iter().map(|c| check_record(c, None)).collect();
    }

    /// A layer stack's results (the top-level keys of its JSON: the top surface, the contact,
    /// and the bottom interface's stresses), its interfaces and its checks with where they
    /// apply.
    fn stack(&mut self, scene: &crate::scene::Scene, o: &crate::check::stack::StackOutcome) {
        let r = self;
        let c = &o.contact.top;
        let design = scene.stack_design();
        let varied = &design.layers[design.thickness_of];
        r.thickness_m = Some(varied.thickness);
        r.thickness_of = Some(varied.name.clone());
        r.h_rms_m = Some(o.h_rms);
        r.rms_slope = Some(o.rms_slope);
        (r.area_fraction, r.area_fraction_err) = split(Some(c.area_fraction));
        (r.mean_contact_pressure_pa, r.mean_contact_pressure_pa_err) =
            split(Some(o.mean_contact_pressure));
        (r.sigma_rms_top_pa, r.sigma_rms_top_pa_err) = split(c.sigma_rms_top);
        (r.e_eff_over_e_film, r.e_eff_over_e_film_err) = split(c.e_eff_over_e_film);
        if let Some(b) = o.interfaces.last() {
            (r.sigma_rms_interface_pa, r.sigma_rms_interface_pa_err) = split(Some(b.sigma_rms));
            (r.tau_rms_interface_pa, r.tau_rms_interface_pa_err) = split(Some(b.tau_rms));
            (r.tau_peak_pa, r.tau_peak_pa_err) = split(Some(b.tau_peak));
            (r.sigma_peak_interface_pa, r.sigma_peak_interface_pa_err) = split(Some(b.sigma_peak));
            if let Some(s) = &b.sliding {
                r.friction = Some(s.friction);
                (r.mean_interface_shear_pa, r.mean_interface_shear_pa_err) = split(Some(s.mean));
                (r.tau_x_rms_interface_pa, r.tau_x_rms_interface_pa_err) = split(Some(s.tau_x_rms));
                (r.tau_y_rms_interface_pa, r.tau_y_rms_interface_pa_err) = split(Some(s.tau_y_rms));
                (r.tau_peak_static_pa, r.tau_peak_static_pa_err) = split(b.tau_peak_static);
            }
        }
        r.interfaces = Some(
            o.interfaces
                .iter()
                .map(|i| {
                    InterfaceRecord {
                        name: i.name.clone(),
                        depth_m: i.depth,
                        sigma_rms_pa: i.sigma_rms.value,
                        sigma_rms_pa_err: i.sigma_rms.err,
                        tau_rms_pa: i.tau_rms.value,
                        tau_rms_pa_err: i.tau_rms.err,
                        tau_peak_pa: i.tau_peak.value,
                        tau_peak_pa_err: i.tau_peak.err,
                        sigma_peak_pa: i.sigma_peak.value,
                        sigma_peak_pa_err: i.sigma_peak.err,
                        bond_strength_pa: i.bond_strength,
                        bond_exceedance: i.bond_exceedance,
                        ..InterfaceRecord::default()
                    }
                    .with_sliding(i)
                })
                .collect(),
        );
        r.checks = o
            .checks
            .iter()
            .map(|c| check_record(&c.result, Some(&c.at)))
            .collect();
    }

    /// One check, if it ran; in a layer stack, where it has the least margin (none counts
    /// least).
    pub fn check(&self, kind: CheckKind) -> Option<&CheckRecord> {
        crate::check::basis::governing(self.checks.iter().filter(|c| c.name == kind.name()), |c| {
            c.margin
        })
    }

    /// A check at one place of a layer stack (a layer's name, or `substrate`).
    pub fn check_at(&self, kind: CheckKind, at: &str) -> Option<&CheckRecord> {
        self.checks
            .iter()
            .find(|c| c.name == kind.name() && c.at.as_deref() == Some(at))
    }

    /// The margin of one check, if it ran.
    pub fn check_margin(&self, kind: CheckKind) -> Option<f64> {
        self.check(kind).and_then(|c| c.margin)
    }

    /// The threshold of one lever, if the design fails and a value in range passes.
    pub fn lever(&self, name: &str) -> Option<f64> {
        self.levers
            .iter()
            .find(|l| l.name == name)
            .and_then(|l| l.value)
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

/// The cells of one check: value, limit, utilisation, margin, pass.
macro_rules! check_columns {
    ($kind:expr, $value:literal, $limit:literal, $used:literal, $margin:literal, $pass:literal) => {
        [
            ($value, |r: &Record| {
                Cell::Number(r.check($kind).map(|c| c.value))
            }),
            ($limit, |r: &Record| {
                Cell::Number(r.check($kind).and_then(|c| c.limit))
            }),
            ($used, |r: &Record| {
                Cell::Number(r.check($kind).and_then(|c| c.utilisation))
            }),
            ($margin, |r: &Record| Cell::Number(r.check_margin($kind))),
            ($pass, |r: &Record| {
                Cell::Text(r.check($kind).map(|c| c.pass.to_string()))
            }),
        ]
    };
}

const BOND: [Column; 5] = check_columns!(
    CheckKind::BondShear,
    "bond_shear_value_pa",
    "bond_shear_limit_pa",
    "bond_shear_utilisation",
    "bond_shear_margin",
    "bond_shear_pass"
);
const YIELD: [Column; 5] = check_columns!(
    CheckKind::SubstrateYield,
    "substrate_yield_value_pa",
    "substrate_yield_limit_pa",
    "substrate_yield_utilisation",
    "substrate_yield_margin",
    "substrate_yield_pass"
);
const THICKNESS: [Column; 5] = check_columns!(
    CheckKind::MinThickness,
    "min_thickness_value_m",
    "min_thickness_limit_m",
    "min_thickness_utilisation",
    "min_thickness_margin",
    "min_thickness_pass"
);

const HEAD: &[Column] = &[
    ("scene", |r| Cell::Text(Some(r.scene.clone()))),
    ("verdict", |r| Cell::Text(Some(r.verdict.into()))),
    ("governing_check", |r| {
        Cell::Text(r.governing_check.map(Into::into))
    }),
    ("utilisation", |r| Cell::Number(r.utilisation)),
    ("margin", |r| Cell::Number(r.margin)),
    ("thickness_m", |r| Cell::Number(r.thickness_m)),
    ("pressure_pa", |r| Cell::Number(r.pressure_pa)),
    ("h_rms_m", |r| Cell::Number(r.h_rms_m)),
    ("rms_slope", |r| Cell::Number(r.rms_slope)),
    ("min_thickness_m", |r| Cell::Number(r.min_thickness_m)),
    ("min_thickness_m_err", |r| {
        Cell::Number(r.min_thickness_m_err)
    }),
    ("area_fraction", |r| Cell::Number(r.area_fraction)),
    ("area_fraction_err", |r| Cell::Number(r.area_fraction_err)),
    ("mean_contact_pressure_pa", |r| {
        Cell::Number(r.mean_contact_pressure_pa)
    }),
    ("mean_contact_pressure_pa_err", |r| {
        Cell::Number(r.mean_contact_pressure_pa_err)
    }),
    ("sigma_rms_top_pa", |r| Cell::Number(r.sigma_rms_top_pa)),
    ("sigma_rms_top_pa_err", |r| {
        Cell::Number(r.sigma_rms_top_pa_err)
    }),
    ("sigma_rms_interface_pa", |r| {
        Cell::Number(r.sigma_rms_interface_pa)
    }),
    ("sigma_rms_interface_pa_err", |r| {
        Cell::Number(r.sigma_rms_interface_pa_err)
    }),
    ("tau_rms_interface_pa", |r| {
        Cell::Number(r.tau_rms_interface_pa)
    }),
    ("tau_rms_interface_pa_err", |r| {
        Cell::Number(r.tau_rms_interface_pa_err)
    }),
    ("tau_peak_pa", |r| Cell::Number(r.tau_peak_pa)),
    ("tau_peak_pa_err", |r| Cell::Number(r.tau_peak_pa_err)),
    ("sigma_peak_interface_pa", |r| {
        Cell::Number(r.sigma_peak_interface_pa)
    }),
    ("sigma_peak_interface_pa_err", |r| {
        Cell::Number(r.sigma_peak_interface_pa_err)
    }),
    ("e_eff_over_e_film", |r| Cell::Number(r.e_eff_over_e_film)),
    ("e_eff_over_e_film_err", |r| {
        Cell::Number(r.e_eff_over_e_film_err)
    }),
    ("friction", |r| Cell::Number(r.friction)),
    ("mean_interface_shear_pa", |r| {
        Cell::Number(r.mean_interface_shear_pa)
    }),
    ("mean_interface_shear_pa_err", |r| {
        Cell::Number(r.mean_interface_shear_pa_err)
    }),
    ("tau_x_rms_interface_pa", |r| {
        Cell::Number(r.tau_x_rms_interface_pa)
    }),
    ("tau_x_rms_interface_pa_err", |r| {
        Cell::Number(r.tau_x_rms_interface_pa_err)
    }),
    ("tau_y_rms_interface_pa", |r| {
        Cell::Number(r.tau_y_rms_interface_pa)
    }),
    ("tau_y_rms_interface_pa_err", |r| {
        Cell::Number(r.tau_y_rms_interface_pa_err)
    }),
    ("tau_peak_static_pa", |r| Cell::Number(r.tau_peak_static_pa)),
    ("tau_peak_static_pa_err", |r| {
        Cell::Number(r.tau_peak_static_pa_err)
    }),
];

const TAIL: &[Column] = &[
    ("lever_thickness_m", |r| Cell::Number(r.lever("thickness"))),
    ("lever_bond_strength_pa", |r| {
        Cell::Number(r.lever("bond_strength"))
    }),
    ("lever_yield_strength_pa", |r| {
        Cell::Number(r.lever("yield_strength"))
    }),
    ("lever_pressure_pa", |r| Cell::Number(r.lever("pressure"))),
    ("lever_low_octave_rms_m", |r| {
        Cell::Number(r.lever("low_octave_rms"))
    }),
    ("verify_verdict", |r| {
        Cell::Text(r.verify_verdict.map(Into::into))
    }),
    ("verify_area_fraction", |r| {
        Cell::Number(r.verify_area_fraction)
    }),
    ("verify_mean_contact_pressure_pa", |r| {
        Cell::Number(r.verify_mean_contact_pressure_pa)
    }),
    ("verify_tau_peak_pa", |r| Cell::Number(r.verify_tau_peak_pa)),
    ("verify_sigma_peak_interface_pa", |r| {
        Cell::Number(r.verify_sigma_peak_interface_pa)
    }),
    ("verify_min_thickness_m", |r| {
        Cell::Number(r.verify_min_thickness_m)
    }),
    ("verify_min_thickness_m_err", |r| {
        Cell::Number(r.verify_min_thickness_m_err)
    }),
    ("verify_realisations", |r| {
        Cell::Number(r.verify_realisations.map(|k| k as f64))
    }),
    ("robust_verdict", |r| {
        Cell::Text(r.robust_verdict.map(Into::into))
    }),
    ("robust_governing_check", |r| {
        Cell::Text(r.robust_governing_check.map(Into::into))
    }),
    ("robust_margin", |r| Cell::Number(r.robust_margin)),
    ("robust_min_thickness_m_min", |r| {
        Cell::Number(r.robust_min_thickness_m_min)
    }),
    ("robust_min_thickness_m_max", |r| {
        Cell::Number(r.robust_min_thickness_m_max)
    }),
    ("worst_file", |r| Cell::Text(r.worst_file.clone())),
    ("files", |r| Cell::Count(r.files as u64)),
    ("warnings", |r| {
        Cell::Text((!r.warnings.is_empty()).then(|| r.warnings.join(" | ")))
    }),
    ("error", |r| Cell::Text(r.error.clone())),
    ("seconds", |r| Cell::Number(Some(r.seconds))),
];

/// The flat columns of one interface of a layer stack, each name after `interface<k>_` (k from
/// 1, the top layer's): its record's static fields, then its bond-shear check's limit,
/// utilisation, margin and pass, then its sliding fields (empty under the paper's rule).
pub type InterfaceColumn = (&'static str, fn(&Record, &InterfaceRecord) -> Cell);

/// The bond-shear check at an interface.
fn bond_at<'a>(r: &'a Record, i: &InterfaceRecord) -> Option<&'a CheckRecord> {
    r.check_at(CheckKind::BondShear, &i.name)
}

pub const INTERFACE_COLUMNS: &[InterfaceColumn] = &[
    ("name", |_, i| Cell::Text(Some(i.name.clone()))),
    ("depth_m", |_, i| Cell::Number(Some(i.depth_m))),
    ("sigma_rms_pa", |_, i| Cell::Number(Some(i.sigma_rms_pa))),
    ("sigma_rms_pa_err", |_, i| {
        Cell::Number(Some(i.sigma_rms_pa_err))
    }),
    ("tau_rms_pa", |_, i| Cell::Number(Some(i.tau_rms_pa))),
    ("tau_rms_pa_err", |_, i| {
        Cell::Number(Some(i.tau_rms_pa_err))
    }),
    ("tau_peak_pa", |_, i| Cell::Number(Some(i.tau_peak_pa))),
    ("tau_peak_pa_err", |_, i| {
        Cell::Number(Some(i.tau_peak_pa_err))
    }),
    ("sigma_peak_pa", |_, i| Cell::Number(Some(i.sigma_peak_pa))),
    ("sigma_peak_pa_err", |_, i| {
        Cell::Number(Some(i.sigma_peak_pa_err))
    }),
    ("bond_strength_pa", |_, i| {
        Cell::Number(Some(i.bond_strength_pa))
    }),
    ("bond_exceedance", |_, i| {
        Cell::Number(Some(i.bond_exceedance))
    }),
    ("bond_shear_limit_pa", |r, i| {
        Cell::Number(bond_at(r, i).and_then(|c| c.limit))
    }),
    ("bond_shear_utilisation", |r, i| {
        Cell::Number(bond_at(r, i).and_then(|c| c.utilisation))
    }),
    ("bond_shear_margin", |r, i| {
        Cell::Number(bond_at(r, i).and_then(|c| c.margin))
    }),
    ("bond_shear_pass", |r, i| {
        Cell::Text(bond_at(r, i).map(|c| c.pass.to_string()))
    }),
    ("mean_interface_shear_pa", |_, i| {
        Cell::Number(i.mean_interface_shear_pa)
    }),
    ("mean_interface_shear_pa_err", |_, i| {
        Cell::Number(i.mean_interface_shear_pa_err)
    }),
    ("tau_x_rms_interface_pa", |_, i| {
        Cell::Number(i.tau_x_rms_interface_pa)
    }),
    ("tau_x_rms_interface_pa_err", |_, i| {
        Cell::Number(i.tau_x_rms_interface_pa_err)
    }),
    ("tau_y_rms_interface_pa", |_, i| {
        Cell::Number(i.tau_y_rms_interface_pa)
    }),
    ("tau_y_rms_interface_pa_err", |_, i| {
        Cell::Number(i.tau_y_rms_interface_pa_err)
    }),
    ("tau_peak_static_pa", |_, i| {
        Cell::Number(i.tau_peak_static_pa)
    }),
    ("tau_peak_static_pa_err", |_, i| {
        Cell::Number(i.tau_peak_static_pa_err)
    }),
];

/// Every flat column, in order: the results, each check's five cells, the levers, the exact
/// check, then the bookkeeping. Records of layer stacks add, after these, `thickness_of` and
/// [`INTERFACE_COLUMNS`] for each interface of the deepest stack.
pub fn columns() -> Vec<Column> {
    let mut all = HEAD.to_vec();
    all.extend(BOND);
    all.extend(YIELD);
    all.extend(THICKNESS);
    all.extend_from_slice(TAIL);
    all
}

/// The batch as JSON: `{"schema_version", "coatcheck_version", "scenes": [records],
/// "totals": {...}}`.
pub fn json(runs: &[SceneRun]) -> String {
    let records: Vec<Record> = runs.iter().map(Record::of).collect();
    let v = serde_json::json!({
        "schema_version": super::SCHEMA_VERSION,
        "coatcheck_version": env!("CARGO_PKG_VERSION"),
        "scenes": records,
        "totals": Totals::of(runs),
    });
    format!("{v:#}\n")
}

/// The batch as CSV: a header and one row per scene ([`columns`]).
pub fn csv(runs: &[SceneRun]) -> Result<String, Error> {
    records_csv(&runs.iter().map(Record::of).collect::<Vec<_>>())
}

/// Records as CSV: a header and one row each ([`columns`]); numbers in Rust's shortest
/// round-trip form.
pub fn records_csv(records: &[Record]) -> Result<String, Error> {
    let ser = |e: csv::Error| Error::Numerical {
        what: "CSV output",
        detail: e.to_string(),
    };
    let columns = columns();
    let depth = records
        .iter()
        .filter_map(|r| r.interfaces.as_ref().map(Vec::len))
        .max();
    let text = |c: Cell| match c {
        Cell::Text(t) => t.unwrap_or_default(),
        Cell::Number(x) => x.map(|x| format!("{x:e}")).unwrap_or_default(),
        Cell::Count(n) => n.to_string(),
    };
    let mut w = csv::Writer::from_writer(Vec::new());
    let mut head: Vec<String> = columns.iter().map(|(name, _)| name.to_string()).collect();
    if let Some(n) = depth {
        head.push("thickness_of".into());
        for k in 1..=n {
            head.extend(
                INTERFACE_COLUMNS
                    .iter()
                    .map(|(name, _)| format!("interface{k}_{name}")),
            );
        }
    }
    w.write_record(&head).map_err(ser)?;
    for r in records {
        let mut row: Vec<String> = columns.iter().map(|(_, get)| text(get(r))).collect();
        if let Some(n) = depth {
            row.push(r.thickness_of.clone().unwrap_or_default());
            let interfaces = r.interfaces.as_deref().unwrap_or_default();
            for k in 0..n {
                row.extend(
                    INTERFACE_COLUMNS
                        .iter()
                        .map(|(_, get)| match interfaces.get(k) {
                            Some(i) => text(get(r, i)),
                            None => String::new(),
                        }),
                );
            }
        }
        w.write_record(&row).map_err(ser)?;
    }
    let bytes = w.into_inner().map_err(|e| Error::Numerical {
        what: "CSV output",
        detail: e.to_string(),
    })?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// The directory every scene file is in, when they share one (shown once above the table so
/// that the scene column fits).
fn common_dir(runs: &[SceneRun]) -> Option<&Path> {
    let first = runs.first()?.file.parent()?;
    let shared =
        first.as_os_str().is_empty().not() && runs.iter().all(|r| r.file.parent() == Some(first));
    shared.then_some(first)
}

/// The summary table: scene, verdict, governing check, its utilisation and margin, d_min
/// (failures first), then the errors and warnings in full, then the totals.
pub fn summary(runs: &[SceneRun], seconds: f64) -> String {
    let mut t = table(&[
        "scene",
        "verdict",
        "governing",
        "utilisation",
        "margin",
        "d_min",
    ]);
    let dir = common_dir(runs);
    let mut notes = String::new();
    for run in runs {
        let mut scene = match dir {
            Some(d) => run.file.strip_prefix(d).unwrap_or(&run.file),
            None => &run.file,
        }
        .display()
        .to_string();
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
                notes += &wrap(&format!("error: {e}"));
                notes.push('\n');
            }
            Ok(j) => {
                if let Some(f) = j.worst_file() {
                    let name = f.file_name().map_or(f.as_os_str(), |n| n);
                    scene += &format!("\n(worst of {}: {})", j.files.len(), name.display());
                }
                let o = &j.outcome;
                let margin = o.margin();
                let dmin = match o.min_thickness() {
                    None => "-".into(),
                    Some(m) => match m.thickness {
                        None => "none passes".into(),
                        Some(d) if m.all_pass_to_floor => {
                            format!("<= {} µm", sig(d.value * 1e6, 4))
                        }
                        Some(d) => format!("{} µm", sig(d.value * 1e6, 4)),
                    },
                };
                t.add_row([
                    scene,
                    verdict,
                    o.governing_name().unwrap_or_else(|| "-".into()),
                    utilisation_cell(margin),
                    margin_cell(margin),
                    dmin,
                ]);
                for w in &j.warnings {
                    notes += &wrap(&format!("warning: {}: {w}", run.file.display()));
                    notes.push('\n');
                }
            }
        }
    }
    let n = Totals::of(runs);
    let head = dir.map_or(String::new(), |d| format!("scenes in {}:\n", d.display()));
    format!(
        "{head}{t}\n{notes}{} scenes: {} passed, {} failed, {} could not be evaluated ({:.2} s)\n",
        n.scenes, n.pass, n.fail, n.error, seconds
    )
}

/// The verdict of every roughness file of a scene that lists several (empty otherwise).
pub fn files_table(j: &Judged) -> String {
    if j.files.len() < 2 {
        return String::new();
    }
    let mut t = table(&[
        "roughness file",
        "verdict",
        "governing check",
        "utilisation",
        "margin",
    ]);
    for f in &j.files {
        t.add_row([
            f.path.display().to_string(),
            if f.pass { "PASS" } else { "FAIL" }.into(),
            f.governing.map_or("-", CheckKind::name).into(),
            utilisation_cell(f.margin),
            margin_cell(f.margin),
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
