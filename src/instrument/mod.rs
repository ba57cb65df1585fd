//! Instrument files: height data as profilometers, interferometers, confocal microscopes and
//! AFMs write them, read with their metadata (grid, pixel size per axis, height unit and scale,
//! channel names) so that no flag is needed.
//!
//! Conventions: heights in metres, pixel sizes in metres; a map is row-major with x along a row
//! (as [`crate::topography::HeightMap`]); a point the instrument did not measure is NaN here,
//! whatever marker the file used. The format is detected from the content (magic bytes), the
//! extension only where the content has no signature.

use std::path::Path;

pub mod al3d;
mod bytes;
pub mod di;
pub mod frt;
pub mod metropro;
pub mod mi;
pub mod opd;
pub mod plu;

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

/// An error reading `path`, with a message saying what was expected. Binary formats have no
/// lines: `line` is 0 and the message names the byte offset.
pub(crate) fn bad(path: &Path, msg: impl Into<String>) -> crate::Error {
    crate::Error::Input {
        path: path.to_path_buf(),
        line: 0,
        msg: msg.into(),
    }
}
