//! The exact check in the HTML report: Persson's numbers beside the exact ones, each exact
//! number with its grid error and, over realisations of a spectrum, its spread (the standard
//! error of the mean over them); the minimum thickness of both models with their errors; and
//! the uncertainty section's sentences on the exact check (the realisations, their grid and
//! the share of the slope variance it cannot hold).

use super::{mpa, sig, um};
use crate::check::{CheckKind, Outcome};
use crate::pipeline::Exact;
use crate::prec::Estimate;
use crate::verify::check_rows;

/// The rows (quantity, Persson, exact) of the exact check, the minimum thickness last.
pub(super) fn rows(e: &Exact, outcome: &Outcome) -> Vec<[String; 3]> {
    let spread = e.realisations.as_ref();
    let mut rows: Vec<[String; 3]> = check_rows(&outcome.evaluation, &e.verification)
        .into_iter()
        .map(|row| {
            let stress = row.key.ends_with("_pa");
            let show = |x: f64| if stress { mpa(x) } else { sig(x) };
            let unit = if stress { " MPa" } else { "" };
            let est = |x: Estimate| format!("{} ± {}{unit}", show(x.value), show(x.err));
            let s = spread
                .and_then(|r| r.spread_of(row.key))
                .map(|s| format!(" (spread ± {}{unit})", show(s)))
                .unwrap_or_default();
            [
                row.name.to_string(),
                row.persson.map_or("-".into(), est),
                format!("{}{s}", est(row.exact)),
            ]
        })
        .collect();
    if let Some(m) = &e.min_thickness {
        let persson = outcome
            .min_thickness
            .as_ref()
            .and_then(|p| p.thickness)
            .map_or("no thickness passes".into(), |d| {
                format!("{} ± {} µm", um(d.value), um(d.err))
            });
        let exact = m.thickness().map_or("no thickness passes".into(), |d| {
            let bracket = m.search.thickness.map_or(f64::NAN, |b| b.err);
            let s = spread
                .map(|r| format!(", spread ± {} µm", um(r.min_thickness_spread)))
                .unwrap_or_default();
            format!(
                "{} ± {} µm (bracket ± {} µm, grid ± {} µm{s}; set by {})",
                um(d.value),
                um(d.err),
                um(bracket),
                um(m.grid_err),
                m.search.governing.map_or("-", CheckKind::name)
            )
        });
        rows.push(["minimum thickness d_min".into(), persson, exact]);
    }
    rows
}

/// The uncertainty section's sentences on the exact check.
pub(super) fn sentences(e: &Exact, outcome: &Outcome) -> Vec<String> {
    let v = &e.verification;
    let mut out = vec![format!(
        "Exact check on {} ({} x {}): exact A/A0 / Persson's = {}. Each exact number carries \
         its grid error (the solve repeated on the map at half and a quarter of the \
         resolution).",
        e.map.display(),
        v.nx,
        v.ny,
        sig(v.area_fraction.value / outcome.evaluation.contact.area_fraction.value)
    )];
    if let Some(r) = &e.realisations {
        let g = &r.grid;
        out.push(format!(
            "The scene gives a spectrum, not a height map: the exact numbers are the mean over \
             {} random-phase realisations of it (seeds 1 to {}) on a {} x {} grid of {} µm \
             pixels, with their spread, the standard error of that mean (sample standard \
             deviation / sqrt(K)). The grid holds the spectrum up to q = {} 1/m of {} 1/m: {} % \
             of its slope variance lies above it and is in no realisation.",
            r.count,
            r.count,
            g.n,
            g.n,
            um(g.dx),
            sig(g.q_nyquist),
            sig(g.q_high),
            sig(100.0 * g.unresolved_slope_share)
        ));
    }
    out
}
