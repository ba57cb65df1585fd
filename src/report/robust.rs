//! The robust section of `check --robust` ([`crate::check::robust`]): the ranges with the
//! governing corner, each check at its worst corner, the robust verdict beside the nominal one
//! and the d_min range, as a table, JSON (the `robust` object of `check.schema.json`) and
//! sentences for the HTML report.

use super::check::{check_json, check_rows_of};
use super::{modulus, mpa, table, um, wrap};
use crate::check::robust::{Param, Robust};
use crate::check::{CheckKind, Design, Outcome};
use serde_json::{Map, Value, json};

/// A property's value in the unit people read it in.
fn show(p: Param, v: f64) -> String {
    match p {
        Param::FilmPoissonRatio | Param::SubstratePoissonRatio => v.to_string(),
        Param::YieldStrength | Param::BondShearStrength => format!("{} MPa", mpa(v)),
        _ => modulus(v),
    }
}

/// `min` or `max`: which end of its range a corner takes.
pub(super) fn end(v: f64, min: f64) -> &'static str {
    if v == min { "min" } else { "max" }
}

/// PASS or FAIL.
pub(super) fn verdict(pass: bool) -> &'static str {
    if pass { "PASS" } else { "FAIL" }
}

/// The nominal d_min (m), when min-thickness ran and a thickness passes.
fn nominal_d_min(outcome: &Outcome) -> Option<f64> {
    outcome
        .min_thickness
        .as_ref()
        .and_then(|m| m.thickness)
        .map(|e| e.value)
}

/// "2.1 µm to 8.3 µm" (an end where no thickness passes: "none passes").
/// A d_min (m) in µm, or "none passes".
pub(super) fn d_min_text(v: Option<f64>) -> String {
    v.map_or("none passes".into(), |d| format!("{} µm", um(d)))
}

/// The robust section as tables and lines of text.
pub fn table_text(r: &Robust, design: &Design, outcome: &Outcome) -> String {
    let mut out = wrap(&format!(
        "Robust: the design at the worst corner of its materials' ranges ({} corner{} of the \
         elastic constants; strengths at their minima)",
        r.corners,
        if r.corners == 1 { "" } else { "s" }
    ));
    out.push('\n');
    if r.ranges.is_empty() {
        out += "no property has a range of non-zero width: the robust verdict is the nominal one\n";
    } else {
        let mut t = table(&["property", "nominal", "range", "governing corner"]);
        for (i, (p, s)) in r.ranges.iter().enumerate() {
            let nominal = p.value(design).map_or("-".into(), |v| show(*p, v));
            let corner = r.corner.get(i).map_or("-".into(), |&v| {
                format!("{} ({})", show(*p, v), end(v, s.min))
            });
            t.add_row(vec![
                p.key().to_string(),
                nominal,
                format!("{} to {}", show(*p, s.min), show(*p, s.max)),
                corner,
            ]);
        }
        out += &format!("{t}\n");
    }
    let mut t = table(&[
        "check",
        "worst value",
        "limit",
        "utilisation",
        "margin",
        "result",
    ]);
    for row in check_rows_of(r.checks.iter().map(|c| &c.result), None) {
        t.add_row(row.to_vec());
    }
    out += &format!("{t}\n");
    out += &format!(
        "robust verdict: {} (nominal: {}){}\n",
        verdict(r.pass),
        verdict(outcome.pass),
        r.governing
            .map(|g| format!("; governing check at its worst corner: {}", g.name()))
            .unwrap_or_default()
    );
    if let Some(m) = &r.min_thickness {
        out += &format!(
            "d_min over the corners: {} to {} (nominal {})\n",
            d_min_text(m.min),
            d_min_text(m.max),
            d_min_text(nominal_d_min(outcome))
        );
    }
    out
}

/// The corner as `{key: value}` (SI).
fn corner_json(r: &Robust, corner: &[f64]) -> Map<String, Value> {
    r.ranges
        .iter()
        .zip(corner)
        .map(|((p, _), v)| (p.key().to_string(), json!(v)))
        .collect()
}

/// The `robust` object.
pub fn json_value(r: &Robust, design: &Design, outcome: &Outcome) -> Value {
    let ranges: Vec<Value> = r
        .ranges
        .iter()
        .enumerate()
        .map(|(i, (p, s))| {
            json!({
                "key": p.key(),
                "unit": p.unit(),
                "nominal": p.value(design),
                "min": s.min,
                "max": s.max,
                "governing_corner": r.corner.get(i),
            })
        })
        .collect();
    let checks: Vec<Value> = r
        .checks
        .iter()
        .map(|c| {
            let mut m = check_json(&c.result);
            m.insert("corner".into(), Value::Object(corner_json(r, &c.corner)));
            Value::Object(m)
        })
        .collect();
    json!({
        "verdict": if r.pass { "pass" } else { "fail" },
        "nominal_verdict": if outcome.pass { "pass" } else { "fail" },
        "governing_check": r.governing.map(CheckKind::name),
        "governing_corner": corner_json(r, &r.corner),
        "corners": r.corners,
        "ranges": ranges,
        "checks": checks,
        "min_thickness_range_m": r.min_thickness.map(|m| json!({
            "min": m.min,
            "max": m.max,
            "nominal": nominal_d_min(outcome),
        })),
    })
}

/// Sentences for the HTML report's "how far to trust these numbers".
pub fn sentences(r: &Robust, design: &Design, outcome: &Outcome) -> Vec<String> {
    let corner: Vec<String> = r
        .ranges
        .iter()
        .zip(&r.corner)
        .map(|((p, s), &v)| format!("{} = {} ({})", p.key(), show(*p, v), end(v, s.min)))
        .collect();
    let ranges: Vec<String> = r
        .ranges
        .iter()
        .map(|(p, s)| {
            let nominal = p.value(design).map_or("-".into(), |v| show(*p, v));
            format!(
                "{} {} ({} to {})",
                p.key(),
                nominal,
                show(*p, s.min),
                show(*p, s.max)
            )
        })
        .collect();
    let mut out = vec![if r.ranges.is_empty() {
        "Materials: no property has a range of non-zero width, so the robust verdict is the \
         nominal one."
            .to_string()
    } else {
        format!(
            "Materials: judged at the worst corner of the ranges {} ({} corners): robust verdict \
             {} (nominal {}){}.",
            ranges.join(", "),
            r.corners,
            verdict(r.pass),
            verdict(outcome.pass),
            r.governing
                .map(|g| format!(", governed by {} at {}", g.name(), corner.join(", ")))
                .unwrap_or_default()
        )
    }];
    if let Some(m) = &r.min_thickness {
        out.push(format!(
            "d_min over the corners of the ranges: {} to {} (nominal {}).",
            d_min_text(m.min),
            d_min_text(m.max),
            d_min_text(nominal_d_min(outcome))
        ));
    }
    out
}
