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
//!   An instrument file (any format [`crate::instrument::detect`] recognises) is read with its
//!   own metadata; a channel with a single row is a line scan, else a height map. Points the
//!   instrument did not measure (NaN): holes of at most [`fill::MAX_HOLE`] points (dropouts)
//!   are filled by harmonic interpolation ([`fill`], with its measured effect on the PSD);
//!   larger holes and bands are cut away by taking the PSD of the largest complete
//!   axis-aligned rectangle (the longest complete run for a line scan), which leaves the
//!   spectrum unbiased at the cost of the longest wavelengths. The shares are reported as
//!   `missing_fraction` (not measured), `filled_fraction` and `used_fraction`. Fewer than
//!   [`MIN_MAP_SIDE`]² (maps) or [`MIN_PROFILE_POINTS`] (line scans) complete points is an error
//!   naming the file.

pub mod fill;
pub mod io;
pub mod plausible;
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
    /// Instrument files: the channel, by name or by 1-based number (default: the first height
    /// channel, [`crate::instrument::Reading::default_channel`]).
    pub channel: Option<String>,
}

/// The fewest rows and columns of complete (measured) points a map from an instrument file
/// must keep.
pub const MIN_MAP_SIDE: usize = 16;
/// The fewest complete points a line scan from an instrument file must keep.
pub const MIN_PROFILE_POINTS: usize = 64;

/// What [`psd_of_file`] read: the data's shape and origin.
#[derive(Debug, Clone, PartialEq)]
pub struct FileInfo {
    pub kind: io::HeightKind,
    /// The instrument format's name, or "csv" for the tool's own text files.
    pub format: String,
    /// The channel used (instrument files), else `None`.
    pub channel: Option<String>,
    /// All channel names of an instrument file (empty for text files).
    pub channels: Vec<String>,
    /// Points used: `[nx, ny]` for a map, `[n]` for line scans (points per scan).
    pub grid: Vec<usize>,
    /// Pixel size(s), m: `[dx, dy]` for a map, `[dx]` for line scans.
    pub pixel_size: Vec<f64>,
    /// The height unit the file stores (instrument files), else `None`.
    pub height_unit_in_file: Option<String>,
    /// Share of the channel's points not measured (NaN).
    pub missing_fraction: f64,
    /// Share of the channel's points used (the complete rectangle); 1 for text files.
    pub used_fraction: f64,
    /// Share of the channel's points not measured but filled ([`fill`]: holes of at most
    /// [`fill::MAX_HOLE`] points); 0 for text files.
    pub filled_fraction: f64,
    /// What the reading found doubtful (data used as periodic whose edges do not join).
    pub warnings: Vec<String>,
}

impl FileInfo {
    /// Physical size per axis, m: grid × pixel size.
    pub fn size(&self) -> Vec<f64> {
        self.grid
            .iter()
            .zip(&self.pixel_size)
            .map(|(&n, &d)| n as f64 * d)
            .collect()
    }
}

/// The rms of `z` about its mean.
fn rms_about_mean(z: &[f64]) -> f64 {
    let n = z.len().max(1) as f64;
    let mean = z.iter().sum::<f64>() / n;
    (z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt()
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

/// Read a height file (an instrument file, or the tool's own line scans or height map) and
/// compute its PSD: the pipeline behind `coatcheck psd` and `coatcheck check --profile`.
/// Returns what the file held and the result.
pub fn psd_of_file(
    path: &std::path::Path,
    file: &HeightFileOptions,
    opts: &spectrum::PsdOptions,
) -> Result<(FileInfo, spectrum::TopographyPsd), crate::Error> {
    if let Some((mut info, data)) = instrument_data(path, file)? {
        let (result, mismatch) = match &data {
            Data::Lines(p) => (
                spectrum::profile_psd(p, opts),
                plausible::edge_mismatch_profile(p),
            ),
            Data::Map(m) => (spectrum::map_psd(m, opts), plausible::edge_mismatch_map(m)),
        };
        let result = result.map_err(|e| in_file(path, e))?;
        if file.periodic == Some(true) {
            info.warnings
                .extend(plausible::periodic_warning(path, mismatch));
        }
        return Ok((info, result));
    }
    if file.channel.is_some() {
        return Err(crate::Error::Input {
            path: path.to_path_buf(),
            line: 0,
            msg: "a channel was chosen, but this is not an instrument file (it has one channel)"
                .into(),
        });
    }
    text_psd(path, file, opts)
}

/// Heights read from an instrument file.
enum Data {
    Lines(Profile),
    Map(HeightMap),
}

/// The file's bytes detected as an instrument format: its chosen channel, cut to the largest
/// complete rectangle; `None` when no instrument format matches.
fn instrument_data(
    path: &std::path::Path,
    file: &HeightFileOptions,
) -> Result<Option<(FileInfo, Data)>, crate::Error> {
    let head = crate::instrument::head(path, crate::instrument::DETECT_BYTES)?;
    if crate::instrument::detect(path, &head).is_none() {
        return Ok(None);
    }
    let reading = crate::instrument::read(path)?;
    let names: Vec<String> = reading.channels.iter().map(|c| c.name.clone()).collect();
    let index = match &file.channel {
        None => reading.default_channel(),
        Some(c) => choose_channel(path, &names, c)?,
    };
    let ch = &reading.channels[index];
    let bad = |msg: String| crate::Error::Input {
        path: path.to_path_buf(),
        line: 0,
        msg,
    };
    let periodic = file.periodic.unwrap_or(false);
    let mut z = ch.z.clone();
    let filled = fill::fill_small_holes(&mut z, ch.nx, ch.ny);
    let (grid, pixel_size, data, kept) = if ch.ny == 1 {
        let (start, len) = longest_run(&z);
        if len < MIN_PROFILE_POINTS {
            return Err(bad(format!(
                "channel '{}': too few points: the longest run of measured points is {len}, \
                 at least {MIN_PROFILE_POINTS} are needed",
                ch.name
            )));
        }
        let p = Profile {
            dx: ch.dx,
            scans: vec![z[start..start + len].to_vec()],
            periodic,
        };
        (vec![len], vec![ch.dx], Data::Lines(p), len)
    } else {
        let r = largest_rectangle(&z, ch.nx, ch.ny);
        if r.w < MIN_MAP_SIDE || r.h < MIN_MAP_SIDE {
            return Err(bad(format!(
                "channel '{}' ({}×{} points): too few points: the largest complete rectangle \
                 of measured points is {}×{}, at least {MIN_MAP_SIDE}×{MIN_MAP_SIDE} are needed",
                ch.name, ch.nx, ch.ny, r.w, r.h
            )));
        }
        let z = (r.y..r.y + r.h)
            .flat_map(|iy| z[iy * ch.nx + r.x..iy * ch.nx + r.x + r.w].iter().copied())
            .collect();
        let m = HeightMap {
            nx: r.w,
            ny: r.h,
            dx: ch.dx,
            dy: ch.dy,
            z,
            periodic,
        };
        (vec![r.w, r.h], vec![ch.dx, ch.dy], Data::Map(m), r.w * r.h)
    };
    let info = FileInfo {
        kind: match data {
            Data::Lines(_) => io::HeightKind::Lines,
            Data::Map(_) => io::HeightKind::Map,
        },
        format: reading.format.to_string(),
        channel: Some(ch.name.clone()),
        channels: names,
        grid,
        pixel_size,
        height_unit_in_file: Some(ch.unit_in_file.clone()),
        missing_fraction: ch.missing_fraction(),
        used_fraction: kept as f64 / ch.z.len() as f64,
        filled_fraction: filled as f64 / ch.z.len() as f64,
        warnings: Vec::new(),
    };
    Ok(Some((info, data)))
}

/// The index of channel `c` (a name, or a 1-based number) among `names`.
fn choose_channel(
    path: &std::path::Path,
    names: &[String],
    c: &str,
) -> Result<usize, crate::Error> {
    if let Some(i) = names.iter().position(|n| n == c) {
        return Ok(i);
    }
    match c.parse::<usize>() {
        Ok(n) if (1..=names.len()).contains(&n) => Ok(n - 1),
        _ => Err(crate::Error::Input {
            path: path.to_path_buf(),
            line: 0,
            msg: format!(
                "no channel '{c}': the file has {} (give a name or a number 1–{})",
                names
                    .iter()
                    .map(|n| format!("'{n}'"))
                    .collect::<Vec<_>>()
                    .join(", "),
                names.len()
            ),
        }),
    }
}

/// The start and length of the longest run of finite values in `z` (the first of equal ones).
fn longest_run(z: &[f64]) -> (usize, usize) {
    let (mut best, mut start) = ((0, 0), 0);
    for (i, v) in z.iter().enumerate() {
        if !v.is_finite() {
            start = i + 1;
        } else if i + 1 - start > best.1 {
            best = (start, i + 1 - start);
        }
    }
    best
}

/// An axis-aligned rectangle of a grid: first column `x`, first row `y`, `w` columns, `h` rows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Rect {
    x: usize,
    y: usize,
    w: usize,
    h: usize,
}

/// The largest-area rectangle of finite values in the row-major `nx`×`ny` grid `z` (the
/// classic histogram-and-stack method, O(nx·ny)): for each row, the heights of the runs of
/// finite values ending there, and for each column the widest span where they are no lower.
fn largest_rectangle(z: &[f64], nx: usize, ny: usize) -> Rect {
    let mut heights = vec![0usize; nx];
    let mut best = Rect {
        x: 0,
        y: 0,
        w: 0,
        h: 0,
    };
    let mut stack: Vec<usize> = Vec::with_capacity(nx + 1);
    for iy in 0..ny {
        for (ix, h) in heights.iter_mut().enumerate() {
            *h = if z[iy * nx + ix].is_finite() {
                *h + 1
            } else {
                0
            };
        }
        stack.clear();
        for ix in 0..=nx {
            let cur = if ix < nx { heights[ix] } else { 0 };
            while let Some(&top) = stack.last() {
                if heights[top] < cur {
                    break;
                }
                stack.pop();
                let h = heights[top];
                let left = stack.last().map_or(0, |&l| l + 1);
                let w = ix - left;
                if w * h > best.w * best.h {
                    best = Rect {
                        x: left,
                        y: iy + 1 - h,
                        w,
                        h,
                    };
                }
            }
            stack.push(ix);
        }
    }
    best
}

/// The tool's own text files: line scans or a CSV height map.
fn text_psd(
    path: &std::path::Path,
    file: &HeightFileOptions,
    opts: &spectrum::PsdOptions,
) -> Result<(FileInfo, spectrum::TopographyPsd), crate::Error> {
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
    let (result, grid, pixel_size, mismatch) = match kind {
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
            let n = p.scans.first().map_or(0, Vec::len);
            if file.z_unit.is_none() {
                let all: Vec<f64> = p.scans.concat();
                plausible::check_si(path, rms_about_mean(&all), p.dx)?;
            }
            let r = spectrum::profile_psd(&p, opts).map_err(|e| in_file(path, e))?;
            (r, vec![n], vec![p.dx], plausible::edge_mismatch_profile(&p))
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
            if file.z_unit.is_none() {
                plausible::check_si(path, m.rms(), m.dx.max(m.dy))?;
            }
            let r = spectrum::map_psd(&m, opts).map_err(|e| in_file(path, e))?;
            (
                r,
                vec![m.nx, m.ny],
                vec![m.dx, m.dy],
                plausible::edge_mismatch_map(&m),
            )
        }
    };
    let info = FileInfo {
        kind,
        format: "csv".into(),
        channel: None,
        channels: vec![],
        grid,
        pixel_size,
        height_unit_in_file: None,
        missing_fraction: 0.0,
        used_fraction: 1.0,
        filled_fraction: 0.0,
        warnings: if file.periodic == Some(true) {
            plausible::periodic_warning(path, mismatch)
                .into_iter()
                .collect()
        } else {
            Vec::new()
        },
    };
    Ok((info, result))
}
