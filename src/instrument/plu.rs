//! Sensofar `.plu` files (confocal, interferometric and focus-variation profilers), laid out
//! as Gwyddion's `sensofar.c` reads them, all little-endian and packed: a 128-byte date, a u32
//! time and a 256-byte comment; at byte 388 the calibration (u32 rows, u32 columns, …, f32 µm
//! per pixel along x at 404 and along y at 408); at 428 the measurement type (3: topography);
//! at 489 the number of layers and at 492 the number of RGB images per layer; from byte 500 the
//! layers, each u32 rows, u32 columns, the heights as f32 µm row by row, f32 min and max, then
//! its RGB images (3 bytes per point each). The value 1000001 marks non-measured points.

use super::bounded::{Bytes, decode, pixel_size};
use super::{Channel, Reading};
use crate::Error;
use std::path::Path;

const TOPOGRAPHY: u32 = 3;
const UNDEFINED: f32 = 1_000_001.0;
const LAYERS: usize = 500;

/// PLU files have no magic number: the grid of the calibration block (byte 388) must be the
/// grid of the first layer (byte 500), and the measurement type one Sensofar defines.
pub fn is_plu(bytes: &[u8]) -> bool {
    let u32_at = |off: usize| -> Option<u32> {
        let b = bytes.get(off..off + 4)?;
        Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    };
    match (
        u32_at(388),
        u32_at(392),
        u32_at(428),
        u32_at(500),
        u32_at(504),
    ) {
        (Some(ny), Some(nx), Some(kind), Some(ly), Some(lx)) => {
            ny > 0 && nx > 0 && ny == ly && nx == lx && (1..=6).contains(&kind)
        }
        _ => false,
    }
}

/// Read a Sensofar `.plu` topography: one channel per layer, heights in m.
pub fn read_plu(path: &Path, bytes: &[u8]) -> Result<Reading, Error> {
    let b = Bytes::new(path, bytes);
    let kind = b.u32_le(428, "measurement type")?;
    if kind != TOPOGRAPHY {
        return Err(b.err(format!(
            "byte 428: measurement type {kind}, expected {TOPOGRAPHY} (topography); other \
             Sensofar measurements (profiles, thickness) are not read"
        )));
    }
    let grid = (b.u32_le(388, "rows")?, b.u32_le(392, "columns")?);
    let layer = (
        b.u32_le(500, "layer rows")?,
        b.u32_le(504, "layer columns")?,
    );
    if grid != layer {
        return Err(b.err(format!(
            "not a Sensofar PLU file: the grid at byte 388 ({} × {}) differs from the first \
             layer's at byte 500 ({} × {})",
            grid.1, grid.0, layer.1, layer.0
        )));
    }
    let dx = pixel_size(
        &b,
        b.f32_le(404, "x pixel size")? * 1e-6,
        "x pixel size (byte 404)",
    )?;
    let dy = pixel_size(
        &b,
        b.f32_le(408, "y pixel size")? * 1e-6,
        "y pixel size (byte 408)",
    )?;
    let layers = usize::from(b.u8(489, "number of layers")?);
    let images = usize::from(b.u8(492, "number of images")?);
    if layers == 0 {
        return Err(b.err("byte 489: the file has no layers"));
    }
    let mut off = LAYERS;
    let mut channels = Vec::with_capacity(layers);
    for k in 0..layers {
        let ny = b.u32_le(off, "layer rows")? as usize;
        let nx = b.u32_le(off + 4, "layer columns")? as usize;
        let raw = b.grid(off + 8, nx, ny, 4, &format!("layer {k} heights"))?;
        let z = decode(raw, |a| {
            let v = f32::from_le_bytes(a);
            if v == UNDEFINED {
                f64::NAN
            } else {
                f64::from(v) * 1e-6
            }
        });
        off += 8 + raw.len() + 8;
        off = off.saturating_add(nx.saturating_mul(ny).saturating_mul(3 * images));
        channels.push(Channel {
            name: if layers == 1 {
                "plu".to_string()
            } else {
                format!("layer {k}")
            },
            nx,
            ny,
            dx,
            dy,
            z,
            unit_in_file: "µm".to_string(),
            is_height: true,
        });
    }
    Ok(Reading {
        format: "plu",
        channels,
    })
}
