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
//! Under sliding (`friction` μ > 0) or with the vector rule asked for, the rule is the film's
//! ([`ShearTail::resolve`], [`super`]): bond-shear at interface k judges the ε-peak of |τ| for
//! that interface's shear vector (μp0 + X_k, Y_k) ([`crate::contact::Engine::evaluate_stack_sliding`]),
//! P(|τ| > τ_bond,k) likewise, and substrate-yield's σ_rms includes the friction-driven part.
//! The min-thickness search is the film's under sliding ([`super::min_thickness`], "Under
//! sliding": the widened steps' thresholds lowered by the vector peak's spread ρ(ε), the peaks
//! one step from the bond limits). Its kernel argument is made for one film's g, √k_x and f_t;
//! on a stack it rests, as the static one does, on the interface kernels decaying like
//! e^{−q z_k} below a thick varied layer. Tested, not proven: the premise of the widened steps
//! on two stacks (every mode, every interface, as functions of the varied thickness) and d_min
//! against dense scans (`tests/it/stack_friction.rs`).
//!
//! The validity warnings are the film's ([`super`], "Validity"), with the bottom interface's
//! depth for the film thickness.
//!
//! Every check carries the interface's name ("bond-shear" at the interface below layer k is
//! named after layer k).

use super::basis::{Basis, Wording, check_warnings, finite_guard, governing, min_thickness_check};
use super::checker::{Peak, vector_peak};
use super::criteria::{limit, upper_check, yield_governing};
use super::{CheckKind, CheckResult, Criteria, MinThickness, ShearTail, Utilisation};
use crate::contact::{self, Engine, NormalStress, Request, SlidingShear, StackContact};
use crate::error::Error;
use crate::layer::Elastic;
use crate::layer::stack::{Layer, Stack};
use crate::prec::{Estimate, Settings};
use crate::psd::Spectrum;
use rayon::prelude::*;
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
    /// Sliding friction coefficient μ (0: static contact).
    pub friction: f64,
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
    /// The interface shear vector, when the vector rule is in force (friction or asked for).
    pub sliding: Option<SlidingShear>,
    /// The paper's half-normal peak of the static shear, beside a sliding `tau_peak`.
    pub tau_peak_static: Option<Estimate>,
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
    /// The rule every interface's `tau_peak` and `bond_exceedance` follow.
    pub shear_tail: ShearTail,
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

/// The stack's results and stress checks with the layer `thickness_of` at one thickness (a
/// row of the thickness sweep).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StackRow {
    /// The varied layer's thickness (m).
    pub thickness: f64,
    pub contact: StackContact,
    /// p0·A0/A (Pa).
    pub mean_contact_pressure: Estimate,
    pub interfaces: Vec<InterfaceEvaluation>,
    /// bond-shear at each interface and substrate-yield (those enabled).
    pub checks: Vec<StackCheck>,
}

impl StackOutcome {
    /// The check with the smallest margin (none passing counts least): the one that decides.
    pub fn governing(&self) -> Option<&StackCheck> {
        governing(&self.checks, |c| c.result.margin)
    }
}

/// Checks a stack design on one spectrum.
pub struct StackChecker {
    basis: Basis,
    design: StackDesign,
}

/// How a stack's validity warnings name its layers.
const STACK: Wording = Wording {
    what: "coating thickness (all layers)",
    depth: "q_L z at the bottom interface",
    exact: |_| String::new(),
    verify: "",
    strained: "coating",
};

impl StackChecker {
    pub fn new(
        spectrum: &Spectrum,
        design: StackDesign,
        settings: Settings,
    ) -> Result<Self, Error> {
        let bonds: Vec<f64> = design.layers.iter().map(|l| l.bond_strength).collect();
        let basis = Basis::new(
            spectrum,
            &design.criteria,
            design.pressure,
            &bonds,
            design.yield_strength,
            settings,
        )?;
        if design.thickness_of >= design.layers.len() {
            return Err(Error::invalid(
                "thickness_of",
                design.thickness_of,
                "a layer of the stack",
            ));
        }
        Ok(Self { basis, design })
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

    /// The peak-shear rule in force ([`ShearTail::resolve`]).
    pub fn shear_tail(&self) -> ShearTail {
        ShearTail::resolve(self.design.criteria.shear_tail, self.design.friction)
    }

    /// The engine quantities with the layer `thickness_of` at `d`, under sliding (every
    /// interface's shear vector too) when the design has friction or the vector rule is asked
    /// for.
    fn contact(
        &self,
        engine: &Engine,
        d: f64,
        req: Request,
    ) -> Result<(StackContact, Option<Vec<SlidingShear>>), Error> {
        let (stack, p0, mu) = (self.stack(d)?, self.design.pressure, self.design.friction);
        if mu > 0.0 || self.shear_tail() == ShearTail::Vector {
            engine.evaluate_stack_sliding(&stack, p0, mu, req)
        } else {
            Ok((engine.evaluate_stack(&stack, p0, req)?, None))
        }
    }

    /// The peak interface shear below `layer` by the rule in force, with P(|τ| > its bond) when
    /// `extras`: the paper's half-normal of τ_rms, or the vector's (`shear` given, found as `how`
    /// says; the film's rule, [`super::Checker`]).
    fn shear_peak(
        &self,
        layer: &StackLayer,
        tau: Estimate,
        shear: Option<&SlidingShear>,
        extras: bool,
        how: Peak,
    ) -> Result<(Estimate, Option<f64>), Error> {
        let c = &self.design.criteria;
        let bond = layer.bond_strength;
        match shear {
            Some(s) => vector_peak(
                s,
                bond,
                limit(bond, c.safety_factor),
                (c.epsilon, self.design.friction),
                extras,
                how,
            ),
            None => {
                let kt = contact::tau_peak(1.0, c.epsilon);
                let exceedance = extras.then(|| contact::tau_exceedance(tau.value, bond));
                Ok((tau.map(|t| kt * t, |_| kt), exceedance))
            }
        }
    }

    /// The stress checks and the interfaces' peaks from a contact on the stack (and every
    /// interface's shear vector under the vector rule, its peak found as `how` says). The
    /// interfaces' evaluations, with the exceedances and the static peaks beside a vector
    /// one, only with `extras` (empty without: the search needs only the checks).
    fn assess(
        &self,
        c: &StackContact,
        sliding: Option<&[SlidingShear]>,
        extras: bool,
        how: Peak,
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
            let shear = sliding.map(|s| &s[k]);
            let (tau_peak, exceedance) = self.shear_peak(layer, tau, shear, extras, how)?;
            let at = |s: f64| NormalStress { p0, sigma_rms: s };
            let yield_here = k == last && on.substrate_yield && ic.sigma_rms.is_some();
            let sigma_peak = (extras || yield_here).then(|| {
                let mut peak = at(sigma.value).peak(eps);
                peak.status = Estimate::worst(peak.status, sigma.status);
                peak.err += (at(sigma.value + sigma.err).peak(eps).value - peak.value).abs();
                peak
            });
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
            if let (true, Some(peak)) = (yield_here, sigma_peak) {
                let y = d.yield_strength.expect("checked in new");
                checks.push(StackCheck {
                    at: "substrate".into(),
                    result: upper_check(
                        CheckKind::SubstrateYield,
                        yield_governing(peak, mean, |e: &Estimate| e.value),
                        limit(y, sf),
                    ),
                });
            }
            let (Some(bond_exceedance), Some(sigma_peak)) = (exceedance, sigma_peak) else {
                continue;
            };
            let tau_peak_static = match shear {
                Some(_) => Some(self.shear_peak(layer, tau, None, false, how)?.0),
                None => None,
            };
            interfaces.push(InterfaceEvaluation {
                name: layer.name.clone(),
                depth: ic.depth,
                sigma_rms: sigma,
                tau_rms: tau,
                tau_peak,
                sigma_peak,
                bond_strength: layer.bond_strength,
                bond_exceedance,
                sliding: shear.copied(),
                tau_peak_static,
            });
        }
        Ok((mean, interfaces, checks))
    }

    /// Utilisation of the enabled stress checks with the layer `thickness_of` at `d`, the
    /// vector rule's peaks found as `how` says.
    fn utilisation(&self, d: f64, how: Peak) -> Result<Utilisation, Error> {
        let (c, sliding) = self.contact(&self.basis.search, d, self.request())?;
        let (_, _, checks) = self.assess(&c, sliding.as_deref(), false, how)?;
        Ok(super::checker::worst_utilisation(
            checks.iter().map(|c| &c.result),
        ))
    }

    /// Everything with the layer `thickness_of` at `d`, the others fixed: all quantities and
    /// the stress checks (those of [`run`](Self::run) at the design's thickness, to the last
    /// bit).
    pub fn evaluate(&self, d: f64) -> Result<StackRow, Error> {
        let (contact, sliding) = self.contact(&self.basis.engine, d, Request::all())?;
        let (mean_contact_pressure, interfaces, checks) =
            self.assess(&contact, sliding.as_deref(), true, Peak::Solved)?;
        Ok(StackRow {
            thickness: d,
            contact,
            mean_contact_pressure,
            interfaces,
            checks,
        })
    }

    /// [`evaluate`](Self::evaluate) at many thicknesses of the layer `thickness_of`, in
    /// parallel.
    pub fn sweep(&self, thicknesses: &[f64]) -> Result<Vec<StackRow>, Error> {
        thicknesses.par_iter().map(|&d| self.evaluate(d)).collect()
    }

    /// The h_rms (m) and rms slope of the spectrum the stack is judged with.
    pub fn roughness(&self) -> (f64, f64) {
        (self.basis.h_rms, self.basis.rms_slope)
    }

    /// Every enabled stress check passes at the design's thicknesses (what the levers
    /// search on, [`super::stack_levers`]).
    pub fn stress_checks_pass(&self) -> Result<bool, Error> {
        let d = &self.design;
        let thickness = d.layers[d.thickness_of].thickness;
        let (c, sliding) = self.contact(&self.basis.engine, thickness, self.request())?;
        let (_, _, checks) = self.assess(&c, sliding.as_deref(), false, Peak::Solved)?;
        Ok(checks.iter().all(|c| c.result.pass))
    }

    /// The scan range of the minimum-thickness search for the varied layer (as for a film).
    pub fn scan_range(&self) -> (f64, f64) {
        self.basis.scan_range()
    }

    /// The smallest thickness of the layer `thickness_of` above which every enabled stress
    /// check passes, the others fixed (under sliding as the film's, [`super::min_thickness`],
    /// "Under sliding", the vector peaks one step from the bond limits).
    pub fn min_thickness(&self) -> Result<MinThickness, Error> {
        let d = &self.design;
        self.basis
            .min_thickness(d.friction, d.criteria.epsilon, |t| {
                self.utilisation(t, Peak::FromLimit)
            })
    }

    /// The full check at the design's thicknesses.
    pub fn run(&self) -> Result<StackOutcome, Error> {
        let d = &self.design;
        let thickness = d.layers[d.thickness_of].thickness;
        let (contact, sliding) = self.contact(&self.basis.engine, thickness, Request::all())?;
        let (mean, interfaces, mut checks) =
            self.assess(&contact, sliding.as_deref(), true, Peak::Solved)?;
        let mut warnings = Vec::new();
        let min_thickness = if d.criteria.checks.min_thickness {
            let m = self.min_thickness()?;
            let layer = &d.layers[d.thickness_of];
            let result = min_thickness_check(layer.thickness, &m);
            if m.thickness.is_none() {
                warnings.push(format!(
                    "no thickness of layer '{}' passes: even a bulk layer fails the enabled checks",
                    layer.name
                ));
            } else if m.all_pass_to_floor {
                warnings.push(format!(
                    "every thickness of layer '{}' down to the scan floor {:.3e} m passes; d_min \
                     is reported as that floor",
                    layer.name, m.floor
                ));
            }
            checks.push(StackCheck {
                at: layer.name.clone(),
                result,
            });
            Some(m)
        } else {
            None
        };
        let depth: f64 = d.layers.iter().map(|l| l.thickness).sum();
        for c in &checks {
            let name = format!("{} at {}", c.result.kind.name(), c.at);
            warnings.extend(check_warnings(&name, &c.result));
            finite_guard(&name, &c.result, "")?;
        }
        warnings.extend(self.basis.validity_warnings(&contact.top, depth, &STACK));
        let pass = checks.iter().all(|c| c.result.pass);
        Ok(StackOutcome {
            contact,
            mean_contact_pressure: mean,
            interfaces,
            shear_tail: self.shear_tail(),
            min_thickness,
            checks,
            pass,
            warnings,
            h_rms: self.basis.h_rms,
            rms_slope: self.basis.rms_slope,
        })
    }
}
