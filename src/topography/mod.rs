//! Surface topography: height data, their power spectra, and synthetic surfaces.
//!
//! Normalisation of the spectra (paper eq. A2 for the 2D PSD; details in [`crate::psd::abel`]):
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
//! - [`synth`]: self-affine random-phase surfaces with a known PSD;
//! - [`psd_of_file`]: file → PSD in one call (`coatcheck psd`, `coatcheck check --profile`).

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

/// How to read a height file for [`psd_of_file`] (lengths in m; units as strings like `um`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct HeightFileOptions {
    /// Line scans or map; `None`: from the file (metadata comment, or a header line means
    /// line scans), else from which spacing was given (`dx`: line scans, `pixel_size`: map).
    pub kind: Option<io::HeightKind>,
    /// Line scans: sample spacing, for files without an x column.
    pub dx: Option<f64>,
    /// Height map: pixel size along x (and y unless `pixel_size_y`).
    pub pixel_size: Option<f64>,
    pub pixel_size_y: Option<f64>,
    pub x_unit: Option<String>,
    pub z_unit: Option<String>,
    /// `Some(true)`: the data are one period of a periodic surface.
    pub periodic: Option<bool>,
}

/// An error about the data of a whole file (no single line is at fault), naming the file.
fn in_file(path: &std::path::Path, e: crate::Error) -> crate::Error {
    match e {
        crate::Error::Input { .. } | crate::Error::Io { .. } => e,
        other => crate::Error::Value {
            origin: path.display().to_string(),
            msg: other.to_string(),
        },
    }
}

/// Read a height file (line scans or a height map) and compute its PSD: the pipeline behind
/// `coatcheck psd` and `coatcheck check --profile`. Returns what the file held and the result.
pub fn psd_of_file(
    path: &std::path::Path,
    file: &HeightFileOptions,
    opts: &spectrum::PsdOptions,
) -> Result<(io::HeightKind, spectrum::TopographyPsd), crate::Error> {
    use io::HeightKind;
    let kind = match file.kind {
        Some(k) => k,
        None => match io::sniff(path)? {
            Some(k) => k,
            None if file.dx.is_some() => HeightKind::Lines,
            None if file.pixel_size.is_some() => HeightKind::Map,
            None => {
                return Err(crate::Error::Input {
                    path: path.to_path_buf(),
                    line: 1,
                    msg: "cannot tell line scans from a height map: give the spacing dx \
                          (line scans), the pixel size (map) or the kind"
                        .into(),
                });
            }
        },
    };
    let result = match kind {
        HeightKind::Lines => {
            let p = io::read_profile(
                path,
                &io::ProfileOptions {
                    dx: file.dx,
                    x_unit: file.x_unit.clone(),
                    z_unit: file.z_unit.clone(),
                    periodic: file.periodic,
                },
            )?;
            spectrum::profile_psd(&p, opts).map_err(|e| in_file(path, e))?
        }
        HeightKind::Map => {
            let m = io::read_height_map(
                path,
                &io::MapOptions {
                    dx: file.pixel_size,
                    dy: file.pixel_size_y,
                    z_unit: file.z_unit.clone(),
                    periodic: file.periodic,
                },
            )?;
            spectrum::map_psd(&m, opts).map_err(|e| in_file(path, e))?
        }
    };
    Ok((kind, result))
}
