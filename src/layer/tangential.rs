//! Interface kernels of a tangential surface traction (sliding friction; not in the paper, whose
//! App. B treats the normal load only): g_t, f_t (in-plane), h (antiplane) and the
//! normal–tangential coupling c.
//!
//! Geometry and conventions as in [`crate::layer`]: film 0 (E0, ν0, thickness d) on 0 ≤ z ≤ d,
//! bonded at z = d to the substrate half-space 1, z into the solid, tension positive; one Fourier
//! mode with wavevector q along x, x = q·d.
//! - In-plane load σ_xz(x, 0) = t0 cos(qx), σ_zz(x, 0) = 0:
//!   σ_xz(x, d) = g_t t0 cos(qx), σ_zz(x, d) = f_t t0 sin(qx), and the surface normal
//!   displacement u_z(x, 0) = 2 c t0 sin(qx)/(q E0*), in the units of S (u_z = 2 S p/(q E0*)
//!   under a pressure mode p cos(qx)). By reciprocity c is also the surface u_x under pressure.
//! - Antiplane load σ_yz(x, 0) = t0 cos(qx): σ_yz(x, d) = h t0 cos(qx).
//! - A traction t0 cos(k·r) along x on a mode whose wavevector k makes the angle φ with x splits
//!   into t0 cos φ along k (in-plane) and −t0 sin φ across it (antiplane), so the interface
//!   carries σ_xz = (g_t cos²φ + h sin²φ) t0 cos(k·r), σ_yz = (g_t − h) cos φ sin φ t0 cos(k·r)
//!   and σ_zz = f_t cos φ t0 sin(k·r) (checked against a direct 3D solution).
//!
//! Derivation. Antiplane: u_y is harmonic, u_y = A e^{−qz} + B e^{qz} in the film and
//! C e^{−q(z−d)} below; σ_yz(0) = t0 and continuity of u_y, σ_yz at d give
//! h = 1/(cosh x + r sinh x), r = G0/G1. In-plane: the Papkovich–Neuber system of
//! [`crate::layer`] with the load column (σ_zz, σ_xz)(0) = (0, t0) in place of (s0, 0); its
//! determinant is the same, so the denominator D of S, f, g serves here too. Cramer's rule gives
//! polynomials in t = e^{−2x} and x, regrouped (symbolically, then checked numerically against a
//! 50-digit solve of the same system, `tests/data/tangential_ref.py`) into
//!
//! ```text
//! g_t = (1 + κ0) e^{−x} G / D,   f_t = (1 + κ0) e^{−x} F / D,   h = 2 e^{−x} / ((1 + t) + r(1 − t))
//! G = 2(1−ν0)(1 + t) − x(1 − t) − r [2(1−ν1) H + (1−2ν1) x(1 − t)]
//! F = (1−2ν0)(1 − t) + x(1 + t) + r [(1−2ν1) H + 2(1−ν1) x(1 − t)]
//! c D = −4r [a1(a0 + t) + a0(1 − t)] + 4x²t (1 − r)(1 + rκ1 − 2a0)
//!       + a0 (r − 1)(κ0 − rκ1) W/(1 + a0)
//! ```
//!
//! with κ = 3 − 4ν, a = 1 − 2ν, H = x(1 + t) − (1 − t) = 2e^{−x}(x cosh x − sinh x) and
//! W = (1 − t)² − 4x²t as in [`crate::layer`] (both ≥ 0, series below their branch points). The
//! expanded Cramer numerators are not usable as they stand: in G the r-terms
//! 2x(κ1 + t) − (1 + κ1)(1 − t) cancel to O(x²) (O(x³) at ν1 = ½), losing up to 16 digits at
//! x = 1e−8, and in c the constant terms cancel to O(r) out of O(r²); the forms above have no such
//! hidden cancellation: F, h and every term of D but one (bounded as in [`crate::layer`]) are
//! sums of non-negative terms, and 2x − (1 − t) = H + x(1 − t) is written as such. G changes sign
//! (once, at x = 1 for identical materials, g_t = (1 − x)e^{−x}): near its zero its two parts are
//! equal, each (1 + κ0)e^{−x} 2(1−ν0)(1 + t)/D, so g_t is accurate there in absolute terms, to a
//! few ulp of that size (measured: 5e−16 e^{−qd}). c changes sign between material pairs
//! (for two incompressible materials c = 4x²t(1 − r²)/D, positive for a soft film) and is
//! accurate to rounding of its largest term. Only decaying exponentials appear; beyond
//! x ≈ 745 e^{−x} underflows and g_t = f_t = h = 0, c = −a0/(1 + a0) to rounding.
//!
//! Difference. The friction-driven shear across the sliding direction goes with g_t − h, which
//! is O(x) (O(x²) on a rigid base) while g_t and h tend to 1. Over the common denominator,
//! g_t − h = e^{−x} N/(D H_d) with H_d = (1 + t) + r(1 − t) and
//!
//! ```text
//! N = −4(1−ν0) [(1 − t)(2ν0(1 − t) + x(1 + t))
//!               + r ((1 − t)(2ν0(1 + t) + 4a1 + x(1 − t)) + P (1 + t)) + r² P (1 − t)]
//!     − 2(r − 1)(1 + rκ1) W,        P = 2(1−ν1) H + a1 x(1 − t)
//! ```
//!
//! (checked against the 50-digit reference). The bracket is a sum of non-negative terms; the
//! W-term is positive only for r < 1, and then at most 2/3 of the bracket's first term:
//! 4(1−ν0)(1 − t)(2ν0(1 − t) + x(1 + t)) ≥ 4(1−ν0)(1 + 2ν0)(1 − t)² ≥ 4(1 − t)² (as
//! x(1 + t) ≥ 1 − t), against 2(1 − r)(1 + rκ1)W ≤ (8/3)(1 − t)². So at most a factor 3 is
//! lost, and g_t − h < 0 for every pair and x > 0.
//!
//! Limits (tested): identical materials g_t = (1 − x)e^{−x}, f_t = x e^{−x}, h = e^{−x},
//! c = −(1−2ν)/(2(1−ν)) (zero for an incompressible half-space); as x → 0 every pair gives
//! g_t → 1, h → 1, f_t/x → 1, c → −r(1−2ν1)/(2(1−ν0)) (the substrate's own coupling); a rigid
//! base gives h = 1/cosh x.
//!
//! Coupling. For rubber on steel (both ν = ½) c is not small against S: a thin incompressible
//! film sheared by t0 squeezes material along x and lifts the surface by ≈ q d² t0/(2G0),
//! against ≈ q² d³ p/(3G0) under pressure, so c/S ≈ 3/(2 q d) for r^{1/3} ≪ qd ≪ 1. The
//! uncoupled approximation (friction traction on the frictionless pressure field) is therefore
//! an assumption about the contact problem, not a property of the stack; see the tests for
//! measured c/S.

use super::{Bilayer, Blocks, x_cosh_minus_sinh};
use serde::Serialize;

/// Error bound of the kernels: relative for f_t and h; for g_t relative, or absolute in units
/// of e^{−qd}/100 where |g_t| is smaller than that (near its zero); for c relative to
/// max(|c|, S). Measured against the 50-digit reference over its 2011 cases
/// (`tangential_kernels_match_high_precision_reference`): at most 7e−16 for f_t, h, c and
/// 5e−16 e^{−qd} absolute for g_t at its zeros.
pub const TANGENTIAL_RTOL: f64 = 1e-13;

/// g_t, f_t, h and the coupling c at one value of q·d.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TangentialResponse {
    /// σ_xz(d)/σ_xz(0) under an in-plane tangential mode (changes sign).
    pub g_t: f64,
    /// σ_zz(x, d) = f_t t0 sin(qx) under σ_xz(x, 0) = t0 cos(qx).
    pub f_t: f64,
    /// σ_yz(d)/σ_yz(0) under an antiplane mode.
    pub h: f64,
    /// Surface u_z under the in-plane tangential mode, in the units of S.
    pub coupling: f64,
}

impl Bilayer {
    /// g_t, f_t, h and c at qd ≥ 0.
    pub fn tangential(&self, qd: f64) -> TangentialResponse {
        debug_assert!(qd >= 0.0);
        let x = qd;
        let b = Blocks::new(x);
        let (r, k0, k1, t, m) = (self.r, self.k0, self.k1, b.t, b.one_minus_t);
        let (nu0, nu1) = (self.film.poisson, self.substrate.poisson);
        let (a0, a1) = (1.0 - 2.0 * nu0, 1.0 - 2.0 * nu1);
        let den = self.denominator(&b);
        let h_blk = if x < 2.0 {
            2.0 * b.e1 * x_cosh_minus_sinh(x)
        } else {
            x * (1.0 + t) - m
        };
        let xm = x * m;
        let pre = (1.0 + k0) * b.e1 / den;
        let g = 2.0 * (1.0 - nu0) * (1.0 + t) - xm - r * (2.0 * (1.0 - nu1) * h_blk + a1 * xm);
        let f = a0 * m + x * (1.0 + t) + r * (a1 * h_blk + 2.0 * (1.0 - nu1) * xm);
        let c = -4.0 * r * (a1 * (a0 + t) + a0 * m)
            + 4.0 * x * x * t * (1.0 - r) * (1.0 + r * k1 - 2.0 * a0)
            + a0 * (r - 1.0) * (k0 - r * k1) * b.w / (1.0 + a0);
        TangentialResponse {
            g_t: pre * g,
            f_t: pre * f,
            h: 2.0 * b.e1 / ((1.0 + t) + r * m),
            coupling: c / den,
        }
    }

    /// f_t, h and g_t − h at qd ≥ 0 times e^{qd} (finite at every qd; the kernels themselves
    /// underflow above qd ≈ 745), with g_t − h from its own stable form (module doc,
    /// "Difference"): the literal difference of g_t and h, both near 1 at small qd, loses
    /// 1e−16/|g_t − h| relative, 5e−5 at qd = 1e−6 on a rigid base, where g_t − h = O(qd²).
    pub fn shear_undecayed(&self, qd: f64) -> ShearUndecayed {
        debug_assert!(qd >= 0.0);
        let x = qd;
        let b = Blocks::new(x);
        let (r, k0, k1, t, m) = (self.r, self.k0, self.k1, b.t, b.one_minus_t);
        let (nu0, nu1) = (self.film.poisson, self.substrate.poisson);
        let (a0, a1) = (1.0 - 2.0 * nu0, 1.0 - 2.0 * nu1);
        let den = self.denominator(&b);
        let h_blk = if x < 2.0 {
            2.0 * b.e1 * x_cosh_minus_sinh(x)
        } else {
            x * (1.0 + t) - m
        };
        let xm = x * m;
        let f = a0 * m + x * (1.0 + t) + r * (a1 * h_blk + 2.0 * (1.0 - nu1) * xm);
        let hd = (1.0 + t) + r * m;
        let p1 = 2.0 * (1.0 - nu1) * h_blk + a1 * xm;
        let neg = m * (2.0 * nu0 * m + x * (1.0 + t))
            + r * (m * (2.0 * nu0 * (1.0 + t) + 4.0 * a1 + xm) + p1 * (1.0 + t))
            + r * r * p1 * m;
        let n = -4.0 * (1.0 - nu0) * neg - 2.0 * (r - 1.0) * (1.0 + r * k1) * b.w;
        ShearUndecayed {
            f_t: (1.0 + k0) * f / den,
            h: 2.0 / hd,
            diff: n / (den * hd),
        }
    }
}

/// f_t, h and g_t − h times e^{qd} ([`Bilayer::shear_undecayed`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShearUndecayed {
    pub f_t: f64,
    pub h: f64,
    /// (g_t − h)·e^{qd}, < 0 for every pair and qd > 0.
    pub diff: f64,
}
