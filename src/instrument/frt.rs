//! FRT `.frt` files (MicroProf optical profilometers), laid out as Gwyddion's `microprof.c`
//! reads them, all little-endian: the 12-byte magic `FRTM_GLIDERV`, a 4-byte version ("1.00"
//! or "1.01"), a u16 block count, then the blocks, each a u16 tag, a size (u32 in version 1.00,
//! u64 in 1.01) and that many bytes. The blocks read here:
//!
//! - 0x0066: u32 nx, ny and bits per point (16: u16, 32: i32);
//! - 0x0067: f64 width and height of the scan, m;
//! - 0x006C: u32 measuring range, f64 metres per count;
//! - 0x000B: the height counts, row by row from the bottom line of the image (flipped here);
//! - 0x007D (files without 0x000B): four u16 buffer ids, then images, each with u32 data type
//!   (bit flags; 0x0004 topography, 0x0080 thickness, 0x0800 sample thickness, 0x1000 AFM are
//!   heights), u32 nx, ny, bits per point, then the counts as in 0x000B.
//!
//! The count 1 marks non-measured points. The pixel size is the scan size over the points.

use super::bounded::{Bytes, decode_flipped, pixel_size};
use super::{Channel, Reading};
use crate::Error;
use std::path::Path;

const MAGIC: &[u8; 12] = b"FRTM_GLIDERV";
const UNDEFINED: f64 = 1.0;
const HEIGHT_TYPES: u32 = 0x0004 | 0x0080 | 0x0800 | 0x1000;

/// An FRT file starts with `FRTM_GLIDERV`.
pub fn is_frt(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

/// A block: its tag, the offset of its payload and the payload's length.
struct Block {
    tag: u16,
    off: usize,
    len: usize,
}

fn blocks(b: &Bytes) -> Result<Vec<Block>, Error> {
    let wide = match b.take(12, 4, "version")? {
        b"1.00" => false,
        b"1.01" => true,
        v => {
            return Err(b.err(format!(
                "byte 12: version '{}', expected 1.00 or 1.01",
                super::bounded::latin1(v)
            )));
        }
    };
    let n = b.u16_le(16, "block count")?;
    let mut off = 18;
    let mut out = Vec::with_capacity(usize::from(n));
    for _ in 0..n {
        let tag = b.u16_le(off, "block tag")?;
        let (len, head) = if wide {
            (b.u64_le(off + 2, "block size")?, 10)
        } else {
            (u64::from(b.u32_le(off + 2, "block size")?), 6)
        };
        let start = off + head;
        let len = usize::try_from(len)
            .ok()
            .filter(|&l| l <= b.len().saturating_sub(start))
            .ok_or_else(|| {
                b.err(format!(
                    "byte {}: block 0x{tag:04x} of {len} bytes runs past the end of the file \
                     ({} bytes)",
                    off + 2,
                    b.len()
                ))
            })?;
        out.push(Block {
            tag,
            off: start,
            len,
        });
        off = start + len;
    }
    Ok(out)
}

/// Height counts of an `nx` × `ny` grid at `off` in m (image orientation, count 1 → NaN).
/// The counts must end within the block, at `end`.
fn heights(
    b: &Bytes,
    (off, end): (usize, usize),
    (nx, ny, bits): (usize, usize, u32),
    scale: f64,
    what: &str,
) -> Result<Vec<f64>, Error> {
    let elsize = match bits {
        16 => 2,
        32 => 4,
        _ => {
            return Err(b.err(format!(
                "{what} at byte {off}: {bits} bits per point, expected 16 or 32"
            )));
        }
    };
    let raw = b.grid(off, nx, ny, elsize, what)?;
    if off + raw.len() > end {
        return Err(b.err(format!(
            "{what} at byte {off}: {nx} × {ny} points of {elsize} bytes run past the end of \
             its block (byte {end})"
        )));
    }
    let height = |c: f64| if c == UNDEFINED { f64::NAN } else { c * scale };
    Ok(if elsize == 2 {
        decode_flipped(raw, nx, |a| height(f64::from(u16::from_le_bytes(a))))
    } else {
        decode_flipped(raw, nx, |a| height(f64::from(i32::from_le_bytes(a))))
    })
}

/// Read an FRT `.frt` file: its topography (or the height images of its multi-image block),
/// heights in m.
pub fn read_frt(path: &Path, bytes: &[u8]) -> Result<Reading, Error> {
    let b = Bytes::new(path, bytes);
    if !is_frt(bytes) {
        return Err(b.err("not an FRT file: expected 'FRTM_GLIDERV' at byte 0"));
    }
    let blocks = blocks(&b)?;
    let block = |tag: u16, min: usize, what: &str| -> Result<&Block, Error> {
        let k = blocks.iter().find(|k| k.tag == tag).ok_or_else(|| {
            b.err(format!(
                "no block 0x{tag:04x} ({what}) among the blocks from byte 18"
            ))
        })?;
        if k.len < min {
            return Err(b.err(format!(
                "byte {}: block 0x{tag:04x} ({what}) has {} bytes, expected at least {min}",
                k.off, k.len
            )));
        }
        Ok(k)
    };
    let size = block(0x67, 16, "scan size")?;
    let (width, height) = (
        b.f64_le(size.off, "width")?,
        b.f64_le(size.off + 8, "height")?,
    );
    let scale_at = block(0x6c, 12, "height scale")?.off + 4;
    let scale = b.f64_le(scale_at, "height scale")?;
    if !(scale.is_finite() && scale != 0.0) {
        return Err(b.err(format!(
            "byte {scale_at}: height scale {scale} m per count, expected a finite nonzero value"
        )));
    }
    let channel = |name: String, nx: usize, ny: usize, z: Vec<f64>| -> Result<Channel, Error> {
        Ok(Channel {
            name,
            nx,
            ny,
            dx: pixel_size(&b, width / nx as f64, "scan width / points (block 0x0067)")?,
            dy: pixel_size(
                &b,
                height / ny as f64,
                "scan height / points (block 0x0067)",
            )?,
            z,
            unit_in_file: "m".to_string(),
            is_height: true,
        })
    };
    let mut channels = Vec::new();
    if let Some(topo) = blocks.iter().find(|k| k.tag == 0x0b) {
        let grid = block(0x66, 12, "grid")?;
        let nx = b.u32_le(grid.off, "nx")? as usize;
        let ny = b.u32_le(grid.off + 4, "ny")? as usize;
        let bits = b.u32_le(grid.off + 8, "bits per point")?;
        let at = (topo.off, topo.off + topo.len);
        let z = heights(&b, at, (nx, ny, bits), scale, "topography (block 0x000b)")?;
        channels.push(channel("frt".to_string(), nx, ny, z)?);
    } else {
        let multi = block(0x7d, 8, "topography")?;
        let (mut off, end) = (multi.off + 8, multi.off + multi.len);
        while off.checked_add(16).is_some_and(|e| e <= end) {
            let kind = b.u32_le(off, "image type")?;
            let nx = b.u32_le(off + 4, "image nx")? as usize;
            let ny = b.u32_le(off + 8, "image ny")? as usize;
            let bits = b.u32_le(off + 12, "image bits per point")?;
            let n = nx.saturating_mul(ny).saturating_mul(bits as usize / 8);
            if kind & HEIGHT_TYPES != 0 {
                let at = (off + 16, end);
                let z = heights(&b, at, (nx, ny, bits), scale, "image (block 0x007d)")?;
                channels.push(channel(image_name(kind), nx, ny, z)?);
            }
            off = off.saturating_add(16).saturating_add(n);
        }
        if channels.is_empty() {
            return Err(b.err(format!(
                "byte {}: block 0x007d holds no height image",
                multi.off
            )));
        }
    }
    Ok(Reading {
        format: "frt",
        channels,
    })
}

/// An image of the multi-image block named by its type flags: kind, sensor and buffer number.
fn image_name(kind: u32) -> String {
    let what = match kind & 0xffdf {
        0x0004 => "Topography",
        0x0080 => "Thickness",
        0x0800 => "Sample thickness",
        0x1000 => "AFM",
        _ => "Unknown",
    };
    let sensor = if kind & 0x1000_0000 != 0 {
        "bottom"
    } else {
        "top"
    };
    format!(
        "{what} ({sensor} sensor) {}",
        ((kind & 0x0f00_0000) >> 24) + 1
    )
}
