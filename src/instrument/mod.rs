//! Instrument files: height data as profilometers, interferometers, confocal microscopes and
//! AFMs write them, read with their metadata (grid, pixel size per axis, height unit and scale,
//! channel names) so that no flag is needed.
//!
//! Conventions: heights in metres, pixel sizes in metres; a map is row-major with x along a row
//! (as [`crate::topography::HeightMap`]); a point the instrument did not measure is NaN here,
//! whatever marker the file used. The format is detected from the content (magic bytes), and
//! from the extension only when no signature matches (e.g. a truncated file, which its
//! format's reader then refuses with a message that says what is missing).

use std::path::Path;

use crate::Error;

pub mod al3d;
mod bounded;
mod bytes;
mod dektak;
pub mod di;
pub mod frt;
mod gwy;
mod gwyddion_txt;
pub mod metropro;
pub mod mi;
mod mitutoyo;
pub mod opd;
pub mod plu;
mod sdf;
mod sur;
mod x3p;
mod xml;
mod zip;

/// One file format: its short name, a test of the file's first bytes (its signature), the
/// extensions it is written with, and its reader.
struct Format {
    name: &'static str,
    sniff: fn(&[u8]) -> bool,
    extensions: &'static [&'static str],
    read: fn(&Path, &[u8]) -> Result<Reading, Error>,
}

/// The formats, in the order their signatures are tried.
const FORMATS: &[Format] = &[
    Format {
        name: "x3p",
        sniff: x3p::sniff,
        extensions: &["x3p"],
        read: x3p::read,
    },
    Format {
        name: "sdf",
        sniff: sdf::sniff,
        extensions: &["sdf"],
        read: sdf::read,
    },
    Format {
        name: "sur",
        sniff: sur::sniff,
        extensions: &["sur"],
        read: sur::read,
    },
    Format {
        name: "gwy",
        sniff: gwy::sniff,
        extensions: &["gwy"],
        read: gwy::read,
    },
    Format {
        name: "metropro",
        sniff: metropro::is_metropro,
        extensions: &["dat"],
        read: metropro::read_metropro,
    },
    Format {
        name: "opd",
        sniff: opd::is_opd,
        extensions: &["opd"],
        read: opd::read_opd,
    },
    Format {
        name: "plu",
        sniff: plu::is_plu,
        extensions: &["plu"],
        read: plu::read_plu,
    },
    Format {
        name: "di",
        sniff: di::is_di,
        extensions: &["di"],
        read: di::read_di,
    },
    Format {
        name: "mi",
        sniff: mi::is_mi,
        extensions: &["mi"],
        read: mi::read_mi,
    },
    Format {
        name: "al3d",
        sniff: al3d::is_al3d,
        extensions: &["al3d"],
        read: al3d::read_al3d,
    },
    Format {
        name: "frt",
        sniff: frt::is_frt,
        extensions: &["frt"],
        read: frt::read_frt,
    },
    Format {
        name: "gwyddion-txt",
        sniff: gwyddion_txt::sniff,
        extensions: &[],
        read: gwyddion_txt::read,
    },
    Format {
        name: "dektak",
        sniff: dektak::sniff,
        extensions: &[],
        read: dektak::read,
    },
    Format {
        name: "mitutoyo",
        sniff: mitutoyo::sniff,
        extensions: &["xlsx"],
        read: mitutoyo::read,
    },
];

/// The format of a file whose content is `bytes`: the first whose signature matches, else the
/// first that is written with the file's extension (case-insensitive); `None` when neither
/// tells (e.g. a plain table of numbers).
pub fn detect(path: &Path, bytes: &[u8]) -> Option<&'static str> {
    find(path, bytes).map(|f| f.name)
}

fn find(path: &Path, bytes: &[u8]) -> Option<&'static Format> {
    FORMATS.iter().find(|f| (f.sniff)(bytes)).or_else(|| {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        FORMATS
            .iter()
            .find(|f| f.extensions.contains(&ext.as_str()))
    })
}

/// The largest instrument file read (1 GiB: 2²⁷ heights of 8 bytes, twice the most heights a
/// map may have), so that an endless or huge input ends with a message, not a hang.
pub const MAX_FILE_BYTES: u64 = 1 << 30;
/// How much of a file [`detect`] needs: every signature lies in its first bytes.
pub const DETECT_BYTES: u64 = 1 << 16;

/// The first `limit` bytes of the file, or all of them when it is shorter.
pub fn head(path: &Path, limit: u64) -> Result<Vec<u8>, Error> {
    use std::io::Read;
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(limit).read_to_end(&mut bytes))
        .map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
    Ok(bytes)
}

/// Reads the instrument file at `path` (at most [`MAX_FILE_BYTES`]), detecting its format with
/// [`detect`].
pub fn read(path: &Path) -> Result<Reading, Error> {
    let bytes = head(path, MAX_FILE_BYTES + 1)?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(bad(
            path,
            format!(
                "the file is larger than {} MiB, the limit for an instrument file",
                MAX_FILE_BYTES >> 20
            ),
        ));
    }
    let format = find(path, &bytes).ok_or_else(|| {
        let names: Vec<&str> = FORMATS.iter().map(|f| f.name).collect();
        bad(
            path,
            format!(
                "not an instrument file of a known format ({}): no signature matches and the \
                 extension names none of them",
                names.join(", ")
            ),
        )
    })?;
    (format.read)(path, &bytes)
}

/// One channel (a height map or a profile) as read from an instrument file.
#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    /// The channel's name as the file gives it (e.g. "Height", "ZSensor"), or the format's name
    /// for its one height channel when the file names none.
    pub name: String,
    /// Points along x (within a row).
    pub nx: usize,
    /// Rows (1 for a profile).
    pub ny: usize,
    /// Pixel size along x, m.
    pub dx: f64,
    /// Pixel size along y, m (equal to `dx` for a profile).
    pub dy: f64,
    /// Heights, m, `z[iy * nx + ix]`; NaN where the instrument did not measure.
    pub z: Vec<f64>,
    /// The height unit the file stores (e.g. "nm", "um", "m"), as the file spells it.
    pub unit_in_file: String,
    /// The channel holds heights (topography), as opposed to e.g. amplitude, phase or intensity.
    pub is_height: bool,
}

impl Channel {
    /// Share of the points that are not measured (NaN).
    pub fn missing_fraction(&self) -> f64 {
        self.z.iter().filter(|z| z.is_nan()).count() as f64 / self.z.len().max(1) as f64
    }
}

/// What an instrument file held.
#[derive(Debug, Clone, PartialEq)]
pub struct Reading {
    /// Short format name, e.g. "x3p", "sur", "metropro".
    pub format: &'static str,
    /// The channels in file order; at least one.
    pub channels: Vec<Channel>,
}

impl Reading {
    /// The default channel: the first that holds heights, else the first.
    pub fn default_channel(&self) -> usize {
        self.channels.iter().position(|c| c.is_height).unwrap_or(0)
    }
}

/// A reading of one profile (a single line scan, ny = 1): spacing `dx` (m), heights `z` (m).
pub(crate) fn profile_reading(
    format: &'static str,
    name: String,
    dx: f64,
    z: Vec<f64>,
    unit_in_file: String,
) -> Reading {
    Reading {
        format,
        channels: vec![Channel {
            name,
            nx: z.len(),
            ny: 1,
            dx,
            dy: dx,
            z,
            unit_in_file,
            is_height: true,
        }],
    }
}

/// An error reading `path`, with a message saying what was expected. Binary formats have no
/// lines: `line` is 0 and the message names the byte offset.
pub(crate) fn bad(path: &Path, msg: impl Into<String>) -> crate::Error {
    crate::Error::Input {
        path: path.to_path_buf(),
        line: 0,
        msg: msg.into(),
    }
}

/// An error at line `line` (1-based) of the text file `path`.
pub(crate) fn bad_line(path: &Path, line: usize, msg: impl Into<String>) -> crate::Error {
    crate::Error::Input {
        path: path.to_path_buf(),
        line,
        msg: msg.into(),
    }
}

/// The step of positions `x` that an export printed on a uniform grid (possibly rounded to
/// fewer digits than the step has): the mean step, (x_last − x_first)/(n − 1). Each step must
/// lie within half a mean step of it (a missing or repeated point fails) and each point within
/// one step of the grid (no drift); else the index of the first point off the grid.
pub(crate) fn uniform_step(x: &[f64]) -> Result<f64, usize> {
    let n = x.len();
    if n < 2 {
        return Err(n.saturating_sub(1));
    }
    let dx = (x[n - 1] - x[0]) / (n - 1) as f64;
    if !(dx.is_finite() && dx > 0.0) {
        return Err(n - 1);
    }
    match (1..n).find(|&i| {
        let step = x[i] - x[i - 1];
        !((step - dx).abs() <= 0.5 * dx && (x[i] - x[0] - i as f64 * dx).abs() <= dx)
    }) {
        Some(i) => Err(i),
        None => Ok(dx),
    }
}
