//! The contact probability P(G) = erf(p0/(2√G)) (eq. B11) as a function of G, with its slope
//! |dP/dG|, its u-derivatives along G(u) (for the quadrature's error terms), and σ_top²/2 =
//! ∫_0^{G1} P dG in closed form (eq. B8 at z = 0, F = 1). x = p0/(2√G) is P's argument; G = 0
//! gives x = ∞ and P = 1.

use crate::special::erf_and_gauss;
use libm::{erf, erfc};
use std::f64::consts::{FRAC_2_SQRT_PI, PI};

/// x = p0/(2√G), the argument of P = erf(x); ∞ at G = 0 (P = 1 there).
#[inline]
pub(super) fn probability_argument(p0: f64, g: f64) -> f64 {
    if g > 0.0 {
        0.5 * p0 / g.sqrt()
    } else {
        f64::INFINITY
    }
}

/// |dP/dG| = (p0 / (2√π)) G^{-3/2} e^{-p0²/(4G)} = (4/(√π p0²)) x³ e^{−x²} at x = p0/(2√G),
/// from e^{−x²} (`gauss`); 0 at G = 0 (x = ∞).
#[inline]
pub(super) fn probability_slope(p0: f64, x: f64, gauss: f64) -> f64 {
    if gauss > 0.0 {
        x * x * x * gauss * (2.0 * FRAC_2_SQRT_PI / (p0 * p0))
    } else {
        0.0
    }
}

/// P(G) = erf(p0 / (2√G)), with P(0) = 1.
pub(super) fn contact_probability(p0: f64, g: f64) -> f64 {
    erf_and_gauss(probability_argument(p0, g)).0
}

/// P(G) and |dP/dG| ([`probability_slope`]); (1, 0) at G = 0.
pub(super) fn probability_and_slope(p0: f64, g: f64) -> (f64, f64) {
    let x = probability_argument(p0, g);
    let (p, gauss) = erf_and_gauss(x);
    (p, probability_slope(p0, x, gauss))
}

/// P(G(u)) and its first four u-derivatives, for G' = `gp` at G = `g` growing locally like
/// e^{λu} (G'' = λG', G''' = λ²G', G'''' = λ³G'), by Faà di Bruno's formula with
/// P_k = d^k P/dG^k = −(a/√π) e^{−w} G^{−(2k+1)/2} Q_k(w), a = p0/2, w = a²/G,
/// Q1 = 1, Q2 = w − 3/2, Q3 = w² − 5w + 15/4, Q4 = w³ − 21w²/2 + 105w/4 − 105/8.
/// Given x = a/√G (∞ at G = 0) and 1/a² rather than G: w = x² and 1/G = x²/a² without a division.
/// `slope` is |dP/dG| = −P_1 at G ([`probability_slope`]), passed in to spare its `exp`.
pub(super) fn probability_derivatives(
    x: f64,
    inv_a2: f64,
    slope: f64,
    gp: f64,
    lam: f64,
    p: f64,
) -> [f64; 5] {
    if slope == 0.0 {
        // G = 0 (x = ∞) or e^{−x²} = 0 in f64: every derivative carries that factor.
        return [p, 0.0, 0.0, 0.0, 0.0];
    }
    // w = a²/G = x², 1/G = x²/a².
    let w = x * x;
    let inv_g = w * inv_a2;
    let q1 = w - 1.5;
    let q2 = w * (w - 5.0) + 3.75;
    let q3 = w * (w * (w - 10.5) + 26.25) - 13.125;
    // P_k = −|P_1| G^{1−k} Q_k.
    let s0 = -slope;
    let s1 = s0 * inv_g;
    let s2 = s1 * inv_g;
    let pk = [s0, s1 * q1, s2 * q2, s2 * inv_g * q3];
    let (g1, g2) = (gp, gp * lam);
    let (g3, g4) = (g2 * lam, g2 * lam * lam);
    let g1sq = g1 * g1;
    [
        p,
        pk[0] * g1,
        pk[1] * g1sq + pk[0] * g2,
        pk[2] * g1sq * g1 + 3.0 * pk[1] * g1 * g2 + pk[0] * g3,
        pk[3] * g1sq * g1sq
            + 6.0 * pk[2] * g1sq * g2
            + pk[1] * (4.0 * g1 * g3 + 3.0 * g2 * g2)
            + pk[0] * g4,
    ]
}

/// σ_top² / 2 = ∫_0^{G1} erf(a/√G) dG with a = p0/2, in closed form.
pub(super) fn top_variance_half(p0: f64, g1: f64) -> f64 {
    if g1 <= 0.0 {
        return 0.0;
    }
    let a = 0.5 * p0;
    let u = a / g1.sqrt();
    g1 * erf(u) + 2.0 * a * a / PI.sqrt() * ((-u * u).exp() / u - PI.sqrt() * erfc(u))
}
