//! [`Checker`]: one spectrum and one design; the quantities and stress checks at a thickness
//! (eqs. B8–B12), the outcome with its validity warnings, the sweep, and the utilisation that
//! the minimum-thickness search ([`super::min_thickness`]) runs on.

use super::basis::{Basis, Wording, check_warnings, finite_guard, governing, min_thickness_check};
use super::criteria::{limit, upper_check, yield_governing};
use super::min_thickness::decision_levels;
use super::*;
use crate::contact::{self, Contact, Engine, NormalStress, Request, SlidingShear};
use crate::error::Error;
use crate::layer::Stack;
use crate::prec::Settings;
use crate::psd::Spectrum;
use crate::tail::ShearVector;
use rayon::prelude::*;

/// One spectrum and one design, with the engine's d-independent precomputation.
pub struct Checker {
    basis: Basis,
    design: Design,
}

/// How a film's validity warnings name it.
const FILM: Wording = Wording {
    what: "film thickness",
    depth: "q_L d",
    exact: super::regime::sentence,
    verify: "; check with --verify on a height map",
    strained: "film",
};

impl Checker {
    pub fn new(spectrum: &Spectrum, design: Design, settings: Settings) -> Result<Self, Error> {
        let basis = Basis::new(
            spectrum,
            &design.criteria,
            design.pressure,
            &[design.bond_strength],
            design.yield_strength,
            settings,
        )?;
        Ok(Self { basis, design })
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
        limit(strength, self.design.criteria.safety_factor)
    }

    /// The peak-shear rule in force ([`ShearTail::resolve`]).
    pub fn shear_tail(&self) -> ShearTail {
        ShearTail::resolve(self.design.criteria.shear_tail, self.design.friction)
    }

    /// The engine quantities at one thickness, under sliding (the shear vector too) when the
    /// design has friction or the vector rule is asked for.
    fn contact(
        &self,
        engine: &Engine,
        thickness: f64,
        req: Request,
    ) -> Result<(Contact, Option<SlidingShear>), Error> {
        let (stack, p0, mu) = (
            self.stack(thickness)?,
            self.design.pressure,
            self.design.friction,
        );
        if mu > 0.0 || self.shear_tail() == ShearTail::Vector {
            engine.evaluate_sliding(&stack, p0, mu, req)
        } else {
            Ok((engine.evaluate(&stack, p0, req)?, None))
        }
    }

    /// Everything at one thickness: all engine quantities and the stress checks.
    pub fn evaluate(&self, thickness: f64) -> Result<Evaluation, Error> {
        let (contact, mut sliding) = self.contact(&self.basis.engine, thickness, Request::all())?;
        if let Some(s) = sliding.as_mut() {
            s.coupling = Some(contact::friction_coupling(
                &self.stack(thickness)?,
                s.friction,
                (self.basis.q_low, self.basis.q_high),
            ));
        }
        self.assess(contact, sliding, true, Peak::Solved)
    }

    /// The peak interface shear by the rule in force, with P(|τ| > τ_bond) when `extras`: the
    /// paper's half-normal of τ_rms, or the vector's ([`ShearVector::peak`], or under
    /// [`Peak::FromLimit`] its one-step estimate from the bond limit; the rms errors enter as
    /// their largest relative error times the peak, which is homogeneous of degree 1 and
    /// increasing in the mean and both rms).
    fn shear_peak(
        &self,
        tau: Estimate,
        sliding: Option<&SlidingShear>,
        extras: bool,
        how: Peak,
    ) -> Result<(Estimate, Option<f64>), Error> {
        let d = &self.design;
        let eps = d.criteria.epsilon;
        match sliding {
            Some(s) => vector_peak(
                s,
                d.bond_strength,
                self.limit(d.bond_strength),
                (eps, d.friction),
                extras,
                how,
            ),
            None => {
                let k = contact::tau_peak(1.0, eps);
                let exceedance =
                    extras.then(|| contact::tau_exceedance(tau.value, d.bond_strength));
                Ok((tau.map(|t| k * t, |_| k), exceedance))
            }
        }
    }

    /// The stress checks from a contact result (and the shear vector under the vector rule).
    /// With `extras`, also the exceedances of the limits themselves (not needed while
    /// searching for d_min).
    fn assess(
        &self,
        contact: Contact,
        sliding: Option<SlidingShear>,
        extras: bool,
        how: Peak,
    ) -> Result<Evaluation, Error> {
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
        let (mut tau_peak, mut bond_exceedance, mut tau_peak_static) = (None, None, None);
        if let Some(tau) = contact.tau_rms_interface {
            let (peak, exceedance) = self.shear_peak(tau, sliding.as_ref(), extras, how)?;
            if on.bond_shear {
                checks.push(upper_check(
                    CheckKind::BondShear,
                    peak,
                    self.limit(d.bond_strength),
                ));
            }
            tau_peak = Some(peak);
            bond_exceedance = exceedance;
            if sliding.is_some() && extras {
                tau_peak_static = Some(self.shear_peak(tau, None, false, how)?.0);
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
                    let governing =
                        yield_governing(peak, mean_contact_pressure, |e: &Estimate| e.value);
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
            shear_tail: self.shear_tail(),
            sliding,
            tau_peak_static,
        })
    }

    /// Utilisation (value/limit, > 1 fails) of the enabled stress checks at `thickness`, with the
    /// check that has the largest; only what those checks need is computed, and the vector
    /// rule's peak is found as `how` says.
    fn utilisation(&self, thickness: f64, how: Peak) -> Result<Utilisation, Error> {
        let req = self.design.criteria.checks.request();
        let (contact, sliding) = self.contact(&self.basis.search, thickness, req)?;
        let ev = self.assess(contact, sliding, false, how)?;
        Ok(worst_utilisation(&ev.checks))
    }

    /// The scan range [d_lo, d_hi] of the minimum-thickness search (module docs).
    pub fn scan_range(&self) -> (f64, f64) {
        self.basis.scan_range()
    }

    /// The smallest thickness above which every enabled stress check passes (module docs).
    pub fn min_thickness(&self) -> Result<MinThickness, Error> {
        self.search(Peak::FromLimit)
    }

    /// [`Self::min_thickness`] with the vector rule's peak solved at every step: the reference
    /// the search's one-step estimates are tested against.
    #[cfg(test)]
    pub(super) fn min_thickness_solving_peaks(&self) -> Result<MinThickness, Error> {
        self.search(Peak::Solved)
    }

    /// The minimum-thickness search with the peaks found as `how` says; under friction the
    /// widened steps allow for the vector peak's spread ([`crate::tail::anisotropy_spread`];
    /// [`super::min_thickness`], "Under sliding").
    fn search(&self, how: Peak) -> Result<MinThickness, Error> {
        let d = &self.design;
        self.basis
            .min_thickness_above(d.friction, d.criteria.epsilon, self.friction_floor(), |t| {
                self.utilisation(t, how)
            })
    }

    /// The utilisation no thickness goes below under sliding ([`super::min_thickness`], "The
    /// friction floor"): the mean shear μp0 over the bond limit when the bond-shear check runs
    /// under the vector rule (the peak |τ| exceeds the mean), else 0.
    fn friction_floor(&self) -> f64 {
        let d = &self.design;
        if d.criteria.checks.bond_shear
            && d.friction > 0.0
            && self.shear_tail() == ShearTail::Vector
        {
            d.friction * d.pressure / self.limit(d.bond_strength)
        } else {
            0.0
        }
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
            checks.push(min_thickness_check(thickness, m));
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
            warnings.extend(check_warnings(c.kind.name(), c));
        }
        warnings.extend(self.validity_warnings(&evaluation.contact, thickness));
        if let Some(c) = evaluation.sliding.and_then(|s| s.coupling)
            && c > COUPLING_WARN
        {
            warnings.push(format!(
                "the normal–tangential coupling the sliding theory neglects reaches mu|c|/S = \
                 {c:.3} on the spectrum (> {COUPLING_WARN}): friction then changes the contact \
                 pressure itself, which the uncoupled approximation does not follow, so the \
                 sliding stresses are indicative only (check with the exact solver)"
            ));
        }
        for c in &checks {
            finite_guard(c.kind.name(), c, &format!(" at d = {thickness:e} m"))?;
        }
        let pass = checks.iter().all(|c| c.pass);
        let governing = governing(&checks, |c| c.margin).map(|c| c.kind);
        Ok(Outcome {
            thickness,
            evaluation,
            min_thickness,
            checks,
            pass,
            governing,
            warnings,
            h_rms: self.basis.h_rms,
            rms_slope: self.basis.rms_slope,
        })
    }

    /// Where the theory's assumptions are strained (module docs, "Validity"): few long waves
    /// carrying the contact, near-full contact, slopes outside small-slope elasticity.
    fn validity_warnings(&self, c: &Contact, thickness: f64) -> Vec<String> {
        self.basis.validity_warnings(c, thickness, &FILM)
    }

    /// The h_rms (m) and rms slope of the spectrum the design is judged with.
    pub fn roughness(&self) -> (f64, f64) {
        (self.basis.h_rms, self.basis.rms_slope)
    }

    /// Evaluations at many thicknesses, in parallel; each equal to [`evaluate`](Self::evaluate)
    /// at its thickness afterwards, to the last bit (one kernel table serves them all).
    pub fn sweep(&self, thicknesses: &[f64]) -> Result<Vec<Evaluation>, Error> {
        let (lo, hi) = thicknesses
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), &d| {
                (lo.min(d), hi.max(d))
            });
        self.basis.engine.prepare(&self.design.layers, lo, hi);
        thicknesses.par_iter().map(|&d| self.evaluate(d)).collect()
    }
}

/// The vector rule's peak interface shear at exceedance `eps` for the shear vector `s`, found
/// as `how` says (the rms errors enter as their largest relative error times the peak), with
/// P(|τ| > `bond_strength`) when `extras`; `limit` is the bond's limit (the start of
/// [`Peak::FromLimit`]'s step, read against the search's levels for the design's `friction`,
/// [`read_vector_peak`]). A film's and a layer stack's interfaces alike.
pub(super) fn vector_peak(
    s: &SlidingShear,
    bond_strength: f64,
    limit: f64,
    (eps, friction): (f64, f64),
    extras: bool,
    how: Peak,
) -> Result<(Estimate, Option<f64>), Error> {
    let v = ShearVector::new(s.mean.value, s.tau_x_rms.value, s.tau_y_rms.value)?;
    let mut peak = match how {
        Peak::Solved => v.peak(eps)?,
        Peak::FromLimit => read_vector_peak(
            &v,
            limit,
            eps,
            &decision_levels(super::basis::peak_spread(friction, eps)),
        )?,
    };
    let rel = s.tau_x_rms.rel_err().max(s.tau_y_rms.rel_err());
    peak.err += rel * peak.value;
    peak.status = Estimate::worst(
        peak.status,
        Estimate::worst(s.tau_x_rms.status, s.tau_y_rms.status),
    );
    let exceedance = extras.then(|| v.exceedance(bond_strength).value);
    Ok((peak, exceedance))
}

/// How the vector rule's peak shear is found at a thickness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Peak {
    /// Solved to [`crate::tail::PEAK_TARGET_RTOL`] ([`ShearVector::peak`]).
    Solved,
    /// One step from the bond limit ([`ShearVector::peak_from`]): on the same side of the
    /// limit as the peak (so the same pass or fail) and close to it near the limit, where the
    /// minimum-thickness search refines its crossing; one evaluation of the tail instead of a
    /// root solve's several. Solved where the step could be on the wrong side of one of the
    /// search's other levels ([`read_vector_peak`]).
    FromLimit,
}

/// The minimum-thickness search's read of the vector peak `v` at exceedance `eps` against
/// `limit` (module docs of `min_thickness`, "Under sliding"): one Newton step from the limit
/// ([`ShearVector::peak_from`]), on the same side of the limit as the peak, except where its
/// utilisation (read/limit) lies below one of `levels` by less than
/// [`crate::tail::one_step_shortfall`]: there the peak itself might be above that level, and it
/// is solved ([`ShearVector::peak`]). So the read is on the same side of every level as the
/// peak.
pub(super) fn read_vector_peak(
    v: &ShearVector,
    limit: f64,
    eps: f64,
    levels: &[f64],
) -> Result<Estimate, Error> {
    let one = v.peak_from(limit, eps)?;
    let (u, keep) = (
        one.value / limit,
        1.0 - crate::tail::one_step_shortfall(eps),
    );
    if levels.iter().any(|&t| u < t && u >= keep * t) {
        return v.peak(eps);
    }
    Ok(one)
}

/// What the roughness data say about a coating of `thickness` (m), named `what` ("film
/// thickness"): thinner than h_rms (the roughness is no small perturbation of the layer), or
/// thicker than the longest measured wavelength 2π/q_low (the interface stress then comes from
/// wavelengths the data do not hold).
pub(crate) fn data_warnings(what: &str, thickness: f64, h_rms: f64, q_low: f64) -> Vec<String> {
    let mut w = Vec::new();
    if thickness < h_rms {
        w.push(format!(
            "the {what} d = {thickness:.4e} m is below the surface's h_rms = {h_rms:.4e} m: \
             the roughness is not a small perturbation of the film, and the theory's layer \
             of uniform thickness does not describe it"
        ));
    }
    let longest = 2.0 * std::f64::consts::PI / q_low;
    if longest < thickness {
        w.push(format!(
            "the longest wavelength of the spectrum, 2π/q_low = {longest:.4e} m, is shorter \
             than the {what} d = {thickness:.4e} m: the interface stress comes from \
             wavelengths of the order of d and longer, which the data do not hold (measure a \
             longer scan or a larger map)"
        ));
    }
    w
}

/// The checks' inputs a design must have, whatever its layers: 0 < ε < 1, a safety factor > 0,
/// a nominal pressure > 0, every bond strength > 0 (Pa), and a yield strength when the
/// substrate-yield check runs.
pub(crate) fn validate(
    c: &Criteria,
    pressure: f64,
    bond_strengths: &[f64],
    yield_strength: Option<f64>,
) -> Result<(), Error> {
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
    if !(pressure.is_finite() && pressure > 0.0) {
        return Err(Error::invalid(
            "pressure",
            pressure,
            "a finite nominal pressure > 0 in Pa",
        ));
    }
    if let Some(&b) = bond_strengths
        .iter()
        .find(|b| !(b.is_finite() && **b > 0.0))
    {
        return Err(Error::invalid(
            "bond shear strength",
            b,
            "a finite strength > 0 in Pa",
        ));
    }
    if c.checks.substrate_yield && yield_strength.is_none() {
        return Err(Error::invalid(
            "substrate",
            "no yield strength",
            "a substrate yield_strength for the substrate-yield check",
        ));
    }
    Ok(())
}

/// The design engine and the search engine (at least [`crate::prec::SEARCH_RTOL`]), which
/// shares the design engine's grids where they coincide, and its kernel tables.
pub(crate) fn engines(spectrum: &Spectrum, settings: Settings) -> (Engine, Engine) {
    let engine = Engine::new(spectrum, settings);
    let search = engine.sibling(Settings {
        rtol: settings.rtol.max(crate::prec::SEARCH_RTOL),
    });
    (engine, search)
}

/// The largest value/limit among `checks` (a check with no limit counts 0), with its relative
/// error and its kind: what the minimum-thickness search drives below 1.
pub(crate) fn worst_utilisation<'a>(
    checks: impl IntoIterator<Item = &'a CheckResult>,
) -> Utilisation {
    let mut worst = Utilisation {
        value: 0.0,
        rel_err: 0.0,
        kind: None,
    };
    for c in checks {
        let u = c.value.value / c.limit.unwrap_or(f64::INFINITY);
        if u > worst.value || worst.kind.is_none() {
            worst = Utilisation {
                value: u,
                rel_err: c.value.err / c.value.value.abs(),
                kind: Some(c.kind),
            };
        }
    }
    worst
}

/// The scan range [d_lo, d_hi] of the minimum-thickness search for a spectrum on [q_low,
/// q_high] (module docs).
pub(crate) fn scan_range(q_low: f64, q_high: f64) -> (f64, f64) {
    let lo = (1e-6 / q_low).min(1e-4 / q_high).max(THINNEST);
    let hi = BULK_QD / q_low;
    (lo.min(hi), hi)
}
