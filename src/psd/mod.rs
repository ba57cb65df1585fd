//! Roughness power spectra C(q): tabulated data and the paper's models, and their moments.
//!
//! Conventions (notes.md): C(q) is the isotropic 2D power spectrum in m^4, q in 1/m, with
//! h_rms² = ∫d²q C = 2π∫ q C dq, rms slope ξ² = 2π∫ q³ C dq and (here) rms Laplacian
//! curvature κ² = ⟨(∇²h)²⟩ = 2π∫ q⁵ C dq.
//!
//! - [`Tabulated`]: measured points, interpolated log–log (a power law between points).
//! - Self-affine model, eq. (2): C = C0 (q/q_r)^{−2(1+H)} for q_r ≤ q ≤ q1, with an optional
//!   flat roll-off C = C0 for q0 ≤ q < q_r (q_r = q0: no roll-off, the paper's form).
//! - Gaussian narrow band, eq. (5): C = h0²/(q Q (2π)^{3/2}) · e^{−(q−q0)²/2Q²}.
//!
//! Every spectrum is zero outside its support [q_lo, q_hi]. Integrals are taken in u = ln q
//! between the spectrum's own knots (its data points, q0, q_r, q1, or steps of Q/2 across the
//! Gaussian band), so no feature of the data is smoothed away.

pub mod abel;
pub mod ce;
pub mod convention;
pub mod read;

use crate::error::Error;
use crate::prec::{Estimate, Termination};
use crate::quad;
use serde::Serialize;

/// Tabulated spectrum: strictly increasing q > 0, C > 0, at least two points.
#[derive(Debug, Clone, PartialEq)]
pub struct Tabulated {
    q: Vec<f64>,
    c: Vec<f64>,
}

impl Tabulated {
    /// Validate and build. Errors name the (0-based) point index; file readers add file and line.
    pub fn new(q: Vec<f64>, c: Vec<f64>) -> Result<Self, Error> {
        if q.len() != c.len() {
            return Err(Error::invalid(
                "spectrum",
                format!("{} q values and {} C values", q.len(), c.len()),
                "as many C values as q values",
            ));
        }
        if q.len() < 2 {
            return Err(Error::invalid(
                "spectrum",
                format!("{} point(s)", q.len()),
                "at least 2 points",
            ));
        }
        for (i, (&qi, &ci)) in q.iter().zip(&c).enumerate() {
            if !(qi.is_finite() && qi > 0.0) {
                return Err(Error::invalid(
                    "wavenumber q",
                    format!("{qi} at point {i}"),
                    "a finite q > 0",
                ));
            }
            if !(ci.is_finite() && ci > 0.0) {
                return Err(Error::invalid(
                    "power spectrum C",
                    format!("{ci} at point {i}"),
                    "a finite C > 0",
                ));
            }
            if i > 0 && qi <= q[i - 1] {
                return Err(Error::invalid(
                    "wavenumber q",
                    format!("{qi} at point {i} after {}", q[i - 1]),
                    "strictly increasing q",
                ));
            }
        }
        Ok(Self { q, c })
    }

    pub fn q(&self) -> &[f64] {
        &self.q
    }

    pub fn c_values(&self) -> &[f64] {
        &self.c
    }

    fn eval(&self, q: f64) -> f64 {
        let n = self.q.len();
        if !(q >= self.q[0] && q <= self.q[n - 1]) {
            return 0.0;
        }
        let i = match self.q.partition_point(|&x| x <= q) {
            0 => 0,
            k if k >= n => n - 2,
            k => k - 1,
        };
        let slope = (self.c[i + 1] / self.c[i]).ln() / (self.q[i + 1] / self.q[i]).ln();
        self.c[i] * (q / self.q[i]).powf(slope)
    }

    /// The part of the spectrum inside [q_min, q_max], with end points interpolated log–log.
    pub fn restricted(&self, q_min: Option<f64>, q_max: Option<f64>) -> Result<Self, Error> {
        let lo = q_min.unwrap_or(self.q[0]).max(self.q[0]);
        let hi = q_max.unwrap_or(f64::INFINITY).min(*self.q.last().unwrap());
        if lo >= hi || lo.is_nan() || hi.is_nan() {
            return Err(Error::invalid(
                "q range",
                format!("[{lo}, {hi}]"),
                "q_min < q_max overlapping the data",
            ));
        }
        let mut q = vec![lo];
        let mut c = vec![self.eval(lo)];
        for (&qi, &ci) in self.q.iter().zip(&self.c) {
            if qi > lo && qi < hi {
                q.push(qi);
                c.push(ci);
            }
        }
        q.push(hi);
        c.push(self.eval(hi));
        Self::new(q, c)
    }
}

/// Self-affine spectrum (eq. 2) with optional flat roll-off below q_r.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SelfAffine {
    pub hurst: f64,
    /// Lowest wavenumber (long-wavelength cut-off), 1/m.
    pub q0: f64,
    /// Roll-off wavenumber (= q0 when there is no roll-off), 1/m.
    pub q_r: f64,
    /// Short-wavelength cut-off, 1/m.
    pub q1: f64,
    /// C at q_r, m^4.
    pub c_r: f64,
}

/// Gaussian narrow-band spectrum (eq. 5).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GaussianBand {
    /// Centre wavenumber, 1/m.
    pub q0: f64,
    /// rms width Q, 1/m.
    pub width: f64,
    /// The amplitude h0 of eq. (5) (the rms height when the band is far from q = 0), m.
    pub h0: f64,
}

/// A roughness power spectrum.
#[derive(Debug, Clone, PartialEq)]
pub enum Spectrum {
    Tabulated(Tabulated),
    SelfAffine(SelfAffine),
    Gaussian(GaussianBand),
}

/// A parameter of the paper's roughness models.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModelParam {
    Hurst,
    Q0,
    Q1,
    RollOff,
    Width,
}

impl ModelParam {
    fn error(self, error: Error) -> ModelError {
        ModelError { param: self, error }
    }
}

/// A model parameter outside the model's domain: which one, and the error that says why.
#[derive(Debug)]
pub struct ModelError {
    pub param: ModelParam,
    pub error: Error,
}

/// How many Gaussian widths either side of the peak are integrated (e^{−h²/2} < 1e-19 beyond).
const GAUSS_HALF_SPAN: f64 = 9.5;

impl Spectrum {
    /// Self-affine model with C(q_r) = 1 m^4; scale it with [`Spectrum::scaled_to_rms_slope`]
    /// or [`Spectrum::scaled_to_rms_height`].
    pub fn self_affine(hurst: f64, q0: f64, q1: f64, roll_off: Option<f64>) -> Result<Self, Error> {
        Self::self_affine_checked(hurst, q0, q1, roll_off).map_err(|e| e.error)
    }

    /// [`Spectrum::self_affine`], its error naming the parameter outside the model's domain.
    pub fn self_affine_checked(
        hurst: f64,
        q0: f64,
        q1: f64,
        roll_off: Option<f64>,
    ) -> Result<Self, ModelError> {
        if !(hurst.is_finite() && hurst > 0.0 && hurst <= 1.0) {
            return Err(ModelParam::Hurst.error(Error::invalid(
                "Hurst exponent H",
                hurst,
                "0 < H <= 1",
            )));
        }
        if !(q0.is_finite() && q0 > 0.0) {
            return Err(ModelParam::Q0.error(Error::invalid("q0", q0, "a finite q0 > 0 in 1/m")));
        }
        if !(q1.is_finite() && q1 > q0) {
            return Err(ModelParam::Q1.error(Error::invalid("q1", q1, "a finite q1 > q0")));
        }
        let q_r = roll_off.unwrap_or(q0);
        if !(q_r >= q0 && q_r < q1) {
            return Err(ModelParam::RollOff.error(Error::invalid(
                "roll-off q_r",
                q_r,
                "q0 <= q_r < q1",
            )));
        }
        Ok(Spectrum::SelfAffine(SelfAffine {
            hurst,
            q0,
            q_r,
            q1,
            c_r: 1.0,
        }))
    }

    /// Gaussian band (eq. 5) with h0 = 1 m; scale it to the wanted rms slope or height.
    pub fn gaussian(q0: f64, width: f64) -> Result<Self, Error> {
        Self::gaussian_checked(q0, width).map_err(|e| e.error)
    }

    /// [`Spectrum::gaussian`], its error naming the parameter outside the model's domain.
    pub fn gaussian_checked(q0: f64, width: f64) -> Result<Self, ModelError> {
        if !(q0.is_finite() && q0 > 0.0) {
            return Err(ModelParam::Q0.error(Error::invalid("q0", q0, "a finite q0 > 0 in 1/m")));
        }
        if !(width.is_finite() && width > 0.0 && width <= q0 / 3.0) {
            return Err(ModelParam::Width.error(Error::invalid(
                "Gaussian width Q",
                width,
                "0 < Q <= q0/3 (a band well away from q = 0)",
            )));
        }
        Ok(Spectrum::Gaussian(GaussianBand { q0, width, h0: 1.0 }))
    }

    /// C(q) in m^4 (0 outside the support).
    pub fn c(&self, q: f64) -> f64 {
        match self {
            Spectrum::Tabulated(t) => t.eval(q),
            Spectrum::SelfAffine(s) => {
                if !(q >= s.q0 && q <= s.q1) {
                    0.0
                } else if q < s.q_r {
                    s.c_r
                } else {
                    s.c_r * (q / s.q_r).powf(-2.0 * (1.0 + s.hurst))
                }
            }
            Spectrum::Gaussian(g) => {
                let (lo, hi) = self.support();
                if !(q >= lo && q <= hi) {
                    return 0.0;
                }
                let x = (q - g.q0) / g.width;
                g.h0 * g.h0 / (q * g.width * (2.0 * std::f64::consts::PI).powf(1.5))
                    * (-0.5 * x * x).exp()
            }
        }
    }

    /// The support [q_lo, q_hi] over which C is integrated.
    pub fn support(&self) -> (f64, f64) {
        match self {
            Spectrum::Tabulated(t) => (t.q[0], *t.q.last().unwrap()),
            Spectrum::SelfAffine(s) => (s.q0, s.q1),
            Spectrum::Gaussian(g) => (
                (g.q0 - GAUSS_HALF_SPAN * g.width).max(g.q0 * 1e-3),
                g.q0 + GAUSS_HALF_SPAN * g.width,
            ),
        }
    }

    /// The lowest wavenumber of the spectrum (q_L, the longest wavelength present).
    pub fn q_low(&self) -> f64 {
        self.support().0
    }

    /// Knots: points between which ln C is smooth (data points, q0, q_r, q1, or steps of Q/2).
    /// Whether C is a power law between consecutive [`knots`](Self::knots) (tabulated and
    /// self-affine spectra; not the Gaussian band).
    pub fn is_piecewise_power_law(&self) -> bool {
        !matches!(self, Spectrum::Gaussian(_))
    }

    pub fn knots(&self) -> Vec<f64> {
        match self {
            Spectrum::Tabulated(t) => t.q.clone(),
            Spectrum::SelfAffine(s) => {
                if s.q_r > s.q0 {
                    vec![s.q0, s.q_r, s.q1]
                } else {
                    vec![s.q0, s.q1]
                }
            }
            Spectrum::Gaussian(g) => {
                let (lo, hi) = self.support();
                let mut k = vec![lo];
                let mut q = g.q0 - GAUSS_HALF_SPAN * g.width + 0.5 * g.width;
                while q < hi {
                    if q > lo {
                        k.push(q);
                    }
                    q += 0.5 * g.width;
                }
                k.push(hi);
                k
            }
        }
    }

    /// The spectrum multiplied by `factor` (> 0).
    pub fn scaled(&self, factor: f64) -> Spectrum {
        match self {
            Spectrum::Tabulated(t) => Spectrum::Tabulated(Tabulated {
                q: t.q.clone(),
                c: t.c.iter().map(|c| c * factor).collect(),
            }),
            Spectrum::SelfAffine(s) => Spectrum::SelfAffine(SelfAffine {
                c_r: s.c_r * factor,
                ..*s
            }),
            Spectrum::Gaussian(g) => Spectrum::Gaussian(GaussianBand {
                h0: g.h0 * factor.sqrt(),
                ..*g
            }),
        }
    }

    /// The moment 2π∫ q^{1+k} C(q) dq (k = 0: h_rms², 2: ξ², 4: κ²). In ln q the integrand
    /// q^{2+k} C is an exact exponential on every knot interval of a tabulated or self-affine
    /// spectrum, integrated in closed form (error: rounding); a Gaussian band's is integrated
    /// numerically ([`Spectrum::moment_numerical`]).
    pub fn moment(&self, k: i32) -> Estimate {
        let (q, c): (Vec<f64>, Vec<f64>) = match self {
            Spectrum::Tabulated(t) => (t.q.clone(), t.c.clone()),
            Spectrum::SelfAffine(_) => {
                let q = self.knots();
                let c = q.iter().map(|&q| self.c(q)).collect();
                (q, c)
            }
            Spectrum::Gaussian(_) => return self.moment_numerical(k),
        };
        let (mut sum, mut abs) = (0.0, 0.0);
        for i in 0..q.len() - 1 {
            let h = (q[i + 1] / q[i]).ln();
            let wa = q[i].powi(2 + k) * c[i];
            let wb = q[i + 1].powi(2 + k) * c[i + 1];
            // ∫ W du for ln W linear over width h: h·W_max·(1 − e^{−z})/z with z = |ln(W_b/W_a)|,
            // from the larger end so that nothing overflows; (1 − e^{−z})/z → 1 as z → 0.
            let (big, small) = if wa >= wb { (wa, wb) } else { (wb, wa) };
            let z = (big / small).ln();
            let shape = if z > 0.0 { -(-z).exp_m1() / z } else { 1.0 };
            let v = h * big * shape;
            sum += v;
            abs += v.abs();
        }
        let two_pi = 2.0 * std::f64::consts::PI;
        let err = two_pi * (q.len() as f64 + 16.0) * crate::prec::EPS * abs;
        Estimate::new(two_pi * sum, err, Termination::Converged)
    }

    /// The moment 2π∫ q^{1+k} C(q) dq integrated in ln q on the knot intervals with 10- and
    /// 5-point Gauss–Legendre; the error is their difference plus rounding. Any spectrum.
    pub fn moment_numerical(&self, k: i32) -> Estimate {
        let knots = self.knots();
        let (x10, w10) = quad::gl10();
        let (x5, w5) = quad::gl5();
        let (mut hi, mut lo, mut abs) = (0.0, 0.0, 0.0);
        for pair in knots.windows(2) {
            let (ua, ub) = (pair[0].ln(), pair[1].ln());
            // Sub-panels no wider than 0.25 in ln q keep 10-point rules at rounding level.
            let n = (((ub - ua) / 0.25).ceil() as usize).max(1);
            let h = (ub - ua) / n as f64;
            for p in 0..n {
                let mid = ua + (p as f64 + 0.5) * h;
                let f = |x: f64| {
                    let u = mid + 0.5 * h * x;
                    let q = u.exp();
                    q.powi(2 + k) * self.c(q)
                };
                let a: f64 = x10.iter().zip(w10).map(|(&x, &w)| w * f(x)).sum::<f64>() * 0.5 * h;
                let b: f64 = x5.iter().zip(w5).map(|(&x, &w)| w * f(x)).sum::<f64>() * 0.5 * h;
                hi += a;
                lo += b;
                abs += a.abs();
            }
        }
        let two_pi = 2.0 * std::f64::consts::PI;
        let err = two_pi * ((hi - lo).abs() + 16.0 * crate::prec::EPS * abs * knots.len() as f64);
        Estimate::new(two_pi * hi, err, Termination::Converged)
    }

    /// Mean-square height h_rms² = 2π∫ q C dq, m².
    pub fn h_rms_sq(&self) -> Estimate {
        self.moment(0)
    }

    /// Mean-square slope ξ² = 2π∫ q³ C dq.
    pub fn slope_sq(&self) -> Estimate {
        self.moment(2)
    }

    /// Mean-square Laplacian curvature κ² = 2π∫ q⁵ C dq, 1/m².
    pub fn curvature_sq(&self) -> Estimate {
        self.moment(4)
    }

    /// The spectrum scaled so that its rms slope is `xi`.
    pub fn scaled_to_rms_slope(&self, xi: f64) -> Result<Spectrum, Error> {
        if !(xi.is_finite() && xi > 0.0) {
            return Err(Error::invalid("rms slope", xi, "a finite slope > 0"));
        }
        Ok(self.scaled(xi * xi / self.slope_sq().value))
    }

    /// The spectrum scaled so that its rms height is `h_rms` (m).
    pub fn scaled_to_rms_height(&self, h_rms: f64) -> Result<Spectrum, Error> {
        if !(h_rms.is_finite() && h_rms > 0.0) {
            return Err(Error::invalid(
                "rms height",
                h_rms,
                "a finite height > 0 in m",
            ));
        }
        Ok(self.scaled(h_rms * h_rms / self.h_rms_sq().value))
    }
}
