//! Persson's theory under sliding (not in the paper, which treats static contact; notes.md,
//! "Sliding friction"): the rubber surface carries, besides its pressure σ(x), the friction
//! traction μσ(x) along the sliding direction x (full sliding, Amontons–Coulomb).
//!
//! Uncoupled approximation: the pressure field is that of frictionless contact (eqs. B8–B12
//! unchanged: the contact area and G(q) ignore the friction), and the friction traction is μ
//! times it. For a homogeneous incompressible solid the normal–tangential coupling vanishes and
//! this is exact; for a soft film bonded to a stiff substrate it does not
//! ([`crate::layer::tangential`], c/S ≈ 3/(2qd) for a thin incompressible film), and
//! [`friction_coupling`] reports its size over the spectrum.
//!
//! A mode of the pressure fluctuation with wavevector at angle φ to x and amplitude s loads the
//! interface with (kernels at q·d: f, g of eq. B7; g_t, f_t, h of the tangential load)
//!
//! ```text
//! σ_xz = s [μ (g_t cos²φ + h sin²φ) cos ψ + g cos φ sin ψ]
//! σ_yz = s [μ (g_t − h) cos φ sin φ cos ψ + g sin φ sin ψ]
//! σ_zz = s [f cos ψ + μ f_t cos φ sin ψ]                      (ψ = k·r + phase)
//! ```
//!
//! The pressure-driven and friction-driven parts are in quadrature (cos ψ against sin ψ), so
//! they are uncorrelated at a point; ⟨τ_x τ_y⟩ is odd in φ and vanishes on averaging over
//! directions: X and Y are independent. With ⟨cos⁴φ⟩ = ⟨sin⁴φ⟩ = 3/8, ⟨cos²φ sin²φ⟩ = 1/8, and
//! dV = (π/2) E0*² q³ C S⁻² P dq the pressure fluctuation's variance per dq (eqs. B8–B10):
//!
//! ```text
//! τ_x,rms² = τ_rms²/2 + μ² ∫ [((g_t + h)/2)² + (g_t − h)²/8] dV
//! τ_y,rms² = τ_rms²/2 + μ² ∫ (g_t − h)²/8 dV
//! σ_rms(d)² = ∫ (f² + μ² f_t²/2) dV
//! ```
//!
//! with τ_rms the static value (eq. B9; its two components share it equally). The mean friction
//! μp0 is a uniform traction (q = 0: g_t = 1) and passes the film unchanged: the interface shear
//! vector is (μp0 + X, Y). All kernels are squares, so the integrals go through the static
//! machinery ([`super::Engine`], with its error estimates and refinement) in one pass: σ's
//! kernel f² + μ²f_t²/2 in place of f², and the two friction kernels in two more slots summed
//! with the same G, P and nodes (each slot with its own cut and error estimate). g_t − h is a difference of two values near 1 at small q·d (it is O(q·d)): its
//! relative error there is about 1e−16/(q·d), 1e−10 at the thinnest films the checks scan
//! (q_L d = 1e−6), where τ_y's friction part is O((q·d)²) of τ_x's.
//!
//! Limits (tested): a thin film passes the friction fluctuation unchanged (g_t, h → 1:
//! τ_x,rms² → τ_rms²/2 + μ² σ_top², τ_y,rms² → τ_rms²/2); a thick one screens it (every kernel
//! decays as e^{−qd}); μ = 0 gives τ_x = τ_y = τ_rms/√2 and the static σ_rms(d) exactly.

use super::kernels::Mix;
use super::{Contact, Engine, Request};
use crate::error::Error;
use crate::layer::Stack;
use crate::prec::{EPS, Estimate};
use serde::Serialize;

/// The interface shear under sliding at one thickness.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SlidingShear {
    /// The friction coefficient μ.
    pub friction: f64,
    /// The mean interface shear μ p0 along x (Pa).
    pub mean: Estimate,
    /// The rms of the fluctuation along x (Pa).
    pub tau_x_rms: Estimate,
    /// The rms of the fluctuation along y (Pa).
    pub tau_y_rms: Estimate,
    /// [`friction_coupling`] where a report asks for it (`None` from the engine).
    pub coupling: Option<f64>,
}

impl Engine {
    /// The contact under sliding with friction μ ≥ 0 (module doc): the static results, except
    /// that `sigma_rms_interface` includes the friction-driven part; with `tau_interface`
    /// requested, also the interface shear vector's mean and rms (the friction slots only when
    /// μ > 0).
    pub fn evaluate_sliding(
        &self,
        stack: &Stack,
        p0: f64,
        mu: f64,
        request: Request,
    ) -> Result<(Contact, Option<SlidingShear>), Error> {
        if !(mu.is_finite() && mu >= 0.0) {
            return Err(Error::invalid(
                "friction coefficient",
                mu,
                "a finite value >= 0",
            ));
        }
        let mu2 = mu * mu;
        let mix = if mu > 0.0 {
            Mix::Sliding { mu2 }
        } else {
            Mix::Static
        };
        let (contact, pair) = self.evaluate_mixed(stack, p0, request, mix)?;
        let Some(tau) = contact.tau_rms_interface else {
            return Ok((contact, None));
        };
        let [fx, fy] = pair.unwrap_or([Estimate::exact(0.0); 2]);
        let component = |f: Estimate| combine(tau, mu2, f);
        let shear = SlidingShear {
            friction: mu,
            mean: Estimate::exact(mu * p0),
            tau_x_rms: component(fx),
            tau_y_rms: component(fy),
            coupling: None,
        };
        Ok((contact, Some(shear)))
    }
}

/// √(τ²/2 + μ² F²) with the errors of τ and F propagated to first order.
pub(super) fn combine(tau: Estimate, mu2: f64, f: Estimate) -> Estimate {
    let v = 0.5 * tau.value * tau.value + mu2 * f.value * f.value;
    let dv = tau.value * tau.err + 2.0 * mu2 * f.value * f.err;
    let s = v.sqrt();
    let err = if s > 0.0 { dv / (2.0 * s) } else { dv.sqrt() };
    Estimate::new(
        s,
        err + 4.0 * EPS * s,
        Estimate::worst(tau.status, f.status),
    )
}

/// The size of the normal–tangential coupling the uncoupled approximation neglects: the
/// largest μ|c(qd)|/S(qd) over the spectrum's wavenumbers [q_lo, q_hi] (the surface normal
/// displacement the friction traction μσ of one mode causes, relative to the pressure's own),
/// sampled at 64 points per decade. Zero for μ = 0.
pub fn friction_coupling(stack: &Stack, mu: f64, (q_lo, q_hi): (f64, f64)) -> f64 {
    if mu == 0.0 {
        return 0.0;
    }
    let (a, b) = ((q_lo * stack.thickness).ln(), (q_hi * stack.thickness).ln());
    let n = (((b - a) / std::f64::consts::LN_10) * 64.0).ceil().max(1.0) as usize;
    (0..=n)
        .map(|i| {
            let x = (a + (b - a) * i as f64 / n as f64).exp();
            let c = stack.layers.tangential(x).coupling;
            mu * c.abs() / stack.layers.s(x)
        })
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    /// The averages of the module doc from its per-mode stresses: over the direction φ and the
    /// phase ψ (trapezoid rule on 64 × 64 points, exact for these trigonometric polynomials),
    /// ⟨σ_xz²⟩, ⟨σ_yz²⟩ and ⟨σ_zz²⟩ per unit s² equal the kernel sums /2, and ⟨σ_xz σ_yz⟩ = 0.
    #[test]
    fn direction_and_phase_averages_match_the_kernel_sums() {
        let (g, f, g_t, f_t, h, mu) = (0.37, 0.81, -0.23, 0.44, 0.66, 0.9);
        let n = 64;
        let (mut xx, mut yy, mut zz, mut xy) = (0.0, 0.0, 0.0, 0.0);
        for i in 0..n {
            let phi = 2.0 * PI * i as f64 / n as f64;
            let (c, s) = (phi.cos(), phi.sin());
            for j in 0..n {
                let psi = 2.0 * PI * j as f64 / n as f64;
                let tx = mu * (g_t * c * c + h * s * s) * psi.cos() + g * c * psi.sin();
                let ty = mu * (g_t - h) * c * s * psi.cos() + g * s * psi.sin();
                let sz = f * psi.cos() + mu * f_t * c * psi.sin();
                xx += tx * tx;
                yy += ty * ty;
                zz += sz * sz;
                xy += tx * ty;
            }
        }
        let m = (n * n) as f64;
        let ky = (g_t - h) * (g_t - h) / 8.0;
        let kx = (0.5 * (g_t + h)) * (0.5 * (g_t + h)) + ky;
        // The variance of a mode of amplitude s is s²/2: the kernel sums are per unit s²/2.
        let want = [
            0.5 * (0.5 * g * g + mu * mu * kx),
            0.5 * (0.5 * g * g + mu * mu * ky),
            0.5 * (f * f + 0.5 * mu * mu * f_t * f_t),
        ];
        for (got, w) in [xx / m, yy / m, zz / m].into_iter().zip(want) {
            assert!((got - w).abs() < 1e-15, "{got} vs {w}");
        }
        assert!((xy / m).abs() < 1e-15);
    }
}
