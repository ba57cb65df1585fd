//! The robust section of `check --robust` ([`crate::check::robust`]): the ranges with the
//! governing corner, each check at its worst corner, the robust verdict beside the nominal one
//! and the d_min range, as a table, JSON (the `robust` object of `check.schema.json`) and
//! sentences for the HTML report.

use super::check::{check_json, check_rows_of};
use super::{modulus, mpa, table, um, wrap};
use crate::check::robust::{MinThicknessRange, Param, Robust};
use crate::check::{CheckKind, Design, MinThickness, Outcome};
use crate::material::Span;
use serde_json::{Map, Value, json};

/// What the robust section needs of a property with a range, a film's ([`Param`]) or a
/// stack's, so that one piece of code writes both sections' ranges.
pub(super) trait Ranged: Copy {
    type Design;
    /// The property's key in the scene file.
    fn key(self) -> String;
    /// The SI unit of its values.
    fn unit(self) -> &'static str;
    /// Its nominal value in the design, when the design has it.
    fn nominal(self, design: &Self::Design) -> Option<f64>;
    /// A value in the unit people read it in.
    fn show(self, v: f64) -> String;
}

impl Ranged for Param {
    type Design = Design;
    fn key(self) -> String {
        Param::key(self).to_string()
    }
    fn unit(self) -> &'static str {
        Param::unit(self)
    }
    fn nominal(self, design: &Design) -> Option<f64> {
        self.value(design)
    }
    fn show(self, v: f64) -> String {
        match self {
            Param::FilmPoissonRatio | Param::SubstratePoissonRatio => v.to_string(),
            Param::YieldStrength | Param::BondShearStrength => format!("{} MPa", mpa(v)),
            _ => modulus(v),
        }
    }
}

/// The ranges as a table of property, nominal value, range and governing corner (`held(i)`:
/// whether range i is held at one end), or the line that says there are none.
pub(super) fn ranges_table<P: Ranged>(
    ranges: &[(P, Span)],
    corner: &[f64],
    design: &P::Design,
    held: impl Fn(usize) -> bool,
) -> String {
    if ranges.is_empty() {
        return "no property has a range of non-zero width: the robust verdict is the nominal one\n"
            .into();
    }
    let mut t = table(&["property", "nominal", "range", "governing corner"]);
    for (i, (p, s)) in ranges.iter().enumerate() {
        let nominal = p.nominal(design).map_or("-".into(), |v| p.show(v));
        let corner = corner.get(i).map_or("-".into(), |&v| {
            let how = if held(i) { ", held" } else { "" };
            format!("{} ({}{how})", p.show(v), end(v, s.min))
        });
        t.add_row(vec![
            p.key(),
            nominal,
            format!("{} to {}", p.show(s.min), p.show(s.max)),
            corner,
        ]);
    }
    format!("{t}\n")
}

/// The `ranges` of the `robust` object; each with `held` when `held` is given.
pub(super) fn ranges_json<P: Ranged>(
    ranges: &[(P, Span)],
    corner: &[f64],
    design: &P::Design,
    held: Option<&dyn Fn(usize) -> bool>,
) -> Vec<Value> {
    ranges
        .iter()
        .enumerate()
        .map(|(i, (p, s))| {
            let mut v = json!({
                "key": p.key(),
                "unit": p.unit(),
                "nominal": p.nominal(design),
                "min": s.min,
                "max": s.max,
                "governing_corner": corner.get(i),
            });
            if let Some(held) = held {
                v["held"] = json!(held(i));
            }
            v
        })
        .collect()
}

/// The corner as `{key: value}` (SI).
pub(super) fn corner_json<P: Ranged>(ranges: &[(P, Span)], corner: &[f64]) -> Map<String, Value> {
    ranges
        .iter()
        .zip(corner)
        .map(|((p, _), v)| (p.key(), json!(v)))
        .collect()
}

/// The ranges for the HTML sentences: "key nominal (min to max)".
pub(super) fn range_texts<P: Ranged>(ranges: &[(P, Span)], design: &P::Design) -> Vec<String> {
    ranges
        .iter()
        .map(|(p, s)| {
            let nominal = p.nominal(design).map_or("-".into(), |v| p.show(v));
            format!(
                "{} {} ({} to {})",
                p.key(),
                nominal,
                p.show(s.min),
                p.show(s.max)
            )
        })
        .collect()
}

/// The governing corner for the HTML sentences: "key = value (min|max)", with ", held" where
/// `held(i)`.
pub(super) fn corner_texts<P: Ranged>(
    ranges: &[(P, Span)],
    corner: &[f64],
    held: impl Fn(usize) -> bool,
) -> Vec<String> {
    ranges
        .iter()
        .zip(corner)
        .enumerate()
        .map(|(i, ((p, s), &v))| {
            let how = if held(i) { ", held" } else { "" };
            format!("{} = {} ({}{how})", p.key(), p.show(v), end(v, s.min))
        })
        .collect()
}

/// The d_min range over the corners beside the nominal d_min, a line of the table text.
pub(super) fn d_min_range_line(m: &MinThicknessRange, nominal: Option<f64>) -> String {
    format!(
        "d_min over the corners: {} to {} (nominal {})\n",
        d_min_text(m.min),
        d_min_text(m.max),
        d_min_text(nominal)
    )
}

/// `min` or `max`: which end of its range a corner takes.
pub(super) fn end(v: f64, min: f64) -> &'static str {
    if v == min { "min" } else { "max" }
}

/// PASS or FAIL.
pub(super) fn verdict(pass: bool) -> &'static str {
    if pass { "PASS" } else { "FAIL" }
}

/// The nominal d_min (m) of a film's or a stack's outcome (its `min_thickness`), when
/// min-thickness ran and a thickness passes.
pub(super) fn nominal_d_min(min_thickness: Option<&MinThickness>) -> Option<f64> {
    min_thickness.and_then(|m| m.thickness).map(|e| e.value)
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
    out += &ranges_table(&r.ranges, &r.corner, design, |_| false);
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
        out += &d_min_range_line(m, nominal_d_min(outcome.min_thickness.as_ref()));
    }
    out
}

/// The `robust` object.
pub fn json_value(r: &Robust, design: &Design, outcome: &Outcome) -> Value {
    let ranges = ranges_json(&r.ranges, &r.corner, design, None);
    let checks: Vec<Value> = r
        .checks
        .iter()
        .map(|c| {
            let mut m = check_json(&c.result);
            let corner = corner_json(&r.ranges, &c.corner);
            m.insert("corner".into(), Value::Object(corner));
            Value::Object(m)
        })
        .collect();
    json!({
        "verdict": if r.pass { "pass" } else { "fail" },
        "nominal_verdict": if outcome.pass { "pass" } else { "fail" },
        "governing_check": r.governing.map(CheckKind::name),
        "governing_corner": corner_json(&r.ranges, &r.corner),
        "corners": r.corners,
        "ranges": ranges,
        "checks": checks,
        "min_thickness_range_m": r.min_thickness.map(|m| json!({
            "min": m.min,
            "max": m.max,
            "nominal": nominal_d_min(outcome.min_thickness.as_ref()),
        })),
    })
}

/// Sentences for the HTML report's "how far to trust these numbers".
pub fn sentences(r: &Robust, design: &Design, outcome: &Outcome) -> Vec<String> {
    let corner = corner_texts(&r.ranges, &r.corner, |_| false);
    let ranges = range_texts(&r.ranges, design);
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
            d_min_text(nominal_d_min(outcome.min_thickness.as_ref()))
        ));
    }
    out
}
