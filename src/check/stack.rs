//! The design checks on a layer stack (the film's checks of [`super`] at every interface):
//!
//! - `bond-shear` at every interface k against its own bond: the ε-peak of the interface shear
//!   (Gaussian with rms τ_rms,k, eq. B9 with g_k) must not exceed τ_bond,k / safety factor;
//! - `substrate-yield` at the bottom interface (the substrate's surface): the larger of the
//!   mean pressure in real contact p0·A0/A and the ε-peak of the normal stress there (σ_rms,N,
//!   eq. B8 with f_N) must not exceed σ_yield / safety factor;
//! - `min-thickness` for one layer (`thickness_of`, default the top), the others fixed: the
//!   search of [`super::min_thickness`] over that layer's thickness, on the utilisation of the
//!   checks above. Its argument that nothing fails above the scan start (q_L·d = 10) holds as
//!   for a film when the varied layer is the top one and the layers below are thin: the
//!   interface stresses below a thick top layer decay like e^{−q_L d}. For a layer lower down,
//!   the stack above it keeps the interfaces above it loaded at every thickness; their
//!   utilisation tends to that of the stack with a half-space of the varied layer's material,
//!   which the bulk bound evaluates.
//!
//! The validity warnings are the film's ([`super`], "Validity"), with the bottom interface's
//! depth for the film thickness.
//!
//! Every check carries the interface's name ("bond-shear" at the interface below layer k is
//! named after layer k).

use super::criteria::{limit, upper_check, yield_governing};
use super::{
    CheckKind, CheckResult, Criteria, FULL_CONTACT_WARN, LOW_OCTAVE_WARN, MinThickness, SLOPE_WARN,
    Utilisation, search_min_thickness,
};
use crate::contact::{self, Contact, Engine, NormalStress, Request, StackContact};
use crate::error::Error;
use crate::layer::Elastic;
use crate::layer::stack::{Layer, Stack};
use crate::prec::{Estimate, Settings};
use crate::psd::Spectrum;
use serde::Serialize;

/// One layer of a stack design: its name, material, thickness (m) and the shear strength of
/// its bond to what lies below (Pa).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StackLayer {
    pub name: String,
    pub material: Elastic,
    pub thickness: f64,
    pub bond_strength: f64,
}

/// A stack design: the layers (top first), the substrate, the load, the criteria and the layer
/// whose minimum thickness is sought.
#[derive(Debug, Clone, PartialEq)]
pub struct StackDesign {
    pub layers: Vec<StackLayer>,
    pub substrate: Elastic,
    /// Nominal pressure p0 (Pa).
    pub pressure: f64,
    /// Substrate yield strength (Pa); required by substrate-yield.
    pub yield_strength: Option<f64>,
    pub criteria: Criteria,
    /// Index of the layer whose minimum thickness is sought (0 = top).
    pub thickness_of: usize,
}

/// The stresses at one interface and their peaks.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InterfaceEvaluation {
    /// The layer above the interface.
    pub name: String,
    pub depth: f64,
    pub sigma_rms: Estimate,
    pub tau_rms: Estimate,
    /// τ at exceedance ε (Pa).
    pub tau_peak: Estimate,
    /// Normal stress at exceedance ε (Pa).
    pub sigma_peak: Estimate,
    /// The bond's shear strength (Pa) and P(|τ| > it).
    pub bond_strength: f64,
    pub bond_exceedance: f64,
}

/// A stack check's result, with the interface (layer name) it concerns.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StackCheck {
    pub at: String,
    pub result: CheckResult,
}

/// The verdict on one stack design.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StackOutcome {
    pub contact: StackContact,
    /// p0·A0/A (Pa).
    pub mean_contact_pressure: Estimate,
    pub interfaces: Vec<InterfaceEvaluation>,
    pub min_thickness: Option<MinThickness>,
    /// bond-shear at each interface, substrate-yield, min-thickness (those enabled).
    pub checks: Vec<StackCheck>,
    pub pass: bool,
    pub warnings: Vec<String>,
    /// h_rms of the spectrum used, m.
    pub h_rms: f64,
    /// Rms slope of the spectrum used.
    pub rms_slope: f64,
}

/// Checks a stack design on one spectrum.
pub struct StackChecker {
    engine: Engine,
    search: Engine,
    design: StackDesign,
    q_low: f64,
    q_high: f64,
    /// Rms slope ξ of the spectrum.
    rms_slope: f64,
    /// h_rms of the spectrum, m.
    h_rms: f64,
}

impl StackChecker {
    pub fn new(
        spectrum: &Spectrum,
        design: StackDesign,
        settings: Settings,
    ) -> Result<Self, Error> {
        let bonds: Vec<f64> = design.layers.iter().map(|l| l.bond_strength).collect();
        super::checker::validate(
            &design.criteria,
            design.pressure,
            &bonds,
            design.yield_strength,
        )?;
        if design.thickness_of >= design.layers.len() {
            return Err(Error::invalid(
                "thickness_of",
                design.thickness_of,
                "a layer of the stack",
            ));
        }
        let (q_low, q_high) = spectrum.support();
        let (engine, search) = super::checker::engines(spectrum, settings);
        Ok(Self {
            engine,
            search,
            design,
            q_low,
            q_high,
            rms_slope: spectrum.slope_sq().value.sqrt(),
            h_rms: spectrum.h_rms_sq().value.sqrt(),
        })
    }

    pub fn design(&self) -> &StackDesign {
        &self.design
    }

    /// The stack with the layer `thickness_of` at thickness `d`.
    fn stack(&self, d: f64) -> Result<Stack, Error> {
        let layers = self
            .design
            .layers
            .iter()
            .enumerate()
            .map(|(i, l)| Layer {
                material: l.material,
                thickness: if i == self.design.thickness_of {
                    d
                } else {
                    l.thickness
                },
            })
            .collect();
        Stack::new(layers, self.design.substrate)
    }

    fn request(&self) -> Request {
        let on = self.design.criteria.checks;
        Request {
            sigma_top: false,
            // Every interface's peaks are reported; the search asks only for what it checks.
            sigma_interface: on.substrate_yield,
            tau_interface: on.bond_shear,
            e_eff: false,
        }
    }

    /// The stress checks and the interfaces' peaks from a contact on the stack.
    fn assess(
        &self,
        c: &StackContact,
    ) -> Result<(Estimate, Vec<InterfaceEvaluation>, Vec<StackCheck>), Error> {
        let d = &self.design;
        let (eps, p0, sf) = (d.criteria.epsilon, d.pressure, d.criteria.safety_factor);
        let area = c.top.area_fraction;
        if area.value.is_nan() || area.value <= 0.0 {
            return Err(Error::Numerical {
                what: "contact area",
                detail: format!("A/A0 = {} on the stack", area.value),
            });
        }
        let mean = area.map(|a| p0 / a, |a| p0 / (a * a));
        let on = d.criteria.checks;
        let mut interfaces = Vec::new();
        let mut checks = Vec::new();
        let last = c.interfaces.len() - 1;
        for (k, (ic, layer)) in c.interfaces.iter().zip(&d.layers).enumerate() {
            let none = Estimate::exact(0.0);
            let tau = ic.tau_rms.unwrap_or(none);
            let sigma = ic.sigma_rms.unwrap_or(none);
            let kt = contact::tau_peak(1.0, eps);
            let tau_peak = tau.map(|t| kt * t, |_| kt);
            let at = |s: f64| NormalStress { p0, sigma_rms: s };
            let mut sigma_peak = at(sigma.value).peak(eps);
            sigma_peak.status = Estimate::worst(sigma_peak.status, sigma.status);
            sigma_peak.err +=
                (at(sigma.value + sigma.err).peak(eps).value - sigma_peak.value).abs();
            if on.bond_shear && ic.tau_rms.is_some() {
                checks.push(StackCheck {
                    at: layer.name.clone(),
                    result: upper_check(
                        CheckKind::BondShear,
                        tau_peak,
                        limit(layer.bond_strength, sf),
                    ),
                });
            }
            if k == last && on.substrate_yield && ic.sigma_rms.is_some() {
                let y = d.yield_strength.expect("checked in new");
                checks.push(StackCheck {
                    at: "substrate".into(),
                    result: upper_check(
                        CheckKind::SubstrateYield,
                        yield_governing(sigma_peak, mean, |e: &Estimate| e.value),
                        limit(y, sf),
                    ),
                });
            }
            interfaces.push(InterfaceEvaluation {
                name: layer.name.clone(),
                depth: ic.depth,
                sigma_rms: sigma,
                tau_rms: tau,
                tau_peak,
                sigma_peak,
                bond_strength: layer.bond_strength,
                bond_exceedance: contact::tau_exceedance(tau.value, layer.bond_strength),
            });
        }
        Ok((mean, interfaces, checks))
    }

    /// Utilisation of the enabled stress checks with the layer `thickness_of` at `d`.
    fn utilisation(&self, d: f64) -> Result<Utilisation, Error> {
        let c =
            self.search
                .evaluate_stack(&self.stack(d)?, self.design.pressure, self.request())?;
        let (_, _, checks) = self.assess(&c)?;
        Ok(super::checker::worst_utilisation(
            checks.iter().map(|c| &c.result),
        ))
    }

    /// The scan range of the minimum-thickness search for the varied layer (as for a film).
    pub fn scan_range(&self) -> (f64, f64) {
        super::checker::scan_range(self.q_low, self.q_high)
    }

    /// The smallest thickness of the layer `thickness_of` above which every enabled stress
    /// check passes, the others fixed.
    pub fn min_thickness(&self) -> Result<MinThickness, Error> {
        let (lo, hi) = self.scan_range();
        search_min_thickness(lo, hi, |d| self.utilisation(d))
    }

    /// Where the theory is strained, as for a film ([`super`], "Validity"), with the depth of
    /// the bottom interface for the film thickness.
    fn validity_warnings(&self, c: &Contact) -> Vec<String> {
        let mut w = Vec::new();
        let depth: f64 = self.design.layers.iter().map(|l| l.thickness).sum();
        if self.q_high > 2.0 * self.q_low && c.low_octave_share > LOW_OCTAVE_WARN {
            w.push(format!(
                "{:.0} % of G(q1) (the contact stress variance) comes from the lowest octave of the \
                 spectrum (q_L z = {:.3} at the bottom interface): a few long waves carry the \
                 contact, where Persson's theory under-estimates the contact area, so the \
                 contact-pressure figures (mean pressure in contact, sigma peaks) are \
                 conservative; the result also depends on where the data start (q_min)",
                100.0 * c.low_octave_share,
                self.q_low * depth
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
                 such slopes the coating's strains are large and the stresses are indicative only",
                self.rms_slope
            ));
        }
        w.extend(super::checker::data_warnings(
            "coating thickness (all layers)",
            depth,
            self.h_rms,
            self.q_low,
        ));
        w
    }

    /// The full check at the design's thicknesses.
    pub fn run(&self) -> Result<StackOutcome, Error> {
        let d = &self.design;
        let req = Request::all();
        let contact = self.engine.evaluate_stack(
            &self.stack(d.layers[d.thickness_of].thickness)?,
            d.pressure,
            req,
        )?;
        let (mean, interfaces, mut checks) = self.assess(&contact)?;
        let mut warnings = Vec::new();
        let min_thickness = if d.criteria.checks.min_thickness {
            let m = self.min_thickness()?;
            let layer = &d.layers[d.thickness_of];
            let value = Estimate::exact(layer.thickness);
            let result = match m.thickness {
                Some(dm) => CheckResult {
                    kind: CheckKind::MinThickness,
                    value,
                    limit: Some(dm.value),
                    margin: Some(1.0 - dm.value / layer.thickness),
                    pass: layer.thickness >= dm.value,
                    undecided: (layer.thickness - dm.value).abs() <= dm.err,
                },
                None => {
                    warnings.push(format!(
                        "no thickness of layer '{}' passes: even a bulk layer fails the enabled checks",
                        layer.name
                    ));
                    CheckResult {
                        kind: CheckKind::MinThickness,
                        value,
                        limit: None,
                        margin: None,
                        pass: false,
                        undecided: false,
                    }
                }
            };
            checks.push(StackCheck {
                at: layer.name.clone(),
                result,
            });
            Some(m)
        } else {
            None
        };
        for c in &checks {
            if c.result.undecided {
                warnings.push(format!(
                    "{} at {}: the value is within its numerical error of the limit; the verdict is fragile",
                    c.result.kind.name(),
                    c.at
                ));
            }
            if !(c.result.value.value.is_finite() && c.result.value.err.is_finite()) {
                return Err(Error::Numerical {
                    what: "design check",
                    detail: format!(
                        "{} at {}: value {:e} ± {:e}",
                        c.result.kind.name(),
                        c.at,
                        c.result.value.value,
                        c.result.value.err
                    ),
                });
            }
        }
        warnings.extend(self.validity_warnings(&contact.top));
        let pass = checks.iter().all(|c| c.result.pass);
        if !pass {
            warnings.push(
                "what alone would make a failing stack pass (the levers of a one-layer check) is \
                 not searched for layer stacks yet"
                    .into(),
            );
        }
        Ok(StackOutcome {
            contact,
            mean_contact_pressure: mean,
            interfaces,
            min_thickness,
            checks,
            pass,
            warnings,
            h_rms: self.h_rms,
            rms_slope: self.rms_slope,
        })
    }
}
