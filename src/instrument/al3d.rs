//! Alicona `.al3d` files (InfiniteFocus focus-variation microscopes), laid out as Gwyddion's
//! `alicona.c` reads them: the 17-byte magic `AliconaImaging\0\r\n`, then tags of 52 bytes (a
//! 20-byte key, a 30-byte value as text, CR LF): "Version", "TagCount", then TagCount tags
//! (among them "Cols", "Rows", "PixelSizeXMeter", "PixelSizeYMeter", "DepthImageOffset",
//! "InvalidPixelValue"), then a 256-byte comment. The depth image is at DepthImageOffset:
//! f32 heights in m, row by row, each row padded to a multiple of 8 bytes. A point is invalid
//! when it is NaN or equals InvalidPixelValue (within 1.5e-7 relative: the value is written as
//! text with fewer digits than the f32 it marks).

use super::bounded::{Bytes, decode, pixel_size};
use super::{Channel, Reading};
use crate::Error;
use std::path::Path;

const MAGIC: &[u8; 17] = b"AliconaImaging\0\r\n";
const TAG: usize = 52;
const INVALID_RELTOL: f64 = 1.5e-7;

/// An AL3D file starts with `AliconaImaging\0\r\n`.
pub fn is_al3d(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

/// The tags (key, value, offset of the tag) of the header.
fn tags(b: &Bytes) -> Result<Vec<(String, String, usize)>, Error> {
    let tag = |k: usize| -> Result<(String, String, usize), Error> {
        let off = MAGIC.len() + k * TAG;
        if b.take(off + 50, 2, "tag end")? != b"\r\n" {
            return Err(b.err(format!("byte {}: expected CR LF ending a tag", off + 50)));
        }
        Ok((
            b.text(off, 20, "tag key")?,
            b.text(off + 20, 30, "tag value")?,
            off,
        ))
    };
    let (version, count) = (tag(0)?, tag(1)?);
    if version.0 != "Version" || count.0 != "TagCount" {
        return Err(b.err(format!(
            "byte {}: expected the tags Version and TagCount, found '{}' and '{}'",
            MAGIC.len(),
            version.0,
            count.0
        )));
    }
    let n: usize = count.1.parse().map_err(|_| {
        b.err(format!(
            "byte {}: TagCount '{}' is not a count",
            count.2 + 20,
            count.1
        ))
    })?;
    if n > b.len() / TAG {
        return Err(b.err(format!(
            "byte {}: TagCount {n} tags of {TAG} bytes do not fit in the file ({} bytes)",
            count.2 + 20,
            b.len()
        )));
    }
    (2..n + 2).map(tag).collect()
}

/// Read an Alicona `.al3d` file: its depth image, heights in m.
pub fn read_al3d(path: &Path, bytes: &[u8]) -> Result<Reading, Error> {
    let b = Bytes::new(path, bytes);
    if !is_al3d(bytes) {
        return Err(b.err("not an Alicona AL3D file: expected 'AliconaImaging' at byte 0"));
    }
    let tags = tags(&b)?;
    let get = |key: &str| -> Result<(&str, usize), Error> {
        tags.iter()
            .find(|t| t.0 == key)
            .map(|t| (t.1.as_str(), t.2 + 20))
            .ok_or_else(|| b.err(format!("no tag {key} in the header (from byte 17)")))
    };
    let number = |key: &str| -> Result<f64, Error> {
        let (v, at) = get(key)?;
        v.parse::<f64>()
            .map_err(|_| b.err(format!("byte {at}: tag {key} '{v}' is not a number")))
    };
    let count = |key: &str| -> Result<usize, Error> {
        let (v, at) = get(key)?;
        v.parse::<usize>()
            .map_err(|_| b.err(format!("byte {at}: tag {key} '{v}' is not a count")))
    };
    let (nx, ny) = (count("Cols")?, count("Rows")?);
    let tag_at = |key: &str| format!("tag {key} (byte {})", get(key).map_or(0, |t| t.1));
    let dx = pixel_size(&b, number("PixelSizeXMeter")?, &tag_at("PixelSizeXMeter"))?;
    let dy = pixel_size(&b, number("PixelSizeYMeter")?, &tag_at("PixelSizeYMeter"))?;
    let invalid = match get("InvalidPixelValue") {
        Ok(_) => number("InvalidPixelValue")?,
        Err(_) => f64::NAN,
    };
    let offset = count("DepthImageOffset")?;
    let row = nx
        .checked_mul(4)
        .and_then(|r| r.checked_next_multiple_of(8))
        .map_or(usize::MAX, |r| r / 4);
    let raw = b.grid(offset, row, ny, 4, "depth image")?;
    let mut z = Vec::with_capacity(nx * ny);
    for r in raw.chunks_exact(row * 4) {
        z.extend(decode(&r[..nx * 4], |a| {
            let v = f64::from(f32::from_le_bytes(a));
            if (v - invalid).abs() < INVALID_RELTOL * invalid.abs() {
                f64::NAN
            } else {
                v
            }
        }));
    }
    Ok(Reading {
        format: "al3d",
        channels: vec![Channel {
            name: "al3d".to_string(),
            nx,
            ny,
            dx,
            dy,
            z,
            unit_in_file: "m".to_string(),
            is_height: true,
        }],
    })
}
