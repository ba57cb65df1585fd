//! [`Basis`]: what the film's checker ([`super::Checker`]) and the stack's
//! ([`super::stack::StackChecker`]) share, whatever the layers: the validated inputs, the design
//! and search engines on one spectrum, the spectrum's support and moments, the d_min scan range
//! and search, the validity and data warnings ([`super`], "Validity"), the min-thickness check
//! from a d_min, and the warnings and guard every check of an outcome goes through.

use super::checker::{data_warnings, engines, scan_range, validate};
use super::*;
use crate::contact::{Contact, Engine};
use crate::error::Error;
use crate::prec::{Settings, Termination};
use crate::psd::Spectrum;

/// How the validity warnings name the coating: a film, or the layers of a stack.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Wording {
    /// The coating thickness in the data warnings ("film thickness").
    pub what: &'static str,
    /// The low-octave warning's q_L·depth, as it reads ("q_L d").
    pub depth: &'static str,
    /// What the exact solutions say about the contact at q_L·depth, with a leading space, or
    /// empty.
    pub exact: fn(f64) -> String,
    /// Where to check the result, with a leading "; ", or empty.
    pub verify: &'static str,
    /// Whose strains the slope warning names ("film").
    pub strained: &'static str,
}

/// One spectrum and a design's checked inputs, with the engines' d-independent precomputation.
pub(crate) struct Basis {
    pub engine: Engine,
    /// The engine of the d_min search, at [`crate::prec::SEARCH_RTOL`] (or the scene's rtol if
    /// looser): d_min is wanted to [`D_MIN_RTOL`], and the utilisation's error enters its
    /// estimate.
    pub search: Engine,
    pub q_low: f64,
    pub q_high: f64,
    /// Rms slope ξ of the spectrum.
    pub rms_slope: f64,
    /// h_rms of the spectrum, m.
    pub h_rms: f64,
}

impl Basis {
    /// Validate the inputs every design must have (bond strengths, top first) and set up the
    /// engines on `spectrum`.
    pub fn new(
        spectrum: &Spectrum,
        criteria: &Criteria,
        pressure: f64,
        bond_strengths: &[f64],
        yield_strength: Option<f64>,
        settings: Settings,
    ) -> Result<Self, Error> {
        validate(criteria, pressure, bond_strengths, yield_strength)?;
        let (q_low, q_high) = spectrum.support();
        let (engine, search) = engines(spectrum, settings);
        Ok(Self {
            engine,
            search,
            q_low,
            q_high,
            rms_slope: spectrum.slope_sq().value.sqrt(),
            h_rms: spectrum.h_rms_sq().value.sqrt(),
        })
    }

    /// The scan range [d_lo, d_hi] of the minimum-thickness search (the film's module docs).
    pub fn scan_range(&self) -> (f64, f64) {
        scan_range(self.q_low, self.q_high)
    }

    /// The smallest thickness above which `utilisation` stays ≤ 1, over the scan range; under
    /// friction μ > 0 the widened steps allow for the vector peak's spread at exceedance
    /// `epsilon` ([`crate::tail::anisotropy_spread`]; [`super::min_thickness`], "Under
    /// sliding").
    pub fn min_thickness(
        &self,
        friction: f64,
        epsilon: f64,
        utilisation: impl FnMut(f64) -> Result<Utilisation, Error>,
    ) -> Result<MinThickness, Error> {
        self.min_thickness_above(friction, epsilon, 0.0, utilisation)
    }

    /// [`Self::min_thickness`] for a utilisation that is at least `floor` at every thickness
    /// (the friction floor, [`super::min_thickness`]: it steers the scan's widened steps).
    pub fn min_thickness_above(
        &self,
        friction: f64,
        epsilon: f64,
        floor: f64,
        utilisation: impl FnMut(f64) -> Result<Utilisation, Error>,
    ) -> Result<MinThickness, Error> {
        let (lo, hi) = self.scan_range();
        let spread = peak_spread(friction, epsilon);
        super::min_thickness::search_min_thickness_spread(lo, hi, spread, floor, utilisation)
    }

    /// Where the theory is strained ([`super`], "Validity"): few long waves carrying the
    /// contact, near-full contact, slopes outside small-slope elasticity, and what the data say
    /// about a coating `depth` (m) thick.
    pub fn validity_warnings(&self, c: &Contact, depth: f64, wording: &Wording) -> Vec<String> {
        let mut w = Vec::new();
        if self.q_high > 2.0 * self.q_low && c.low_octave_share > LOW_OCTAVE_WARN {
            w.push(format!(
                "{:.0} % of G(q1) (the contact stress variance) comes from the lowest octave of the \
                 spectrum ({} = {:.3}): a few long waves carry the contact, where Persson's theory \
                 under-estimates the contact area{}, so the contact-pressure figures (mean \
                 pressure in contact, sigma peaks) are conservative; the result also depends on \
                 where the data start (q_min){}",
                100.0 * c.low_octave_share,
                wording.depth,
                self.q_low * depth,
                (wording.exact)(self.q_low * depth),
                wording.verify
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
                 such slopes the {}'s strains are large and the stresses are indicative only",
                self.rms_slope, wording.strained
            ));
        }
        w.extend(data_warnings(wording.what, depth, self.h_rms, self.q_low));
        w
    }
}

/// How much more than its rms the shear peak may fall between a failing point and the better
/// end of a widened step of the minimum-thickness search: [`crate::tail::anisotropy_spread`]
/// at exceedance `epsilon` under `friction`, else 1 ([`super::min_thickness`], "Under sliding").
pub(super) fn peak_spread(friction: f64, epsilon: f64) -> f64 {
    if friction > 0.0 {
        crate::tail::anisotropy_spread(epsilon)
    } else {
        1.0
    }
}

/// The min-thickness check of a coating `thickness` (m) thick against the search's d_min.
pub(crate) fn min_thickness_check(thickness: f64, m: &MinThickness) -> CheckResult {
    let value = Estimate::exact(thickness);
    match m.thickness {
        Some(dm) => CheckResult {
            kind: CheckKind::MinThickness,
            value,
            limit: Some(dm.value),
            margin: Some(1.0 - dm.value / thickness),
            pass: thickness >= dm.value,
            undecided: (thickness - dm.value).abs() <= dm.err,
        },
        None => CheckResult {
            kind: CheckKind::MinThickness,
            value,
            limit: None,
            margin: None,
            pass: false,
            undecided: false,
        },
    }
}

/// The warnings a check itself raises, the check named `name`: a verdict within the value's
/// error of the limit, a tolerance not reached.
pub(crate) fn check_warnings(name: &str, c: &CheckResult) -> Vec<String> {
    let mut w = Vec::new();
    if c.undecided {
        w.push(format!(
            "{name}: the value is within its numerical error of the limit; the verdict is fragile"
        ));
    }
    if c.value.status == Termination::ToleranceNotReached {
        w.push(format!(
            "{name}: the requested tolerance was not reached (error estimate {:.2e})",
            c.value.err
        ));
    }
    w
}

/// No NaN or infinity reaches a verdict: a check whose value, error or margin is not finite is
/// a numerical failure, named `name` and placed by `at` (" at d = … m").
pub(crate) fn finite_guard(name: &str, c: &CheckResult, at: &str) -> Result<(), Error> {
    if c.value.value.is_finite() && c.value.err.is_finite() && c.margin.is_none_or(f64::is_finite) {
        return Ok(());
    }
    Err(Error::Numerical {
        what: "design check",
        detail: format!(
            "{name}: value {:e} ± {:e}, margin {:?}{at}",
            c.value.value, c.value.err, c.margin
        ),
    })
}

/// The check with the smallest margin (a check with no margin, nothing passing, counts least):
/// the one that decides the verdict; the first of equals.
pub(crate) fn governing<'a, T>(
    checks: impl IntoIterator<Item = &'a T>,
    margin: impl Fn(&T) -> Option<f64>,
) -> Option<&'a T> {
    checks.into_iter().min_by(|a, b| {
        let ma = margin(a).unwrap_or(f64::NEG_INFINITY);
        let mb = margin(b).unwrap_or(f64::NEG_INFINITY);
        ma.total_cmp(&mb)
    })
}
