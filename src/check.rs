//! The design checks of `coatcheck check` (definitions: notes.md, "Distributions and peak
//! values" and "Minimum thickness"; paper App. B, eqs. B8–B12, Figs. 6–7).
//!
//! - `bond-shear`: the interface shear is Gaussian with rms τ_rms (eq. B9); its peak at exceedance
//!   ε solves erfc(τ_peak/(√2 τ_rms)) = ε. It must not exceed τ_bond / safety factor. Also
//!   reported: P(|τ| > τ_bond), the fraction of the interface where the bond strength is exceeded.
//! - `substrate-yield`: the mean pressure in real contact p0·A0/A (A/A0 = P(q1), eq. B11) and the
//!   ε-peak of the interface normal stress (Persson's form centred at p0 with the interface width
//!   σ_rms(d), eq. B8) must not exceed σ_yield / safety factor; the larger governs.
//! - `min-thickness`: the smallest d_min such that the checks above pass at every d ≥ d_min. The
//!   given thickness passes it when d ≥ d_min.
//!
//! A check's margin is the unused fraction of its limit: 1 − value/limit for an upper limit
//! (stresses), 1 − d_min/d for the thickness; a check passes when its margin is ≥ 0.
//!
//! ## Minimum thickness: why scan, then refine
//! τ_rms(d) is not monotone: it rises as the film thins and falls to 0 as d → 0 (a vanishing film
//! has a frictionless top), so pass/fail in d can change more than once and a bisection on the
//! whole range can land inside a failing band. [`Checker::min_thickness`] therefore
//! 1. starts at q_L·d = [`SCAN_START_QD`] = 10 (q_L the spectrum's lowest wavenumber). Every
//!    mode of a thicker film has qd ≥ 10, where |f| and |g| only decrease with qd (|g| peaks at
//!    qd ≤ 2.1) and |S⁻² − 1| ≤ 1.8e-6 (test `thick_films_only_relax_beyond_the_scan_start`):
//!    the interface stresses fall as d grows and A/A0 moves by a few 1e-6 at most, so when
//!    u ≤ 1 − [`THICK_SLACK`] there, every thicker film passes. Otherwise the bulk bound
//!    d_hi = 50/q_L is evaluated too: f, g decay like (1 + qd)e^{−qd}, at most twice that on a
//!    stiff substrate, so at q_L·d = 50 the interface stresses are below 1e-19 of the surface
//!    ones and S(qd) = 1 to rounding: every thicker film behaves the same. If d_hi fails, no
//!    thickness passes;
//! 2. steps down in ln d and stops at the first failing thickness (the largest failing sample).
//!    Only the upper end of the failing region matters for d_min, so nothing thinner is
//!    evaluated. The base step is 1/[`POINTS_PER_DECADE`] of a decade; it is widened, to at
//!    most 0.75 decade while the utilisation u (value/limit) stays below 0.15 over the step, or
//!    0.5 decade below 0.3 ([`WIDE_STEPS`]), with u extrapolated log-linearly from the last two
//!    samples at a growth rate of ln u per unit of ln d of at least [`MIN_GROWTH`] (aimed at
//!    [`WIDE_AIM`] of the threshold). A widened step that lands above its threshold is redone
//!    with base steps (its sample is reused).
//!    A thick film's utilisation is flat (its interface stresses are exponentially small) and
//!    these steps cross it in a few evaluations instead of eight per decade. Why a failing band
//!    cannot hide inside a widened step whose ends are below its threshold: with P and S frozen,
//!    τ_rms² = Σ_q w_q g²(qd) with w_q ≥ 0, and |g| is unimodal in ln(qd), above a quarter of
//!    its maximum on a stretch at least 1.90 wide and above half of it on one at least 1.32
//!    wide (the narrowest pair: a ν = 0 film on a rigid substrate; test
//!    `wide_steps_are_narrower_than_the_shear_kernel`), more than the steps (1.73 and 1.15 in
//!    ln d). Any such superlevel set through a point d* is at least as wide, so for every mode
//!    one end of a step around d* sees |g| ≥ c·|g(q d*)| (c = 1/4, 1/2), and the larger end
//!    utilisation is at least c·u(d*)/√2 (0.177, 0.354): a failing point (u > 1) inside would
//!    put an end above the threshold (0.15, 0.3); test `few_mode_shear_bands_match_a_dense_scan`
//!    checks this on random spectra. The substrate-yield values go through |f|, monotone in qd,
//!    and through S (in P and G), which has at most one turn in qd (test
//!    `s_turns_at_most_once_and_f_never_rises`: 88 pairs from E0/E1 = 1e-8 to 1e8, ν 0 to 0.5;
//!    22 of them turn once, none twice);
//! 3. guards against a failing band narrower than the step: at every sampled local maximum of
//!    u above [`PEAK_GUARD`] it maximises u between the neighbouring samples by successive
//!    parabolic interpolation (golden-section steps where the parabola does not help) and treats
//!    the first failing point as a failing sample. It stops, after at least one evaluation, when
//!    the parabola through the best three points promises less than [`GUARD_RESOLVED`] of the
//!    remaining headroom 1 − u (a smooth maximum below 1 costs one or two evaluations);
//! 4. refines the pass/fail crossing in ln d until the bracket's relative width is at most
//!    [`D_MIN_RTOL`], by the ITP method (Oliveira & Takahashi 2020: a projection onto a shrinking
//!    interval around the midpoint; never more steps than bisection plus one) with inverse
//!    quadratic interpolation on ln u as its estimate (the scan sample above the bracket is its
//!    third point from the start). An estimate within δ of a bracket end is moved to 4δ from
//!    it, so that it lands across the crossing and closes the bracket: a smooth utilisation
//!    needs two or three steps. d_min is the bracket's geometric midpoint; its error is the
//!    distance to the bracket's upper end plus the shift of the crossing by the utilisation's
//!    own relative error, δu/|d ln u/d ln d|;
//! 5. stops at the floor d_lo = max(1 nm, min(1e-6/q_L, 1e-4/q_hi)): a film thinner than 1 nm
//!    is not a continuum, and when the floor is above 1 nm every mode of the spectrum has
//!    q·d ≤ 1e-4 there, the thin-film limit in which the interface stresses only fall further
//!    as d → 0 (τ ∝ g → q·d). When every sample down to d_lo passes, d_min is reported as d_lo
//!    with `all_pass_to_floor` set (and a warning naming the floor).
//!
//! Each evaluation during the search requests only what the enabled checks need (bond-shear:
//! τ_rms; substrate-yield: A/A0 and σ_rms at the interface), reusing one [`Engine`] per spectrum.
//!
//! ## Validity
//! The outcome carries a warning, with the number that triggered it, where the theory is
//! strained: a low-octave share of G(q1) above [`LOW_OCTAVE_WARN`] (few long waves carry the
//! contact: Persson under-estimates the area, so its contact-pressure figures are conservative),
//! A/A0 above [`FULL_CONTACT_WARN`], and an rms slope above [`SLOPE_WARN`].

use crate::contact::{self, Contact, Engine, NormalStress, Request};
use crate::error::Error;
use crate::layer::{Bilayer, Stack};
use crate::prec::{Estimate, Settings, Termination};
use crate::psd::Spectrum;
use rayon::prelude::*;
use serde::Serialize;

/// Scan density of the minimum-thickness search (points per decade of d).
pub const POINTS_PER_DECADE: f64 = 8.0;
/// Relative width of the final d_min bracket (0.2 %: d_min to ±0.1 %).
pub const D_MIN_RTOL: f64 = 2e-3;
/// The bulk bound: q_L·d at which the film is effectively infinitely thick.
pub const BULK_QD: f64 = 50.0;
/// q_L·d where the scan starts: thicker films only relax (module docs, step 1).
pub const SCAN_START_QD: f64 = 10.0;
/// How much the utilisation may grow beyond the scan start, relative (module docs, step 1).
pub const THICK_SLACK: f64 = 1e-5;
/// Sampled local maxima of the utilisation above this are refined (narrow failing bands).
pub const PEAK_GUARD: f64 = 0.5;
/// A widened scan step: taken while the utilisation stays below `below` over it, at most
/// `decades` long; `level` is the fraction of |g|'s maximum whose superlevel set in ln(qd) is
/// wider than the step (module docs, step 2), and `below` < level/√2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WideStep {
    pub below: f64,
    pub decades: f64,
    pub level: f64,
}

/// The widened scan steps (module docs, step 2).
pub const WIDE_STEPS: [WideStep; 2] = [
    WideStep {
        below: 0.15,
        decades: 0.75,
        level: 0.25,
    },
    WideStep {
        below: 0.3,
        decades: 0.5,
        level: 0.5,
    },
];
/// A widened step aims its extrapolated utilisation at this fraction of its threshold.
pub const WIDE_AIM: f64 = 0.7;
/// The growth rate of ln u per unit of ln d (thinner) assumed at least when widening a step.
pub const MIN_GROWTH: f64 = 1.0;
/// The narrow-band guard stops when the parabola through its best three points promises less
/// than this fraction of the headroom 1 − u to failure.
pub const GUARD_RESOLVED: f64 = 0.1;
/// The most evaluations the narrow-band guard spends at one sampled maximum.
pub const GUARD_MAX_STEPS: usize = 16;
/// Share of G(q1) from the lowest octave above which the result is flagged (README, "Checking
/// the theory on the measured surface": above 0.5 the bundled map's exact contact area is 2.7x
/// Persson's or more; at a share of 0.42 they agree within the grid error).
pub const LOW_OCTAVE_WARN: f64 = 0.5;
/// A/A0 above which the contact is called nearly full.
pub const FULL_CONTACT_WARN: f64 = 0.9;
/// Rms slope above which small-slope linear elasticity is strained (the paper uses ξ = 1).
pub const SLOPE_WARN: f64 = 1.0 + 1e-6;

/// The thinnest film considered (m).
pub const THINNEST: f64 = 1e-9;

/// The checks that can be enabled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum CheckKind {
    BondShear,
    SubstrateYield,
    MinThickness,
}

impl CheckKind {
    pub const ALL: [CheckKind; 3] = [
        CheckKind::BondShear,
        CheckKind::SubstrateYield,
        CheckKind::MinThickness,
    ];

    pub fn name(self) -> &'static str {
        match self {
            CheckKind::BondShear => "bond-shear",
            CheckKind::SubstrateYield => "substrate-yield",
            CheckKind::MinThickness => "min-thickness",
        }
    }

    pub fn from_name(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|c| c.name() == s.trim())
    }
}

/// Which checks run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Checks {
    pub bond_shear: bool,
    pub substrate_yield: bool,
    pub min_thickness: bool,
}

impl Checks {
    pub fn all() -> Self {
        Self {
            bond_shear: true,
            substrate_yield: true,
            min_thickness: true,
        }
    }

    pub fn none() -> Self {
        Self {
            bond_shear: false,
            substrate_yield: false,
            min_thickness: false,
        }
    }

    pub fn enable(&mut self, c: CheckKind) {
        match c {
            CheckKind::BondShear => self.bond_shear = true,
            CheckKind::SubstrateYield => self.substrate_yield = true,
            CheckKind::MinThickness => self.min_thickness = true,
        }
    }

    /// The engine quantities the stress checks need.
    pub fn request(&self) -> Request {
        Request {
            sigma_top: false,
            sigma_interface: self.substrate_yield,
            tau_interface: self.bond_shear,
            e_eff: false,
        }
    }
}

/// Pass/fail criteria.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Criteria {
    /// Exceedance probability that defines a peak value (fraction of the interface area).
    pub epsilon: f64,
    /// Limits are strengths divided by this (≥ 1).
    pub safety_factor: f64,
    pub checks: Checks,
}

impl Default for Criteria {
    fn default() -> Self {
        Self {
            epsilon: crate::prec::DEFAULT_EPSILON,
            safety_factor: 1.0,
            checks: Checks::all(),
        }
    }
}

/// A coating design without its thickness: the layers, the load, the strengths and criteria.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    pub layers: Bilayer,
    /// Nominal pressure p0 (Pa).
    pub pressure: f64,
    /// Substrate yield strength (Pa); required by substrate-yield.
    pub yield_strength: Option<f64>,
    /// Bond shear strength (Pa).
    pub bond_strength: f64,
    pub criteria: Criteria,
}

/// The outcome of one check at one thickness.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckResult {
    pub kind: CheckKind,
    /// The checked value (Pa for stresses, m for min-thickness).
    pub value: Estimate,
    /// The limit (`None` for min-thickness when no thickness passes).
    pub limit: Option<f64>,
    /// Unused fraction of the limit (≥ 0 passes); `None` when there is no limit.
    pub margin: Option<f64>,
    pub pass: bool,
    /// True when the value is within its error estimate of the limit (the verdict is fragile).
    pub undecided: bool,
}

/// Everything computed at one thickness.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Evaluation {
    pub contact: Contact,
    /// p0·A0/A (Pa).
    pub mean_contact_pressure: Estimate,
    /// τ at exceedance ε (Pa).
    pub tau_peak: Option<Estimate>,
    /// P(|τ| > τ_bond).
    pub bond_exceedance: Option<f64>,
    /// Interface normal stress at exceedance ε (Pa).
    pub sigma_peak_interface: Option<Estimate>,
    /// P(σ_interface > σ_yield).
    pub yield_exceedance: Option<f64>,
    /// bond-shear and substrate-yield (those enabled).
    pub checks: Vec<CheckResult>,
}

/// The minimum thickness.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MinThickness {
    /// d_min, the geometric midpoint of the final bracket, with the distance to its upper end
    /// plus the shift by the utilisation's own error as error; `None` when no thickness passes.
    pub thickness: Option<Estimate>,
    /// The check that fails just below d_min (or at every thickness when none passes).
    pub governing: Option<CheckKind>,
    /// The scan range [d_lo, d_hi].
    pub floor: f64,
    pub bulk: f64,
    /// Every scanned thickness passed down to the floor (d_min is then the floor).
    pub all_pass_to_floor: bool,
    /// Engine evaluations used.
    pub evaluations: usize,
}

/// The verdict for one design at its thickness.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Outcome {
    pub thickness: f64,
    pub evaluation: Evaluation,
    pub min_thickness: Option<MinThickness>,
    /// All enabled checks (stress checks, then min-thickness).
    pub checks: Vec<CheckResult>,
    pub pass: bool,
    /// The enabled check with the smallest margin (the one that decides the verdict).
    pub governing: Option<CheckKind>,
    pub warnings: Vec<String>,
}

/// The largest enabled check's value/limit at one thickness (> 1 fails), the relative error
/// of that value, and which check it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Utilisation {
    pub value: f64,
    pub rel_err: f64,
    pub kind: Option<CheckKind>,
}

/// One spectrum and one design, with the engine's d-independent precomputation.
pub struct Checker {
    engine: Engine,
    /// The engine of the d_min search, at [`crate::prec::SEARCH_RTOL`] (or the scene's rtol if
    /// looser): d_min is wanted to [`D_MIN_RTOL`], and the utilisation's error enters its
    /// estimate.
    search: Engine,
    design: Design,
    q_low: f64,
    q_high: f64,
    /// Rms slope ξ of the spectrum.
    rms_slope: f64,
}

impl Checker {
    pub fn new(spectrum: &Spectrum, design: Design, settings: Settings) -> Result<Self, Error> {
        let c = &design.criteria;
        if !(c.epsilon.is_finite() && c.epsilon > 0.0 && c.epsilon < 1.0) {
            return Err(Error::invalid("epsilon", c.epsilon, "0 < epsilon < 1"));
        }
        if !(c.safety_factor.is_finite() && c.safety_factor > 0.0) {
            return Err(Error::invalid(
                "safety factor",
                c.safety_factor,
                "a finite factor > 0",
            ));
        }
        if !(design.pressure.is_finite() && design.pressure > 0.0) {
            return Err(Error::invalid(
                "pressure",
                design.pressure,
                "a finite nominal pressure > 0 in Pa",
            ));
        }
        if !(design.bond_strength.is_finite() && design.bond_strength > 0.0) {
            return Err(Error::invalid(
                "bond shear strength",
                design.bond_strength,
                "a finite strength > 0 in Pa",
            ));
        }
        if c.checks.substrate_yield && design.yield_strength.is_none() {
            return Err(Error::invalid(
                "substrate",
                "no yield strength",
                "a substrate yield_strength for the substrate-yield check",
            ));
        }
        let (q_low, q_high) = spectrum.support();
        let engine = Engine::new(spectrum, settings);
        // The search engine shares the design engine's grids where they coincide, and its
        // kernel tables.
        let search = engine.sibling(Settings {
            rtol: settings.rtol.max(crate::prec::SEARCH_RTOL),
        });
        Ok(Self {
            engine,
            search,
            design,
            q_low,
            q_high,
            rms_slope: spectrum.slope_sq().value.sqrt(),
        })
    }

    pub fn design(&self) -> &Design {
        &self.design
    }

    fn stack(&self, thickness: f64) -> Result<Stack, Error> {
        if !(thickness.is_finite() && thickness > 0.0) {
            return Err(Error::invalid(
                "thickness",
                thickness,
                "a finite film thickness > 0 in m",
            ));
        }
        Ok(Stack {
            layers: self.design.layers,
            thickness,
        })
    }

    fn limit(&self, strength: f64) -> f64 {
        strength / self.design.criteria.safety_factor
    }

    /// Everything at one thickness: all engine quantities and the stress checks.
    pub fn evaluate(&self, thickness: f64) -> Result<Evaluation, Error> {
        let contact = self.engine.evaluate(
            &self.stack(thickness)?,
            self.design.pressure,
            Request::all(),
        )?;
        self.assess(contact, true)
    }

    /// The stress checks from a contact result. With `extras`, also the exceedances of the
    /// limits themselves (not needed while searching for d_min).
    fn assess(&self, contact: Contact, extras: bool) -> Result<Evaluation, Error> {
        let d = &self.design;
        let eps = d.criteria.epsilon;
        let p0 = d.pressure;
        let area = contact.area_fraction;
        if area.value.is_nan() || area.value <= 0.0 {
            return Err(Error::Numerical {
                what: "contact area",
                detail: format!("A/A0 = {} at d = {} m", area.value, contact.thickness),
            });
        }
        let mean_contact_pressure = area.map(|a| p0 / a, |a| p0 / (a * a));
        let on = d.criteria.checks;
        let mut checks = Vec::new();
        let (mut tau_peak, mut bond_exceedance) = (None, None);
        if let Some(tau) = contact.tau_rms_interface {
            let k = contact::tau_peak(1.0, eps);
            let peak = tau.map(|t| k * t, |_| k);
            if on.bond_shear {
                checks.push(upper_check(
                    CheckKind::BondShear,
                    peak,
                    self.limit(d.bond_strength),
                ));
            }
            tau_peak = Some(peak);
            if extras {
                bond_exceedance = Some(contact::tau_exceedance(tau.value, d.bond_strength));
            }
        }
        let (mut sigma_peak_interface, mut yield_exceedance) = (None, None);
        if let Some(sigma) = contact.sigma_rms_interface {
            let at = |s: f64| NormalStress { p0, sigma_rms: s };
            let mut peak = at(sigma.value).peak(eps);
            peak.status = Estimate::worst(peak.status, sigma.status);
            if extras {
                // First-order propagation of σ_rms's error into the peak.
                peak.err += (at(sigma.value + sigma.err).peak(eps).value - peak.value).abs();
            }
            if let Some(y) = d.yield_strength {
                if on.substrate_yield {
                    let governing = if peak.value >= mean_contact_pressure.value {
                        peak
                    } else {
                        mean_contact_pressure
                    };
                    checks.push(upper_check(
                        CheckKind::SubstrateYield,
                        governing,
                        self.limit(y),
                    ));
                }
                if extras {
                    yield_exceedance = Some(at(sigma.value).exceedance(y));
                }
            }
            sigma_peak_interface = Some(peak);
        }
        Ok(Evaluation {
            contact,
            mean_contact_pressure,
            tau_peak,
            bond_exceedance,
            sigma_peak_interface,
            yield_exceedance,
            checks,
        })
    }

    /// Utilisation (value/limit, > 1 fails) of the enabled stress checks at `thickness`, with the
    /// check that has the largest; only what those checks need is computed.
    fn utilisation(&self, thickness: f64) -> Result<Utilisation, Error> {
        let req = self.design.criteria.checks.request();
        let contact = self
            .search
            .evaluate(&self.stack(thickness)?, self.design.pressure, req)?;
        let ev = self.assess(contact, false)?;
        let mut worst = Utilisation {
            value: 0.0,
            rel_err: 0.0,
            kind: None,
        };
        for c in &ev.checks {
            let u = c.value.value / c.limit.unwrap_or(f64::INFINITY);
            if u > worst.value || worst.kind.is_none() {
                worst = Utilisation {
                    value: u,
                    rel_err: c.value.err / c.value.value.abs(),
                    kind: Some(c.kind),
                };
            }
        }
        Ok(worst)
    }

    /// The scan range [d_lo, d_hi] of the minimum-thickness search (module docs).
    pub fn scan_range(&self) -> (f64, f64) {
        let lo = (1e-6 / self.q_low).min(1e-4 / self.q_high).max(THINNEST);
        let hi = BULK_QD / self.q_low;
        (lo.min(hi), hi)
    }

    /// The smallest thickness above which every enabled stress check passes (module docs).
    pub fn min_thickness(&self) -> Result<MinThickness, Error> {
        let (lo, hi) = self.scan_range();
        search_min_thickness(lo, hi, |d| self.utilisation(d))
    }

    /// The full check at the design's thickness: all quantities, the enabled checks, d_min.
    pub fn run(&self, thickness: f64) -> Result<Outcome, Error> {
        let evaluation = self.evaluate(thickness)?;
        let checks_on = self.design.criteria.checks;
        let min_thickness = if checks_on.min_thickness {
            Some(self.min_thickness()?)
        } else {
            None
        };
        let mut checks = evaluation.checks.clone();
        let mut warnings = Vec::new();
        if let Some(m) = &min_thickness {
            let value = Estimate::exact(thickness);
            checks.push(match m.thickness {
                Some(dm) => {
                    let pass = thickness >= dm.value;
                    CheckResult {
                        kind: CheckKind::MinThickness,
                        value,
                        limit: Some(dm.value),
                        margin: Some(1.0 - dm.value / thickness),
                        pass,
                        undecided: (thickness - dm.value).abs() <= dm.err,
                    }
                }
                None => CheckResult {
                    kind: CheckKind::MinThickness,
                    value,
                    limit: None,
                    margin: None,
                    pass: false,
                    undecided: false,
                },
            });
            if m.thickness.is_none() {
                warnings.push(
                    "no film thickness passes: even a bulk film fails the enabled checks".into(),
                );
            } else if m.all_pass_to_floor {
                warnings.push(format!(
                    "every thickness down to the scan floor {:.3e} m passes; d_min is reported as that floor",
                    m.floor
                ));
            }
        }
        for c in &checks {
            if c.undecided {
                warnings.push(format!(
                    "{}: the value is within its numerical error of the limit; the verdict is fragile",
                    c.kind.name()
                ));
            }
            if c.value.status == Termination::ToleranceNotReached {
                warnings.push(format!(
                    "{}: the requested tolerance was not reached (error estimate {:.2e})",
                    c.kind.name(),
                    c.value.err
                ));
            }
        }
        warnings.extend(self.validity_warnings(&evaluation.contact, thickness));
        // No NaN or infinity reaches a verdict: a non-finite value is a numerical failure.
        if let Some(c) = checks.iter().find(|c| {
            !(c.value.value.is_finite() && c.value.err.is_finite())
                || c.margin.is_some_and(|m| !m.is_finite())
        }) {
            return Err(Error::Numerical {
                what: "design check",
                detail: format!(
                    "{}: value {:e} ± {:e}, margin {:?} at d = {thickness:e} m",
                    c.kind.name(),
                    c.value.value,
                    c.value.err,
                    c.margin
                ),
            });
        }
        let pass = checks.iter().all(|c| c.pass);
        let governing = checks
            .iter()
            .min_by(|a, b| {
                let ma = a.margin.unwrap_or(f64::NEG_INFINITY);
                let mb = b.margin.unwrap_or(f64::NEG_INFINITY);
                ma.total_cmp(&mb)
            })
            .map(|c| c.kind);
        Ok(Outcome {
            thickness,
            evaluation,
            min_thickness,
            checks,
            pass,
            governing,
            warnings,
        })
    }

    /// Where the theory's assumptions are strained (module docs, "Validity"): few long waves
    /// carrying the contact, near-full contact, slopes outside small-slope elasticity.
    fn validity_warnings(&self, c: &Contact, thickness: f64) -> Vec<String> {
        let mut w = Vec::new();
        if self.q_high > 2.0 * self.q_low && c.low_octave_share > LOW_OCTAVE_WARN {
            w.push(format!(
                "{:.0} % of G(q1) (the contact stress variance) comes from the lowest octave of the \
                 spectrum (q_L d = {:.3}): a few long waves carry the contact, where Persson's theory \
                 under-estimates the contact area (exact solutions: 2x at q_L d = 0.3, 10x or more \
                 at q_L d <= 0.1), so the contact-pressure figures (mean pressure in contact, \
                 sigma peaks) are conservative; the result also depends on where the data start \
                 (q_min); check with --verify on a height map",
                100.0 * c.low_octave_share,
                self.q_low * thickness
            ));
        }
        if c.area_fraction.value > FULL_CONTACT_WARN {
            w.push(format!(
                "near full contact (A/A0 = {:.3}): the rms stresses tend to the exact full-contact \
                 values, but the partial-contact distribution of eq. (B11) and the peak values \
                 drawn from it are outside the range the theory was built and tested for",
                c.area_fraction.value
            ));
        }
        if self.rms_slope > SLOPE_WARN {
            w.push(format!(
                "rms slope {:.3} > 1: the theory is small-slope linear elasticity; at \
                 such slopes the film's strains are large and the stresses are indicative only",
                self.rms_slope
            ));
        }
        w
    }

    /// Evaluations at many thicknesses, in parallel; each equal to [`evaluate`](Self::evaluate)
    /// at its thickness afterwards, to the last bit (one kernel table serves them all).
    pub fn sweep(&self, thicknesses: &[f64]) -> Result<Vec<Evaluation>, Error> {
        let (lo, hi) = thicknesses
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), &d| {
                (lo.min(d), hi.max(d))
            });
        self.engine.prepare(&self.design.layers, lo, hi);
        thicknesses.par_iter().map(|&d| self.evaluate(d)).collect()
    }
}

/// The minimum-thickness search on [lo, hi] (module docs, steps 1–5) for a utilisation
/// function `util(d) = (max over checks of value/limit, the check attaining it)`; a thickness
/// fails when its utilisation exceeds 1.
pub fn search_min_thickness(
    lo: f64,
    hi: f64,
    mut util: impl FnMut(f64) -> Result<Utilisation, Error>,
) -> Result<MinThickness, Error> {
    let mut evaluations = 0usize;
    // The largest relative error of any utilisation used.
    let mut u_rel_err = 0.0f64;
    let mut util = |x: f64| -> Result<Sample, Error> {
        evaluations += 1;
        let u = util(x.exp())?;
        u_rel_err = u_rel_err.max(u.rel_err);
        Ok(Sample {
            x,
            u: u.value,
            kind: u.kind,
        })
    };
    let result = |thickness, governing, all_pass_to_floor, evaluations| MinThickness {
        thickness,
        governing,
        floor: lo,
        bulk: hi,
        all_pass_to_floor,
        evaluations,
    };
    // The scan starts at q_L·d = SCAN_START_QD; the bulk bound is needed only when that fails
    // or nearly does (module docs, step 1).
    let start = util((hi * SCAN_START_QD / BULK_QD).clamp(lo, hi).ln())?;
    if start.kind.is_none() {
        // No stress check enabled: every thickness passes.
        return Ok(result(Some(Estimate::exact(lo)), None, true, 1));
    }
    // Samples from the top, and the first failing one with the passing sample above it.
    let mut samples = Vec::new();
    if start.u > 1.0 - THICK_SLACK && start.x < hi.ln() {
        let top = util(hi.ln())?;
        if top.u > 1.0 {
            return Ok(result(None, top.kind, false, 2));
        }
        samples.push(top);
    } else if start.u > 1.0 {
        return Ok(result(None, start.kind, false, 1));
    }
    samples.push(start);
    let mut failing: Option<(Sample, Sample)> = (start.u > 1.0).then(|| (start, samples[0]));
    let (x_lo, h) = (lo.ln(), std::f64::consts::LN_10 / POINTS_PER_DECADE);
    // A sample that a widened step found above its threshold: the stretch above it may hide
    // a failing band, so it is scanned again with base steps down to that sample (reused).
    let mut pending: Option<Sample> = None;
    while failing.is_none() {
        let cur = samples[samples.len() - 1];
        if cur.x <= x_lo {
            break;
        }
        let above = samples.len().checked_sub(2).map(|i| samples[i]);
        let ((step, below), floor) = match pending {
            Some(p) => ((h, f64::INFINITY), p.x),
            None => (scan_step(above, cur, h), x_lo),
        };
        let x = (cur.x - step).max(floor);
        let next = match pending.take_if(|p| p.x == x) {
            Some(p) => p,
            None => {
                let s = util(x)?;
                if s.u >= below {
                    pending = Some(s);
                    continue;
                }
                s
            }
        };
        samples.push(next);
        if next.u > 1.0 {
            failing = Some((next, cur));
        } else if let Some(a) = above {
            // A sampled local maximum: look between the neighbours for a narrow failing band.
            if cur.u > a.u && cur.u >= next.u && cur.u > PEAK_GUARD {
                failing = peak_guard(next, cur, a, &mut util)?;
            }
        }
    }
    let Some((fail, pass)) = failing else {
        return Ok(result(Some(Estimate::exact(lo)), None, true, evaluations));
    };
    let mut governing = fail.kind;
    // Refine the crossing of y = ln u through 0 (y_fail > 0 ≥ y_pass) by the ITP method
    // (Oliveira & Takahashi 2020) with inverse quadratic interpolation as its estimate: never
    // more evaluations than bisection plus one, about three on a smooth utilisation.
    let (mut x_fail, mut y_fail) = (fail.x, fail.u.ln());
    let (mut x_pass, mut y_pass) = (pass.x, pass.u.ln());
    // The interpolation's points (x, y), newest last: the scan sample above the bracket too.
    let mut recent: Vec<(f64, f64)> = samples
        .iter()
        .filter(|s| s.x > x_pass)
        .min_by(|a, b| a.x.total_cmp(&b.x))
        .map(|s| (s.x, s.u.ln()))
        .into_iter()
        .chain([(x_pass, y_pass), (x_fail, y_fail)])
        .filter(|p| p.1.is_finite())
        .collect();
    let eps = 0.5 * D_MIN_RTOL.ln_1p();
    let n_max = ((x_pass - x_fail) / (2.0 * eps)).log2().ceil().max(0.0) as i32 + 1;
    let mut j = 0;
    while x_pass - x_fail > 2.0 * eps {
        let w = x_pass - x_fail;
        let half = 0.5 * (x_fail + x_pass);
        let r = (eps * 2f64.powi(n_max - j) - 0.5 * w).max(0.0);
        let falsi = (y_fail.is_finite() && y_pass.is_finite() && y_fail > y_pass)
            .then(|| (x_fail * y_pass - x_pass * y_fail) / (y_pass - y_fail));
        let guess = inverse_quadratic(&recent)
            .filter(|x| *x > x_fail && *x < x_pass)
            .or(falsi)
            .unwrap_or(half);
        // Closing the bracket: an estimate within `near` of an end (the end came from a good
        // estimate) is moved to 4·near from it, at most 0.95·(2 eps), so that it lands across
        // the crossing and leaves a bracket of that width.
        let near = (guess - x_fail).min(x_pass - guess);
        let c = (4.0 * near).clamp(0.01 * eps, 1.9 * eps).min(0.5 * w);
        let x = half + (guess.clamp(x_fail + c, x_pass - c) - half).clamp(-r, r);
        let s = util(x)?;
        let y = s.u.ln();
        if s.u > 1.0 {
            (x_fail, y_fail) = (x, y);
            governing = s.kind;
        } else {
            (x_pass, y_pass) = (x, y);
        }
        if y.is_finite() {
            recent.push((x, y));
        }
        j += 1;
    }
    let mid = (0.5 * (x_fail + x_pass)).exp();
    // The geometric midpoint is nearer the bracket's lower end: its distance to the upper one
    // bounds the bracket error.
    let bracket = x_pass.exp() - mid;
    // The utilisations' own errors shift the crossing by δ(ln u)/|d ln u/d ln d| in ln d, with
    // δ(ln u) = −ln(1 − relative error), the larger side; the slope is the secant over the
    // final bracket.
    let slope = (y_fail - y_pass) / (x_pass - x_fail);
    let shift = mid * (-(-u_rel_err.min(0.5)).ln_1p() / slope.abs()).exp_m1();
    let d_min = Estimate::new(mid, bracket + shift, Termination::Converged);
    Ok(result(Some(d_min), governing, false, evaluations))
}

/// One sample of the minimum-thickness search: x = ln d, the utilisation and its check.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Sample {
    x: f64,
    u: f64,
    kind: Option<CheckKind>,
}

type Util<'a> = dyn FnMut(f64) -> Result<Sample, Error> + 'a;

/// The scan's next step down in ln d after `cur` (module docs, step 2) and the utilisation
/// its end must stay below (infinite for the base step `h`): the longest of the [`WIDE_STEPS`]
/// over which the log-linear extrapolation of u (growth rate of ln u per unit of ln d from the
/// last two samples, at least [`MIN_GROWTH`]) stays below [`WIDE_AIM`] of the step's
/// threshold, else `h`.
fn scan_step(above: Option<Sample>, cur: Sample, h: f64) -> (f64, f64) {
    let base = (h, f64::INFINITY);
    let rate = match above {
        _ if cur.u <= 0.0 => return base,
        None => MIN_GROWTH,
        Some(a) if a.u > 0.0 => ((cur.u / a.u).ln() / (a.x - cur.x)).max(MIN_GROWTH),
        Some(_) => return base,
    };
    WIDE_STEPS
        .iter()
        .filter(|w| cur.u < w.below)
        .map(|w| {
            let longest = w.decades * std::f64::consts::LN_10;
            (
                ((WIDE_AIM * w.below / cur.u).ln() / rate).min(longest),
                w.below,
            )
        })
        .fold(base, |best, s| if s.0 > best.0 { s } else { best })
}

/// The narrow-band guard (module docs, step 3) at a sampled local maximum `mid` between the
/// samples `lo` and `hi` (lo.x < mid.x < hi.x): successive parabolic interpolation for the
/// maximum of the utilisation, stopping at the first failing point, else once the parabola
/// through the best three points promises less than [`GUARD_RESOLVED`] of the remaining
/// headroom (after at least one evaluation), or the bracket is 1e-3 wide in ln d, or after
/// [`GUARD_MAX_STEPS`] evaluations (the golden-section search it replaces took 13). Returns the
/// failing point and the nearest passing point above it.
fn peak_guard(
    mut lo: Sample,
    mut mid: Sample,
    mut hi: Sample,
    f: &mut Util<'_>,
) -> Result<Option<(Sample, Sample)>, Error> {
    let mut seen = vec![lo, mid, hi];
    let mut evaluated = false;
    while hi.x - lo.x > 1e-3 && seen.len() < 3 + GUARD_MAX_STEPS {
        let w = hi.x - lo.x;
        let vertex = parabola_vertex(lo, mid, hi);
        if evaluated && vertex.is_none_or(|v| v.1 - mid.u <= GUARD_RESOLVED * (1.0 - mid.u)) {
            break;
        }
        // The wider side of the bracket, for a golden-section step when the parabola is flat
        // or its vertex too close to the best point.
        let side = if hi.x - mid.x >= mid.x - lo.x {
            hi.x
        } else {
            lo.x
        };
        let golden = mid.x + 0.381_966 * (side - mid.x);
        let sep = 0.05 * w;
        let x = match vertex {
            Some((xv, _)) if (xv - mid.x).abs() >= sep => xv.clamp(lo.x + sep, hi.x - sep),
            _ => golden,
        };
        let s = f(x)?;
        evaluated = true;
        if s.u > 1.0 {
            let above = seen
                .iter()
                .filter(|p| p.x > x)
                .min_by(|a, b| a.x.total_cmp(&b.x))
                .copied()
                .unwrap_or(hi);
            return Ok(Some((s, above)));
        }
        seen.push(s);
        if s.u > mid.u {
            if s.x < mid.x {
                hi = mid;
            } else {
                lo = mid;
            }
            mid = s;
        } else if s.x < mid.x {
            lo = s;
        } else {
            hi = s;
        }
    }
    Ok(None)
}

/// The vertex (x, value) of the parabola through three samples, when it opens downwards.
fn parabola_vertex(a: Sample, b: Sample, c: Sample) -> Option<(f64, f64)> {
    let ab = (b.u - a.u) / (b.x - a.x);
    let bc = (c.u - b.u) / (c.x - b.x);
    let curv = (bc - ab) / (c.x - a.x);
    if curv.is_nan() || curv >= 0.0 {
        return None;
    }
    let x = 0.5 * (a.x + b.x) - 0.5 * ab / curv;
    Some((x, a.u + ab * (x - a.x) + curv * (x - a.x) * (x - b.x))).filter(|v| v.0.is_finite())
}

/// The zero of the inverse quadratic through the last three points (x, y) (x as a quadratic
/// in y), when their y are distinct.
fn inverse_quadratic(points: &[(f64, f64)]) -> Option<f64> {
    let [(x0, y0), (x1, y1), (x2, y2)] = *points.get(points.len().checked_sub(3)?..)? else {
        return None;
    };
    if y0 == y1 || y1 == y2 || y0 == y2 {
        return None;
    }
    let x = x0 * y1 * y2 / ((y0 - y1) * (y0 - y2))
        + x1 * y0 * y2 / ((y1 - y0) * (y1 - y2))
        + x2 * y0 * y1 / ((y2 - y0) * (y2 - y1));
    x.is_finite().then_some(x)
}

/// A stress check against an upper limit.
fn upper_check(kind: CheckKind, value: Estimate, limit: f64) -> CheckResult {
    CheckResult {
        kind,
        value,
        limit: Some(limit),
        margin: Some(1.0 - value.value / limit),
        pass: value.value <= limit,
        undecided: (value.value - limit).abs() <= value.err,
    }
}

/// Log-spaced thicknesses for `from:to:n` (n ≥ 2 includes both ends; n = 1 gives `from`).
pub fn log_space(from: f64, to: f64, n: usize) -> Vec<f64> {
    if n <= 1 {
        return vec![from];
    }
    let (a, b) = (from.ln(), to.ln());
    (0..n)
        .map(|i| {
            if i == 0 {
                from
            } else if i == n - 1 {
                to
            } else {
                (a + (b - a) * i as f64 / (n - 1) as f64).exp()
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(x: f64, u: f64) -> Sample {
        Sample {
            x,
            u,
            kind: Some(CheckKind::BondShear),
        }
    }

    #[test]
    fn peak_guard_resolves_a_smooth_maximum_below_one() {
        let mut n = 0;
        let mut f = |x: f64| {
            n += 1;
            Ok(sample(x, 0.9 - (x - 0.7) * (x - 0.7)))
        };
        let got = peak_guard(
            sample(-0.5, -0.54),
            sample(0.5, 0.86),
            sample(1.5, 0.26),
            &mut f,
        );
        assert_eq!(got.unwrap(), None);
        // A parabola is resolved by its vertex and one confirmation at most.
        assert!(n <= 2, "{n}");
    }

    #[test]
    fn peak_guard_finds_a_peak_above_one_between_samples() {
        // A Gaussian bump of height 1.3 and width 0.08 between samples that see < 0.75.
        let u = |x: f64| 0.2 + 1.1 * (-((x - 0.62) / 0.08f64).powi(2)).exp();
        let mut f = |x: f64| Ok(sample(x, u(x)));
        let (fail, pass) = peak_guard(
            sample(0.3, u(0.3)),
            sample(0.5, u(0.5)),
            sample(0.9, u(0.9)),
            &mut f,
        )
        .unwrap()
        .expect("the bump fails");
        assert!(
            fail.u > 1.0 && pass.u <= 1.0 && pass.x > fail.x,
            "{fail:?} {pass:?}"
        );
    }

    #[test]
    fn inverse_quadratic_is_exact_for_a_quadratic_inverse() {
        // x = 2 + 0.5 y − 0.1 y²: the zero is x = 2.
        let x = |y: f64| 2.0 + 0.5 * y - 0.1 * y * y;
        let pts = [(x(-1.0), -1.0), (x(0.3), 0.3), (x(2.0), 2.0)];
        assert!((inverse_quadratic(&pts).unwrap() - 2.0).abs() < 1e-14);
        assert_eq!(inverse_quadratic(&pts[..2]), None);
    }

    /// Synthetic utilisations u(ln d) with known crossings.
    fn search(u: impl Fn(f64) -> f64) -> MinThickness {
        search_min_thickness(1e-9, 1e-2, |d| {
            Ok(Utilisation {
                value: u(d.ln()),
                rel_err: 0.0,
                kind: Some(CheckKind::BondShear),
            })
        })
        .unwrap()
    }

    fn assert_crossing(m: &MinThickness, want: f64) {
        let d = m.thickness.unwrap();
        assert!(!m.all_pass_to_floor);
        assert!((d.value - want).abs() <= d.err * 1.0001, "{d:?} vs {want}");
        assert!(d.err <= 0.5 * D_MIN_RTOL * d.value * 1.001, "{d:?}");
    }

    #[test]
    fn monotone_utilisation_crossing() {
        // u = (d0/d)^1.5 fails below d0 = 3.7e-6.
        let m = search(|x| (3.7e-6f64.ln() - x).exp().powf(1.5));
        assert_crossing(&m, 3.7e-6);
        // Eight per decade would take 29 scan samples (3.4 decades, plus the bulk bound); the
        // widened steps cross u < 0.15, and the interpolation with its closing step needs two
        // refinement steps where bisection needs 8.
        assert!(m.evaluations <= 12, "{}", m.evaluations);
    }

    /// The utilisations' own error enters d_min's estimate: perturbing u by its stated relative
    /// error moves d_min by no more than the estimate.
    #[test]
    fn utilisation_error_widens_the_estimate() {
        let run = |scale: f64, rel_err: f64| {
            search_min_thickness(1e-9, 1e-2, |d| {
                Ok(Utilisation {
                    value: scale * (3.7e-6f64.ln() - d.ln()).exp().powf(0.05),
                    rel_err,
                    kind: Some(CheckKind::BondShear),
                })
            })
            .unwrap()
            .thickness
            .unwrap()
        };
        let exact = run(1.0, 0.0);
        let stated = run(1.0, 1e-3);
        // A shallow crossing (d ln u/d ln d = -0.05): 1e-3 in u is 2 % in d, beyond the bracket.
        assert!(stated.err >= 0.02 * stated.value, "{stated:?}");
        for scale in [1.0 - 1e-3, 1.0 + 1e-3] {
            let moved = run(scale, 0.0);
            assert!(
                (moved.value - exact.value).abs() <= stated.err,
                "{moved:?} {stated:?}"
            );
        }
    }

    /// |g(qd)| on a dense grid in ln(qd) over [1e-4, 1e3] for a film on a substrate.
    fn shear_kernel(film: (f64, f64), substrate: (f64, f64)) -> Vec<(f64, f64)> {
        let e = |(y, nu): (f64, f64)| crate::layer::Elastic::new(y, nu).unwrap();
        let b = Bilayer::new(e(film), e(substrate));
        (0..=3500)
            .map(|i| {
                let t = (1e-4f64).ln() + i as f64 * 7.0 * std::f64::consts::LN_10 / 3500.0;
                (t, b.response(t.exp()).g.abs())
            })
            .collect()
    }

    /// The premise of the widened scan steps (module docs, step 2): |g| is unimodal in ln(qd)
    /// and exceeds each step's `level` of its maximum on a stretch wider than the step, for
    /// films softer and stiffer than their substrates and any Poisson ratios; each step's
    /// threshold is under level/√2.
    #[test]
    fn wide_steps_are_narrower_than_the_shear_kernel() {
        let mut narrowest = [f64::INFINITY; WIDE_STEPS.len()];
        for nu0 in [0.0, 0.25, 0.5] {
            for ratio in [1e-3, 1.0, 1e5] {
                for nu1 in [0.0, 0.5] {
                    let g = shear_kernel((1e6, nu0), (1e6 * ratio, nu1));
                    let (i_max, g_max) = g
                        .iter()
                        .enumerate()
                        .map(|(i, p)| (i, p.1))
                        .max_by(|a, b| a.1.total_cmp(&b.1))
                        .unwrap();
                    assert!(i_max > 0 && i_max < g.len() - 1, "{nu0} {ratio} {nu1}");
                    // Rising up to the maximum and falling after it (to rounding).
                    let tol = 1e-12 * g_max;
                    assert!(g[..=i_max].windows(2).all(|w| w[1].1 >= w[0].1 - tol));
                    assert!(g[i_max..].windows(2).all(|w| w[1].1 <= w[0].1 + tol));
                    for (n, w) in narrowest.iter_mut().zip(WIDE_STEPS) {
                        let above: Vec<f64> = g
                            .iter()
                            .filter(|p| p.1 >= w.level * g_max)
                            .map(|p| p.0)
                            .collect();
                        *n = n.min(above[above.len() - 1] - above[0]);
                    }
                }
            }
        }
        // The narrowest, a ν = 0 film on a much stiffer substrate: 1.90 above a quarter of
        // the maximum, 1.32 above half of it.
        for (n, w) in narrowest.into_iter().zip(WIDE_STEPS) {
            let longest = w.decades * std::f64::consts::LN_10;
            assert!(n > 1.05 * longest, "{w:?}: {n} vs {longest}");
            assert!(w.below < w.level / 2f64.sqrt(), "{w:?}");
        }
    }

    /// The premise of the scan start (module docs, step 1): beyond q·d = 10, |f| and |g|
    /// decrease and S⁻² is within 1.8e-6 of 1, for films softer and stiffer than their
    /// substrates and any Poisson ratios; the slack covers the latter's effect on A/A0.
    #[test]
    fn thick_films_only_relax_beyond_the_scan_start() {
        let e = |y: f64, nu: f64| crate::layer::Elastic::new(y, nu).unwrap();
        let mut dev = 0.0f64;
        for nu0 in [0.0, 0.25, 0.5] {
            for ratio in [1e-4, 1e-2, 1.0, 1e2, 1e5] {
                for nu1 in [0.0, 0.5] {
                    let b = Bilayer::new(e(1e6, nu0), e(1e6 * ratio, nu1));
                    let r: Vec<_> = (0..=2000)
                        .map(|i| b.response(SCAN_START_QD * 10f64.powf(i as f64 / 1000.0)))
                        .collect();
                    for w in r.windows(2) {
                        assert!(w[1].f.abs() <= w[0].f.abs() && w[1].g.abs() <= w[0].g.abs());
                    }
                    dev = r
                        .iter()
                        .map(|x| (x.s.powi(-2) - 1.0).abs())
                        .fold(dev, f64::max);
                }
            }
        }
        assert!(dev <= 1.9e-6, "{dev:e}");
        // A/A0 moves by at most half the relative change of G, the rms stresses by about
        // that of G: the slack covers it five times over, and the search engine's error.
        assert!(5.0 * dev <= THICK_SLACK, "{dev:e}");
    }

    /// A bond-shear band of the sharpest physical shape (one roughness mode on the narrowest
    /// kernel, module docs, step 2) failing at its peak, at every position relative to the
    /// widened steps: its upper edge is found.
    #[test]
    fn a_single_mode_shear_band_is_found_between_wide_steps() {
        let g = shear_kernel((1e6, 0.0), (1e11, 0.5));
        let g_max = g.iter().map(|p| p.1).fold(0.0, f64::max);
        let b = Bilayer::new(
            crate::layer::Elastic::new(1e6, 0.0).unwrap(),
            crate::layer::Elastic::new(1e11, 0.5).unwrap(),
        );
        for k in 0..12 {
            let q0 = 1e5 * 10f64.powf(WIDE_STEPS[0].decades * k as f64 / 12.0);
            let u = |d: f64| 1.05 * b.response(q0 * d).g.abs() / g_max;
            let m = search(|x| u(x.exp()));
            // The upper edge by bisection from the kernel's maximum (q0·d = 2.07) upwards.
            let (mut lo, mut hi) = (2.07 / q0, 100.0 / q0);
            assert!(u(lo) > 1.0 && u(hi) < 1.0);
            while hi / lo > 1.0 + 1e-12 {
                let mid = (lo * hi).sqrt();
                if u(mid) > 1.0 { lo = mid } else { hi = mid }
            }
            assert_crossing(&m, lo);
        }
    }

    /// Bond-shear utilisations of random few-mode spectra on the narrowest kernel (module docs,
    /// step 2), peaking between 1.02 and 1.6: the search agrees with a dense scan at 400
    /// points per decade (bisected to 1e-12) on the band's upper edge.
    #[test]
    fn few_mode_shear_bands_match_a_dense_scan() {
        let e = |y: f64, nu: f64| crate::layer::Elastic::new(y, nu).unwrap();
        let b = Bilayer::new(e(1e6, 0.0), e(1e11, 0.5));
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut rand = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let grid: Vec<f64> = (0..=2800)
            .map(|i| 1e-2 * 10f64.powf(-i as f64 / 400.0))
            .collect();
        for case in 0..24 {
            let modes: Vec<(f64, f64)> = (0..1 + case % 4)
                .map(|_| (1e5 * 10f64.powf(3.0 * rand()), 10f64.powf(-2.0 * rand())))
                .collect();
            let tau = |d: f64| {
                modes
                    .iter()
                    .map(|&(q, w)| w * b.response(q * d).g.powi(2))
                    .sum::<f64>()
                    .sqrt()
            };
            let peak = grid.iter().map(|&d| tau(d)).fold(0.0, f64::max);
            let scale = (1.02 + 0.58 * rand()) / peak;
            let u = |d: f64| scale * tau(d);
            let m = search(|x| u(x.exp()));
            // The dense scan's largest failing thickness, then bisection to the edge above it.
            let i = grid.iter().position(|&d| u(d) > 1.0).unwrap();
            assert!(i > 0);
            let (mut lo, mut hi) = (grid[i], grid[i - 1]);
            while hi / lo > 1.0 + 1e-12 {
                let mid = (lo * hi).sqrt();
                if u(mid) > 1.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let d = m.thickness.unwrap();
            assert!(
                (d.value - lo).abs() <= d.err * 1.0001,
                "case {case} {modes:?}: {d:?} vs {lo:e}"
            );
        }
    }

    #[test]
    fn a_flat_low_utilisation_is_crossed_in_wide_steps() {
        // Flat at 0.01 on the thick side, failing below d0 = 3.7e-6.
        let m = search(|x| 0.01 + (3.7e-6f64.ln() - x).exp().powf(1.5));
        let d = m.thickness.unwrap();
        assert!((d.value / 3.7e-6 - 1.0).abs() < 0.01, "{d:?}");
        // Eight per decade down to the crossing would be 29 samples.
        assert!(m.evaluations <= 16, "{}", m.evaluations);
    }

    #[test]
    fn a_failing_band_gives_its_upper_edge() {
        // A broad hump in ln d failing on [1e-7, 2e-5]; passing below and above.
        let (a, b) = (1e-7f64.ln(), 2e-5f64.ln());
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let m = search(|x| 2.0 - ((x - mid) / half).powi(2));
        assert_crossing(&m, 2e-5);
        // Bisection on the whole range cannot work: both ends pass.
        assert!(2.0 - ((1e-9f64.ln() - mid) / half).powi(2) < 1.0);
    }

    #[test]
    fn a_band_narrower_than_the_scan_step_is_found() {
        // Peak 1.02 midway between two samples (the scan step in ln d is h = ln(1e7)/56);
        // it fails for |ln d − c| < 0.1, a band narrower than the step, so no sample fails.
        let h = 1e7f64.ln() / 56.0;
        let c = (1e-2 * SCAN_START_QD / BULK_QD).ln() - 20.5 * h;
        let m = search(|x| 1.02 - 2.0 * (x - c).powi(2));
        let edge = (c + 0.1).exp();
        assert_crossing(&m, edge);
    }

    #[test]
    fn ends_of_the_search() {
        let m = search(|_| 1.5);
        assert_eq!(m.thickness, None);
        assert_eq!(m.governing, Some(CheckKind::BondShear));
        let m = search(|_| 0.2);
        assert!(m.all_pass_to_floor);
        assert_eq!(m.thickness.unwrap().value, 1e-9);
    }

    #[test]
    fn log_space_hits_both_ends() {
        let v = log_space(1e-6, 1e-3, 4);
        assert_eq!(v.len(), 4);
        assert_eq!(v[0], 1e-6);
        assert_eq!(v[3], 1e-3);
        assert!((v[1] / 1e-5 - 1.0).abs() < 1e-14);
        assert_eq!(log_space(2.0, 3.0, 1), vec![2.0]);
    }

    #[test]
    fn check_names_round_trip() {
        for c in CheckKind::ALL {
            assert_eq!(CheckKind::from_name(c.name()), Some(c));
        }
        assert_eq!(CheckKind::from_name("bond"), None);
    }

    #[test]
    fn upper_checks_margin_and_pass() {
        let c = upper_check(CheckKind::BondShear, Estimate::exact(2.0), 8.0);
        assert!(c.pass && (c.margin.unwrap() - 0.75).abs() < 1e-15 && !c.undecided);
        let c = upper_check(
            CheckKind::BondShear,
            Estimate::new(8.1, 0.2, Termination::Converged),
            8.0,
        );
        assert!(!c.pass && c.undecided && c.margin.unwrap() < 0.0);
    }
}
