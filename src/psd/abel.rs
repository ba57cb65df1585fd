//! One- and two-dimensional power spectra of an isotropic surface: the exact Abel pair.
//!
//! Conventions (used everywhere in `coatcheck`):
//! - 2D PSD (m^4, notes.md and paper eq. A2): C(q) = (2π)^−2 ∫d²x ⟨h(x)h(0)⟩ e^{−iq·x}, so
//!   h_rms² = ∫d²q C = 2π∫_0^∞ q C(q) dq.
//! - 1D PSD of a line scan (m^3), **one-sided**: C1D(q) = π^−1 ∫dx ⟨h(x)h(0)⟩ e^{−iqx} for q ≥ 0,
//!   so h_rms² = ∫_0^∞ C1D(q) dq (twice the two-sided (2π)^−1 convention, which integrates
//!   over −∞ < q < ∞).
//!
//! For an isotropic surface a line scan sees the 2D spectrum integrated across the scan
//! direction, C1D(q) = 2∫_{−∞}^{∞} C(√(q² + k_y²)) dk_y, i.e. twice the forward Abel transform:
//!
//!   C1D(q) = 4 ∫_q^∞ k C(k) / √(k² − q²) dk,                                (forward)
//!   C(k)   = −(1/2π) ∫_k^∞ C1D′(q) / √(q² − k²) dq.                          (inverse)
//!
//! Both kernels have an integrable inverse-square-root singularity at the lower end. The
//! substitution k = q cosh u (forward) or q = k cosh u (inverse) removes it exactly:
//! dk/√(k² − q²) = du, leaving smooth integrands that 10- and 5-point Gauss–Legendre rules
//! integrate on panels no wider than 0.25 in u, split at the data's knots (the difference of
//! the two rules is the error estimate). In the inverse transform, data segments more than a
//! factor 2 above k see a smooth kernel; they are integrated in ln q on fixed nodes shared by
//! all k, which makes the O(n²) conversion cheap.
//!
//! Tabulated C1D enters through its derivative, so it is interpolated smoothly: ln C1D as a
//! piecewise cubic Hermite polynomial in ln q with second-order three-point knot slopes (a
//! piecewise power law would make C1D′ jump at every point, and the singular kernel turns such
//! jumps into O(h^1.5) errors; the cubic gives O(h^3)-accurate derivatives).
//! Beyond the last point the inverse transform needs C1D to go on: it is continued as the power
//! law q^s fitted (least squares, log–log) to the points in the last octave, which must fall
//! faster than 1/q (s < −1, a finite h_rms²). C near the last octave depends on that
//! assumption; the reader says so in a warning.
//!
//! A measured C1D (a periodogram binned in q, [`c2d_from_measured_c1d`]) scatters by 1/√m in a
//! bin of m modes, and the transform, a half derivative, turns a local rise of that scatter
//! into C < 0 (a single stylus profile nearly always has one). For an isotropic surface whose
//! C(k) does not increase with k (self-affine, with or without roll-off: the surfaces this tool
//! models) C1D(q) = 2∫C(√(q² + k_y²)) dk_y does not increase either, so the measured ln C1D is
//! replaced by its least-squares non-increasing fit weighted by m (isotonic regression) and
//! interpolated by a monotone cubic (Fritsch–Carlson slopes). Then C1D′ ≤ 0 everywhere and
//! every quadrature term of C is ≥ 0, with the tail's strictly > 0: C is positive and finite
//! by construction. Points that already fall are kept as they are. Accuracy on one row of
//! synthetic self-affine maps (H = 0.3 … 1): rms slope² within 35 % and C within the
//! single-scan scatter, mean ln(C/C_exact) within ±0.35 (test
//! `one_line_scan_converts_to_a_positive_2d_psd_near_the_true_one`); with many scans the
//! data are already non-increasing and only the end slopes can change. A ring spectrum (C
//! peaked away from q = 0) has a rising C1D that this fit flattens: read such data as a 2D map.
//! Tabulated C1D that never rises ([`c2d_from_c1d`], e.g. a 1D PSD file) is interpolated by
//! the same monotone cubic; C1D that rises somewhere by the plain one.
//!
//! The shortcut C(q) ≈ C1D(q)/(πq) ([`Conversion::PiQShortcut`]) is exact only for a pure
//! power law with H = 1; in general C1D/(πq C) = 2Γ(H + ½)/(√π Γ(H + 1)), which is 4/π
//! (27 % too high a C) for H = 0.5. It is offered only as a named option.

use crate::error::Error;
use crate::prec::{EPS, Estimate, Termination};
use crate::psd::{Spectrum, Tabulated};
use crate::quad;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Widest panel (in u) integrated with one pair of Gauss–Legendre rules.
const PANEL: f64 = 0.25;

/// acosh(e^t) for t ≥ 0 without forming e^t: t + ln(1 + √(1 − e^{−2t})). e^t overflows above
/// t ≈ 709 (points more than 308 decades apart, which the reader accepts), and acosh(∞) = ∞
/// would be an endless panel count.
fn acosh_exp(t: f64) -> f64 {
    t + (-(-2.0 * t).exp_m1()).sqrt().ln_1p()
}

/// ln cosh u for u ≥ 0 without forming cosh u (which overflows above u ≈ 710):
/// u − ln 2 + ln(1 + e^{−2u}).
fn ln_cosh(u: f64) -> f64 {
    u - std::f64::consts::LN_2 + (-2.0 * u).exp().ln_1p()
}

/// How a 1D PSD is turned into the isotropic 2D PSD.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Conversion {
    /// The exact relation: inverse Abel transform of C1D (default).
    #[default]
    InverseAbel,
    /// C = C1D/(πq): exact only for a power law with H = 1 (see the module docs).
    PiQShortcut,
}

/// ∫ f over consecutive `breaks` (each interval split into panels no wider than `width`):
/// returns (10-point value, |10-point − 5-point|, Σ|panel values|).
fn integrate(breaks: &[f64], width: f64, f: impl Fn(f64) -> f64) -> (f64, f64, f64) {
    let (x10, w10) = quad::gl10();
    let (x5, w5) = quad::gl5();
    let (mut hi, mut diff, mut abs) = (0.0, 0.0, 0.0);
    for pair in breaks.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if b <= a {
            continue;
        }
        let n = ((b - a) / width).ceil().max(1.0) as usize;
        let h = (b - a) / n as f64;
        for p in 0..n {
            let mid = a + (p as f64 + 0.5) * h;
            let g = |x: f64| f(mid + 0.5 * h * x);
            let v10: f64 = x10.iter().zip(w10).map(|(&x, &w)| w * g(x)).sum::<f64>() * 0.5 * h;
            let v5: f64 = x5.iter().zip(w5).map(|(&x, &w)| w * g(x)).sum::<f64>() * 0.5 * h;
            hi += v10;
            diff += (v10 - v5).abs();
            abs += v10.abs();
        }
    }
    (hi, diff, abs)
}

fn estimate(value: f64, diff: f64, abs: f64, panels: usize) -> Estimate {
    Estimate::new(
        value,
        diff + 16.0 * EPS * abs * panels.max(1) as f64,
        Termination::Converged,
    )
}

/// Forward transform: C1D(q) = 4∫_q^∞ k C(k)/√(k² − q²) dk for a 2D PSD `c` that is zero
/// outside `[knots[0], knots[last]]` and smooth between consecutive knots (sorted, > 0).
pub fn c1d_at(c: impl Fn(f64) -> f64, knots: &[f64], q: f64) -> Estimate {
    let (Some(&lo), Some(&hi)) = (knots.first(), knots.last()) else {
        return Estimate::exact(0.0);
    };
    if !(q > 0.0 && q < hi) {
        return Estimate::exact(0.0);
    }
    let lnq = q.ln();
    let mut breaks = vec![acosh_exp(lo.max(q).ln() - lnq)];
    breaks.extend(
        knots
            .iter()
            .filter(|&&k| k > lo.max(q))
            .map(|&k| acosh_exp(k.ln() - lnq)),
    );
    let (v, d, a) = integrate(&breaks, PANEL, |u| {
        let k = (lnq + ln_cosh(u)).exp();
        k * c(k)
    });
    estimate(4.0 * v, 4.0 * d, 4.0 * a, breaks.len())
}

/// Forward transform of a [`Spectrum`]: its one-sided 1D PSD at `q` (m^3).
pub fn c1d_of_spectrum(spectrum: &Spectrum, q: f64) -> Estimate {
    c1d_at(|k| spectrum.c(k), &spectrum.knots(), q)
}

/// A 2D PSD converted from a 1D PSD, point by point at the input's q (not yet validated:
/// noisy or inconsistent data can give C ≤ 0 somewhere; [`Converted::into_tabulated`] checks).
#[derive(Debug, Clone, PartialEq)]
pub struct Converted {
    pub q: Vec<f64>,
    /// C(q) in m^4 with the quadrature error of each point.
    pub c: Vec<Estimate>,
    pub method: Conversion,
    /// The power-law exponent s of the tail C1D ∝ q^s assumed beyond the data (inverse Abel).
    pub tail_exponent: Option<f64>,
    /// What the non-increasing fit of a measured C1D changed ([`c2d_from_measured_c1d`]).
    pub fit: Option<MonotoneFit>,
}

impl Converted {
    /// The largest relative quadrature error over the points.
    pub fn max_rel_err(&self) -> f64 {
        self.c.iter().map(|e| e.rel_err()).fold(0.0, f64::max)
    }

    /// Validate into a [`Tabulated`] spectrum (errors name the point index).
    pub fn into_tabulated(self) -> Result<Tabulated, Error> {
        Tabulated::new(self.q, self.c.iter().map(|e| e.value).collect())
    }
}

/// The exponent s of the power-law tail C1D ∝ q^s: a log–log least-squares fit to the points
/// with q ≥ q_last/2 (at least the last two).
pub fn tail_exponent(q: &[f64], c1d: &[f64]) -> f64 {
    let n = q.len();
    let q_last = q[n - 1];
    let first = q
        .iter()
        .position(|&x| x >= 0.5 * q_last)
        .unwrap_or(n - 2)
        .min(n - 2);
    let pts: Vec<(f64, f64)> = (first..n)
        .map(|i| ((q[i] / q_last).ln(), c1d[i].ln()))
        .collect();
    let m = pts.len() as f64;
    let (sx, sy) = pts
        .iter()
        .fold((0.0, 0.0), |(a, b), &(x, y)| (a + x, b + y));
    let (mx, my) = (sx / m, sy / m);
    let (sxy, sxx) = pts.iter().fold((0.0, 0.0), |(a, b), &(x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx))
    });
    sxy / sxx
}

/// Convert a tabulated one-sided 1D PSD (q in 1/m, C1D in m^3; validated like
/// [`Tabulated::new`]) to the isotropic 2D PSD at the same q, interpolating the points: by a
/// monotone cubic when they never rise (then every C is positive), else by the plain cubic.
pub fn c2d_from_c1d(q: &[f64], c1d: &[f64], method: Conversion) -> Result<Converted, Error> {
    let t = Tabulated::new(q.to_vec(), c1d.to_vec())?;
    let monotone = t.c_values().windows(2).all(|w| w[1] <= w[0]);
    convert(t.q(), t.c_values(), method, monotone)
}

/// Convert a measured 1D PSD, binned from `modes[i]` Fourier modes per point, to the
/// isotropic 2D PSD (inverse Abel; the shortcut takes the points as they are). ln C1D is first
/// replaced by its non-increasing least-squares fit weighted by the mode counts
/// ([`non_increasing_fit`]) and then interpolated by a monotone cubic, so C1D′ ≤ 0 everywhere
/// and every C is positive (see the module docs).
pub fn c2d_from_measured_c1d(
    q: &[f64],
    c1d: &[f64],
    modes: &[f64],
    method: Conversion,
) -> Result<Converted, Error> {
    let t = Tabulated::new(q.to_vec(), c1d.to_vec())?;
    if modes.len() != q.len() || modes.iter().any(|&m| !(m.is_finite() && m > 0.0)) {
        return Err(Error::invalid(
            "mode counts",
            format!("{} counts for {} points", modes.len(), q.len()),
            "one finite count > 0 per point",
        ));
    }
    if method == Conversion::PiQShortcut {
        return c2d_from_c1d(q, c1d, method);
    }
    let ln_c: Vec<f64> = t.c_values().iter().map(|c| c.ln()).collect();
    let ln_fit = non_increasing_fit(&ln_c, modes);
    let fitted: Vec<f64> = (t.c_values().iter().zip(&ln_c).zip(&ln_fit))
        .map(|((&c, a), &b)| if *a == b { c } else { b.exp() })
        .collect();
    let mut conv = c2d_from_c1d(q, &fitted, method)?;
    let changes = ln_c.iter().zip(&ln_fit).filter(|(a, b)| a != b);
    conv.fit = Some(MonotoneFit {
        changed: changes.clone().count(),
        max_rel_change: changes
            .map(|(a, b)| (b - a).exp_m1().abs())
            .fold(0.0, f64::max),
    });
    Ok(conv)
}

/// The weighted least-squares fit of `y` by a non-increasing sequence (isotonic regression,
/// pool-adjacent-violators): min Σ w_i (f_i − y_i)² subject to f_0 ≥ f_1 ≥ … . Points
/// already non-increasing are returned unchanged; a run that rises is replaced by its weighted
/// mean. With y = ln C1D of a bin and w its mode count (var ln C1D ≈ 1/w for a mean of w
/// exponentially distributed periodogram values), this is the maximum-likelihood
/// non-increasing ln C1D to leading order.
pub fn non_increasing_fit(y: &[f64], w: &[f64]) -> Vec<f64> {
    // Blocks of pooled points: (weighted sum, weight, count).
    let mut blocks: Vec<(f64, f64, usize)> = Vec::with_capacity(y.len());
    for (&yi, &wi) in y.iter().zip(w) {
        blocks.push((wi * yi, wi, 1));
        while let [.., a, b] = blocks[..] {
            if a.0 / a.1 >= b.0 / b.1 {
                break;
            }
            blocks.pop();
            *blocks.last_mut().unwrap() = (a.0 + b.0, a.1 + b.1, a.2 + b.2);
        }
    }
    let mut out = Vec::with_capacity(y.len());
    let mut start = 0;
    for (sum, weight, count) in blocks {
        if count == 1 {
            out.push(y[start]);
        } else {
            out.extend(std::iter::repeat_n(sum / weight, count));
        }
        start += count;
    }
    out
}

/// What [`c2d_from_measured_c1d`]'s non-increasing fit changed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MonotoneFit {
    /// Points whose C1D the fit changed.
    pub changed: usize,
    /// The largest relative change of C1D at a point.
    pub max_rel_change: f64,
}

/// The conversion of validated points; `monotone`: C1D is non-increasing and is interpolated
/// by a monotone cubic.
fn convert(q: &[f64], f: &[f64], method: Conversion, monotone: bool) -> Result<Converted, Error> {
    match method {
        Conversion::PiQShortcut => Ok(Converted {
            q: q.to_vec(),
            c: q.iter()
                .zip(f)
                .map(|(&qi, &fi)| Estimate::exact(fi / (PI * qi)))
                .collect(),
            method,
            tail_exponent: None,
            fit: None,
        }),
        Conversion::InverseAbel => {
            let n = q.len();
            let s_tail = tail_exponent(q, f);
            if s_tail.is_nan() || s_tail >= -1.0 {
                return Err(Error::invalid(
                    "1D PSD high-q tail",
                    format!(
                        "C1D ∝ q^{s_tail:.3} over the last octave (q ≥ {:.4e} 1/m)",
                        0.5 * q[n - 1]
                    ),
                    "C1D falling faster than 1/q at its high-q end (cut any noise floor off with a q_max)",
                ));
            }
            let x: Vec<f64> = q.iter().map(|v| v.ln()).collect();
            let y: Vec<f64> = f.iter().map(|v| v.ln()).collect();
            let mut m = hermite_slopes(&x, &y);
            if monotone {
                limit_to_monotone(&x, &y, &mut m);
            }
            let far = far_segments(&x, &y, &m);
            // O(n²) work in all (each point integrates over all points above it): in parallel.
            let c = (0..n)
                .into_par_iter()
                .map(|j| inverse_at(&x, &y, &m, &far, s_tail, j))
                .collect();
            Ok(Converted {
                q: q.to_vec(),
                c,
                method,
                tail_exponent: Some(s_tail),
                fit: None,
            })
        }
    }
}

/// Fritsch–Carlson limiting of the knot slopes of non-increasing data (x, y): a slope of the
/// wrong sign, or at a knot next to a flat segment, becomes 0, and on every segment the slopes
/// relative to the secant d, α = m_i/d and β = m_{i+1}/d, are scaled into α² + β² ≤ 9, a
/// sufficient condition for the cubic to be monotone on the segment (Fritsch & Carlson 1980).
/// Scaling only shrinks slopes, so segments already in the region stay there.
fn limit_to_monotone(x: &[f64], y: &[f64], m: &mut [f64]) {
    let n = x.len();
    for i in 0..n - 1 {
        let d = (y[i + 1] - y[i]) / (x[i + 1] - x[i]);
        if d == 0.0 {
            m[i] = 0.0;
            m[i + 1] = 0.0;
            continue;
        }
        for k in [i, i + 1] {
            if m[k] * d < 0.0 {
                m[k] = 0.0;
            }
        }
        let (a, b) = (m[i] / d, m[i + 1] / d);
        let r = a.hypot(b);
        if r > 3.0 {
            m[i] *= 3.0 / r;
            m[i + 1] *= 3.0 / r;
        }
    }
}

/// Knot slopes dy/dx of the piecewise cubic Hermite interpolant of (x, y) = (ln q, ln C1D):
/// three-point (second-order) differences, one-sided at the ends.
fn hermite_slopes(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let d: Vec<f64> = (0..n - 1)
        .map(|i| (y[i + 1] - y[i]) / (x[i + 1] - x[i]))
        .collect();
    if n == 2 {
        return vec![d[0], d[0]];
    }
    let h = |i: usize| x[i + 1] - x[i];
    let mut m = vec![0.0; n];
    for i in 1..n - 1 {
        m[i] = (h(i) * d[i - 1] + h(i - 1) * d[i]) / (h(i - 1) + h(i));
    }
    m[0] = ((2.0 * h(0) + h(1)) * d[0] - h(0) * d[1]) / (h(0) + h(1));
    let (a, b) = (h(n - 2), h(n - 3));
    m[n - 1] = ((2.0 * a + b) * d[n - 2] - a * d[n - 3]) / (a + b);
    m
}

/// P and P′ of the cubic Hermite interpolant on segment i at ln q.
fn hermite(x: &[f64], y: &[f64], m: &[f64], i: usize, lnq: f64) -> (f64, f64) {
    let h = x[i + 1] - x[i];
    let t = (lnq - x[i]) / h;
    let (t2, t3) = (t * t, t * t * t);
    let p = (2.0 * t3 - 3.0 * t2 + 1.0) * y[i]
        + (t3 - 2.0 * t2 + t) * h * m[i]
        + (-2.0 * t3 + 3.0 * t2) * y[i + 1]
        + (t3 - t2) * h * m[i + 1];
    let dp = ((6.0 * t2 - 6.0 * t) * (y[i] - y[i + 1])) / h
        + (3.0 * t2 - 4.0 * t + 1.0) * m[i]
        + (3.0 * t2 - 2.0 * t) * m[i + 1];
    (p, dp)
}

/// Quadrature nodes of one data segment in ln q, used where the segment lies at q ≥ 2k: there
/// the kernel 1/√(q² − k²) is smooth, so fixed nodes serve every k. Per node: q² and the
/// weight times q·dC1D/dq = C1D·P′, for the 10- and the 5-point rule (panels ≤ 0.25 in ln q).
struct FarSegment {
    q2_10: Vec<f64>,
    g10: Vec<f64>,
    q2_5: Vec<f64>,
    g5: Vec<f64>,
}

/// Nearest distance in ln q between k and a segment integrated with [`FarSegment`] nodes.
const FAR: f64 = std::f64::consts::LN_2;

fn far_segments(x: &[f64], y: &[f64], m: &[f64]) -> Vec<FarSegment> {
    let (x10, w10) = quad::gl10();
    let (x5, w5) = quad::gl5();
    (0..x.len() - 1)
        .map(|i| {
            let (a, b) = (x[i], x[i + 1]);
            let panels = ((b - a) / PANEL).ceil().max(1.0) as usize;
            let h = (b - a) / panels as f64;
            let mut seg = FarSegment {
                q2_10: Vec::new(),
                g10: Vec::new(),
                q2_5: Vec::new(),
                g5: Vec::new(),
            };
            for p in 0..panels {
                let mid = a + (p as f64 + 0.5) * h;
                for (xs, ws, q2, g) in [
                    (x10, w10, &mut seg.q2_10, &mut seg.g10),
                    (x5, w5, &mut seg.q2_5, &mut seg.g5),
                ] {
                    for (&xn, &wn) in xs.iter().zip(ws) {
                        let lnq = mid + 0.5 * h * xn;
                        let (pv, dp) = hermite(x, y, m, i, lnq);
                        q2.push((2.0 * lnq).exp());
                        g.push(0.5 * h * wn * pv.exp() * dp);
                    }
                }
            }
            seg
        })
        .collect()
}

/// C(k) at k = q[j] by the inverse Abel transform of C1D = exp(P(ln q)), P the cubic Hermite
/// interpolant of the knots (x, y) = (ln q, ln C1D) with slopes m, continued beyond the last
/// knot as the power law q^s_tail. Segments within a factor 2 of k are integrated in
/// u = acosh(q/k) (singularity removed), those beyond with the fixed nodes of `far`.
fn inverse_at(
    x: &[f64],
    y: &[f64],
    m: &[f64],
    far: &[FarSegment],
    s_tail: f64,
    j: usize,
) -> Estimate {
    let n = x.len();
    let lnk = x[j];
    let k2 = (2.0 * lnk).exp();
    let (mut v, mut d, mut a, mut panels) = (0.0, 0.0, 0.0, 0);
    for i in j..n - 1 {
        panels += 1;
        if x[i] - lnk >= FAR {
            let f = &far[i];
            let s10: f64 = f
                .q2_10
                .iter()
                .zip(&f.g10)
                .map(|(q2, g)| g / (q2 - k2).sqrt())
                .sum();
            let s5: f64 = f
                .q2_5
                .iter()
                .zip(&f.g5)
                .map(|(q2, g)| g / (q2 - k2).sqrt())
                .sum();
            v += s10;
            d += (s10 - s5).abs();
            a += s10.abs();
            continue;
        }
        let breaks = [acosh_exp(x[i].max(lnk) - lnk), acosh_exp(x[i + 1] - lnk)];
        // dC1D/dq = C1D(q) P'(ln q)/q, written in u with ln q = ln k + ln cosh u.
        let (vi, di, ai) = integrate(&breaks, PANEL, |u| {
            let lnq = lnk + ln_cosh(u);
            let (p, dp) = hermite(x, y, m, i, lnq);
            (p - lnq).exp() * dp
        });
        v += vi;
        d += di;
        a += ai;
    }
    // Tail: the integrand falls like e^{(s−1)u}; 42 e-folds leave < 1e-18 of it.
    let (xn, yn) = (x[n - 1], y[n - 1]);
    let u0 = acosh_exp(xn - lnk);
    let width = PANEL.min(1.0 / (1.0 - s_tail));
    let u1 = u0 + 42.0 / (1.0 - s_tail);
    let (vt, dt, at) = integrate(&[u0, u1], width, |u| {
        let lnq = lnk + ln_cosh(u);
        s_tail * (yn + s_tail * (lnq - xn) - lnq).exp()
    });
    v += vt;
    d += dt;
    a += at;
    panels += 1;
    let scale = 1.0 / (2.0 * PI);
    estimate(-scale * v, scale * d, scale * a, panels)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// acosh(e^t) and ln cosh u agree with the direct forms where those do not overflow (the
    /// stable forms are the more accurate near 0, where acosh(1 + t) cancels), and stay finite
    /// and linear beyond: acosh(e^t) → t + ln 2, ln cosh u → u − ln 2.
    /// The non-increasing fit against its definition: the result never rises, points that
    /// already fall are kept, a rising run becomes its weighted mean, and no other
    /// non-increasing sequence has a smaller weighted squared error (checked against small
    /// perturbations that stay non-increasing).
    #[test]
    fn non_increasing_fit_is_the_weighted_least_squares_one() {
        assert_eq!(
            non_increasing_fit(&[3.0, 2.0, 1.0], &[1.0; 3]),
            [3.0, 2.0, 1.0]
        );
        assert_eq!(
            non_increasing_fit(&[3.0, 1.0, 2.0, 0.0], &[1.0; 4]),
            [3.0, 1.5, 1.5, 0.0]
        );
        // Weights 1 and 3: (1·1 + 3·2)/4 = 1.75; then 1.75 < 4 pools all three: (7 + 4)/5.
        assert_eq!(
            non_increasing_fit(&[1.0, 2.0, 4.0], &[1.0, 3.0, 1.0]),
            [2.2, 2.2, 2.2]
        );
        let y = [0.3, -0.2, 0.5, 0.1, 0.4, -1.0, -0.9, -2.0];
        let w = [1.0, 2.0, 1.0, 4.0, 1.0, 3.0, 1.0, 2.0];
        let f = non_increasing_fit(&y, &w);
        assert!(f.windows(2).all(|p| p[1] <= p[0]), "{f:?}");
        let cost = |g: &[f64]| -> f64 {
            g.iter()
                .zip(&y)
                .zip(&w)
                .map(|((a, b), c)| c * (a - b).powi(2))
                .sum()
        };
        for i in 0..y.len() {
            for eps in [-1e-3, 1e-3] {
                let mut g = f.clone();
                g[i] += eps;
                if g.windows(2).all(|p| p[1] <= p[0]) {
                    assert!(cost(&g) > cost(&f), "{i} {eps}");
                }
            }
        }
    }

    #[test]
    fn substitution_without_overflow() {
        for i in 1..=700 {
            let t = f64::from(i) * 0.999;
            let direct = t.exp().acosh();
            assert!((acosh_exp(t) / direct - 1.0).abs() <= 4.0 * EPS, "t = {t}");
            assert!(
                (ln_cosh(t) / t.cosh().ln() - 1.0).abs() <= 4.0 * EPS,
                "u = {t}"
            );
        }
        // Near 0: acosh(e^t) = √(2t)(1 + t/12 + …).
        let t = 1e-12;
        assert!((acosh_exp(t) / (2.0 * t).sqrt() - 1.0).abs() <= 1e-12);
        assert_eq!(ln_cosh(0.0), 0.0);
        for t in [1e3, 1e5, 1e300] {
            assert_eq!(acosh_exp(t), t + std::f64::consts::LN_2);
            assert_eq!(ln_cosh(t), t - std::f64::consts::LN_2);
        }
    }
}
