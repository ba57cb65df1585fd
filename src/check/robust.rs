//! The design judged at the worst corner of its materials' ranges (`check --robust`; no
//! equation of its own: the checks of eqs. B8–B12 through [`Checker`] at each corner).
//!
//! The ranges are those of the library entries and the scene ([`crate::material::Ranges`]):
//! the film's and the substrate's E and ν, the substrate's yield strength and the bond's shear
//! strength. A strength enters a check only through its limit, strength / safety factor, so
//! each utilisation falls as its strength rises: the worst case takes every strength at its
//! minimum, and the thinnest d_min every strength at its maximum, with no evaluation of the
//! others. The elastic constants enter through the layered response (eq. 7) and the contact
//! area (eq. B11); the checks are evaluated at all 2^k corners of the k elastic constants whose
//! range has a width (at most 16), in parallel. That the worst case of each check lies at a
//! corner is tested on the library's ranges (the utilisation at the 3^k points of the box's
//! grid never exceeds the corners' largest; module tests), as the paper's Figs. 5–7 suggest:
//! a stiffer film or a more nearly incompressible one concentrates the stress at the
//! interface, a stiffer substrate does too, each monotonically.
//!
//! Each check is reported at its own worst corner (the smallest margin over the corners); the
//! robust verdict passes when every check passes there. The governing check is the one with the
//! smallest margin, and its corner the governing corner: a scene with that corner's values
//! written explicitly has the robust verdict as its nominal one. The d_min range is the least
//! and the largest d_min over the corners of the whole box.

use super::{CheckKind, CheckResult, Checker, Design};
use crate::error::Error;
use crate::layer::{Bilayer, Elastic};
use crate::material::{Bond, Material, Span};
use crate::prec::Settings;
use crate::psd::Spectrum;
use crate::scene::Scene;
use rayon::prelude::*;
use serde::Serialize;

/// A property that may have a range.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Param {
    FilmYoungsModulus,
    FilmPoissonRatio,
    SubstrateYoungsModulus,
    SubstratePoissonRatio,
    YieldStrength,
    BondShearStrength,
}

impl Param {
    /// Every property, elastic constants first.
    pub const ALL: [Param; 6] = [
        Param::FilmYoungsModulus,
        Param::FilmPoissonRatio,
        Param::SubstrateYoungsModulus,
        Param::SubstratePoissonRatio,
        Param::YieldStrength,
        Param::BondShearStrength,
    ];

    /// The scene key of the property.
    pub fn key(self) -> &'static str {
        match self {
            Param::FilmYoungsModulus => "film.youngs_modulus",
            Param::FilmPoissonRatio => "film.poisson_ratio",
            Param::SubstrateYoungsModulus => "substrate.youngs_modulus",
            Param::SubstratePoissonRatio => "substrate.poisson_ratio",
            Param::YieldStrength => "substrate.yield_strength",
            Param::BondShearStrength => "bond.shear_strength",
        }
    }

    /// `Pa`, or `1` for a ratio.
    pub fn unit(self) -> &'static str {
        match self {
            Param::FilmPoissonRatio | Param::SubstratePoissonRatio => "1",
            _ => "Pa",
        }
    }

    fn elastic(self) -> bool {
        !matches!(self, Param::YieldStrength | Param::BondShearStrength)
    }

    /// The property's value in `design`.
    pub fn value(self, design: &Design) -> Option<f64> {
        let (f, s) = (design.layers.film, design.layers.substrate);
        match self {
            Param::FilmYoungsModulus => Some(f.youngs),
            Param::FilmPoissonRatio => Some(f.poisson),
            Param::SubstrateYoungsModulus => Some(s.youngs),
            Param::SubstratePoissonRatio => Some(s.poisson),
            Param::YieldStrength => design.yield_strength,
            Param::BondShearStrength => Some(design.bond_strength),
        }
    }

    /// `design` with this property set to `v`.
    fn set(self, design: &mut Design, v: f64) -> Result<(), Error> {
        let (mut f, mut s) = (design.layers.film, design.layers.substrate);
        match self {
            Param::FilmYoungsModulus => f = Elastic::new(v, f.poisson)?,
            Param::FilmPoissonRatio => f = Elastic::new(f.youngs, v)?,
            Param::SubstrateYoungsModulus => s = Elastic::new(v, s.poisson)?,
            Param::SubstratePoissonRatio => s = Elastic::new(s.youngs, v)?,
            Param::YieldStrength => design.yield_strength = Some(v),
            Param::BondShearStrength => design.bond_strength = v,
        }
        design.layers = Bilayer::new(f, s);
        Ok(())
    }
}

/// The ranges of a film, a substrate and a bond that have a width, in [`Param::ALL`] order.
pub fn ranges(film: &Material, substrate: &Material, bond: &Bond) -> Vec<(Param, Span)> {
    let spans = [
        film.ranges.youngs_modulus,
        film.ranges.poisson_ratio,
        substrate.ranges.youngs_modulus,
        substrate.ranges.poisson_ratio,
        substrate.ranges.strength,
        bond.ranges.strength,
    ];
    Param::ALL
        .into_iter()
        .zip(spans)
        .filter_map(|(p, s)| s.filter(Span::is_wide).map(|s| (p, s)))
        .collect()
}

/// One check at its worst corner.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorstCheck {
    pub result: CheckResult,
    /// The corner, one value per range of [`Robust::ranges`] (SI).
    pub corner: Vec<f64>,
}

/// The d_min range over the corners (m); `None` at an end where no thickness passes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MinThicknessRange {
    pub min: Option<f64>,
    pub max: Option<f64>,
}

/// The design judged at the worst corner of its ranges.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Robust {
    /// The ranges with a width, each property once.
    pub ranges: Vec<(Param, Span)>,
    /// Each enabled check at its worst corner, in the nominal outcome's order.
    pub checks: Vec<WorstCheck>,
    pub pass: bool,
    /// The check with the smallest margin at its worst corner.
    pub governing: Option<CheckKind>,
    /// The governing check's corner, one value per range (SI).
    pub corner: Vec<f64>,
    /// The d_min range over the corners (when min-thickness runs).
    pub min_thickness: Option<MinThicknessRange>,
    /// The corners evaluated (2^k for k elastic ranges).
    pub corners: usize,
}

/// One corner's design: each elastic constant with a range at an end (bit i of `bits` set: the
/// maximum of the i-th), each strength at its minimum, or at its maximum with `strong`.
fn corner(
    nominal: &Design,
    ranges: &[(Param, Span)],
    bits: usize,
    strong: bool,
) -> Result<Design, Error> {
    let mut d = nominal.clone();
    let mut i = 0;
    for &(p, s) in ranges {
        let high = if p.elastic() {
            i += 1;
            bits & (1 << (i - 1)) != 0
        } else {
            strong
        };
        p.set(&mut d, if high { s.max } else { s.min })?;
    }
    Ok(d)
}

/// Judge a film scene at `thickness` at the worst corner of its materials' ranges.
pub fn judge_scene(scene: &Scene, thickness: f64) -> Result<Robust, Error> {
    let (spectrum, _) = scene.roughness.spectrum()?;
    let ranges = ranges(&scene.film, &scene.substrate, &scene.bond);
    judge_robust(
        &spectrum,
        &scene.design(),
        scene.settings,
        thickness,
        ranges,
    )
}

/// What one corner gives (a film's or a stack's, `C` its checks): its checks (strengths at
/// their minima) and its d_min with the strengths at their maxima (when they have ranges and
/// min-thickness runs).
pub(super) struct CornerRun<C> {
    pub(super) values: Vec<f64>,
    pub(super) checks: Vec<C>,
    pub(super) thinnest: Option<Option<f64>>,
}

/// Judge `nominal` at `thickness` on `spectrum` at the worst corner of `ranges` (module docs;
/// ranges of zero width are dropped).
pub fn judge_robust(
    spectrum: &Spectrum,
    nominal: &Design,
    settings: Settings,
    thickness: f64,
    mut ranges: Vec<(Param, Span)>,
) -> Result<Robust, Error> {
    // A range of zero width is the nominal value: no corner of its own.
    ranges.retain(|(_, s)| s.is_wide());
    let k = ranges.iter().filter(|(p, _)| p.elastic()).count();
    let strengths = ranges.iter().any(|(p, _)| !p.elastic());
    let min_on = nominal.criteria.checks.min_thickness;
    let runs = run_corners(
        k,
        strengths && min_on,
        |bits, strong| corner(nominal, &ranges, bits, strong),
        |d| {
            ranges
                .iter()
                .map(|(p, _)| p.value(d).unwrap_or(f64::NAN))
                .collect()
        },
        |d| Ok(Checker::new(spectrum, d, settings)?.run(thickness)?.checks),
        |d| {
            Ok(Checker::new(spectrum, d, settings)?
                .min_thickness()?
                .thickness
                .map(|e| e.value))
        },
    )?;
    Ok(worst_of(ranges, &runs))
}

/// Every corner run in parallel (a film's or a stack's; `2^k` for `k` varied elastic
/// ranges): `corner(bits, strong)` is its design (strengths at their maxima with `strong`),
/// `values` the ranges' values in its weak design, `checks` the weak design's checks and, when
/// `strong_d_min`, `d_min` the strong design's d_min.
pub(super) fn run_corners<D, C: Send>(
    k: usize,
    strong_d_min: bool,
    corner: impl Fn(usize, bool) -> Result<D, Error> + Sync,
    values: impl Fn(&D) -> Vec<f64> + Sync,
    checks: impl Fn(D) -> Result<Vec<C>, Error> + Sync,
    d_min: impl Fn(D) -> Result<Option<f64>, Error> + Sync,
) -> Result<Vec<CornerRun<C>>, Error> {
    (0..1usize << k)
        .into_par_iter()
        .map(|bits| {
            let weak = corner(bits, false)?;
            let values = values(&weak);
            let checks = checks(weak)?;
            let thinnest = if strong_d_min {
                Some(d_min(corner(bits, true)?)?)
            } else {
                None
            };
            Ok(CornerRun {
                values,
                checks,
                thinnest,
            })
        })
        .collect()
}

/// The smaller margin first (`None`, no limit, is the worst).
pub(super) fn margin_key(c: &CheckResult) -> f64 {
    c.margin.unwrap_or(f64::NEG_INFINITY)
}

/// The d_min range over the corners (a film's or a stack's), `min_check` finding a corner's
/// min-thickness check among its checks.
pub(super) fn min_thickness_range<C>(
    runs: &[CornerRun<C>],
    min_check: impl Fn(&C) -> Option<&CheckResult>,
) -> MinThicknessRange {
    let at = |r: &CornerRun<C>| r.checks.iter().find_map(&min_check).and_then(|c| c.limit);
    // d_min with the strengths at their minima: the largest over the corners, or none if
    // no thickness passes at one of them.
    let weak: Option<Vec<f64>> = runs.iter().map(at).collect();
    let strong = runs.iter().map(|r| r.thinnest.unwrap_or_else(|| at(r)));
    MinThicknessRange {
        min: strong.flatten().reduce(f64::min),
        max: weak.and_then(|v| v.into_iter().reduce(f64::max)),
    }
}

/// Each check's worst corner, the verdict, the governing corner and the d_min range.
fn worst_of(ranges: Vec<(Param, Span)>, runs: &[CornerRun<CheckResult>]) -> Robust {
    let kinds: Vec<CheckKind> = runs[0].checks.iter().map(|c| c.kind).collect();
    let checks: Vec<WorstCheck> = kinds
        .iter()
        .map(|&kind| {
            runs.iter()
                .filter_map(|r| {
                    let c = r.checks.iter().find(|c| c.kind == kind)?;
                    Some(WorstCheck {
                        result: c.clone(),
                        corner: r.values.clone(),
                    })
                })
                .min_by(|a, b| margin_key(&a.result).total_cmp(&margin_key(&b.result)))
                .expect("every corner runs the same checks")
        })
        .collect();
    let worst = checks
        .iter()
        .min_by(|a, b| margin_key(&a.result).total_cmp(&margin_key(&b.result)));
    let min_thickness = kinds.contains(&CheckKind::MinThickness).then(|| {
        min_thickness_range(runs, |c| {
            Some(c).filter(|c| c.kind == CheckKind::MinThickness)
        })
    });
    Robust {
        pass: checks.iter().all(|c| c.result.pass),
        governing: worst.map(|w| w.result.kind),
        corner: worst.map(|w| w.corner.clone()).unwrap_or_default(),
        checks,
        min_thickness,
        corners: runs.len(),
        ranges,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::Criteria;
    use crate::material::Library;

    /// A turned flange face (the NBR gasket example's roughness).
    fn flange() -> Spectrum {
        Spectrum::self_affine(0.8, 1e4, 1e7, Some(5e4))
            .unwrap()
            .scaled_to_rms_slope(0.3)
            .unwrap()
    }

    /// The library's NBR on carbon steel with a chemlok-type bond, its ranges, and the design.
    /// The nominal check of `design` at thickness `d`.
    fn nominal(spectrum: &Spectrum, design: &Design, d: f64) -> crate::check::Outcome {
        Checker::new(spectrum, design.clone(), Settings::default())
            .unwrap()
            .run(d)
            .unwrap()
    }

    fn nbr_on_steel() -> (Design, Vec<(Param, Span)>) {
        let lib = Library::builtin().unwrap();
        let (film, substrate, bond) = (
            lib.material("nbr").unwrap(),
            lib.material("carbon-steel").unwrap(),
            lib.bond("chemlok-type").unwrap(),
        );
        let design = Design {
            layers: Bilayer::new(film.elastic, substrate.elastic),
            pressure: 2e6,
            yield_strength: substrate.yield_strength,
            bond_strength: bond.shear_strength,
            friction: 0.0,
            criteria: Criteria::default(),
        };
        (design, ranges(film, substrate, bond))
    }

    /// Each stress check's utilisation (value/limit) at `d`.
    fn utilisations(spectrum: &Spectrum, design: &Design, d: f64) -> Vec<(CheckKind, f64)> {
        let ev = Checker::new(spectrum, design.clone(), Settings::default())
            .unwrap()
            .evaluate(d)
            .unwrap();
        ev.checks
            .iter()
            .map(|c| (c.kind, c.value.value / c.limit.unwrap()))
            .collect()
    }

    /// The utilisation of each stress check on the 3^k grid of the elastic ranges (ends and
    /// midpoints) never exceeds its largest value at the corners: the worst case is a corner.
    fn worst_is_a_corner(spectrum: &Spectrum, design: &Design, ranges: &[(Param, Span)]) {
        let elastic: Vec<(Param, Span)> = ranges
            .iter()
            .copied()
            .filter(|(p, _)| p.elastic())
            .collect();
        let k = elastic.len();
        assert!(k >= 2, "{ranges:?}");
        for d in [3e-6, 25e-6, 300e-6] {
            let (mut corners, mut inside) = (vec![0.0f64; 2], vec![0.0f64; 2]);
            for mut n in 0..3usize.pow(k as u32) {
                let mut x = design.clone();
                let mut corner = true;
                for (p, s) in &elastic {
                    let t = n % 3;
                    n /= 3;
                    corner &= t != 1;
                    p.set(&mut x, s.min + (s.max - s.min) * t as f64 / 2.0)
                        .unwrap();
                }
                for (i, (_, u)) in utilisations(spectrum, &x, d).into_iter().enumerate() {
                    let slot = if corner {
                        &mut corners[i]
                    } else {
                        &mut inside[i]
                    };
                    *slot = slot.max(u);
                }
            }
            for i in 0..2 {
                assert!(
                    inside[i] <= corners[i] * (1.0 + 1e-9),
                    "d = {d}: check {i}: inside {} > corners {}",
                    inside[i],
                    corners[i]
                );
            }
        }
    }

    #[test]
    fn the_worst_case_of_each_check_is_at_a_corner() {
        let (design, ranges) = nbr_on_steel();
        worst_is_a_corner(&flange(), &design, &ranges);
        // A rubber near incompressibility on a compliant metal, where ν matters most (the
        // paper's Fig. 5), with wide ranges.
        let spectrum = Spectrum::self_affine(1.0, 1e5, 1e8, None)
            .unwrap()
            .scaled_to_rms_slope(1.0)
            .unwrap();
        let design = Design {
            layers: Bilayer::new(
                Elastic::new(1e6, 0.49).unwrap(),
                Elastic::new(7e10, 0.3).unwrap(),
            ),
            pressure: 1e5,
            ..design
        };
        let ranges = [
            (
                Param::FilmYoungsModulus,
                Span {
                    min: 0.5e6,
                    max: 2e6,
                },
            ),
            (
                Param::FilmPoissonRatio,
                Span {
                    min: 0.45,
                    max: 0.5,
                },
            ),
            (
                Param::SubstrateYoungsModulus,
                Span {
                    min: 5e10,
                    max: 2e11,
                },
            ),
            (
                Param::SubstratePoissonRatio,
                Span {
                    min: 0.25,
                    max: 0.35,
                },
            ),
        ];
        worst_is_a_corner(&spectrum, &design, &ranges);
    }

    #[test]
    fn ranges_of_zero_width_give_the_nominal_answer() {
        let (design, _) = nbr_on_steel();
        let spectrum = flange();
        let d = 25e-6;
        let nominal = nominal(&spectrum, &design, d);
        let points: Vec<(Param, Span)> = Param::ALL
            .into_iter()
            .map(|p| (p, Span::point(p.value(&design).unwrap())))
            .collect();
        for given in [Vec::new(), points] {
            let r = judge_robust(&spectrum, &design, Settings::default(), d, given).unwrap();
            let checks: Vec<CheckResult> = r.checks.iter().map(|c| c.result.clone()).collect();
            assert_eq!(checks, nominal.checks);
            assert_eq!((r.pass, r.governing), (nominal.pass, nominal.governing));
            let dm = nominal
                .min_thickness
                .as_ref()
                .unwrap()
                .thickness
                .unwrap()
                .value;
            let m = r.min_thickness.unwrap();
            assert_eq!((m.min, m.max), (Some(dm), Some(dm)));
        }
    }

    #[test]
    fn the_worst_corner_is_no_better_than_nominal_and_d_min_is_bracketed() {
        let (design, ranges) = nbr_on_steel();
        let spectrum = flange();
        let d = 25e-6;
        let nominal = nominal(&spectrum, &design, d);
        let r = judge_robust(&spectrum, &design, Settings::default(), d, ranges.clone()).unwrap();
        assert_eq!(r.corners, 16);
        assert_eq!(r.ranges, ranges);
        for (w, n) in r.checks.iter().zip(&nominal.checks) {
            assert_eq!(w.result.kind, n.kind);
            assert!(w.result.margin.unwrap() < n.margin.unwrap(), "{w:?} {n:?}");
        }
        let dm = nominal
            .min_thickness
            .as_ref()
            .unwrap()
            .thickness
            .unwrap()
            .value;
        let m = r.min_thickness.unwrap();
        assert!(m.min.unwrap() < dm && dm < m.max.unwrap(), "{m:?} {dm}");
        // The largest d_min is the worst corner's min-thickness limit.
        let worst = r
            .checks
            .iter()
            .find(|c| c.result.kind == CheckKind::MinThickness)
            .unwrap();
        assert_eq!(worst.result.limit, m.max);
    }

    #[test]
    fn a_strength_range_acts_through_its_limit_only() {
        let (design, _) = nbr_on_steel();
        let spectrum = flange();
        let d = 25e-6;
        let span = Span { min: 4e6, max: 9e6 };
        let ranges = vec![(Param::BondShearStrength, span)];
        let r = judge_robust(&spectrum, &design, Settings::default(), d, ranges).unwrap();
        assert_eq!(r.corners, 1);
        assert_eq!(r.corner, vec![4e6]);
        let at = |strength: f64| {
            let x = Design {
                bond_strength: strength,
                ..design.clone()
            };
            Checker::new(&spectrum, x, Settings::default()).unwrap()
        };
        let nominal = at(design.bond_strength).run(d).unwrap();
        let bond = |checks: &[CheckResult]| {
            checks
                .iter()
                .find(|c| c.kind == CheckKind::BondShear)
                .cloned()
                .unwrap()
        };
        let worst: Vec<CheckResult> = r.checks.iter().map(|c| c.result.clone()).collect();
        let (w, n) = (bond(&worst), bond(&nominal.checks));
        // The same peak shear against the weakest bond.
        assert_eq!(w.value, n.value);
        assert_eq!(w.limit, Some(4e6));
        let m = r.min_thickness.unwrap();
        let thinnest = at(9e6).min_thickness().unwrap().thickness.map(|e| e.value);
        let thickest = at(4e6).min_thickness().unwrap().thickness.map(|e| e.value);
        assert_eq!((m.min, m.max), (thinnest, thickest));
    }
}
