//! Contact: G(q), P(q), A/A0 (eqs. B11, B12), rms stresses (B8–B10), E_eff (Fig. 10) and the
//! stress distributions of Appendix B.
//!
//! Conventions (notes.md): z = 0 is the film's top surface, z = d the film–substrate interface;
//! SI units throughout.
//! - G(q) = (π/4) E0*² ∫_{q_L}^{q} q'³ C S⁻² dq' (eq. B12, q_L the spectrum's lowest q),
//!   P(q) = erf(p0/(2√G)) (B11), A/A0 = P(q1).
//! - σ_rms(z)² = (π/2) E0*² ∫ q³ C S⁻² P F² dq = 2∫ P F² dG, F = 1 at z = 0, f at z = d; τ_rms² the
//!   same with g (B8–B10 with d²q = 2πq dq). At z = 0 this has a closed form in G(q1):
//!   σ_top² = 2[G1 erf(u) + (p0²/(2√π))(e^{−u²}/u − √π erfc u)], u = p0/(2√G1).
//! - E_eff*² = E0*² ∫q³C S⁻² dq / ∫q³C dq; reported as E_eff*/E0* ("E_eff/E_film").
//!
//! The modules: `grid` (the d-independent two-node quadrature in ln q and its error model),
//! `graded` (the interface integrals' graded panels near q_L), `kernels` (S⁻², f², g² at the
//! nodes), `engine` (the [`Engine`] and what it caches per spectrum), `evaluate` (one
//! evaluation on one grid, in phases), `probability` (P, its slope and derivatives) and
//! `distributions` (Appendix B's stress distributions and peak values), `stack` (the same on a
//! layer stack, at every interface); `sliding` the same integrals under a friction traction
//! (not in the paper).
//!
//! Every result is an [`Estimate`]: if the estimate misses rtol, the
//! evaluation is repeated on grids with panels halved, up to [`MAX_REFINE`] times, and reports
//! `ToleranceNotReached` if it still misses. An interface stress also counts as converged when
//! its error is below [`crate::prec::INTERFACE_ATOL`] (a few subnormal steps: a thick film's
//! stress that rounds into the subnormals or to 0).

mod distributions;
mod engine;
mod evaluate;
mod graded;
mod grid;
mod kernels;
mod probability;
mod sliding;
mod stack;
mod stack_sliding;

pub use distributions::{NormalStress, tau_exceedance, tau_pdf, tau_peak};
pub use engine::{Engine, ROUNDING_FLOOR, panel_width, rounding_floor};
pub use sliding::{SlidingShear, friction_coupling};
pub use stack::{InterfaceContact, StackContact};

use crate::prec::Estimate;
use serde::Serialize;

/// How many times a grid may be refined (panels halved) when the error estimate misses rtol.
pub const MAX_REFINE: usize = 3;
/// Safety factor on the divided-difference error estimate.
const ERR_SAFETY: f64 = 2.0;

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

    fn interface(&self) -> bool {
        self.sigma_interface || self.tau_interface
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
    /// Share of G(q1) from the lowest octave [q_L, 2 q_L] of the spectrum (1 when the spectrum
    /// spans less than an octave).
    pub low_octave_share: f64,
    /// How many kernel evaluations the result took (all grids tried).
    pub kernel_evaluations: usize,
    /// How many of them evaluated the interface kernels f, g as well as S (0 unless an
    /// interface stress was requested).
    pub interface_kernel_evaluations: usize,
}

/// `v` resized to `n` entries, keeping its allocation and its old values (new entries are
/// `x`): every buffer here is written before it is read, over the range that is read, so
/// clearing it first only cost a memset of every buffer per evaluation.
fn sized<T: Copy>(v: &mut Vec<T>, n: usize, x: T) -> &mut Vec<T> {
    v.resize(n, x);
    v
}
