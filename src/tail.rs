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
//! and the density of |τ| at R is R/(π sx sy) ∫_0^π e^{−Q_R/2} dθ. Both terms of J are positive;
//! K, which vanishes like 1/(2u²), is taken from Laplace's continued fraction for erfcx
//! (√π erfcx(u) = 1/(u + r), K = r/(u + r)) for u ≥ 2, so no digits cancel; for u < 0 the
//! factor e^{u²} is moved into the exponent. Q_R is quadratic in cos θ, so its minima over θ
//! (θ = 0 or the vertex, and θ = π) are known in closed form; the θ-integral is split into panels
//! growing geometrically from each minimum in units of the peak's width √(2/Q_θθ), and each panel
//! is bisected until 10- and 20-point Gauss–Legendre agree to 1e−14 of the total (their
//! difference summed is the error estimate). The integrand is scaled by its value at the peak
//! before exponentiation, so ε = 1e−300 and far below are computed like ε = 0.1.
//!
//! Degenerate cases in closed form: sy = 0 (or sy < 1e−20 sx, which moves τ* by less than
//! 1e−40 relative) is the folded normal; sx = 0 likewise gives P = erfc(√(R² − m²)/(√2 sy));
//! sx = sy = 0 is the constant |τ| = m.

use crate::error::Error;
use crate::prec::{EPS, Estimate, Termination};
use crate::quad::gauss_legendre;
use std::f64::consts::PI;
use std::sync::OnceLock;

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
        for _ in 0..200 {
            let f = at.ln_p.value - target;
            if f > 0.0 {
                lo = x;
            } else {
                hi = x;
            }
            let mut next = phi_step(at, x, phi_eps).unwrap_or(x - f / at.slope);
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            step = (next - x).abs();
            x = next;
            at = self.ln_exceedance(x);
            if step <= PEAK_RTOL * x || hi - lo <= PEAK_RTOL * x {
                break;
            }
        }
        let err = (at.ln_p.value - target).abs().max(at.ln_p.err) / at.slope.abs()
            + step.min(hi - lo)
            + 4.0 * EPS * x;
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

fn rules() -> &'static [(Vec<f64>, Vec<f64>); 2] {
    static R: OnceLock<[(Vec<f64>, Vec<f64>); 2]> = OnceLock::new();
    R.get_or_init(|| [gauss_legendre(10), gauss_legendre(20)])
}

/// The scaled problem (max(sx, sy) = 1): the two θ-integrands and their peak.
struct Polar {
    m: f64,
    alpha: f64,
    beta: f64,
    r: f64,
    /// ln of the P-integrand and −Q_R/2 at the peak, subtracted before exponentiating.
    ref_p: f64,
    ref_f: f64,
}

impl Polar {
    /// (ln of e^{−Q_R/2} J, −Q_R/2) at θ.
    fn ln_integrands(&self, theta: f64) -> (f64, f64) {
        let (s, c) = theta.sin_cos();
        let (al, be, r, m) = (self.alpha, self.beta, self.r, self.m);
        let a = al * c * c + be * s * s;
        let dx = r * c - m;
        let half_q = 0.5 * (al * dx * dx + be * r * r * s * s);
        let g = r * a - al * m * c;
        let sa = (2.0 * a).sqrt();
        let u = g / sa;
        let k = (PI / (2.0 * a)).sqrt();
        let ln_p = if u >= 0.0 {
            let (ex, kk) = erfcx_and_k(u);
            -half_q + (r * k * ex + kk / a).ln()
        } else {
            let ec = libm::erfc(u);
            -half_q + u * u + (r * k * ec + ((-u * u).exp() - PI.sqrt() * u * ec) / a).ln()
        };
        (ln_p, -half_q)
    }

    /// ∫ over [a, b] of both scaled integrands by 10- and 20-point Gauss–Legendre.
    fn panel(&self, a: f64, b: f64) -> [[f64; 2]; 2] {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let mut out = [[0.0; 2]; 2];
        for (k, (x, w)) in rules().iter().enumerate() {
            for (xi, wi) in x.iter().zip(w) {
                let (lp, lf) = self.ln_integrands(mid + half * xi);
                out[k][0] += wi * half * (lp - self.ref_p).exp();
                out[k][1] += wi * half * (lf - self.ref_f).exp();
            }
        }
        out
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

/// The general case, scaled so that max(sx, sy) = 1.
fn polar(m: f64, sx: f64, sy: f64, r: f64, rtol: f64) -> LnExceedance {
    let (alpha, beta) = (1.0 / (sx * sx), 1.0 / (sy * sy));
    let peaks = peaks_of(m, alpha, beta, r);
    let theta_p = peaks[0].0;
    let mut pol = Polar {
        m,
        alpha,
        beta,
        r,
        ref_p: 0.0,
        ref_f: 0.0,
    };
    let (lp, lf) = pol.ln_integrands(theta_p);
    pol.ref_p = lp;
    pol.ref_f = lf;
    // Breakpoints θ ± w·2^k (k = −1..) around each peak, clipped to [0, π].
    let mut cuts = vec![0.0, PI];
    for &(theta, w) in &peaks {
        cuts.push(theta);
        let mut d = 0.5 * w;
        while d < PI {
            for t in [theta - d, theta + d] {
                if t > 0.0 && t < PI {
                    cuts.push(t);
                }
            }
            d *= 2.0;
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let mut stack: Vec<(f64, f64, u32, [[f64; 2]; 2])> = cuts
        .windows(2)
        .map(|c| (c[0], c[1], 0, pol.panel(c[0], c[1])))
        .collect();
    // The panels around the peak set the scale against which the others are judged.
    let total: [f64; 2] = [0, 1].map(|j| stack.iter().map(|p| p.3[1][j]).sum());
    let (mut sum, mut err) = ([0.0; 2], [0.0; 2]);
    let mut status = Termination::Converged;
    while let Some((a, b, depth, p)) = stack.pop() {
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
            stack.push((a, c, depth + 1, pol.panel(a, c)));
            stack.push((c, b, depth + 1, pol.panel(c, b)));
        }
    }
    let norm = -(PI * sx * sy).ln();
    let ln_p = norm + pol.ref_p + sum[0].ln();
    let ln_f = norm + r.ln() + pol.ref_f + sum[1].ln();
    // Rounding: the exponent (up to ~|ln P|) to a few ulp, and J's erfcx and K (K loses up to a
    // digit below u = 2) to ~1e-15 each; the sum over the nodes was measured off the 30-digit
    // reference by up to 1.2e-14 for sy/sx = 1e-3, so 2e-14 is allowed.
    let rel = err[0] / sum[0] + 2e-14 + 8.0 * EPS * pol.ref_p.abs();
    LnExceedance {
        ln_p: Estimate::new(ln_p, rel, status),
        slope: -(ln_f - ln_p).exp(),
    }
}
