//! The robust section of `check --robust` on a layer stack ([`crate::check::stack_robust`]): the
//! ranges with the governing corner (and those held at one end when the corners are capped),
//! each check at every interface at its worst corner, the robust verdict beside the nominal one
//! and the d_min range of the layer `criteria.thickness_of`, as a table, JSON (the film's
//! `robust` object of `check.schema.json`, each check with `at`, each range with `held`) and
//! sentences for the HTML report.

use super::check::{check_json, check_rows_of};
use super::robust::{
    Ranged, corner_json, corner_texts, d_min_range_line, d_min_text, nominal_d_min, range_texts,
    ranges_json, ranges_table, verdict,
};
use super::{modulus, mpa, table, wrap};
use crate::check::stack::{StackDesign, StackOutcome};
use crate::check::stack_robust::{MAX_VARIED, StackParam, StackRobust};
use serde_json::{Value, json};

impl Ranged for StackParam {
    type Design = StackDesign;
    fn key(self) -> String {
        StackParam::key(self)
    }
    fn unit(self) -> &'static str {
        StackParam::unit(self)
    }
    fn nominal(self, design: &StackDesign) -> Option<f64> {
        self.value(design)
    }
    fn show(self, v: f64) -> String {
        match self {
            _ if self.is_ratio() => v.to_string(),
            StackParam::YieldStrength | StackParam::BondStrength(_) => format!("{} MPa", mpa(v)),
            _ => modulus(v),
        }
    }
}

/// Whether range `i` is held at one end.
fn held(r: &StackRobust, i: usize) -> bool {
    r.held.iter().any(|&(h, _)| h == i)
}

/// The robust section as tables and lines of text.
pub fn table_text(r: &StackRobust, design: &StackDesign, o: &StackOutcome) -> String {
    let mut out = wrap(&format!(
        "Robust: the stack at the worst corner of its materials' ranges ({} corner{} of the \
         elastic constants; strengths at their minima){}",
        r.corners,
        if r.corners == 1 { "" } else { "s" },
        if r.held.is_empty() {
            String::new()
        } else {
            format!(
                "; more than {MAX_VARIED} elastic ranges: the {MAX_VARIED} that change the \
                 utilisation most are varied, the other {} held at their worse end (screened one \
                 at a time)",
                r.held.len()
            )
        }
    ));
    out.push('\n');
    out += &ranges_table(&r.ranges, &r.corner, design, |i| held(r, i));
    let mut t = table(&[
        "check",
        "at",
        "worst value",
        "limit",
        "utilisation",
        "margin",
        "result",
    ]);
    for (c, row) in r.checks.iter().zip(check_rows_of(
        r.checks.iter().map(|c| &c.check.result),
        None,
    )) {
        let mut row = row.to_vec();
        row.insert(1, c.check.at.clone());
        t.add_row(row);
    }
    out += &format!("{t}\n");
    out += &format!(
        "robust verdict: {} (nominal: {}){}\n",
        verdict(r.pass),
        verdict(o.pass),
        r.governing
            .as_ref()
            .map(|(k, at)| format!(
                "; governing check at its worst corner: {} at {at}",
                k.name()
            ))
            .unwrap_or_default()
    );
    if let Some(m) = &r.min_thickness {
        out += &d_min_range_line(m, nominal_d_min(o.min_thickness.as_ref()));
    }
    out
}

/// The `robust` object of a stack.
pub fn json_value(r: &StackRobust, design: &StackDesign, o: &StackOutcome) -> Value {
    let ranges = ranges_json(&r.ranges, &r.corner, design, Some(&|i| held(r, i)));
    let checks: Vec<Value> = r
        .checks
        .iter()
        .map(|c| {
            let mut m = check_json(&c.check.result);
            m.insert("at".into(), json!(c.check.at));
            let corner = corner_json(&r.ranges, &c.corner);
            m.insert("corner".into(), Value::Object(corner));
            Value::Object(m)
        })
        .collect();
    json!({
        "verdict": if r.pass { "pass" } else { "fail" },
        "nominal_verdict": if o.pass { "pass" } else { "fail" },
        "governing_check": r.governing.as_ref().map(|(k, _)| k.name()),
        "governing_at": r.governing.as_ref().map(|(_, at)| at),
        "governing_corner": corner_json(&r.ranges, &r.corner),
        "corners": r.corners,
        "ranges": ranges,
        "checks": checks,
        "min_thickness_range_m": r.min_thickness.map(|m| json!({
            "min": m.min,
            "max": m.max,
            "nominal": nominal_d_min(o.min_thickness.as_ref()),
        })),
    })
}

/// Sentences for the HTML report's "how far to trust these numbers": the ranges, the robust
/// verdict with its governing check and corner, each check's utilisation at its worst corner,
/// and the d_min range of the layer `criteria.thickness_of`.
pub fn sentences(r: &StackRobust, design: &StackDesign, o: &StackOutcome) -> Vec<String> {
    if r.ranges.is_empty() {
        return vec![
            "Materials: no property has a range of non-zero width, so the robust verdict is the \
             nominal one."
                .into(),
        ];
    }
    let ranges = range_texts(&r.ranges, design);
    let corner = corner_texts(&r.ranges, &r.corner, |i| held(r, i));
    let held_note = if r.held.is_empty() {
        String::new()
    } else {
        format!(
            "; {} elastic range{} held at the worse end, the {MAX_VARIED} that change the \
             utilisation most varied",
            r.held.len(),
            if r.held.len() == 1 { "" } else { "s" }
        )
    };
    let mut out = vec![format!(
        "Materials: judged at the worst corner of the ranges {} ({} corners{held_note}): robust \
         verdict {} (nominal {}){}.",
        ranges.join(", "),
        r.corners,
        verdict(r.pass),
        verdict(o.pass),
        r.governing
            .as_ref()
            .map(|(k, at)| format!(
                ", governed by {} at {at} (corner: {})",
                k.name(),
                corner.join(", ")
            ))
            .unwrap_or_default()
    )];
    let each: Vec<String> = r
        .checks
        .iter()
        .map(|c| {
            let res = &c.check.result;
            format!(
                "{} at {} {} ({})",
                res.kind.name(),
                c.check.at,
                super::utilisation_cell(res.margin),
                verdict(res.pass)
            )
        })
        .collect();
    out.push(format!(
        "Utilisation of each check at its own worst corner: {}.",
        each.join(", ")
    ));
    if let Some(m) = &r.min_thickness {
        out.push(format!(
            "d_min of layer '{}' over the corners of the ranges: {} to {} (nominal {}).",
            design.layers[design.thickness_of].name,
            d_min_text(m.min),
            d_min_text(m.max),
            d_min_text(nominal_d_min(o.min_thickness.as_ref()))
        ));
    }
    out
}
