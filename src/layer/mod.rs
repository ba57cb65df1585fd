//! Layered response: S(q) of eq. (7) and the static interface kernels f(qd), g(qd) (App. B).
//!
//! Geometry (notes.md): a film, material 0 (E0, ν0, thickness d), occupies 0 ≤ z ≤ d and is
//! bonded to a substrate half-space, material 1, at z = d; z points into the solid. One Fourier
//! mode of normal stress σ_zz(x, 0) = s0 cos(qx) acts on the frictionless top surface.
//! - S(qd) = u_z(0) q E0* / (2p): the surface compliance over that of a half-space of film
//!   material, so M_zz = −2S/(qE0*) (eq. 6) and u_z(q) = 2 S p(q)/(q E0*).
//! - f(qd) = σ_zz(d)/σ_zz(0), and g(qd) by σ_xz(x, d) = g s0 sin(qx): the static limit of
//!   eq. (B7). Both are ≥ 0 for every pair of materials.
//!
//! Derivation: Papkovich–Neuber potentials 2μu = ∇(φ + zψ) − 4(1−ν)ψ e_z (finite at ν = ½),
//! φ, ψ ∝ e^{iqx ± qz} in the film and decaying in the substrate; six boundary conditions
//! (σ_zz, σ_xz at z = 0; u_x, u_z, σ_zz, σ_xz continuous at z = d) solved by Cramer's rule. The
//! surface displacement reproduces eq. (7) exactly (tested to 1e-13 against a 100-digit solve of
//! the same 6×6 system, `tests/data/kernels_ref.py`).
//!
//! Stable form. With x = qd, t = e^{−2x}, κ = 3 − 4ν, r = G0/G1 and P = (r + κ0)(1 + rκ1) (eq. 7
//! multiplied through by P):
//!
//! ```text
//! S = N/D,  N = (1 + rκ1)[r B + Cm + (κ0 − 1) A] + t² r (1 + κ0)(1 + κ1)
//!           D = (1 + κ0)[(1 − t) + κ0 t + t²] + r(1 + κ0)(1 − t)(κ1 + t) + (r − 1)(1 + rκ1) W
//! f = (1 + κ0) e^{−x} [2(1−ν0)(1 + t) + 2r(1−ν1)(1 − t) + x((1 − t) + r(κ1 + t))] / D
//! g = (1 + κ0) e^{−x} [(1−2ν0) H + 2ν0 x(1 + t) + r x(κ1 − t) + r(1−2ν1)(1 − t)] / D
//! A = 1 − t²,  B = 1 − t² + 4xt,  Cm = 2t(sinh 2x − 2x),  W = 4t(sinh²x − x²),
//! H = 2e^{−x}(x cosh x − sinh x)
//! ```
//!
//! κ − 1 and κ1 − t are evaluated as 2(1 − 2ν) and 2(1 − 2ν1) + (1 − t), exact near ν = ½.
//! Every term is non-negative except (r − 1)(1 + rκ1)W for r < 1, which is at most 2/3 of the
//! positive part of D (W ≤ (1 − t)² and (1 − r)(1 + rκ1) ≤ 4/3), so no digits are lost to
//! cancellation: the literal eq. (7) loses up to 7 digits at small qd (all of them for a rigid
//! base), these forms lose none. A, B, 1 − t use `exp_m1`; Cm, W, H, which vanish like x³, x⁴,
//! x³, use their Taylor series below the branch points (x < 1 for Cm, x < 2 for W and H), where
//! the series are truncated below 1e-19 of their sum, and the direct forms above, where
//! the subtraction loses at most a factor 2.2 (≈ 1 bit). For x > 700, S = 1 to all f64 digits
//! (corrections are O(x² e^{−2x})); f and g keep their forms, with e^{−x} applied last (as
//! e^{−x/2}·e^{−x/2}) when e^{−x}/D would leave the normal range, so they keep full relative
//! accuracy down to 2.2e−308 and round into the subnormal range below it.
//!
//! [`KernelTable`] tabulates S⁻², f², g² for one material pair, checked against these forms to
//! 2e−14, for the contact integrals' many evaluations per thickness.

use crate::error::Error;
use serde::Serialize;

/// An isotropic linear-elastic material: Young's modulus (Pa) and Poisson ratio in [0, 0.5].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Elastic {
    pub youngs: f64,
    pub poisson: f64,
}

impl Elastic {
    pub fn new(youngs: f64, poisson: f64) -> Result<Self, Error> {
        if !(youngs.is_finite() && youngs > 0.0) {
            return Err(Error::invalid(
                "Young's modulus",
                youngs,
                "a finite E > 0 in Pa",
            ));
        }
        if !(poisson.is_finite() && (0.0..=0.5).contains(&poisson)) {
            return Err(Error::invalid("Poisson ratio", poisson, "0 <= nu <= 0.5"));
        }
        Ok(Self { youngs, poisson })
    }

    /// Plane-strain modulus E* = E/(1 − ν²).
    pub fn e_star(&self) -> f64 {
        self.youngs / (1.0 - self.poisson * self.poisson)
    }

    /// Shear modulus E/(2(1 + ν)).
    pub fn shear_modulus(&self) -> f64 {
        self.youngs / (2.0 * (1.0 + self.poisson))
    }
}

/// S, f and g at one value of q·d.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Response {
    pub s: f64,
    pub f: f64,
    pub g: f64,
}

/// A film (material 0) bonded to a substrate half-space (material 1): the d-independent part,
/// with the material constants of the stable forms precomputed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bilayer {
    pub film: Elastic,
    pub substrate: Elastic,
    r: f64,
    k0: f64,
    k1: f64,
}

/// Above this q·d, S = 1 in f64 (S − 1 = O(x² e^{−2x})).
const QD_BULK: f64 = 700.0;
/// Above this q·d, f and g (e^{−x} times a rational factor of order x: at most 2(1 + x) for f,
/// and far below e^{745} for both) are below half the smallest subnormal: exactly 0 in f64.
const QD_ZERO: f64 = 1490.0;

pub mod stack;
mod table;
pub mod tangential;
mod tangential_table;
pub use table::{KernelTable, Nodes, Squared, X_FAR};
pub use tangential_table::{TangentialTable, undecayed_squares};

/// 1/(2k+3)! for k = 0..14: Taylor coefficients of (sinh y − y)/y³ in y².
const SINH_COEF: [f64; 15] = {
    let mut c = [0.0; 15];
    let mut fact = 6.0; // 3!
    let mut k = 0;
    while k < 15 {
        c[k] = 1.0 / fact;
        fact *= ((2 * k + 4) * (2 * k + 5)) as f64;
        k += 1;
    }
    c
};

/// (2k+2)/(2k+3)! for k = 0..14: Taylor coefficients of (x cosh x − sinh x)/x³ in x².
const XCOSH_COEF: [f64; 15] = {
    let mut c = [0.0; 15];
    let mut k = 0;
    while k < 15 {
        c[k] = SINH_COEF[k] * (2 * k + 2) as f64;
        k += 1;
    }
    c
};

/// Σ c_k y^{2k} by Horner's rule, with as many terms as 0 ≤ y ≤ 2 needs: the first term
/// left out is below 1e-19 of the sum (6 terms for y < 1/4, 9 for y < 1, all 15 up to 2).
fn even_series(c: &[f64; 15], y: f64) -> f64 {
    let y2 = y * y;
    let m = if y < 0.25 {
        6
    } else if y < 1.0 {
        9
    } else {
        15
    };
    c[..m].iter().rev().fold(0.0, |acc, &ck| acc * y2 + ck)
}

/// sinh y − y for 0 ≤ y ≤ 2 by its Taylor series.
fn sinh_minus_id(y: f64) -> f64 {
    y * y * y * even_series(&SINH_COEF, y)
}

/// x cosh x − sinh x = Σ_{k≥1} 2k x^{2k+1}/(2k+1)! for 0 ≤ x ≤ 2 (all terms positive).
fn x_cosh_minus_sinh(x: f64) -> f64 {
    x * x * x * even_series(&XCOSH_COEF, x)
}

/// The x-dependent building blocks of the stable forms, all ≥ 0.
struct Blocks {
    e1: f64,
    t: f64,
    one_minus_t: f64,
    a: f64,
    b: f64,
    cm: f64,
    w: f64,
}

impl Blocks {
    fn new(x: f64) -> Self {
        let e1 = (-x).exp();
        let t = e1 * e1;
        let one_minus_t = -(-2.0 * x).exp_m1();
        let a = one_minus_t * (1.0 + t);
        let xt = x * t;
        let b = a + 4.0 * xt;
        let cm = if x < 1.0 {
            2.0 * t * sinh_minus_id(2.0 * x)
        } else {
            a - 4.0 * xt
        };
        let w = if x < 2.0 {
            let smx = sinh_minus_id(x);
            4.0 * t * smx * (smx + 2.0 * x)
        } else {
            let xe = x * e1;
            one_minus_t * one_minus_t - 4.0 * xe * xe
        };
        Self {
            e1,
            t,
            one_minus_t,
            a,
            b,
            cm,
            w,
        }
    }
}

impl Bilayer {
    pub fn new(film: Elastic, substrate: Elastic) -> Self {
        let r = film.shear_modulus() / substrate.shear_modulus();
        Self {
            film,
            substrate,
            r,
            k0: 3.0 - 4.0 * film.poisson,
            k1: 3.0 - 4.0 * substrate.poisson,
        }
    }

    /// The ratio of shear moduli G0/G1.
    pub fn shear_ratio(&self) -> f64 {
        self.r
    }

    fn denominator(&self, b: &Blocks) -> f64 {
        let (r, k0, k1, t) = (self.r, self.k0, self.k1, b.t);
        (1.0 + k0) * (b.one_minus_t + k0 * t + t * t)
            + r * (1.0 + k0) * b.one_minus_t * (k1 + t)
            + (r - 1.0) * (1.0 + r * k1) * b.w
    }

    fn numerator_s(&self, b: &Blocks) -> f64 {
        let (r, k0, k1, t) = (self.r, self.k0, self.k1, b.t);
        (1.0 + r * k1) * (r * b.b + b.cm + 2.0 * (1.0 - 2.0 * self.film.poisson) * b.a)
            + t * t * r * (1.0 + k0) * (1.0 + k1)
    }

    /// S(qd), eq. (7), for qd ≥ 0 (S(0) = E0*/E1*; S → 1 as qd → ∞).
    pub fn s(&self, qd: f64) -> f64 {
        debug_assert!(qd >= 0.0);
        if qd > QD_BULK {
            return 1.0;
        }
        let b = Blocks::new(qd);
        self.numerator_s(&b) / self.denominator(&b)
    }

    /// The brackets of f and g in the stable forms (module doc): f = (1 + κ0) e^{−x} fb/D and
    /// g = (1 + κ0) e^{−x} gb/D; returns (D, fb, gb), all > 0 and of order x at most.
    fn interface_parts(&self, x: f64, b: &Blocks) -> (f64, f64, f64) {
        let (r, k1, t) = (self.r, self.k1, b.t);
        let (nu0, nu1) = (self.film.poisson, self.substrate.poisson);
        let den = self.denominator(b);
        let fb = 2.0 * (1.0 - nu0) * (1.0 + t)
            + 2.0 * r * (1.0 - nu1) * b.one_minus_t
            + x * (b.one_minus_t + r * (k1 + t));
        let h = if x < 2.0 {
            2.0 * b.e1 * x_cosh_minus_sinh(x)
        } else {
            x * (1.0 + t) - b.one_minus_t
        };
        let gb = (1.0 - 2.0 * nu0) * h
            + 2.0 * nu0 * x * (1.0 + t)
            + r * x * (2.0 * (1.0 - 2.0 * nu1) + b.one_minus_t)
            + r * (1.0 - 2.0 * nu1) * b.one_minus_t;
        (den, fb, gb)
    }

    /// f(qd)·e^{qd} and g(qd)·e^{qd}: f and g without their decay, finite and of order qd at
    /// every qd ≥ 0 (f and g themselves leave the f64 range above qd ≈ 745). For integrals of
    /// f², g² that apply e^{−2qd} relative to a reference point (the contact engine's interface
    /// integrals of a thick film).
    pub fn interface_undecayed(&self, qd: f64) -> (f64, f64) {
        debug_assert!(qd >= 0.0);
        let b = Blocks::new(qd);
        let (den, fb, gb) = self.interface_parts(qd, &b);
        let c = (1.0 + self.k0) / den;
        (c * fb, c * gb)
    }

    /// S, f and g at qd ≥ 0.
    pub fn response(&self, qd: f64) -> Response {
        debug_assert!(qd >= 0.0);
        let x = qd;
        let b = Blocks::new(x);
        let k0 = self.k0;
        let (den, fb, gb) = self.interface_parts(x, &b);
        let pre = (1.0 + k0) * b.e1 / den;
        let (f, g) = if x > QD_ZERO {
            (0.0, 0.0)
        } else if pre >= f64::MIN_POSITIVE {
            (pre * fb, pre * gb)
        } else {
            // e^{−x}/D below the normal range (a stiff film, or x > 708): the rational factor
            // first, then e^{−x/2} twice, so that only a result that is itself subnormal
            // loses digits.
            let half = (-0.5 * x).exp();
            let c = (1.0 + k0) / den;
            (c * fb * half * half, c * gb * half * half)
        };
        Response {
            s: if x > QD_BULK {
                1.0
            } else {
                self.numerator_s(&b) / den
            },
            f,
            g,
        }
    }
}

/// A film of given thickness (m) on its substrate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stack {
    pub layers: Bilayer,
    pub thickness: f64,
}

impl Stack {
    pub fn new(layers: Bilayer, thickness: f64) -> Result<Self, Error> {
        if !(thickness.is_finite() && thickness > 0.0) {
            return Err(Error::invalid(
                "film thickness",
                thickness,
                "a finite thickness > 0 in m",
            ));
        }
        Ok(Self { layers, thickness })
    }
}
