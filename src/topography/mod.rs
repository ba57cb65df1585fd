//! Surface topography: height data, their power spectra, and synthetic surfaces (issue 4).
//!
//! Normalisation of the spectra (paper eq. A2 for the 2D PSD; details in [`convert`]):
//! - 2D PSD C(q) in m^4: h_rms² = 2π∫_0^∞ q C(q) dq. From a map of N = nx·ny heights with
//!   pixel sizes dx, dy and discrete Fourier transform H_k = Σ_n h_n e^{−ik·n}, the periodogram
//!   is C(q_k) = dx dy |H_k|² / ((2π)² N ⟨w²⟩) (w the window), so that
//!   Σ_k C(q_k) Δq_x Δq_y = ⟨h²⟩ with Δq = 2π/L (Parseval; exact without a window).
//! - 1D PSD C1D(q) in m^3, one-sided: h_rms² = ∫_0^∞ C1D dq. From a scan of n heights,
//!   C1D(q_k) = 2 dx |H_k|² / (2π n ⟨w²⟩) for 0 < k < n/2 (the factor 2 folds in −q; the
//!   Nyquist term k = n/2 is counted once).
//!
//! - [`Profile`], [`HeightMap`]: the data, SI inside (m);
//! - [`io`]: readers (line scans, height maps) and the height-map writer;
//! - [`spectrum`]: detrend → window → FFT → radial average → log binning → cut-off;
//! - [`convert`]: the exact 1D ↔ 2D PSD relation of an isotropic surface (Abel pair);
//! - [`synth`]: self-affine random-phase surfaces with a known PSD.

pub mod convert;
pub mod io;
pub mod spectrum;
pub mod synth;

/// One or more line scans of equal length and spacing (heights in m).
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    /// Sample spacing along the scan, m.
    pub dx: f64,
    /// The scans, each with the same number of heights.
    pub scans: Vec<Vec<f64>>,
    /// The data are one period of a periodic surface (no window needed).
    pub periodic: bool,
}

/// A height map: `ny` rows of `nx` heights (row-major; x along a row), pixel sizes dx, dy.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    pub nx: usize,
    pub ny: usize,
    /// Pixel size along x (within a row), m.
    pub dx: f64,
    /// Pixel size along y (between rows), m.
    pub dy: f64,
    /// Heights, m, `z[iy * nx + ix]`.
    pub z: Vec<f64>,
    /// The map is one period of a periodic surface (no window needed).
    pub periodic: bool,
}

impl HeightMap {
    /// Row `iy` of the map.
    pub fn row(&self, iy: usize) -> &[f64] {
        &self.z[iy * self.nx..(iy + 1) * self.nx]
    }

    /// The rms height about the mean, m.
    pub fn rms(&self) -> f64 {
        let n = self.z.len() as f64;
        let mean = self.z.iter().sum::<f64>() / n;
        (self.z.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / n).sqrt()
    }
}
