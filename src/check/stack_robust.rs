//! A layer stack judged at the worst corner of its materials' ranges (`check --robust` on a
//! `[[layer]]` scene; no equation of its own: the checks of [`super::stack`] at each corner), as
//! [`super::robust`] judges a film.
//!
//! The ranges are those of the library entries and the scene: every layer's E and ν and the
//! shear strength of its bond to what lies below, the substrate's E, ν and yield strength. A
//! strength enters a check only through its limit, so the worst case takes every strength at its
//! minimum and the thinnest d_min every strength at its maximum, as for a film. The elastic
//! constants are evaluated at the 2^k corners of the k whose range has a width, in parallel,
//! when k ≤ [`MAX_VARIED`] (64 corners; a film has at most 4, a two-layer stack 6). A deeper
//! stack has more: its elastic ranges are then screened one at a time (each at its two ends with
//! the others nominal, the stress checks at the design's thicknesses), the [`MAX_VARIED`] with
//! the largest change of any check's utilisation are varied over their corners, and every other
//! is held at the end of its range where the screening found the larger utilisation (reported
//! as held; the corners then cover a face of the box, not the whole box).
//!
//! Each check (a check at one interface) is reported at its own worst corner (the smallest
//! margin over the corners); the robust verdict passes when every check passes there. The
//! governing check is the one with the smallest margin, and its corner the governing corner: a
//! scene with that corner's values written explicitly has the robust verdict as its nominal one.
//! The d_min range is the least and the largest d_min of the layer `thickness_of` over the
//! corners.

use super::CheckKind;
use super::robust::{CornerRun, MinThicknessRange, margin_key, min_thickness_range, run_corners};
use super::stack::{StackCheck, StackChecker, StackDesign};
use crate::error::Error;
use crate::layer::Elastic;
use crate::material::Span;
use crate::prec::Settings;
use crate::psd::Spectrum;
use crate::scene::Scene;
use rayon::prelude::*;
use serde::Serialize;

/// The most elastic ranges varied over their corners (2^6 = 64 corners).
pub const MAX_VARIED: usize = 6;

/// A property of a stack that may have a range: a layer's (index from 0, the top) or the
/// substrate's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StackParam {
    YoungsModulus(usize),
    PoissonRatio(usize),
    SubstrateYoungsModulus,
    SubstratePoissonRatio,
    YieldStrength,
    /// The shear strength of the layer's bond to what lies below.
    BondStrength(usize),
}

impl StackParam {
    /// The scene key of the property (`layer[1].youngs_modulus`, layers counted from 1, the
    /// top; `layer[k].bond` for a bond's shear strength).
    pub fn key(self) -> String {
        match self {
            StackParam::YoungsModulus(k) => format!("layer[{}].youngs_modulus", k + 1),
            StackParam::PoissonRatio(k) => format!("layer[{}].poisson_ratio", k + 1),
            StackParam::BondStrength(k) => format!("layer[{}].bond", k + 1),
            StackParam::SubstrateYoungsModulus => "substrate.youngs_modulus".into(),
            StackParam::SubstratePoissonRatio => "substrate.poisson_ratio".into(),
            StackParam::YieldStrength => "substrate.yield_strength".into(),
        }
    }

    /// `Pa`, or `1` for a ratio.
    pub fn unit(self) -> &'static str {
        match self {
            StackParam::PoissonRatio(_) | StackParam::SubstratePoissonRatio => "1",
            _ => "Pa",
        }
    }

    /// Whether the property is a Poisson ratio.
    pub fn is_ratio(self) -> bool {
        self.unit() == "1"
    }

    /// Whether the property is an elastic constant (not a strength).
    pub fn elastic(self) -> bool {
        !matches!(
            self,
            StackParam::YieldStrength | StackParam::BondStrength(_)
        )
    }

    /// The property's value in `design`.
    pub fn value(self, design: &StackDesign) -> Option<f64> {
        let s = design.substrate;
        match self {
            StackParam::YoungsModulus(k) => Some(design.layers[k].material.youngs),
            StackParam::PoissonRatio(k) => Some(design.layers[k].material.poisson),
            StackParam::BondStrength(k) => Some(design.layers[k].bond_strength),
            StackParam::SubstrateYoungsModulus => Some(s.youngs),
            StackParam::SubstratePoissonRatio => Some(s.poisson),
            StackParam::YieldStrength => design.yield_strength,
        }
    }

    /// `design` with this property set to `v`.
    pub fn set(self, design: &mut StackDesign, v: f64) -> Result<(), Error> {
        let s = design.substrate;
        match self {
            StackParam::YoungsModulus(k) => {
                let m = &mut design.layers[k].material;
                *m = Elastic::new(v, m.poisson)?;
            }
            StackParam::PoissonRatio(k) => {
                let m = &mut design.layers[k].material;
                *m = Elastic::new(m.youngs, v)?;
            }
            StackParam::BondStrength(k) => design.layers[k].bond_strength = v,
            StackParam::SubstrateYoungsModulus => design.substrate = Elastic::new(v, s.poisson)?,
            StackParam::SubstratePoissonRatio => design.substrate = Elastic::new(s.youngs, v)?,
            StackParam::YieldStrength => design.yield_strength = Some(v),
        }
        Ok(())
    }
}

/// The ranges of a stack scene's layers, bonds and substrate that have a width: every layer's
/// E and ν (top first), the substrate's E, ν and yield strength, then every layer's bond (a
/// one-layer stack's order is the film's of [`super::robust::Param::ALL`]).
pub fn ranges(scene: &Scene) -> Vec<(StackParam, Span)> {
    let mut out = Vec::new();
    for (k, l) in scene.layers.iter().enumerate() {
        out.push((
            StackParam::YoungsModulus(k),
            l.material.ranges.youngs_modulus,
        ));
        out.push((StackParam::PoissonRatio(k), l.material.ranges.poisson_ratio));
    }
    let sub = &scene.substrate.ranges;
    out.push((StackParam::SubstrateYoungsModulus, sub.youngs_modulus));
    out.push((StackParam::SubstratePoissonRatio, sub.poisson_ratio));
    out.push((StackParam::YieldStrength, sub.strength));
    for (k, l) in scene.layers.iter().enumerate() {
        out.push((StackParam::BondStrength(k), l.bond.ranges.strength));
    }
    out.into_iter()
        .filter_map(|(p, s)| s.filter(Span::is_wide).map(|s| (p, s)))
        .collect()
}

/// One check (at one interface) at its worst corner.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StackWorstCheck {
    pub check: StackCheck,
    /// The corner, one value per range of [`StackRobust::ranges`] (SI).
    pub corner: Vec<f64>,
}

/// A stack design judged at the worst corner of its ranges.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StackRobust {
    /// The ranges with a width, each property once.
    pub ranges: Vec<(StackParam, Span)>,
    /// Each enabled check at its worst corner, in the nominal outcome's order.
    pub checks: Vec<StackWorstCheck>,
    pub pass: bool,
    /// The check with the smallest margin at its worst corner, and where it applies.
    pub governing: Option<(CheckKind, String)>,
    /// The governing check's corner, one value per range (SI).
    pub corner: Vec<f64>,
    /// The d_min range of the layer `thickness_of` over the corners (when min-thickness runs).
    pub min_thickness: Option<MinThicknessRange>,
    /// The corners evaluated.
    pub corners: usize,
    /// The elastic ranges held at one end instead of varied, by index into `ranges` with the
    /// value held (more than [`MAX_VARIED`] elastic ranges; module docs).
    pub held: Vec<(usize, f64)>,
}

/// One corner's design: the varied elastic constants at an end (bit i of `bits` set: the
/// maximum of the i-th varied), the held ones at their held value, each strength at its
/// minimum, or at its maximum with `strong`.
fn corner(
    nominal: &StackDesign,
    ranges: &[(StackParam, Span)],
    held: &[(usize, f64)],
    bits: usize,
    strong: bool,
) -> Result<StackDesign, Error> {
    let mut d = nominal.clone();
    let mut i = 0;
    for (r, &(p, s)) in ranges.iter().enumerate() {
        let v = if let Some(&(_, v)) = held.iter().find(|(h, _)| *h == r) {
            v
        } else if p.elastic() {
            i += 1;
            if bits & (1 << (i - 1)) != 0 {
                s.max
            } else {
                s.min
            }
        } else if strong {
            s.max
        } else {
            s.min
        };
        p.set(&mut d, v)?;
    }
    Ok(d)
}

/// Judge a stack scene at its thicknesses at the worst corner of its materials' ranges.
pub fn judge_scene(scene: &Scene) -> Result<StackRobust, Error> {
    let (spectrum, _) = scene.roughness.spectrum()?;
    judge_robust(
        &spectrum,
        &scene.stack_design(),
        scene.settings,
        ranges(scene),
    )
}

/// The largest utilisation (value/limit) over the stress checks of `design` at its thicknesses.
fn largest_utilisation(
    spectrum: &Spectrum,
    design: &StackDesign,
    settings: Settings,
) -> Result<f64, Error> {
    let checker = StackChecker::new(spectrum, design.clone(), settings)?;
    let row = checker.evaluate(design.layers[design.thickness_of].thickness)?;
    Ok(row
        .checks
        .iter()
        .filter_map(|c| c.result.limit.map(|l| c.result.value.value / l))
        .fold(0.0, f64::max))
}

/// The elastic ranges held at one end when more than [`MAX_VARIED`] have a width (module
/// docs): each screened at its two ends, the least influential held where the utilisation was
/// larger.
fn screen(
    spectrum: &Spectrum,
    nominal: &StackDesign,
    settings: Settings,
    ranges: &[(StackParam, Span)],
) -> Result<Vec<(usize, f64)>, Error> {
    let elastic: Vec<usize> = (0..ranges.len())
        .filter(|&i| ranges[i].0.elastic())
        .collect();
    if elastic.len() <= MAX_VARIED {
        return Ok(Vec::new());
    }
    let mut ends = elastic
        .par_iter()
        .map(|&i| {
            let (p, s) = ranges[i];
            let at = |v: f64| -> Result<f64, Error> {
                let mut d = nominal.clone();
                p.set(&mut d, v)?;
                largest_utilisation(spectrum, &d, settings)
            };
            let (lo, hi) = (at(s.min)?, at(s.max)?);
            let worse = if hi > lo { s.max } else { s.min };
            Ok((i, (hi - lo).abs(), worse))
        })
        .collect::<Result<Vec<_>, Error>>()?;
    // The most influential first; ties keep the ranges' order.
    ends.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    let mut held: Vec<(usize, f64)> = ends[MAX_VARIED..].iter().map(|&(i, _, v)| (i, v)).collect();
    held.sort_by_key(|&(i, _)| i);
    Ok(held)
}

/// Judge `nominal` at its thicknesses on `spectrum` at the worst corner of `ranges` (module
/// docs; ranges of zero width are dropped).
pub fn judge_robust(
    spectrum: &Spectrum,
    nominal: &StackDesign,
    settings: Settings,
    mut ranges: Vec<(StackParam, Span)>,
) -> Result<StackRobust, Error> {
    // A range of zero width is the nominal value: no corner of its own.
    ranges.retain(|(_, s)| s.is_wide());
    let held = screen(spectrum, nominal, settings, &ranges)?;
    let k = ranges.iter().filter(|(p, _)| p.elastic()).count() - held.len();
    let strengths = ranges.iter().any(|(p, _)| !p.elastic());
    let min_on = nominal.criteria.checks.min_thickness;
    let runs = run_corners(
        k,
        strengths && min_on,
        |bits, strong| corner(nominal, &ranges, &held, bits, strong),
        |d| {
            ranges
                .iter()
                .map(|(p, _)| p.value(d).unwrap_or(f64::NAN))
                .collect()
        },
        |d| Ok(StackChecker::new(spectrum, d, settings)?.run()?.checks),
        |d| {
            let m = StackChecker::new(spectrum, d, settings)?.min_thickness()?;
            Ok(m.thickness.map(|e| e.value))
        },
    )?;
    Ok(worst_of(ranges, held, &runs))
}

/// Each check's worst corner, the verdict, the governing corner and the d_min range.
fn worst_of(
    ranges: Vec<(StackParam, Span)>,
    held: Vec<(usize, f64)>,
    runs: &[CornerRun<StackCheck>],
) -> StackRobust {
    let same = |a: &StackCheck, b: &StackCheck| a.result.kind == b.result.kind && a.at == b.at;
    let checks: Vec<StackWorstCheck> = runs[0]
        .checks
        .iter()
        .map(|nominal| {
            runs.iter()
                .filter_map(|r| {
                    let c = r.checks.iter().find(|c| same(c, nominal))?;
                    Some(StackWorstCheck {
                        check: c.clone(),
                        corner: r.values.clone(),
                    })
                })
                .min_by(|a, b| margin_key(&a.check.result).total_cmp(&margin_key(&b.check.result)))
                .expect("every corner runs the same checks")
        })
        .collect();
    let worst = checks
        .iter()
        .min_by(|a, b| margin_key(&a.check.result).total_cmp(&margin_key(&b.check.result)));
    let min_on = checks
        .iter()
        .any(|c| c.check.result.kind == CheckKind::MinThickness);
    let min_thickness = min_on.then(|| {
        min_thickness_range(runs, |c| {
            Some(&c.result).filter(|r| r.kind == CheckKind::MinThickness)
        })
    });
    StackRobust {
        pass: checks.iter().all(|c| c.check.result.pass),
        governing: worst.map(|w| (w.check.result.kind, w.check.at.clone())),
        corner: worst.map(|w| w.corner.clone()).unwrap_or_default(),
        checks,
        min_thickness,
        corners: runs.len(),
        ranges,
        held,
    }
}
