//! What to change when a check fails: for each failing stress check, the design changes that
//! alone (everything else as given) would make every stress check pass at the design thickness.
//!
//! - thickness: d ≥ d_min (the minimum-thickness search's answer);
//! - strength: bond shear strength ≥ τ_peak·SF, substrate yield strength ≥ (the governing
//!   stress)·SF, read off the evaluation directly;
//! - load: the largest nominal pressure p ≤ p0 at which every stress check passes;
//! - roughness: the largest rms height of the lowest octave [q_L, 2 q_L] of the spectrum (that
//!   octave scaled by a factor k ≤ 1, the rest kept) at which every stress check passes.
//!
//! The last two are searched on a log grid from the design value down (p/p0 and k from 1 to
//! [`SPAN`]), taking the largest grid point below which every grid point passes, then bisected
//! between it and its failing neighbour to [`REL_TOL`] in the log; so a pass/fail that is not
//! monotone in p or k is never reported as a single threshold above a failing point. Each step
//! is one new [`Checker`] and one evaluation (about a millisecond).

use crate::Error;
use crate::check::{CheckKind, Checker, Design, Outcome};
use crate::prec::Settings;
use crate::psd::{Spectrum, Tabulated};
use serde::Serialize;

/// The grid of the load and roughness searches spans factors 1 to 1e-6.
pub const SPAN: f64 = 1e-6;
/// Grid points of that span.
const GRID: usize = 25;
/// Relative width (in p or k) to which a threshold is bisected.
pub const REL_TOL: f64 = 1e-3;
/// Points per decade of the tabulated spectrum with a scaled lowest octave.
const TAB_PER_DECADE: f64 = 200.0;

/// One design change that alone would make the stress checks pass.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Lever {
    /// `thickness`, `bond_strength`, `yield_strength`, `pressure` or `low_octave_rms`.
    pub name: &'static str,
    /// `>=` or `<=`.
    pub relation: &'static str,
    /// The threshold, SI (m or Pa); `None` when no value in the searched range passes.
    pub value: Option<f64>,
    /// The design's present value, SI.
    pub current: f64,
    pub unit: &'static str,
    /// In a layer stack, the layer the lever changes (its thickness, or the bond below it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at: Option<String>,
}

fn all_stress_checks_pass(
    spectrum: &Spectrum,
    design: &Design,
    settings: Settings,
    d: f64,
) -> Result<bool, Error> {
    let ev = Checker::new(spectrum, design.clone(), settings)?.evaluate(d)?;
    Ok(ev.checks.iter().all(|c| c.pass))
}

/// The largest factor f in [SPAN, 1] such that `passes(g)` for every grid factor g ≤ f, refined
/// by bisection; `None` when the smallest grid factor fails.
fn largest_passing(passes: impl Fn(f64) -> Result<bool, Error>) -> Result<Option<f64>, Error> {
    let grid: Vec<f64> = (0..GRID)
        .map(|i| SPAN.powf(1.0 - i as f64 / (GRID - 1) as f64))
        .collect();
    let mut last_pass = None;
    for (i, &g) in grid.iter().enumerate() {
        if passes(g)? {
            last_pass = Some(i);
        } else {
            break;
        }
    }
    let Some(i) = last_pass else {
        return Ok(None);
    };
    if i + 1 == grid.len() {
        return Ok(Some(1.0));
    }
    let (mut lo, mut hi) = (grid[i], grid[i + 1]);
    while hi / lo > 1.0 + REL_TOL {
        let mid = (lo * hi).sqrt();
        if passes(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(Some(lo))
}

/// The spectrum with its lowest octave scaled by `k` (tabulated, log-spaced).
fn low_octave_scaled(spectrum: &Spectrum, k: f64) -> Result<Spectrum, Error> {
    let (lo, hi) = spectrum.support();
    let edge = (2.0 * lo).min(hi);
    let n = ((hi / lo).log10() * TAB_PER_DECADE).ceil().max(2.0) as usize;
    let mut q: Vec<f64> = (0..=n)
        .map(|i| lo * (hi / lo).powf(i as f64 / n as f64))
        .collect();
    q.extend(spectrum.knots());
    q.push(edge);
    q.sort_by(f64::total_cmp);
    q.dedup_by(|a, b| (*a / *b - 1.0).abs() < 1e-12);
    let c = q
        .iter()
        .map(|&x| spectrum.c(x) * if x <= edge { k } else { 1.0 })
        .collect();
    Ok(Spectrum::Tabulated(Tabulated::new(q, c)?))
}

/// rms height of the lowest octave [q_L, 2 q_L], m.
fn low_octave_rms(spectrum: &Spectrum) -> Result<f64, Error> {
    let (lo, hi) = spectrum.support();
    let octave = low_octave_scaled(spectrum, 1.0)?;
    let part = match octave {
        Spectrum::Tabulated(t) => t.restricted(None, Some((2.0 * lo).min(hi)))?,
        _ => unreachable!("low_octave_scaled tabulates"),
    };
    Ok(Spectrum::Tabulated(part).h_rms_sq().value.sqrt())
}

/// The levers for a failing outcome (empty when every check passes).
pub fn levers(
    spectrum: &Spectrum,
    design: &Design,
    settings: Settings,
    outcome: &Outcome,
) -> Result<Vec<Lever>, Error> {
    let failing: Vec<_> = outcome
        .evaluation
        .checks
        .iter()
        .filter(|c| !c.pass)
        .collect();
    let mut out = Vec::new();
    if failing.is_empty() && outcome.pass {
        return Ok(out);
    }
    let d = outcome.thickness;
    if let Some(m) = outcome.min_thickness.as_ref().and_then(|m| m.thickness)
        && m.value > d
    {
        out.push(Lever {
            name: "thickness",
            relation: ">=",
            value: Some(m.value),
            current: d,
            unit: "m",
            at: None,
        });
    }
    if failing.is_empty() {
        return Ok(out);
    }
    let sf = design.criteria.safety_factor;
    for c in &failing {
        let (name, current) = match c.kind {
            CheckKind::BondShear => ("bond_strength", design.bond_strength),
            CheckKind::SubstrateYield => match design.yield_strength {
                Some(y) => ("yield_strength", y),
                None => continue,
            },
            CheckKind::MinThickness => continue,
        };
        out.push(Lever {
            name,
            relation: ">=",
            value: Some(c.value.value * sf),
            current,
            unit: "Pa",
            at: None,
        });
    }
    let set_pressure = |at: &mut Design, p| at.pressure = p;
    let passes = |s: &Spectrum, at: &Design| all_stress_checks_pass(s, at, settings, d);
    out.extend(load_levers(
        spectrum,
        design,
        design.pressure,
        set_pressure,
        passes,
    )?);
    Ok(out)
}

/// The pressure and low-octave-rms levers (a film's or a stack's `design`, at pressure `p0`):
/// the largest pressure, and the largest rms of the lowest octave, at which `passes(spectrum,
/// design)`; `set_pressure(design, p)` sets a design's pressure.
pub(crate) fn load_levers<D: Clone>(
    spectrum: &Spectrum,
    design: &D,
    p0: f64,
    set_pressure: impl Fn(&mut D, f64),
    passes: impl Fn(&Spectrum, &D) -> Result<bool, Error>,
) -> Result<[Lever; 2], Error> {
    let pressure = largest_passing(|f| {
        let mut at = design.clone();
        set_pressure(&mut at, p0 * f);
        passes(spectrum, &at)
    })?;
    let rms = low_octave_rms(spectrum)?;
    let k = largest_passing(|k| passes(&low_octave_scaled(spectrum, k)?, design))?;
    Ok([
        Lever {
            name: "pressure",
            relation: "<=",
            value: pressure.map(|f| p0 * f),
            current: p0,
            unit: "Pa",
            at: None,
        },
        Lever {
            name: "low_octave_rms",
            relation: "<=",
            value: k.map(|k| rms * k.sqrt()),
            current: rms,
            unit: "m",
            at: None,
        },
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn largest_passing_finds_a_monotone_threshold_and_stops_at_the_first_failure() {
        let t = largest_passing(|f| Ok(f <= 3e-3)).unwrap().unwrap();
        assert!(t <= 3e-3 && t > 3e-3 / (1.0 + 2.0 * REL_TOL), "{t}");
        assert_eq!(largest_passing(|_| Ok(true)).unwrap(), Some(1.0));
        assert_eq!(largest_passing(|_| Ok(false)).unwrap(), None);
        // Passing again above a failing band is not taken: the threshold stays below the band.
        let t = largest_passing(|f| Ok(!(1e-4..1e-2).contains(&f)))
            .unwrap()
            .unwrap();
        assert!(t < 1e-4, "{t}");
    }

    #[test]
    fn scaling_the_lowest_octave_scales_its_rms_and_keeps_the_rest() {
        let s = Spectrum::self_affine(0.8, 1e5, 1e8, None)
            .unwrap()
            .scaled_to_rms_slope(1.0)
            .unwrap();
        let rms = low_octave_rms(&s).unwrap();
        // Independent: h² of the octave from C(q) = C0 (q/q0)^{-2(1+H)}, 2π∫ q C dq in closed
        // form.
        let (q0, h) = (1e5f64, 0.8f64);
        let c0 = s.c(q0);
        let a = 2.0 * h;
        let exact = (2.0 * std::f64::consts::PI * c0 * q0 * q0 * (1.0 - 2f64.powf(-a)) / a).sqrt();
        assert!((rms / exact - 1.0).abs() < 1e-6, "{rms} vs {exact}");
        let scaled = low_octave_scaled(&s, 0.25).unwrap();
        let r2 = low_octave_rms(&scaled).unwrap();
        assert!((r2 / (0.5 * rms) - 1.0).abs() < 1e-6, "{r2}");
        assert!((scaled.c(1e7) / s.c(1e7) - 1.0).abs() < 1e-9);
    }
}
