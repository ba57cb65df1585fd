//! Spectral moments (h_rms², ξ², κ²): the closed form on power-law pieces against the model's
//! analytic integrals and against Gauss–Legendre quadrature of the same spectrum.

use crate::fixtures::measured_like;
use coatcheck::psd::Spectrum;
use std::f64::consts::PI;

/// 2π∫_{q0}^{q1} q^{1+k} (q/q0)^{−2(1+H)} dq in closed form (C0 = 1 at q0, no roll-off).
fn self_affine_moment(h: f64, q0: f64, q1: f64, k: i32) -> f64 {
    let p = f64::from(k) - 2.0 * h; // exponent of q in the integrand, minus one
    let scale = 2.0 * PI * q0.powf(2.0 + 2.0 * h);
    if p.abs() < 1e-15 {
        scale * (q1 / q0).ln()
    } else {
        scale * q0.powf(p) * ((p * (q1 / q0).ln()).exp_m1()) / p
    }
}

#[test]
fn self_affine_moments_match_the_analytic_integrals() {
    for h in [0.3, 0.8, 1.0] {
        for roll_off in [None, Some(3e5)] {
            let s = Spectrum::self_affine(h, 1e5, 1e8, roll_off).unwrap();
            for k in [0, 2, 4] {
                let m = s.moment(k);
                let mut want = self_affine_moment(h, 1e5, 1e8, k);
                if let Some(qr) = roll_off {
                    // Plateau C = C(q_r) on [q0, q_r], the power law from q_r on.
                    let c_r = 1.0;
                    let plateau =
                        2.0 * PI * c_r * (qr.powi(2 + k) - 1e5f64.powi(2 + k)) / f64::from(2 + k);
                    let tail = self_affine_moment(h, qr, 1e8, k);
                    want = plateau + tail;
                }
                let rel = ((m.value - want) / want).abs();
                assert!(rel < 1e-14, "H {h} {roll_off:?} k {k}: {rel:e}");
                assert!(
                    (m.value - want).abs() <= m.err,
                    "H {h} k {k}: estimate {:e}",
                    m.err
                );
            }
        }
    }
}

/// The closed form against 10-point Gauss–Legendre on every knot interval (a second route),
/// within the quadrature's own error estimate.
#[test]
fn tabulated_closed_form_equals_quadrature() {
    let s = measured_like(1000);
    for k in [-1, 0, 2, 4] {
        let a = s.moment(k);
        let b = s.moment_numerical(k);
        let rel = ((a.value - b.value) / b.value).abs();
        assert!(rel < 1e-13, "k {k}: {rel:e}");
        assert!((a.value - b.value).abs() <= a.err + b.err, "k {k}");
    }
}
