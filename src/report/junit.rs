//! JUnit XML of a batch, for CI systems that display test reports natively. Written
//! with `quick-junit` (the serializer cargo-nextest uses: escaping, counts and the Jenkins
//! schema handled there).
//!
//! Layout: one `<testsuite>` per scene (named by its file), one `<testcase>` per enabled check
//! (`bond-shear`, `substrate-yield`, `min-thickness`; classname = the scene file); in a layer
//! stack one per check and interface, named with where it applies (`bond-shear at primer`,
//! `substrate-yield at substrate`); with `--robust`, one more per check at its worst corner of
//! the materials' ranges, named `… (robust)` (`bond-shear at primer (robust)`). A failing
//! check is a `<failure>` whose message carries the value, the limit and the margin (human
//! units; SI in the text node), a robust one also its corner (SI); a scene that could not be
//! evaluated is one `<testcase name="evaluate">` with an `<error>` carrying the message (file
//! and line). Warnings go to the suite's `<system-out>`.

use super::{margin_cell, sig, utilisation_cell};
use crate::batch::SceneRun;
use crate::check::{CheckKind, CheckResult};
use crate::error::Error;
use crate::pipeline::Judged;
use quick_junit::{NonSuccessKind, Report, TestCase, TestCaseStatus, TestSuite};
use std::time::Duration;

/// A check's value or limit in human units (MPa for stresses, µm for thickness).
fn human(kind: CheckKind, x: f64) -> String {
    match kind {
        CheckKind::MinThickness => format!("{} µm", sig(x * 1e6, 4)),
        _ => format!("{} MPa", sig(x * 1e-6, 4)),
    }
}

/// The failure message of a check: the numbers that decide it.
pub fn failure_message(c: &CheckResult) -> String {
    let v = human(c.kind, c.value.value);
    match (c.kind, c.limit, c.margin) {
        (CheckKind::MinThickness, Some(l), Some(m)) => format!(
            "min-thickness: thickness {v} is below d_min = {} (utilisation {}, margin {})",
            human(c.kind, l),
            utilisation_cell(Some(m)),
            margin_cell(Some(m))
        ),
        (CheckKind::MinThickness, _, _) => {
            format!("min-thickness: no film thickness passes (thickness {v})")
        }
        (k, Some(l), Some(m)) => format!(
            "{}: {v} exceeds the limit {} (utilisation {}, margin {})",
            k.name(),
            human(k, l),
            utilisation_cell(Some(m)),
            margin_cell(Some(m))
        ),
        (k, _, _) => format!("{}: {v} (no limit)", k.name()),
    }
}

/// The test case of check `c` (at `at` in a stack) of the scene `classname`; with `corner`,
/// the check at its worst corner of the materials' ranges (`--robust`), named `… (robust)`,
/// its failure message naming the corner.
fn case(
    classname: &str,
    at: Option<&str>,
    c: &CheckResult,
    worst: Option<&str>,
    corner: Option<&str>,
) -> TestCase {
    let status = if c.pass {
        TestCaseStatus::success()
    } else {
        let mut s = TestCaseStatus::non_success(NonSuccessKind::Failure);
        s.set_message(format!(
            "{}{}{}",
            failure_message(c),
            corner
                .map(|k| format!(" at the worst corner of the materials' ranges ({k})"))
                .unwrap_or_default(),
            worst.unwrap_or("")
        ))
        .set_type("check failed")
        .set_description(format!(
            "value = {:e} ± {:e} (SI), limit = {}, margin = {}",
            c.value.value,
            c.value.err,
            c.limit.map_or("none".into(), |l| format!("{l:e}")),
            c.margin.map_or("none".into(), |m| format!("{m:.4}")),
        ));
        s
    };
    let mut name = match at {
        Some(at) => format!("{} at {at}", c.kind.name()),
        None => c.kind.name().to_string(),
    };
    if corner.is_some() {
        name.push_str(" (robust)");
    }
    let mut case = TestCase::new(name, status);
    case.set_classname(classname);
    case
}

/// `key = value` (SI) for each range of a corner.
fn corner_text(keys: impl Iterator<Item = String>, values: &[f64]) -> String {
    keys.zip(values)
        .map(|(k, v)| format!("{k} = {v:e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Each check of a judged scene at its worst corner (`--robust`; none without): where it
/// applies in a stack, the check there, and the corner.
fn robust_checks(j: &Judged) -> Vec<(Option<&str>, &CheckResult, String)> {
    if let Some(r) = &j.robust {
        let keys = || r.ranges.iter().map(|(p, _)| p.key().to_string());
        return r
            .checks
            .iter()
            .map(|c| (None, &c.result, corner_text(keys(), &c.corner)))
            .collect();
    }
    if let Some(r) = &j.stack_robust {
        let keys = || r.ranges.iter().map(|(p, _)| p.key());
        return r
            .checks
            .iter()
            .map(|c| {
                let at = Some(c.check.at.as_str());
                (at, &c.check.result, corner_text(keys(), &c.corner))
            })
            .collect();
    }
    Vec::new()
}

/// The JUnit XML of a batch.
pub fn report(runs: &[SceneRun]) -> Result<String, Error> {
    let mut report = Report::new("coatcheck check");
    let mut total = 0.0;
    for run in runs {
        let name = run.file.display().to_string();
        let mut suite = TestSuite::new(name.as_str());
        suite.set_time(Duration::from_secs_f64(run.seconds));
        total += run.seconds;
        match &run.result {
            Err(e) => {
                let mut status = TestCaseStatus::non_success(NonSuccessKind::Error);
                status
                    .set_message(e.to_string())
                    .set_type("could not be evaluated");
                let mut case = TestCase::new("evaluate", status);
                case.set_classname(name.as_str());
                suite.add_test_case(case);
            }
            Ok(j) => {
                let worst = j
                    .worst_file()
                    .map(|f| format!(" [worst of {} files: {}]", j.files.len(), f.display()));
                for (at, c) in j.outcome.checks() {
                    suite.add_test_case(case(&name, at, c, worst.as_deref(), None));
                }
                for (at, c, corner) in robust_checks(j) {
                    let case = case(&name, at, c, worst.as_deref(), Some(&corner));
                    suite.add_test_case(case);
                }
                if !j.warnings.is_empty() {
                    suite.set_system_out(
                        j.warnings
                            .iter()
                            .map(|w| format!("warning: {w}\n"))
                            .collect::<String>(),
                    );
                }
            }
        }
        report.add_test_suite(suite);
    }
    report.set_time(Duration::from_secs_f64(total));
    report.to_string().map_err(|e| Error::Numerical {
        what: "JUnit output",
        detail: e.to_string(),
    })
}
