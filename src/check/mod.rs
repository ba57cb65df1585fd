//! The design checks of `coatcheck check` (definitions: notes.md, "Distributions and peak
//! values" and "Minimum thickness"; paper App. B, eqs. B8–B12, Figs. 6–7).
//!
//! - `bond-shear`: the interface shear is Gaussian with rms τ_rms (eq. B9); its peak at exceedance
//!   ε solves erfc(τ_peak/(√2 τ_rms)) = ε. It must not exceed τ_bond / safety factor. Also
//!   reported: P(|τ| > τ_bond), the fraction of the interface where the bond strength is exceeded.
//! - `substrate-yield`: the mean pressure in real contact p0·A0/A (A/A0 = P(q1), eq. B11) and the
//!   ε-peak of the interface normal stress (Persson's form centred at p0 with the interface width
//!   σ_rms(d), eq. B8) must not exceed σ_yield / safety factor; the larger governs.
//! - Under sliding (`load.friction` μ > 0, [`crate::contact::SlidingShear`]) or with the vector
//!   rule ([`ShearTail::Vector`]), bond-shear's peak is that of |τ| for the vector (μp0 + X, Y)
//!   ([`crate::tail`]), P(|τ| > τ_bond) likewise, and substrate-yield's interface σ_rms includes
//!   the friction-driven part.
//! - `min-thickness`: the smallest d_min such that the checks above pass at every d ≥ d_min. The
//!   given thickness passes it when d ≥ d_min.
//!
//! A check's margin is the unused fraction of its limit: 1 − value/limit for an upper limit
//! (stresses), 1 − d_min/d for the thickness; a check passes when its margin is ≥ 0. The rules
//! shared with the exact check ([`crate::verify`]) are in [`criteria`]; the minimum-thickness
//! search and the argument for it in [`min_thickness`], its root finder in [`itp`]; what alone
//! would make a failing design pass in [`levers`]; the same checks at every interface of a
//! layer stack in [`stack`], its levers in [`stack_levers`]; what the film's and the stack's
//! checkers share in `basis`; the design at the worst corner of its materials' ranges in
//! [`robust`] (a stack's in [`stack_robust`]).
//!
//! ## Validity
//! The outcome carries a warning, with the number that triggered it, where the theory is
//! strained: a low-octave share of G(q1) above [`LOW_OCTAVE_WARN`] (few long waves carry the
//! contact: Persson under-estimates the area, so its contact-pressure figures are conservative),
//! A/A0 above [`FULL_CONTACT_WARN`], and an rms slope above [`SLOPE_WARN`]. Two more say the
//! data do not fit the film: a film thinner than the surface's h_rms (the roughness is not a
//! small perturbation of the film), and a longest wavelength of the spectrum, 2π/q_low, shorter
//! than the film thickness (the interface stress comes from wavelengths of the order of d and
//! longer, which were not measured).

pub(crate) mod basis;
pub(crate) mod checker;
pub mod criteria;
pub mod itp;
pub mod levers;
pub mod min_thickness;
pub mod regime;
pub mod robust;
pub mod stack;
pub mod stack_levers;
pub mod stack_robust;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_sliding;

use crate::contact::{Contact, Request};
use crate::layer::Bilayer;
use crate::prec::Estimate;
use serde::Serialize;

pub use checker::Checker;
pub use min_thickness::search_min_thickness;

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
/// The growth rate of ln(u − floor) per unit of ln d assumed at most when widening a step
/// from the friction floor ([`min_thickness`], "The friction floor"): the secant between two
/// samples on the thick side, where the excess still falls exponentially in q_L·d, can be
/// several times the power law it follows on the thin side.
pub const MAX_EXCESS_GROWTH: f64 = 3.0;
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

/// Above this largest μ|c|/S over the spectrum (the normal–tangential coupling the sliding
/// theory neglects, [`crate::contact::friction_coupling`]) a run warns: the neglected term is
/// then as large as the one kept.
pub const COUPLING_WARN: f64 = 1.0;

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

/// The largest sliding friction coefficient accepted (`load.friction`): rubber on clean steel
/// reaches 2–4; beyond 10 the value is a typo.
pub const MAX_FRICTION: f64 = 10.0;

/// How the peak interface shear is read from its distribution (notes.md, "Distributions and
/// peak values" and "Sliding friction").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ShearTail {
    /// The paper's rule: |τ| half-normal with the total rms τ_rms (static contact only).
    HalfNormal,
    /// |τ| of the vector (μp0 + X, Y), X and Y independent Gaussians ([`crate::tail`]).
    Vector,
}

impl ShearTail {
    pub fn name(self) -> &'static str {
        match self {
            ShearTail::HalfNormal => "half-normal",
            ShearTail::Vector => "vector",
        }
    }

    pub fn from_name(s: &str) -> Option<Self> {
        [ShearTail::HalfNormal, ShearTail::Vector]
            .into_iter()
            .find(|t| t.name() == s.trim())
    }

    /// The rule in force: the one asked for, else half-normal without friction and vector with.
    pub fn resolve(asked: Option<ShearTail>, friction: f64) -> ShearTail {
        asked.unwrap_or(if friction > 0.0 {
            ShearTail::Vector
        } else {
            ShearTail::HalfNormal
        })
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
    /// The peak-shear rule asked for (`None`: [`ShearTail::resolve`]'s default).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shear_tail: Option<ShearTail>,
}

impl Default for Criteria {
    fn default() -> Self {
        Self {
            epsilon: crate::prec::DEFAULT_EPSILON,
            safety_factor: 1.0,
            checks: Checks::all(),
            shear_tail: None,
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
    /// Sliding friction coefficient μ (0: static contact).
    pub friction: f64,
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
    /// The rule `tau_peak` and `bond_exceedance` follow.
    pub shear_tail: ShearTail,
    /// The interface shear vector, when the vector rule is in force (friction or asked for).
    pub sliding: Option<crate::contact::SlidingShear>,
    /// The paper's half-normal peak of the static shear, beside a sliding `tau_peak`.
    pub tau_peak_static: Option<Estimate>,
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
    /// h_rms of the spectrum used (as read or scaled), m.
    pub h_rms: f64,
    /// Rms slope of the spectrum used.
    pub rms_slope: f64,
}

/// The largest enabled check's value/limit at one thickness (> 1 fails), the relative error
/// of that value, and which check it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Utilisation {
    pub value: f64,
    pub rel_err: f64,
    pub kind: Option<CheckKind>,
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
