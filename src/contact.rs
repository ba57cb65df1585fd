//! Contact: G(q), P(q), A/A0, rms stresses and their distributions (App. B).
//! (Skeleton: filled in by the engine commit.)

use crate::layer::Stack;
use crate::prec::{Estimate, Settings};
use crate::psd::Spectrum;
use serde::Serialize;

/// Which quantities to compute; only these are evaluated (the area alone never touches f, g).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct Request {
    /// σ_rms at the top surface (z = 0).
    pub sigma_top: bool,
    /// σ_rms of the interface normal stress (z = d).
    pub sigma_interface: bool,
    /// τ_rms of the interface shear stress (z = d).
    pub tau_interface: bool,
    /// E_eff / E0 (Fig. 10).
    pub e_eff: bool,
}

impl Request {
    pub fn all() -> Self {
        Self {
            sigma_top: true,
            sigma_interface: true,
            tau_interface: true,
            e_eff: true,
        }
    }
}

/// Results at one thickness; fields not requested are `None`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Contact {
    pub thickness: f64,
    pub pressure: f64,
    /// G(q1), Pa².
    pub g1: Estimate,
    /// A/A0 = P(q1).
    pub area_fraction: Estimate,
    pub sigma_rms_top: Option<Estimate>,
    pub sigma_rms_interface: Option<Estimate>,
    pub tau_rms_interface: Option<Estimate>,
    pub e_eff_over_e_film: Option<Estimate>,
    /// Share of G(q1) that comes from the lowest octave [q_L, 2 q_L] of the spectrum.
    pub low_octave_share: f64,
}

/// The d-independent part of the contact integrals for one spectrum (quadrature grid, weights).
pub struct Engine {
    _spectrum: Spectrum,
    _settings: Settings,
}

impl Engine {
    pub fn new(spectrum: &Spectrum, settings: Settings) -> Self {
        Self {
            _spectrum: spectrum.clone(),
            _settings: settings,
        }
    }

    /// Evaluate at one stack (thickness) and nominal pressure p0 (Pa).
    pub fn evaluate(
        &self,
        _stack: &Stack,
        _p0: f64,
        _request: Request,
    ) -> Result<Contact, crate::Error> {
        todo!()
    }
}
