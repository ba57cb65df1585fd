//! Heights → power spectrum: detrend, window, FFT, radial average, log binning, cut-off.
//!
//! Conventions: see [`crate::topography`] (2D: h_rms² = 2π∫q C dq; 1D one-sided:
//! h_rms² = ∫_0^∞ C1D dq). Each step is recorded by name in [`TopographyPsd::steps`].
//!
//! - Detrend: least squares removal of the mean, a tilt (plane) or a curvature (quadratic),
//!   fitted with discrete orthogonal polynomials on the grid (exact, no normal equations).
//! - Window: Hann, w_i = sin²(π(i + ½)/n) (separable in 2D), by default for non-periodic data,
//!   none for periodic data. The power it removes is restored by dividing by ⟨w²⟩, so
//!   Parseval holds on average.
//! - FFT: rustfft (any length). Maps are transformed row by row into the half spectrum
//!   (kx ≥ 0; the rest follows from H(−k) = H(k)*) and then column by column, accumulating
//!   the bins on the fly, so memory stays at the heights plus one half spectrum.
//! - Radial average and log binning: modes are averaged in bins of ln q, `points_per_decade`
//!   per decade, centred on the fundamental 2π/L; each output point is the mean q and the mean
//!   C of the modes in its bin.
//!   With a window the first mode is dropped (it leaks into the removed mean).
//! - Cut-off: modes with λ < `cutoff_pixels` pixels (q > 2π/(cutoff·dx)) are dropped as
//!   unreliable (instrument transfer, noise); the summary says how much of h_rms² they held.
//!
//! The summary's moments (rms slope, curvature) are the discrete sums over the kept modes
//! (for line scans converted to the isotropic 2D values: ξ² = 2⟨h′²⟩, κ² = (8/3)⟨h″²⟩).

use super::{HeightMap, Profile};
use crate::error::Error;
use crate::psd::Tabulated;
use crate::psd::abel::{self, Conversion};
use rayon::prelude::*;
use rustfft::FftPlanner;
use rustfft::num_complex::Complex64;
use serde::Serialize;
use std::f64::consts::PI;

/// Trend removed before the FFT.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Detrend {
    /// Subtract the mean.
    Mean,
    /// Subtract the least-squares line (scans) or plane (maps).
    Tilt,
    /// Subtract the least-squares quadratic.
    Curvature,
}

impl Detrend {
    fn degree(self) -> usize {
        match self {
            Detrend::Mean => 0,
            Detrend::Tilt => 1,
            Detrend::Curvature => 2,
        }
    }
}

/// Window applied before the FFT.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Window {
    Hann,
    None,
}

/// Processing options. `None` fields take the defaults for the data: Hann window and tilt
/// removal for non-periodic data, no window and mean removal for periodic data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PsdOptions {
    pub detrend: Option<Detrend>,
    pub window: Option<Window>,
    /// Log-spaced bins per decade of q.
    pub points_per_decade: usize,
    /// Shortest wavelength kept, in pixels (≥ 2, the Nyquist limit).
    pub cutoff_pixels: f64,
    /// How the 1D PSD of line scans is turned into the 2D PSD.
    pub conversion: Conversion,
}

impl Default for PsdOptions {
    fn default() -> Self {
        Self {
            detrend: None,
            window: None,
            points_per_decade: 10,
            cutoff_pixels: 4.0,
            conversion: Conversion::InverseAbel,
        }
    }
}

/// What the spectrum says about the surface (SI).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Summary {
    /// rms height of the detrended heights (all wavelengths), m.
    pub h_rms: f64,
    /// rms height within the kept q-range, m.
    pub h_rms_kept: f64,
    /// rms slope ξ (2D, isotropic) within the kept q-range.
    pub rms_slope: f64,
    /// rms Laplacian curvature κ (2D, isotropic) within the kept q-range, 1/m.
    pub rms_curvature: f64,
    /// Kept q-range, 1/m.
    pub q_min: f64,
    pub q_max: f64,
    /// Fraction of h_rms² in modes outside the kept q-range.
    pub outside_fraction: f64,
}

/// The spectrum of measured heights.
#[derive(Debug, Clone, PartialEq)]
pub struct TopographyPsd {
    /// Isotropic 2D PSD (m^4), binned, within the kept range.
    pub c2d: Tabulated,
    /// One-sided 1D PSD (m^3), binned (line scans only).
    pub c1d: Option<Tabulated>,
    pub summary: Summary,
    /// The processing steps, in order, by name and parameters.
    pub steps: Vec<String>,
}

fn check_options(opts: &PsdOptions) -> Result<(), Error> {
    if opts.points_per_decade == 0 || opts.points_per_decade > 1000 {
        return Err(Error::invalid(
            "points per decade",
            opts.points_per_decade,
            "1 to 1000",
        ));
    }
    if !(opts.cutoff_pixels.is_finite() && opts.cutoff_pixels >= 2.0) {
        return Err(Error::invalid(
            "cut-off",
            opts.cutoff_pixels,
            "at least 2 pixels (the Nyquist wavelength)",
        ));
    }
    Ok(())
}

/// Discrete orthogonal polynomials of degree 0..=deg on the points 0..n (Gram–Schmidt on the
/// grid), each as its values.
fn orthogonal_polys(n: usize, deg: usize) -> Vec<Vec<f64>> {
    let x: Vec<f64> = (0..n).map(|i| i as f64 - 0.5 * (n as f64 - 1.0)).collect();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for d in 0..=deg.min(n.saturating_sub(1)) {
        let mut p: Vec<f64> = x.iter().map(|v| v.powi(d as i32)).collect();
        for b in &basis {
            let c = dot(&p, b) / dot(b, b);
            p.iter_mut().zip(b).for_each(|(pi, bi)| *pi -= c * bi);
        }
        basis.push(p);
    }
    basis
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Hann window of length n and its mean square.
fn hann(n: usize) -> (Vec<f64>, f64) {
    let w: Vec<f64> = (0..n)
        .map(|i| (PI * (i as f64 + 0.5) / n as f64).sin().powi(2))
        .collect();
    let ms = w.iter().map(|v| v * v).sum::<f64>() / n as f64;
    (w, ms)
}

/// Log bins of q centred on `q_lo`, with the kept range [q_lo, q_hi].
#[derive(Debug, Clone)]
struct Bins {
    q_lo: f64,
    q_hi: f64,
    ppd: f64,
    count: Vec<f64>,
    sum_q: Vec<f64>,
    sum_c: Vec<f64>,
    /// Σ C Δq (1D) or Σ C Δq² (2D) over all modes, kept modes, and the kept q², q⁴ moments.
    total: f64,
    kept: f64,
    kept_q2: f64,
    kept_q4: f64,
}

impl Bins {
    fn new(q_lo: f64, q_hi: f64, ppd: usize) -> Self {
        let ppd = ppd as f64;
        let nb = (ppd * (q_hi / q_lo).log10() + 0.5).floor() as usize + 1;
        Self {
            q_lo,
            q_hi,
            ppd,
            count: vec![0.0; nb],
            sum_q: vec![0.0; nb],
            sum_c: vec![0.0; nb],
            total: 0.0,
            kept: 0.0,
            kept_q2: 0.0,
            kept_q4: 0.0,
        }
    }

    /// Add `mult` modes at q with PSD c, each carrying power c·cell.
    fn add(&mut self, q: f64, c: f64, cell: f64, mult: f64) {
        let p = c * cell * mult;
        self.total += p;
        let tol = 1e-9;
        if q < self.q_lo * (1.0 - tol) || q > self.q_hi * (1.0 + tol) {
            return;
        }
        self.kept += p;
        self.kept_q2 += p * q * q;
        self.kept_q4 += p * q * q * q * q;
        let b = ((self.ppd * (q / self.q_lo).log10() + 0.5).floor().max(0.0) as usize)
            .min(self.count.len() - 1);
        self.count[b] += mult;
        self.sum_q[b] += mult * q;
        self.sum_c[b] += mult * c;
    }

    fn merge(mut self, o: Bins) -> Bins {
        for b in 0..self.count.len() {
            self.count[b] += o.count[b];
            self.sum_q[b] += o.sum_q[b];
            self.sum_c[b] += o.sum_c[b];
        }
        self.total += o.total;
        self.kept += o.kept;
        self.kept_q2 += o.kept_q2;
        self.kept_q4 += o.kept_q4;
        self
    }

    fn tabulated(&self, what: &'static str) -> Result<Tabulated, Error> {
        let (q, c): (Vec<f64>, Vec<f64>) = (0..self.count.len())
            .filter(|&b| self.count[b] > 0.0 && self.sum_c[b] > 0.0)
            .map(|b| (self.sum_q[b] / self.count[b], self.sum_c[b] / self.count[b]))
            .unzip();
        if self.total == 0.0 {
            return Err(Error::invalid(
                "heights",
                "flat after detrending (every Fourier mode is zero)",
                "a rough surface: heights that vary beyond the removed trend",
            ));
        }
        if q.len() < 2 {
            return Err(Error::invalid(
                what,
                format!("{} non-empty q bin(s)", q.len()),
                "at least 2: more pixels, a smaller cut-off or more points per decade",
            ));
        }
        Tabulated::new(q, c)
    }

    /// Modes per point of [`Bins::tabulated`] (same order).
    fn counts(&self) -> Vec<f64> {
        (0..self.count.len())
            .filter(|&b| self.count[b] > 0.0 && self.sum_c[b] > 0.0)
            .map(|b| self.count[b])
            .collect()
    }
}

/// A fitted 2D polynomial trend: the terms c·P_i(x)·P_j(y) on the grid's orthogonal
/// polynomials.
struct Trend {
    px: Vec<Vec<f64>>,
    py: Vec<Vec<f64>>,
    terms: Vec<(usize, usize, f64)>,
}

impl Trend {
    /// The least-squares trend of degree `deg`: coefficients of the products P_i(x) P_j(y),
    /// i + j ≤ deg.
    fn fit(map: &HeightMap, deg: usize) -> Self {
        let px = orthogonal_polys(map.nx, deg);
        let py = orthogonal_polys(map.ny, deg);
        let mut terms: Vec<(usize, usize, f64)> = Vec::new();
        for (i, pxi) in px.iter().enumerate() {
            for (j, pyj) in py.iter().enumerate() {
                if i + j > deg {
                    continue;
                }
                // Summed in row order after the parallel map: the same bits whatever the threads.
                let num: f64 = (0..map.ny)
                    .into_par_iter()
                    .map(|iy| pyj[iy] * dot(map.row(iy), pxi))
                    .collect::<Vec<f64>>()
                    .iter()
                    .sum();
                let c = num / (dot(pxi, pxi) * dot(pyj, pyj));
                terms.push((i, j, c));
            }
        }
        Self { px, py, terms }
    }

    fn at(&self, ix: usize, iy: usize) -> f64 {
        self.terms
            .iter()
            .map(|&(i, j, c)| c * self.px[i][ix] * self.py[j][iy])
            .sum()
    }
}

/// The window along one axis and its mean square.
fn window_of(window: Window, n: usize) -> (Vec<f64>, f64) {
    match window {
        Window::Hann => hann(n),
        Window::None => (vec![1.0; n], 1.0),
    }
}

/// Row FFTs of the detrended, windowed map into the half spectrum (kx ≥ 0, `nx/2 + 1` per
/// row), and the sum of squares of the detrended heights.
fn row_spectra(map: &HeightMap, trend: &Trend, wx: &[f64], wy: &[f64]) -> (Vec<Complex64>, f64) {
    let (nx, ny) = (map.nx, map.ny);
    let half = nx / 2 + 1;
    let fx = FftPlanner::new().plan_fft_forward(nx);
    let mut spec = vec![Complex64::new(0.0, 0.0); ny * half];
    let mut rms_sum = 0.0;
    spec.par_chunks_mut(half)
        .enumerate()
        .map(|(iy, out)| {
            let row = map.row(iy);
            let mut buf: Vec<Complex64> = Vec::with_capacity(nx);
            let mut sq = 0.0;
            for ix in 0..nx {
                let v = row[ix] - trend.at(ix, iy);
                sq += v * v;
                buf.push(Complex64::new(v * wx[ix] * wy[iy], 0.0));
            }
            fx.process(&mut buf);
            out.copy_from_slice(&buf[..half]);
            sq
        })
        .collect::<Vec<f64>>()
        .iter()
        .for_each(|s| rms_sum += s);
    (spec, rms_sum)
}

/// Column FFTs of the half spectrum, each mode binned as it comes: `norm` turns |H|² into C,
/// `empty` is the (empty) binning to fill.
fn column_bins(map: &HeightMap, spec: &[Complex64], norm: f64, empty: &Bins) -> Bins {
    let (nx, ny) = (map.nx, map.ny);
    let half = nx / 2 + 1;
    let fy = FftPlanner::new().plan_fft_forward(ny);
    let (dqx, dqy) = (
        2.0 * PI / (nx as f64 * map.dx),
        2.0 * PI / (ny as f64 * map.dy),
    );
    let cell = dqx * dqy;
    // Columns in fixed blocks, each binned on its own, merged in block order: the sums do not
    // depend on the thread count or scheduling.
    const BLOCK: usize = 16;
    (0..half)
        .into_par_iter()
        .chunks(BLOCK)
        .map(|block| {
            let mut bins = empty.clone();
            let mut col = vec![Complex64::new(0.0, 0.0); ny];
            for kx in block {
                for iy in 0..ny {
                    col[iy] = spec[iy * half + kx];
                }
                fy.process(&mut col);
                let mult = if kx == 0 || (nx.is_multiple_of(2) && kx == nx / 2) {
                    1.0
                } else {
                    2.0
                };
                let qx = kx as f64 * dqx;
                for (ky, v) in col.iter().enumerate() {
                    let fyk = if ky <= ny / 2 {
                        ky as f64
                    } else {
                        ky as f64 - ny as f64
                    };
                    let q = qx.hypot(fyk * dqy);
                    if q == 0.0 {
                        continue;
                    }
                    bins.add(q, v.norm_sqr() * norm, cell, mult);
                }
            }
            bins
        })
        .collect::<Vec<Bins>>()
        .into_iter()
        .fold(empty.clone(), Bins::merge)
}

/// The PSD of a height map.
pub fn map_psd(map: &HeightMap, opts: &PsdOptions) -> Result<TopographyPsd, Error> {
    check_options(opts)?;
    let (nx, ny) = (map.nx, map.ny);
    if nx < 4 || ny < 4 || map.z.len() != nx * ny {
        return Err(Error::invalid(
            "height map",
            format!("{nx} x {ny} with {} heights", map.z.len()),
            "at least 4 x 4 pixels, nx*ny heights",
        ));
    }
    if !(map.dx > 0.0 && map.dy > 0.0 && map.dx.is_finite() && map.dy.is_finite()) {
        return Err(Error::invalid(
            "pixel size",
            format!("dx = {}, dy = {}", map.dx, map.dy),
            "finite sizes > 0 in m",
        ));
    }
    let detrend = opts.detrend.unwrap_or(if map.periodic {
        Detrend::Mean
    } else {
        Detrend::Tilt
    });
    let window = opts.window.unwrap_or(if map.periodic {
        Window::None
    } else {
        Window::Hann
    });
    let mut steps = Vec::new();
    let deg = detrend.degree();
    let trend = Trend::fit(map, deg);
    steps.push(
        format!("detrend: {detrend:?} (least-squares polynomial of degree {deg})").to_lowercase(),
    );
    let (wx, msx) = window_of(window, nx);
    let (wy, msy) = window_of(window, ny);
    steps.push(match window {
        Window::Hann => format!(
            "window: hann (separable), power loss corrected by 1/<w^2> = {:.4}",
            1.0 / (msx * msy)
        ),
        Window::None => "window: none".into(),
    });
    let (spec, rms_sum) = row_spectra(map, &trend, &wx, &wy);
    let h_rms = (rms_sum / (nx * ny) as f64).sqrt();
    steps.push(format!("fft: {nx} x {ny} (rustfft, half spectrum kx >= 0)"));

    let (lx, ly) = (nx as f64 * map.dx, ny as f64 * map.dy);
    let (dqx, dqy) = (2.0 * PI / lx, 2.0 * PI / ly);
    // A window blurs each mode with its neighbours; the first mode then also leaks into the
    // (removed) mean, so with a window the kept range starts at the second mode.
    let q_lo = dqx.max(dqy) * if window == Window::Hann { 2.0 } else { 1.0 };
    let q_nyq = (PI / map.dx).min(PI / map.dy);
    let q_hi = q_nyq.min(2.0 * PI / (opts.cutoff_pixels * map.dx.max(map.dy)));
    if q_hi <= q_lo {
        return Err(Error::invalid(
            "cut-off",
            opts.cutoff_pixels,
            "a cut-off wavelength shorter than the map",
        ));
    }
    let norm = map.dx * map.dy / ((2.0 * PI).powi(2) * (nx * ny) as f64 * msx * msy);
    let ppd = opts.points_per_decade;
    let bins = column_bins(map, &spec, norm, &Bins::new(q_lo, q_hi, ppd));
    drop(spec);
    steps.push(format!(
        "radial average: log bins, {ppd} per decade, from q = {q_lo:.4e} 1/m"
    ));
    steps.push(format!(
        "cut-off: q <= {q_hi:.4e} 1/m (wavelengths >= {} pixels; Nyquist {q_nyq:.4e} 1/m)",
        opts.cutoff_pixels
    ));
    let c2d = bins.tabulated("2D PSD")?;
    let summary = Summary {
        h_rms,
        h_rms_kept: bins.kept.sqrt(),
        rms_slope: bins.kept_q2.sqrt(),
        rms_curvature: bins.kept_q4.sqrt(),
        q_min: q_lo,
        q_max: q_hi,
        outside_fraction: outside(bins.total, bins.kept),
    };
    Ok(TopographyPsd {
        c2d,
        c1d: None,
        summary,
        steps,
    })
}

fn outside(total: f64, kept: f64) -> f64 {
    if total > 0.0 {
        ((total - kept) / total).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// The 1D stage of the line-scan pipeline: the one-sided 1D PSD averaged over the scans and
/// binned, with the summary and steps so far.
#[derive(Debug, Clone, PartialEq)]
pub struct LinePsd {
    /// One-sided 1D PSD (m^3), binned, within the kept range.
    pub c1d: Tabulated,
    pub summary: Summary,
    pub steps: Vec<String>,
    /// The number of Fourier modes averaged in each point of `c1d`.
    pub modes: Vec<f64>,
}

/// The 1D PSD of line scans (no conversion to 2D).
pub fn profile_c1d(profile: &Profile, opts: &PsdOptions) -> Result<LinePsd, Error> {
    check_options(opts)?;
    let n = profile.scans.first().map_or(0, Vec::len);
    if n < 8 || profile.scans.iter().any(|s| s.len() != n) {
        return Err(Error::invalid(
            "line scans",
            format!("{} scan(s) of {n} points", profile.scans.len()),
            "scans of equal length with at least 8 points",
        ));
    }
    if !(profile.dx.is_finite() && profile.dx > 0.0) {
        return Err(Error::invalid(
            "dx",
            profile.dx,
            "a finite spacing > 0 in m",
        ));
    }
    let detrend = opts.detrend.unwrap_or(if profile.periodic {
        Detrend::Mean
    } else {
        Detrend::Tilt
    });
    let window = opts.window.unwrap_or(if profile.periodic {
        Window::None
    } else {
        Window::Hann
    });
    let mut steps = Vec::new();
    let deg = detrend.degree();
    let polys = orthogonal_polys(n, deg);
    steps.push(
        format!("detrend: {detrend:?} (least-squares polynomial of degree {deg}, per scan)")
            .to_lowercase(),
    );
    let (w, ms) = match window {
        Window::Hann => hann(n),
        Window::None => (vec![1.0; n], 1.0),
    };
    steps.push(match window {
        Window::Hann => format!(
            "window: hann, power loss corrected by 1/<w^2> = {:.4}",
            1.0 / ms
        ),
        Window::None => "window: none".into(),
    });
    let dq = 2.0 * PI / (n as f64 * profile.dx);
    let q_nyq = PI / profile.dx;
    let q_hi = q_nyq.min(2.0 * PI / (opts.cutoff_pixels * profile.dx));
    // With a window the first mode leaks into the removed mean: start at the second.
    let q_lo = dq * if window == Window::Hann { 2.0 } else { 1.0 };
    let mut bins = Bins::new(q_lo, q_hi, opts.points_per_decade);
    let fft = FftPlanner::new().plan_fft_forward(n);
    let scans = profile.scans.len() as f64;
    let norm = 2.0 * profile.dx / (2.0 * PI * n as f64 * ms) / scans;
    let mut sq = 0.0;
    let mut power = vec![0.0; n / 2 + 1];
    for s in &profile.scans {
        let coef: Vec<f64> = polys.iter().map(|p| dot(s, p) / dot(p, p)).collect();
        let mut buf: Vec<Complex64> = (0..n)
            .map(|i| {
                let v = s[i] - polys.iter().zip(&coef).map(|(p, c)| c * p[i]).sum::<f64>();
                sq += v * v;
                Complex64::new(v * w[i], 0.0)
            })
            .collect();
        fft.process(&mut buf);
        for k in 1..=n / 2 {
            let fold = if n.is_multiple_of(2) && k == n / 2 {
                0.5
            } else {
                1.0
            };
            power[k] += fold * buf[k].norm_sqr() * norm;
        }
    }
    for (k, &c) in power.iter().enumerate().skip(1) {
        bins.add(k as f64 * dq, c, dq, 1.0);
    }
    steps.push(format!(
        "fft: {} scan(s) of {n} points (rustfft), one-sided 1D PSD averaged over the scans",
        profile.scans.len()
    ));
    steps.push(format!(
        "binning: log bins, {} per decade, from q = {q_lo:.4e} 1/m",
        opts.points_per_decade
    ));
    steps.push(format!(
        "cut-off: q <= {q_hi:.4e} 1/m (wavelengths >= {} pixels; Nyquist {q_nyq:.4e} 1/m)",
        opts.cutoff_pixels
    ));
    let c1d = bins.tabulated("1D PSD")?;
    let summary = Summary {
        h_rms: (sq / (n as f64 * scans)).sqrt(),
        h_rms_kept: bins.kept.sqrt(),
        rms_slope: (2.0 * bins.kept_q2).sqrt(),
        rms_curvature: (8.0 / 3.0 * bins.kept_q4).sqrt(),
        q_min: q_lo,
        q_max: q_hi,
        outside_fraction: outside(bins.total, bins.kept),
    };
    Ok(LinePsd {
        c1d,
        summary,
        steps,
        modes: bins.counts(),
    })
}

/// The PSD of line scans: the 1D PSD averaged over the scans, and the isotropic 2D PSD from it
/// by the inverse Abel transform of its non-increasing fit (or the option's shortcut; see
/// [`abel::c2d_from_measured_c1d`]).
pub fn profile_psd(profile: &Profile, opts: &PsdOptions) -> Result<TopographyPsd, Error> {
    let LinePsd {
        c1d,
        summary,
        mut steps,
        modes,
    } = profile_c1d(profile, opts)?;
    let conv = abel::c2d_from_measured_c1d(c1d.q(), c1d.c_values(), &modes, opts.conversion)?;
    if let Some(fit) = conv.fit
        && fit.changed > 0
    {
        steps.push(format!(
            "1D -> 2D: C1D fitted as non-increasing in q (isotonic least squares of ln C1D, \
             weighted by modes per bin): {} of {} point(s) changed, by at most {:.1} %",
            fit.changed,
            modes.len(),
            100.0 * fit.max_rel_change
        ));
    }
    steps.push(match opts.conversion {
        Conversion::InverseAbel => format!(
            "1D -> 2D: exact inverse Abel transform (isotropic surface), C1D continued as q^{:.3} beyond the cut-off",
            conv.tail_exponent.unwrap_or(f64::NAN)
        ),
        Conversion::PiQShortcut => "1D -> 2D: shortcut C = C1D/(pi q)".into(),
    });
    let c2d = conv.into_tabulated().map_err(|e| {
        Error::invalid(
            "1D -> 2D conversion",
            e,
            "a 2D PSD that is finite and > 0 (heights in SI too large or too small?)",
        )
    })?;
    Ok(TopographyPsd {
        c2d,
        c1d: Some(c1d),
        summary,
        steps,
    })
}
