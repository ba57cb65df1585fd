//! Stress distributions and peak values at the film's top surface and interface (Appendix B;
//! notes.md, "Distributions and peak values"): the interface shear is Gaussian with rms τ_rms,
//! the normal stress Persson's form centred at p0 with width σ_rms, restricted to σ ≥ 0.

use crate::prec::{Estimate, Termination};
use libm::{erf, erfc};
use statrs::function::erf::erfc_inv;
use std::f64::consts::PI;

/// Interface shear: Gaussian, zero mean, rms τ_rms; P(|τ| > level) = erfc(level/(√2 τ_rms)).
pub fn tau_exceedance(tau_rms: f64, level: f64) -> f64 {
    if tau_rms <= 0.0 {
        if level < 0.0 { 1.0 } else { 0.0 }
    } else {
        erfc(level / (std::f64::consts::SQRT_2 * tau_rms))
    }
}

/// The shear level exceeded on a fraction ε of the interface: √2 τ_rms erfc⁻¹(ε).
/// statrs' erfc⁻¹ is good to ~1e-11; two Newton steps on erfc bring it to rounding.
pub fn tau_peak(tau_rms: f64, epsilon: f64) -> f64 {
    let mut x = erfc_inv(epsilon);
    for _ in 0..2 {
        let slope = -2.0 / PI.sqrt() * (-x * x).exp();
        if slope == 0.0 {
            break;
        }
        x -= (erfc(x) - epsilon) / slope;
    }
    std::f64::consts::SQRT_2 * tau_rms * x
}

/// Half-normal density of |τ| (normalised on [0, ∞)).
pub fn tau_pdf(tau_rms: f64, tau: f64) -> f64 {
    let s = tau_rms;
    (2.0 / PI).sqrt() / s * (-0.5 * (tau / s).powi(2)).exp()
}

/// Normal stress: Persson's form centred at p0 with width σ_rms (4G → 2σ_rms²), restricted
/// to σ ≥ 0 and normalised there. At the top surface σ_rms² = 2G(q1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalStress {
    pub p0: f64,
    pub sigma_rms: f64,
}

impl NormalStress {
    fn scaled(&self, s: f64) -> (f64, f64, f64) {
        let k = std::f64::consts::SQRT_2 * self.sigma_rms;
        ((s - self.p0) / k, (s + self.p0) / k, self.p0 / k)
    }

    /// Density on σ ≥ 0: [e^{−(σ−p0)²/2σ²} − e^{−(σ+p0)²/2σ²}] / (√(2π) σ_rms erf(p0/(√2 σ_rms))).
    pub fn pdf(&self, s: f64) -> f64 {
        if s < 0.0 {
            return 0.0;
        }
        let (a, b, delta) = self.scaled(s);
        // e^{−a²} − e^{−b²} = e^{−a²}(1 − e^{−(b²−a²)}), b² − a² = 4 δ s/(√2 σ_rms) ≥ 0.
        let diff = (-a * a).exp() * -(-(b * b - a * a)).exp_m1();
        diff / ((2.0 * PI).sqrt() * self.sigma_rms * erf(delta))
    }

    /// Fraction of the area where the stress exceeds `level`.
    pub fn exceedance(&self, level: f64) -> f64 {
        if level <= 0.0 {
            return 1.0;
        }
        let (a, b, delta) = self.scaled(level);
        if delta < 1e-6 {
            // p0 ≪ σ_rms: the ratio tends to e^{−c²}, c = level/(√2σ_rms), with relative
            // corrections O(δ² c²).
            let c = 0.5 * (a + b);
            return (-c * c).exp();
        }
        ((erfc(a) - erfc(b)) / (2.0 * erf(delta))).clamp(0.0, 1.0)
    }

    /// The level exceeded on a fraction ε of the area, by bisection on the monotone tail to a
    /// relative width of 1e-13.
    pub fn peak(&self, epsilon: f64) -> Estimate {
        let mut lo = 0.0;
        let mut hi = self.p0 + self.sigma_rms;
        while self.exceedance(hi) > epsilon {
            lo = hi;
            hi *= 2.0;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if self.exceedance(mid) > epsilon {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo <= 1e-13 * hi {
                break;
            }
        }
        Estimate::new(
            0.5 * (lo + hi),
            (hi - lo) + 1e-12 * hi,
            Termination::Converged,
        )
    }
}
