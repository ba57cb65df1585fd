//! The tail of the interface shear magnitude under sliding (not in the paper, which treats
//! static contact): |τ| for the vector τ = (m + X, Y), X ~ N(0, sx²), Y ~ N(0, sy²) independent,
//! m = μ p0 ≥ 0 the mean friction traction along x (notes.md, "Sliding friction").
//!
//! - [`ShearVector::ln_exceedance`] gives ln P(|τ| > R) with its absolute error (the relative
//!   error of P) and the slope d ln P/dR, down to P ≈ e^{−700} and beyond (no underflow: every
//!   step is in logarithms); [`ShearVector::exceedance`] is its exponential.
//! - [`ShearVector::density`] is the density of |τ|, −dP/dR.
//! - [`ShearVector::peak`] solves P(|τ| > τ*) = ε for ε in (0, ½), to 1e−12 relative (the issue
//!   asks for 1e−10), by Newton's method on φ = √(−2 ln P) (nearly linear in the level, so
//!   that a few steps from the upper bound converge) with a bracket;
//!   [`ShearVector::peak_from`] takes one such step from a given level, for the
//!   minimum-thickness search.
//!
//! Convention: with equal rms and m = 0, |τ| is Rayleigh: P = exp(−R²/(2s²)), so
//! τ* = s √(2 ln(1/ε)) = τ_rms √(ln(1/ε)) with τ_rms² = ⟨τ_x² + τ_y²⟩ = 2s². (The paper's static
//! rule instead takes the half-normal tail of one component's rms.)
//!
//! Method. In polar coordinates about the origin the radial integral is closed-form: on the ray
//! at angle θ the Gaussian exponent is quadratic in ρ, Q(ρ) = Q_R + 2g(ρ − R) + a(ρ − R)² with
//! a = cos²θ/sx² + sin²θ/sy², g = Ra − m cos θ/sx², Q_R = (R cos θ − m)²/sx² + R² sin²θ/sy², so
//!
//! ```text
//! P = 1/(π sx sy) ∫_0^π e^{−Q_R/2} J(θ) dθ,   J = R √(π/(2a)) erfcx(u) + K(u)/a,  u = g/√(2a)
//! K(u) = 1 − √π u erfcx(u)
//! ```
//!
//! and the density of |τ| at R is R/(π sx sy) ∫_0^π e^{−Q_R/2} dθ. Since K = 1 − √π u erfcx(u)
//! and Ra − g = mα cos θ (α = 1/sx²), J·a = 1 + t·erfcx(u) with t = √(π/(2a))·mα cos θ: a sum
//! of two non-negative terms where cos θ ≥ 0, and one losing at most a bit elsewhere as long as
//! R ≥ m and sy ≤ sx (then t·erfcx(u) ≥ −(1 − K)·m/(R + m) > −½); where that fails, J is
//! taken as R√(π/(2a)) erfcx(u) + K/a, with K from Laplace's continued fraction for erfcx
//! (√π erfcx(u) = 1/(u + r), K = r/(u + r)) for u ≥ 2, so no digits cancel. For u < 0 the
//! factor e^{u²} is moved into the exponent. Q_R is quadratic in cos θ, so its minima over θ
//! (θ = 0 or the vertex, and θ = π) are known in closed form; the θ-integral is split into
//! panels growing geometrically from each minimum in units of the peak's width √(2/Q_θθ), on
//! [π/2, π] in the distance π − θ (so that the nodes near θ = π carry no rounding of π), and
//! each panel is bisected until the 21-point Gauss–Kronrod rule and its embedded 10-point
//! Gauss rule agree to 1e−14 of the total (their difference summed is the error estimate). A
//! panel on which no ray's Gaussian factor has an interior maximum in θ (always when sy ≤ sx)
//! has integrals at most its width times the sum of the integrands at its ends; panels so
//! bounded are left out, largest bound first, while all those left out stay below a tenth of
//! the tolerance, and their bounds join the error estimate. The integrands are scaled by their
//! exponent at the peak before exponentiation, so ε = 1e−300 and far below are computed like
//! ε = 0.1.
//!
//! Degenerate cases in closed form: sy = 0 (or sy < 1e−20 sx, which moves τ* by less than
//! 1e−40 relative) is the folded normal; sx = 0 likewise gives P = erfc(√(R² − m²)/(√2 sy));
//! sx = sy = 0 is the constant |τ| = m.

use crate::error::Error;
use crate::prec::{EPS, Estimate, Termination};
use crate::simd::with_avx2;
use std::f64::consts::PI;

mod erfcx_far;

/// Relative tolerance of the θ-integral (the error estimate is reported, not this).
const QUAD_RTOL: f64 = 1e-14;

/// Relative tolerance of the θ-integral in [`ShearVector::peak_from`]: a relative error δ of
/// P moves its level by δ/|d ln P/dR|, about δ·level/28 at ε = 1e−6, far below the 1e−6 the
/// minimum-thickness search resolves utilisations to.
const SEARCH_QUAD_RTOL: f64 = 1e-10;

/// Relative tolerance of the peak level's Newton iteration.
const PEAK_RTOL: f64 = 1e-13;

/// The requested accuracy of the peak level: above it the status is `ToleranceNotReached`.
pub const PEAK_TARGET_RTOL: f64 = 1e-10;

/// Bisections of a θ-panel before giving up on `QUAD_RTOL`.
const MAX_DEPTH: u32 = 40;

/// (level − m)/s beyond which e^{−gap²/2} < 5e−324 (the smallest subnormal double):
/// √(2 · 745.2) = 38.6.
const UNDERFLOW_GAP: f64 = 38.61;

/// Below this ratio to the larger rms, a component is treated as zero.
const NEGLIGIBLE: f64 = 1e-20;

/// ln P(|τ| > R) with the slope d ln P/dR (≤ 0) and the absolute error of ln P.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LnExceedance {
    pub ln_p: Estimate,
    pub slope: f64,
}

/// The interface shear vector (m + X, Y) (Pa).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShearVector {
    mean: f64,
    sx: f64,
    sy: f64,
}

impl ShearVector {
    /// Mean m ≥ 0 along x and the rms of the x and y fluctuations (all ≥ 0 and finite).
    pub fn new(mean: f64, sx: f64, sy: f64) -> Result<Self, Error> {
        for (what, v) in [
            ("mean interface shear", mean),
            ("x rms of the interface shear", sx),
            ("y rms of the interface shear", sy),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::invalid(what, v, "a finite value >= 0 in Pa"));
            }
        }
        let big = sx.max(sy);
        let cut = |s: f64| if s < NEGLIGIBLE * big { 0.0 } else { s };
        Ok(Self {
            mean,
            sx: cut(sx),
            sy: cut(sy),
        })
    }

    /// P(|τ| > level) with its error estimate (underflows to 0 below about 1e−308; use
    /// [`Self::ln_exceedance`] there). Where the bound P ≤ e^{−(level − m)²/(2 s²)}
    /// (s = max(sx, sy)) is below the smallest subnormal double, 0 at once (ln P itself is not
    /// needed there, and its polar quadrature slows down as (level − m)/s grows).
    pub fn exceedance(&self, level: f64) -> Estimate {
        let s = self.sx.max(self.sy);
        if level > self.mean && s > 0.0 && (level - self.mean) / s > UNDERFLOW_GAP {
            return Estimate::new(0.0, f64::from_bits(1), Termination::Exact);
        }
        let l = self.ln_exceedance(level).ln_p;
        let p = l.value.exp();
        Estimate::new(p, p * l.err.exp_m1() + 4.0 * EPS * p, l.status)
    }

    /// The probability density of |τ| at `level` ≥ 0 (1/Pa): −dP/dR from [`Self::ln_exceedance`]
    /// (the θ-integral of the module doc), 0 where P underflows as in [`Self::exceedance`], and
    /// 0 for the constant |τ| = m (sx = sy = 0, a point mass).
    pub fn density(&self, level: f64) -> f64 {
        let s = self.sx.max(self.sy);
        if s == 0.0 || (level > self.mean && (level - self.mean) / s > UNDERFLOW_GAP) {
            return 0.0;
        }
        let l = self.ln_exceedance(level);
        -l.slope * l.ln_p.value.exp()
    }

    /// ln P(|τ| > level) for level ≥ 0, and its slope in the level.
    pub fn ln_exceedance(&self, level: f64) -> LnExceedance {
        self.ln_exceedance_to(level, QUAD_RTOL)
    }

    /// [`Self::ln_exceedance`] with the θ-integral to relative tolerance `rtol`.
    fn ln_exceedance_to(&self, level: f64, rtol: f64) -> LnExceedance {
        let (m, sx, sy, r) = (self.mean, self.sx, self.sy, level.max(0.0));
        if sx == 0.0 && sy == 0.0 {
            let v = if r < m { 0.0 } else { f64::NEG_INFINITY };
            return LnExceedance {
                ln_p: Estimate::new(v, 0.0, Termination::Exact),
                slope: 0.0,
            };
        }
        if sy == 0.0 {
            return folded_normal(m, sx, r);
        }
        if sx == 0.0 {
            return across_only(m, sy, r);
        }
        let s0 = sx.max(sy);
        let mut t = polar(m / s0, sx / s0, sy / s0, r / s0, rtol);
        t.slope /= s0;
        t
    }

    /// The level τ* with P(|τ| > τ*) = ε, for 0 < ε < ½.
    pub fn peak(&self, epsilon: f64) -> Result<Estimate, Error> {
        if !(epsilon > 0.0 && epsilon < 0.5) {
            return Err(Error::invalid(
                "exceedance probability",
                epsilon,
                "0 < epsilon < 0.5",
            ));
        }
        let (m, s_max) = (self.mean, self.sx.max(self.sy));
        if s_max == 0.0 {
            return Ok(Estimate::exact(m));
        }
        let target = epsilon.ln();
        let phi_eps = (-2.0 * target).sqrt();
        // P(|τ| > m) ≥ ½ and P(|τ| > m + r) ≤ P(|(X, Y)| > r) ≤ e^{−r²/(2 s_max²)}.
        let mut lo = m;
        let mut hi = m + s_max * phi_eps;
        let mut x = hi;
        let mut step = f64::INFINITY;
        let mut at = self.ln_exceedance(x);
        // |ln P − ln ε| at x, unknown after a last step (P is not evaluated there).
        let mut residual = 0.0;
        for _ in 0..200 {
            let f = at.ln_p.value - target;
            if f > 0.0 {
                lo = x;
            } else {
                hi = x;
            }
            let mut next = phi_step(at, x, phi_eps).unwrap_or(x - f / at.slope);
            // A step within the tolerance is the last one, taken as it is: x may be an end of
            // the bracket (f rounds to its sign there), and the step just across it is not a
            // reason to bisect. P is not evaluated at its end: Newton's method converges
            // quadratically there, so the step bounds that end's distance from the root, and
            // P's error at x stands for its error a step away.
            let last = (next - x).abs() <= PEAK_RTOL * x;
            if !(last || next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            step = (next - x).abs();
            x = next;
            if last {
                residual = 0.0;
                break;
            }
            at = self.ln_exceedance(x);
            residual = (at.ln_p.value - target).abs();
            if step <= PEAK_RTOL * x || hi - lo <= PEAK_RTOL * x {
                break;
            }
        }
        let err = residual.max(at.ln_p.err) / at.slope.abs() + step.min(hi - lo) + 4.0 * EPS * x;
        let status = if err <= PEAK_TARGET_RTOL * x {
            Estimate::worst(at.ln_p.status, Termination::Converged)
        } else {
            Termination::ToleranceNotReached
        };
        Ok(Estimate::new(x, err, status))
    }
}

impl ShearVector {
    /// For the minimum-thickness search, which only needs to know on which side of a limit
    /// the peak τ* (P(|τ| > τ*) = ε) lies and, smoothly, how far: one Newton step from
    /// L = min(level, τ_hi) towards τ* in φ(R) = √(−2 ln P(|τ| > R)), with τ_hi = m +
    /// max(sx, sy)·√(−2 ln ε) ≥ τ* ([`Self::peak`]'s upper bound), clipped to τ_hi. φ is
    /// nearly linear in R (exactly (R − m)/s for one component, R/s for equal rms at m = 0),
    /// so the step lands within O((L − τ*)²) of τ*, and on τ* itself when L = τ*. The result
    /// exceeds `level` exactly when τ* does: below τ_hi, R₁ − L has the sign of φ(τ*) − φ(L),
    /// and φ increases; above it, τ* ≤ τ_hi < level. One evaluation of P (to
    /// a tolerance of 1e−10) instead of the root solve's several; the error estimate is that
    /// of the step from P's error, not the distance to τ*.
    pub fn peak_from(&self, level: f64, epsilon: f64) -> Result<Estimate, Error> {
        if !(epsilon > 0.0 && epsilon < 0.5) {
            return Err(Error::invalid(
                "exceedance probability",
                epsilon,
                "0 < epsilon < 0.5",
            ));
        }
        let (m, s_max) = (self.mean, self.sx.max(self.sy));
        if s_max == 0.0 {
            return Ok(Estimate::exact(m));
        }
        let phi_eps = (-2.0 * epsilon.ln()).sqrt();
        let hi = m + s_max * phi_eps;
        let x = level.min(hi);
        let at = self.ln_exceedance_to(x, SEARCH_QUAD_RTOL);
        // Where P rounds to 1 (far below the mean) the peak is above x; τ_hi says so.
        let r1 = phi_step(at, x, phi_eps).map_or(hi, |r| r.min(hi));
        let err = at.ln_p.err / at.slope.abs() + 4.0 * EPS * r1;
        Ok(Estimate::new(
            r1,
            if err.is_finite() { err } else { 0.0 },
            Estimate::worst(at.ln_p.status, Termination::Converged),
        ))
    }
}

/// A bound on how far below the peak τ* [`ShearVector::peak_from`] can land, as a fraction of
/// τ*, from any level above τ* when sy ≤ sx (as under sliding, where the minimum-thickness
/// search reads its peaks so): 0.06/ln²ε. φ is not convex everywhere above τ*, so
/// the step can fall short of it. Measured over ε from 1e−300 to 0.49, m/sx from 0 to 1e3,
/// sy/sx from 0 to 1 and starts from τ* to τ_hi (test
/// `one_step_peaks_fall_short_of_the_peak_by_at_most_the_bound`, and once on a grid twice as
/// fine): the largest shortfall is about 0.035/ln²ε (1.2e−4 at ε = 1e−6, 1.2e−3 at 1e−2, 0.064
/// at 0.49), at most 0.6 of the bound. With sy > sx it can be larger (0.076 at ε = 1e−6 over
/// sx/sy from 1e−2 to 1).
pub fn one_step_shortfall(epsilon: f64) -> f64 {
    0.06 / epsilon.ln().powi(2)
}

/// The largest ratio, over the mean m ≥ 0, of the peak at exceedance ε (0 < ε < ½) of
/// (m + X, Y) with equal rms to the peak with Y = 0: √(−2 ln ε)/k_ε, its value at m = 0 (the
/// Rayleigh level over the half-normal one, k_ε = √2 erfc⁻¹(ε)); the ratio falls towards 1 as m
/// grows (test `isotropic_peak_exceeds_the_folded_one_by_at_most_the_spread`). With sy ≤ sx the
/// peak lies between the two, so it is at most this factor above the folded normal's of sx
/// alone: what the minimum-thickness search allows for under sliding.
pub fn anisotropy_spread(epsilon: f64) -> f64 {
    (-2.0 * epsilon.ln()).sqrt() / crate::contact::tau_peak(1.0, epsilon)
}

/// The Newton step from x towards φ(R) = φ_ε in φ = √(−2 ln P), φ' = −(d ln P/dR)/φ; `None`
/// where φ or the slope is 0 (P = 1 to rounding).
fn phi_step(at: LnExceedance, x: f64, phi_eps: f64) -> Option<f64> {
    let phi = (-2.0 * at.ln_p.value).max(0.0).sqrt();
    (phi > 0.0 && at.slope < 0.0).then(|| x + (phi_eps - phi) * phi / -at.slope)
}

/// ln(e^a + e^b).
fn ln_add(a: f64, b: f64) -> f64 {
    let (hi, lo) = if a >= b { (a, b) } else { (b, a) };
    if hi == f64::NEG_INFINITY {
        hi
    } else {
        hi + (lo - hi).exp().ln_1p()
    }
}

/// ln erfc(z) for any z, without underflow: libm's erfc (relative accuracy kept through its
/// tail) up to z = 26, beyond it −z² + ln erfcx(z).
pub fn ln_erfc(z: f64) -> f64 {
    if z < 26.0 {
        libm::erfc(z).ln()
    } else {
        -z * z + erfcx_and_k(z).0.ln()
    }
}

/// erfcx(u) = e^{u²} erfc(u) and K(u) = 1 − √π u erfcx(u) for u ≥ 0: directly below u = 2
/// (where K ≥ 0.09, so at most a digit cancels), and from Laplace's continued fraction above,
/// √π erfcx(u) = 1/(u + r), r = (1/2)/(u + 1/(u + (3/2)/(u + …))), so K = r/(u + r) with no
/// cancellation (depth 80 at u = 2 reaches 1e−16, measured against mpmath; fewer beyond).
fn erfcx_and_k(u: f64) -> (f64, f64) {
    if u < 2.0 {
        let e = libm::erfc(u) * (u * u).exp();
        return (e, 1.0 - PI.sqrt() * u * e);
    }
    let depth = if u < 3.0 {
        80
    } else if u < 6.0 {
        40
    } else {
        20
    };
    let mut t = u;
    for k in (2..=depth).rev() {
        t = u + 0.5 * k as f64 / t;
    }
    let r = 0.5 / t;
    (1.0 / (PI.sqrt() * (u + r)), r / (u + r))
}

/// sy = 0: |m + X| is folded normal.
fn folded_normal(m: f64, sx: f64, r: f64) -> LnExceedance {
    let z1 = (r - m) / (std::f64::consts::SQRT_2 * sx);
    let z2 = (r + m) / (std::f64::consts::SQRT_2 * sx);
    let ln_p = ln_add(ln_erfc(z1), ln_erfc(z2)) - std::f64::consts::LN_2;
    // The density of |m + X| at R: (e^{−z1²} + e^{−z2²})/(√(2π) sx).
    let ln_f = ln_add(-z1 * z1, -z2 * z2) - ((2.0 * PI).sqrt() * sx).ln();
    let err = 1e-15 * (1.0 + z1.abs().max(z2.abs()).powi(2));
    LnExceedance {
        ln_p: Estimate::new(ln_p, err, Termination::Exact),
        slope: -(ln_f - ln_p).exp(),
    }
}

/// sx = 0: |τ| = √(m² + Y²).
fn across_only(m: f64, sy: f64, r: f64) -> LnExceedance {
    if r <= m {
        return LnExceedance {
            ln_p: Estimate::new(0.0, 0.0, Termination::Exact),
            slope: 0.0,
        };
    }
    let root = ((r - m) * (r + m)).sqrt();
    let z = root / (std::f64::consts::SQRT_2 * sy);
    let ln_p = ln_erfc(z);
    // dP/dR = −(2/√π) e^{−z²} dz/dR, dz/dR = R/(√2 sy √(R² − m²))
    let ln_f = -z * z + (2.0 / PI.sqrt() * r / (std::f64::consts::SQRT_2 * sy * root)).ln();
    LnExceedance {
        ln_p: Estimate::new(ln_p, 1e-15 * (1.0 + z * z), Termination::Exact),
        slope: -(ln_f - ln_p).exp(),
    }
}

/// erfcx(u) = e^{u²} erfc(u) for u ≥ 0, to a few ulp: below u = 1.25 libm's erfc times
/// e^{u²}, with u² split exactly into hi + lo (Dekker's product) as e^{hi}(1 + lo), so that the
/// rounding of u² does not enter; from 1.25 to 26 the same approximation as libm's erfc with
/// e^{−u²} left out ([`erfcx_far::erfcx_far`], one exponential instead of three); above,
/// Laplace's continued fraction ([`erfcx_and_k`]).
fn erfcx(u: f64) -> f64 {
    if u >= 26.0 {
        return erfcx_and_k(u).0;
    }
    if u >= 1.25 {
        return erfcx_far::erfcx_far(u);
    }
    let hi = u * u;
    // Veltkamp's split of u into 26-bit halves, so that the partial products are exact.
    let c = 134_217_729.0 * u;
    let uh = c - (c - u);
    let ul = u - uh;
    let lo = ((uh * uh - hi) + 2.0 * uh * ul) + ul * ul;
    libm::erfc(u) * (hi.exp() * (1.0 + lo))
}

/// The 21-point Gauss–Kronrod rule on [−1, 1] and its embedded 10-point Gauss rule
/// (QUADPACK's qk21; test `kronrod_21_is_exact_to_degree_31_and_embeds_gauss_10`): the
/// non-negative nodes, descending, with the Kronrod weights, and the Gauss weights of the odd
/// ones (the Gauss nodes).
const KRONROD_21_NODES: [f64; 11] = [
    0.995_657_163_025_808_1,
    0.973_906_528_517_171_7,
    0.930_157_491_355_708_2,
    0.865_063_366_688_984_5,
    0.780_817_726_586_416_9,
    0.679_409_568_299_024_4,
    0.562_757_134_668_604_7,
    0.433_395_394_129_247_2,
    0.294_392_862_701_460_2,
    0.148_874_338_981_631_22,
    0.0,
];
const KRONROD_21_WEIGHTS: [f64; 11] = [
    0.011_694_638_867_371_874,
    0.032_558_162_307_964_725,
    0.054_755_896_574_351_995,
    0.075_039_674_810_919_96,
    0.093_125_454_583_697_6,
    0.109_387_158_802_297_64,
    0.123_491_976_262_065_84,
    0.134_709_217_311_473_34,
    0.142_775_938_577_060_09,
    0.147_739_104_901_338_49,
    0.149_445_554_002_916_9,
];
const GAUSS_10_WEIGHTS: [f64; 5] = [
    0.066_671_344_308_688_14,
    0.149_451_349_150_580_6,
    0.219_086_362_515_982_04,
    0.269_266_719_309_996_35,
    0.295_524_224_714_752_87,
];

/// Lanes of [`Polar::panel`]'s node arrays: the 21 nodes and three copies of the midpoint, a
/// multiple of four lanes.
const LANES: usize = 24;

/// Panels whose integrals are bounded (from the values at their ends) by at most this fraction
/// of the θ-integral's tolerance, all together, are left out and their bound added to the error.
const SKIP_SHARE: f64 = 0.1;

/// The scaled problem (max(sx, sy) = 1): the two θ-integrands and their peak.
struct Polar {
    m: f64,
    alpha: f64,
    beta: f64,
    r: f64,
    /// −Q_R/2 at the peak, subtracted from the density integrand's exponent.
    ref_f: f64,
    /// The P-integrand's exponent at the peak (−Q_R/2, plus u² where u < 0), subtracted from
    /// its exponent.
    ref_p: f64,
    /// e^{ref_f − ref_p}: the P-integrand's scale where its exponent is −Q_R/2.
    scale: f64,
}

/// The factors of the P-integrand at one θ: e^{exponent} · ja/a with exponent = −Q_R/2 (the
/// density integrand's), plus u² where u < 0 (`fold`).
struct Terms {
    neg_half_q: f64,
    fold: Option<f64>,
    ja: f64,
    a: f64,
}

impl Polar {
    fn new(m: f64, alpha: f64, beta: f64, r: f64, theta_peak: f64) -> Self {
        let mut pol = Self {
            m,
            alpha,
            beta,
            r,
            ref_f: 0.0,
            ref_p: 0.0,
            scale: 1.0,
        };
        let t = if theta_peak == PI {
            pol.terms(0.0, Half::Upper)
        } else {
            pol.terms(theta_peak, Half::Lower)
        };
        pol.ref_f = t.neg_half_q;
        pol.ref_p = t.neg_half_q + t.fold.unwrap_or(0.0);
        pol.scale = (pol.ref_f - pol.ref_p).exp();
        pol
    }

    /// The P-integrand's factors at θ (module docs): J·a = 1 + t·erfcx(u) with
    /// t = √(π/(2a))·mα cos θ, both terms ≥ 0 where cos θ ≥ 0; where cos θ < 0 and t·erfcx(u) <
    /// −½ (which needs R < m or sy > sx) the sum would cancel, and instead
    /// J·a = R a √(π/(2a)) erfcx(u) + K(u). For u < 0 (then cos θ > 0) e^{u²} moves into the exponent:
    /// J·a e^{−u²} = e^{−u²} + t·erfc(u).
    fn terms(&self, t: f64, half: Half) -> Terms {
        self.terms_at(t.sin_cos(), half)
    }

    /// [`Self::terms`] from (sin t, cos t).
    fn terms_at(&self, (s, c): (f64, f64), half: Half) -> Terms {
        let c = if half == Half::Upper { -c } else { c };
        let (al, be, r, m) = (self.alpha, self.beta, self.r, self.m);
        let a = al * c * c + be * s * s;
        let dx = r * c - m;
        let neg_half_q = -0.5 * (al * dx * dx + be * r * r * s * s);
        let g = r * a - al * m * c;
        let sa = (2.0 * a).sqrt();
        let u = g / sa;
        let k = PI.sqrt() / sa;
        let t = k * al * m * c;
        if u < 0.0 {
            let ec = libm::erfc(u);
            return Terms {
                neg_half_q,
                fold: Some(u * u),
                ja: (-u * u).exp() + t * ec,
                a,
            };
        }
        let ex = erfcx(u);
        let ja = if t * ex >= -0.5 {
            1.0 + t * ex
        } else {
            let (ex, kk) = erfcx_and_k(u);
            r * a * k * ex + kk
        };
        Terms {
            neg_half_q,
            fold: None,
            ja,
            a,
        }
    }

    /// The P-integrand e^{−Q_R/2} J and the density integrand e^{−Q_R/2} at θ, scaled by their
    /// values' exponents at the peak; θ = t on the lower half, π − t on the upper.
    fn integrands(&self, t: f64, half: Half) -> [f64; 2] {
        self.integrands_at(t.sin_cos(), half)
    }

    /// [`Self::integrands`] from (sin t, cos t).
    fn integrands_at(&self, sin_cos: (f64, f64), half: Half) -> [f64; 2] {
        let t = self.terms_at(sin_cos, half);
        let f = (t.neg_half_q - self.ref_f).exp();
        let p = match t.fold {
            None => f * self.scale,
            Some(u2) => (t.neg_half_q + u2 - self.ref_p).exp(),
        };
        [p * t.ja / t.a, f]
    }

    /// ∫ over [a, b] of both scaled integrands by the 10-point Gauss rule ([0]) and the
    /// 21-point Kronrod rule through its nodes ([1]), in θ or in π − θ as `half` says: the
    /// values of [`Self::integrands_at`] at the nodes, to the last bit. The sines and cosines of
    /// the nodes mid ± δ come from those of mid and δ by the addition theorems (one sin_cos per
    /// pair of nodes). The nodes' factors up to the exponentials run in loops over arrays of
    /// nodes, vectorised (AVX2 where the CPU has it, `crate::simd`), for the nodes on
    /// [`Self::terms_at`]'s common path (1.25 ≤ u < 26 and J·a = 1 + t·erfcx(u)); the others
    /// are recomputed by [`Self::integrands_at`].
    fn panel(&self, a: f64, b: f64, which: Half) -> [[f64; 2]; 2] {
        with_avx2!(self.panel_avx2(a, b, which), self.panel_in(a, b, which))
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn panel_avx2(&self, a: f64, b: f64, which: Half) -> [[f64; 2]; 2] {
        self.panel_in(a, b, which)
    }

    #[inline(always)]
    fn panel_in(&self, a: f64, b: f64, which: Half) -> [[f64; 2]; 2] {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let (sm, cm) = mid.sin_cos();
        // Lanes 0..10 are the nodes mid − δ_i, 10..20 mid + δ_i, 20 and the padding mid.
        let (mut sin, mut cos) = ([sm; LANES], [cm; LANES]);
        for (i, &x) in KRONROD_21_NODES[..10].iter().enumerate() {
            let (sd, cd) = (half * x).sin_cos();
            (sin[i], cos[i]) = (sm * cd - cm * sd, cm * cd + sm * sd);
            (sin[10 + i], cos[10 + i]) = (sm * cd + cm * sd, cm * cd - sm * sd);
        }
        let (al, be, r, m) = (self.alpha, self.beta, self.r, self.m);
        let upper = which == Half::Upper;
        let [mut nhq, mut aa, mut u, mut t, mut arg] = [[0.0; LANES]; 5];
        for i in 0..LANES {
            // Self::terms_at's operations, in its order.
            let (s, c) = (sin[i], if upper { -cos[i] } else { cos[i] });
            let a = al * c * c + be * s * s;
            let dx = r * c - m;
            nhq[i] = -0.5 * (al * dx * dx + be * r * r * s * s);
            let g = r * a - al * m * c;
            let sa = (2.0 * a).sqrt();
            u[i] = g / sa;
            let k = PI.sqrt() / sa;
            t[i] = k * al * m * c;
            aa[i] = a;
            arg[i] = erfcx_far::exponent(u[i]);
        }
        // The exponentials (libm's, not vectorised) at the 21 nodes only, not the padding.
        let (mut ex, mut f) = ([0.0; LANES], [0.0; LANES]);
        for i in 0..21 {
            ex[i] = arg[i].exp();
            f[i] = (nhq[i] - self.ref_f).exp();
        }
        let (mut vp, mut tex) = ([0.0; LANES], [0.0; LANES]);
        for i in 0..LANES {
            tex[i] = t[i] * (ex[i] / u[i]);
            vp[i] = f[i] * self.scale * (1.0 + tex[i]) / aa[i];
        }
        for i in 0..21 {
            if !(u[i] >= 1.25 && u[i] < 26.0 && tex[i] >= -0.5) {
                [vp[i], f[i]] = self.integrands_at((sin[i], cos[i]), which);
            }
        }
        let mut out = [[0.0; 2]; 2];
        for (i, (&x, &wk)) in KRONROD_21_NODES.iter().zip(&KRONROD_21_WEIGHTS).enumerate() {
            let wg = if i % 2 == 1 {
                GAUSS_10_WEIGHTS[i / 2]
            } else {
                0.0
            };
            let v = if x == 0.0 {
                [vp[20], f[20]]
            } else {
                [vp[i] + vp[10 + i], f[i] + f[10 + i]]
            };
            for j in 0..2 {
                out[0][j] += wg * half * v[j];
                out[1][j] += wk * half * v[j];
            }
        }
        out
    }

    /// Whether on a panel [t1, t2] no ray's Gaussian factor e^{−Q(ρ, θ)/2} (ρ ≥ R) has an interior
    /// local maximum in θ, so that each is at most the larger of its values at the ends and
    /// each integrand's integral over [t1, t2] at most (t2 − t1) times the sum of its values
    /// there. Q(ρ, θ) = ρ²(α − β)cos²θ − 2ρmα cos θ + const: with α ≤ β (sy ≤ sx) it is concave
    /// in cos θ, so it always holds; else Q's minimum over cos θ is at mα/(ρ(α − β)), which
    /// for ρ ≥ R lies in (0, mα/(R(α − β))] (at 0 for m = 0), θ ∈ (0, π/2], and [t1, t2] (on
    /// the lower half) must avoid those θ.
    fn bounded_by_ends(&self, t2: f64, half: Half) -> bool {
        let (al, be) = (self.alpha, self.beta);
        if al <= be || half == Half::Upper {
            return true;
        }
        let c_max = self.m * al / (self.r * (al - be));
        t2 <= c_max.min(1.0).acos()
    }
}

/// The local minima of Q_R over θ ∈ [0, π], each with the peak's width √(2/Q_θθ) there.
/// Q = A c² − 2B c + const in c = cos θ with B ≥ 0: the global minimum is at θ = 0 or at the
/// vertex; θ = π is a second, lower peak when Q is concave in c (A + B < 0; at m = 0 it is as
/// high as the first, the two tails of X).
fn peaks_of(m: f64, alpha: f64, beta: f64, r: f64) -> Vec<(f64, f64)> {
    let aq = r * r * (alpha - beta);
    let bq = r * m * alpha;
    let width = |qtt: f64| {
        if qtt > 0.0 {
            (2.0 / qtt).sqrt().min(PI)
        } else {
            PI
        }
    };
    let mut out = Vec::with_capacity(2);
    if aq > bq {
        let theta = (bq / aq).acos();
        out.push((theta, width(2.0 * aq * theta.sin().powi(2))));
    } else {
        out.push((0.0, width(2.0 * (bq - aq))));
    }
    if aq + bq < 0.0 {
        out.push((PI, width(-2.0 * (aq + bq))));
    }
    out
}

/// Breakpoints θ ± w·2^k (k = −1, 0, 1, …) around each peak (θ, w), with 0, π/2 and the peaks:
/// those in [0, π/2] as θ, and those in [π/2, π] as their distance π − θ from π ([`Half`]),
/// each half sorted.
fn cuts_around(peaks: &[(f64, f64)]) -> [Vec<f64>; 2] {
    let half_pi = 0.5 * PI;
    // Room for the cuts around peaks down to a width of 1e−4 (16 doublings to π), so that
    // the pushes below seldom reallocate.
    let mut cuts = [0, 1].map(|_| {
        let mut c = Vec::with_capacity(36);
        c.extend([0.0, half_pi]);
        c
    });
    let push = |cuts: &mut [Vec<f64>; 2], t: f64, from_pi: f64| {
        if t > 0.0 && t < half_pi {
            cuts[0].push(t);
        } else if from_pi > 0.0 && from_pi < half_pi {
            cuts[1].push(from_pi);
        }
    };
    for &(theta, w) in peaks {
        let mut d = 0.5 * w;
        while d < PI {
            if theta == PI {
                push(&mut cuts, PI - d, d);
            } else {
                push(&mut cuts, theta - d, PI - (theta - d));
                push(&mut cuts, theta + d, PI - (theta + d));
            }
            d *= 2.0;
        }
        if theta < half_pi {
            cuts[0].push(theta);
        }
    }
    for c in &mut cuts {
        c.sort_by(f64::total_cmp);
        c.dedup();
    }
    cuts
}

/// Which half of [0, π] a θ-panel lies in: the upper half is parametrised by the distance
/// φ = π − θ from π, so that near θ = π, where the integrands vary on the scale of sin θ, the
/// nodes carry no rounding of π.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Half {
    Lower,
    Upper,
}

/// A θ-panel [a, b] (in φ = π − θ on the upper half) with its Gauss and Kronrod integrals and
/// its bisection depth.
type Panel = (f64, f64, Half, u32, [[f64; 2]; 2]);

/// The first panels of the θ-integral, between the cuts of each half, with the bound on the
/// integrals of the panels left out. A panel whose integrals are bounded by its end values
/// ([`Polar::bounded_by_ends`]) is left out when, largest bound first, the bounds of all panels
/// left out stay below [`SKIP_SHARE`] of `rtol` times the integrals of those computed.
fn first_panels(pol: &Polar, cuts: &[Vec<f64>; 2], rtol: f64) -> (Vec<Panel>, [f64; 2]) {
    let mut order = Vec::with_capacity(cuts[0].len() + cuts[1].len());
    for (half, c) in [Half::Lower, Half::Upper].into_iter().zip(cuts) {
        let at: Vec<[f64; 2]> = c.iter().map(|&t| pol.integrands(t, half)).collect();
        for i in 0..c.len() - 1 {
            let (t1, t2) = (c[i], c[i + 1]);
            let bound = if pol.bounded_by_ends(t2, half) {
                [0, 1].map(|j| (t2 - t1) * (at[i][j] + at[i + 1][j]))
            } else {
                [f64::INFINITY; 2]
            };
            order.push((t1, t2, half, bound));
        }
    }
    order.sort_by(|x, y| y.3[0].total_cmp(&x.3[0]));
    // The bound of every panel from the k-th on in this order.
    let mut rest = vec![[0.0; 2]; order.len() + 1];
    for k in (0..order.len()).rev() {
        rest[k] = [0, 1].map(|j| rest[k + 1][j] + order[k].3[j]);
    }
    // Room for the bisections `polar` pushes onto these panels, its stack (each bisection
    // replaces one panel by two), so that it seldom grows.
    let mut panels = Vec::with_capacity(2 * order.len());
    let mut total = [0.0; 2];
    for (k, &(t1, t2, half, _)) in order.iter().enumerate() {
        if (0..2).all(|j| rest[k][j] <= SKIP_SHARE * rtol * total[j]) {
            return (panels, rest[k]);
        }
        let p = pol.panel(t1, t2, half);
        for j in 0..2 {
            total[j] += p[1][j];
        }
        panels.push((t1, t2, half, 0, p));
    }
    (panels, [0.0; 2])
}

/// The general case, scaled so that max(sx, sy) = 1.
fn polar(m: f64, sx: f64, sy: f64, r: f64, rtol: f64) -> LnExceedance {
    let (alpha, beta) = (1.0 / (sx * sx), 1.0 / (sy * sy));
    let peaks = peaks_of(m, alpha, beta, r);
    let pol = Polar::new(m, alpha, beta, r, peaks[0].0);
    let (mut stack, left_out) = first_panels(&pol, &cuts_around(&peaks), rtol);
    // The panels around the peak set the scale against which the others are judged.
    let total: [f64; 2] = [0, 1].map(|j| stack.iter().map(|p| p.4[1][j]).sum());
    let (mut sum, mut err) = ([0.0; 2], left_out);
    let mut status = Termination::Converged;
    while let Some((a, b, half, depth, p)) = stack.pop() {
        let diff = [0, 1].map(|j| (p[1][j] - p[0][j]).abs());
        if (0..2).all(|j| diff[j] <= rtol * total[j]) || depth >= MAX_DEPTH {
            if depth >= MAX_DEPTH {
                status = Termination::ToleranceNotReached;
            }
            for j in 0..2 {
                sum[j] += p[1][j];
                err[j] += diff[j];
            }
        } else {
            let c = 0.5 * (a + b);
            stack.push((a, c, half, depth + 1, pol.panel(a, c, half)));
            stack.push((c, b, half, depth + 1, pol.panel(c, b, half)));
        }
    }
    let norm = -(PI * sx * sy).ln();
    let ln_p = norm + pol.ref_p + sum[0].ln();
    let ln_f = norm + r.ln() + pol.ref_f + sum[1].ln();
    // Rounding: the exponent (up to ~|ln P|) to a few ulp, and J (erfcx to a few ulp, J·a a
    // sum of two non-negative terms or one losing at most a bit) to ~1e-15; the sum over the
    // nodes was measured off the 30-digit reference by up to 1.2e-14 for sy/sx = 1e-3, so
    // 2e-14 is allowed.
    let rel = err[0] / sum[0] + 2e-14 + 8.0 * EPS * pol.ref_p.abs();
    LnExceedance {
        ln_p: Estimate::new(ln_p, rel, status),
        slope: -(ln_f - ln_p).exp(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tabulated Kronrod rule integrates x^k over [−1, 1] exactly (2/(k + 1) for even k)
    /// to degree 31 and its embedded Gauss rule to degree 19, both to 4e−16, and no further;
    /// the Gauss nodes and weights are those of `quad::gauss_legendre(10)` to 2e−16 and 1e−15
    /// (its weights are good to a few ulp). A wrong digit in any constant breaks one of these.
    #[test]
    fn kronrod_21_is_exact_to_degree_31_and_embeds_gauss_10() {
        let integral = |k: i32, gauss: bool| {
            let mut sum = 0.0;
            for (i, (&x, &wk)) in KRONROD_21_NODES.iter().zip(&KRONROD_21_WEIGHTS).enumerate() {
                let w = match gauss {
                    true if i % 2 == 1 => GAUSS_10_WEIGHTS[i / 2],
                    true => 0.0,
                    false => wk,
                };
                let f = if x == 0.0 {
                    f64::from(u8::from(k == 0))
                } else {
                    x.powi(k) + (-x).powi(k)
                };
                sum += w * f;
            }
            sum
        };
        for k in 0..=31 {
            let want = if k % 2 == 0 {
                2.0 / f64::from(k + 1)
            } else {
                0.0
            };
            assert!((integral(k, false) - want).abs() < 4e-16, "Kronrod x^{k}");
            if k <= 19 {
                assert!((integral(k, true) - want).abs() < 4e-16, "Gauss x^{k}");
            }
        }
        assert!((integral(32, false) - 2.0 / 33.0).abs() > 1e-12);
        assert!((integral(20, true) - 2.0 / 21.0).abs() > 1e-8);
        let (x, w) = crate::quad::gauss_legendre(10);
        for i in 0..5 {
            assert!((x[9 - i] - KRONROD_21_NODES[2 * i + 1]).abs() < 2e-16);
            assert!((w[9 - i] - GAUSS_10_WEIGHTS[i]).abs() < 1e-15);
        }
    }

    /// The panel rule from arrays of nodes gives the values of the node-by-node rule (each
    /// node through `Polar::integrands_at`) to the last bit, in the dispatched (AVX2 where
    /// available) and the baseline build: on both halves, on the panels between the cuts and
    /// their halves and quarters, for levels below, near and far above the mean and sy/sx from
    /// 1e−3 to 10 (nodes with u < 0, u < 1.25, u ≥ 26 and J·a's cancelling form among them).
    #[test]
    fn panel_equals_the_node_by_node_rule() {
        let node_by_node = |pol: &Polar, a: f64, b: f64, which: Half| {
            let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
            let (sm, cm) = mid.sin_cos();
            let mut out = [[0.0; 2]; 2];
            for (i, (&x, &wk)) in KRONROD_21_NODES.iter().zip(&KRONROD_21_WEIGHTS).enumerate() {
                let wg = if i % 2 == 1 {
                    GAUSS_10_WEIGHTS[i / 2]
                } else {
                    0.0
                };
                let v = if x == 0.0 {
                    pol.integrands_at((sm, cm), which)
                } else {
                    let (sd, cd) = (half * x).sin_cos();
                    let lo = pol.integrands_at((sm * cd - cm * sd, cm * cd + sm * sd), which);
                    let hi = pol.integrands_at((sm * cd + cm * sd, cm * cd - sm * sd), which);
                    [lo[0] + hi[0], lo[1] + hi[1]]
                };
                for j in 0..2 {
                    out[0][j] += wg * half * v[j];
                    out[1][j] += wk * half * v[j];
                }
            }
            out
        };
        let bits = |p: [[f64; 2]; 2]| p.map(|q| q.map(f64::to_bits));
        let mut panels = 0;
        for (sx, sy) in [(1.0, 1e-3), (1.0, 0.3), (1.0, 1.0), (0.1, 1.0)] {
            for m in [0.0, 0.5, 3.0, 40.0] {
                for r in [0.2, 0.9 * m, m + 0.5, m + 4.0, m + 30.0] {
                    if r <= 0.0 {
                        continue;
                    }
                    let (alpha, beta) = (1.0 / (sx * sx), 1.0 / (sy * sy));
                    let peaks = peaks_of(m, alpha, beta, r);
                    let pol = Polar::new(m, alpha, beta, r, peaks[0].0);
                    let cuts = cuts_around(&peaks);
                    for (which, c) in [Half::Lower, Half::Upper].into_iter().zip(&cuts) {
                        for w in c.windows(2) {
                            for k in 0..7 {
                                let (a, b) = match k {
                                    0 => (w[0], w[1]),
                                    1 | 2 => {
                                        let h = 0.5 * (w[1] - w[0]);
                                        (w[0] + h * f64::from(k - 1), w[0] + h * f64::from(k))
                                    }
                                    _ => {
                                        let h = 0.25 * (w[1] - w[0]);
                                        (w[0] + h * f64::from(k - 3), w[0] + h * f64::from(k - 2))
                                    }
                                };
                                let want = bits(node_by_node(&pol, a, b, which));
                                assert_eq!(bits(pol.panel(a, b, which)), want);
                                assert_eq!(bits(pol.panel_in(a, b, which)), want);
                                panels += 1;
                            }
                        }
                    }
                }
            }
        }
        assert!(panels > 1000);
    }

    /// erfcx against 40-digit values (mpmath: erfc(u)·e^{u²}) on both sides of the switches
    /// to the one-exponential form at u = 1.25, between its two ranges at 1/0.35 and to the
    /// continued fraction at u = 26 (and at 1.794135…, the largest error of the one-exponential
    /// form on 8000 points of [1.25, 26], 2.7e−16): to 4e−16 relative.
    #[test]
    fn erfcx_matches_high_precision() {
        for (u, want) in [
            (0.0, 1.0),
            (0.3, 0.7345993345676551),
            (1.249_999_999_999_999_8, 0.367_822_916_452_361_15),
            (1.25, 0.3678229164523611),
            (1.5, 0.3215854164543175),
            (1.794_135_453_615_805_6, 0.2792982760539694),
            (2.857, 0.1871148342026104),
            (2.8572, 0.1871029939203215),
            (5.0, 0.11070463773306863),
            (17.3, 0.03255790299363966),
            (2.0, 0.25539567631050575),
            (3.5, 0.1552936556088943),
            (10.0, 0.05614099274382259),
            (25.9, 0.02176718115073821),
            (26.0, 0.021683584850562907),
            (30.0, 0.01879588886141675),
            (100.0, 0.005641613782989433),
        ] {
            let e = erfcx(u);
            assert!((e / want - 1.0).abs() < 4e-16, "erfcx({u}) = {e} vs {want}");
        }
    }
}
