//! Wyko `.opd` files (Vision software of Bruker/Veeco Wyko white-light interferometers), laid
//! out as Gwyddion's `opdfile.c` reads them: a 2-byte prelude, then a directory of 24-byte
//! little-endian entries (16-byte name, i16 type, i32 length, u16 attribute) whose first entry,
//! "Directory", gives the directory's length; the blocks follow the directory back to back in
//! directory order, each `length` bytes long.
//!
//! An array block (type 3) starts with u16 nx, ny and element size (1: u8, 2: i16, 4: f32),
//! then the values with the x index outermost (column by column); its y axis runs opposite to
//! the image's, so it is flipped here. The arrays named "RAW DATA", "RAW_DATA", "OPD", "Raw" or
//! "SAMPLE_DATA" hold heights in units of the wavelength: z = value · λ / `Mult`, with λ the
//! "Wavelength" block in nm and `Mult` (default 1) a block of its own. Values that are not
//! finite or reach 1e38 (f32) or 32766 (i16) are non-measured. The pixel size is "Pixel_size"
//! in mm along x, times "Aspect" (default 1) along y. Other arrays (e.g. "Image", intensity)
//! are listed as non-height channels with their stored values.

use super::bounded::{Bytes, pixel_size};
use super::{Channel, Reading};
use crate::Error;
use std::path::Path;

const ENTRY: usize = 24;
const TYPE_ARRAY: i16 = 3;
const HEIGHT_ARRAYS: [&str; 5] = ["RAW DATA", "RAW_DATA", "OPD", "Raw", "SAMPLE_DATA"];

/// A Wyko OPD file has the name "Directory" after a 2-byte prelude.
pub fn is_opd(bytes: &[u8]) -> bool {
    bytes.len() >= 11 && &bytes[2..11] == b"Directory"
}

/// A directory entry: the block's name, type, payload offset and length.
struct Block {
    name: String,
    kind: i16,
    off: usize,
    len: usize,
}

fn directory(b: &Bytes) -> Result<Vec<Block>, Error> {
    let dir_len = b.i32_le(20, "directory length")?;
    let dir_len = usize::try_from(dir_len)
        .ok()
        .filter(|&l| l >= ENTRY && l % ENTRY == 0 && l <= b.len())
        .ok_or_else(|| {
            b.err(format!(
                "byte 20: directory length {dir_len}, expected a positive multiple of \
                 {ENTRY} within the file ({} bytes)",
                b.len()
            ))
        })?;
    let mut off = 2 + dir_len;
    let mut blocks = Vec::new();
    for k in 1..dir_len / ENTRY {
        let at = 2 + k * ENTRY;
        let len = b.i32_le(at + 18, "block length")?;
        let len = usize::try_from(len).unwrap_or(0);
        blocks.push(Block {
            name: b.text(at, 16, "block name")?,
            kind: b.i16_le(at + 16, "block type")?,
            off,
            len,
        });
        off = off.saturating_add(len);
    }
    Ok(blocks)
}

/// A scalar block's value (short, float, double or long, as its length says), if numeric.
fn scalar(b: &Bytes, block: &Block) -> Result<Option<f64>, Error> {
    let what = &block.name;
    Ok(match (block.kind, block.len) {
        (6 | 7, 2) => Some(f64::from(b.i16_le(block.off, what)?)),
        (6 | 12, l) if l >= 4 => Some(f64::from(b.i32_le(block.off, what)?)),
        (7, l) if l >= 4 => Some(b.f32_le(block.off, what)?),
        (8, l) if l >= 8 => Some(b.f64_le(block.off, what)?),
        _ => None,
    })
}

/// An array block as a channel in file units (flipped to image orientation, undefined → NaN).
fn array(b: &Bytes, block: &Block, dx: f64, dy: f64) -> Result<Channel, Error> {
    let nx = usize::from(b.u16_le(block.off, "array width")?);
    let ny = usize::from(b.u16_le(block.off + 2, "array height")?);
    let elsize = usize::from(b.u16_le(block.off + 4, "array element size")?);
    let start = block.off + 6;
    if !matches!(elsize, 1 | 2 | 4) {
        return Err(b.err(format!(
            "array '{}' at byte {}: element size {elsize}, expected 1, 2 or 4",
            block.name,
            block.off + 4
        )));
    }
    let raw = b.grid(start, nx, ny, elsize, &format!("array '{}'", block.name))?;
    if 6 + raw.len() > block.len {
        return Err(b.err(format!(
            "array '{}' at byte {}: {nx} × {ny} points of {elsize} bytes do not fit in its \
             block of {} bytes",
            block.name, block.off, block.len
        )));
    }
    let value = |i: usize| -> f64 {
        let e = &raw[i * elsize..(i + 1) * elsize];
        match elsize {
            1 => f64::from(e[0]),
            2 => match i16::from_le_bytes([e[0], e[1]]) {
                v if v >= 32766 => f64::NAN,
                v => f64::from(v),
            },
            _ => match f32::from_le_bytes([e[0], e[1], e[2], e[3]]) {
                v if !v.is_finite() || v >= 1e38 => f64::NAN,
                v => f64::from(v),
            },
        }
    };
    let mut z = Vec::with_capacity(nx * ny);
    for iy in 0..ny {
        z.extend((0..nx).map(|ix| value(ix * ny + (ny - 1 - iy))));
    }
    Ok(Channel {
        name: block.name.clone(),
        nx,
        ny,
        dx,
        dy,
        z,
        unit_in_file: String::new(),
        is_height: HEIGHT_ARRAYS.contains(&block.name.as_str()),
    })
}

/// Read a Wyko `.opd` file: its height arrays (heights in m) and other arrays.
pub fn read_opd(path: &Path, bytes: &[u8]) -> Result<Reading, Error> {
    let b = Bytes::new(path, bytes);
    if !is_opd(bytes) {
        return Err(b.err("not a Wyko OPD file: expected 'Directory' at byte 2"));
    }
    let blocks = directory(&b)?;
    // A scalar block's value and offset.
    let find = |name: &str| -> Result<Option<(f64, usize)>, Error> {
        match blocks
            .iter()
            .find(|k| k.name == name && k.kind != TYPE_ARRAY)
        {
            Some(block) => Ok(scalar(&b, block)?.map(|v| (v, block.off))),
            None => Ok(None),
        }
    };
    let (wavelength_nm, at) = find("Wavelength")?.ok_or_else(|| {
        b.err("no 'Wavelength' block in the directory at byte 2: the height scale is unknown")
    })?;
    let (mult, _) = find("Mult")?.unwrap_or((1.0, at));
    let (aspect, _) = find("Aspect")?.unwrap_or((1.0, at));
    let (pixel_mm, pixel_at) = find("Pixel_size")?.ok_or_else(|| {
        b.err("no 'Pixel_size' block in the directory at byte 2: the pixel size is unknown")
    })?;
    let dx = pixel_size(
        &b,
        pixel_mm * 1e-3,
        &format!("'Pixel_size' (byte {pixel_at})"),
    )?;
    let dy = pixel_size(
        &b,
        dx * aspect,
        &format!("'Pixel_size' (byte {pixel_at}) × 'Aspect'"),
    )?;
    let z_scale = wavelength_nm / mult * 1e-9;
    if !(z_scale.is_finite() && z_scale != 0.0) {
        return Err(b.err(format!(
            "'Wavelength' {wavelength_nm} nm (byte {at}) and 'Mult' {mult} give a height per \
             unit of {z_scale} m, expected a finite nonzero value"
        )));
    }
    let mut channels = Vec::new();
    for block in blocks.iter().filter(|k| k.kind == TYPE_ARRAY && k.len > 0) {
        let mut c = array(&b, block, dx, dy)?;
        if c.is_height {
            c.z.iter_mut().for_each(|z| *z *= z_scale);
            c.unit_in_file = "nm".to_string();
        }
        channels.push(c);
    }
    if !channels.iter().any(|c| c.is_height) {
        return Err(b.err(format!(
            "no height array (one of {}) in the directory at byte 2",
            HEIGHT_ARRAYS.join(", ")
        )));
    }
    Ok(Reading {
        format: "opd",
        channels,
    })
}
