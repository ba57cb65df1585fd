//! Digital Surf SUR (MountainsMap's native format): a 512-byte little-endian header, a comment
//! and a private zone, then nx × ny integers (16 or 32 bit), row by row with x along a row;
//! several objects (channels) may follow one another, each with its own header.
//!
//! Header fields used (byte offsets): `DIGITAL SURF` at 0, number of objects (u16) at 14, the
//! "special points" flag (u16) at 86, bits per point (u16) at 98, z min (i32) at 100, nx, ny
//! (i32) at 108 and 112, the point count (u32) at 116, the pixel sizes dx, dy and the height
//! step dz (f32) at 120, 124 and 128 in the units at 180, 196 and 212 (16-byte strings; the
//! z axis name at 164), the inversion code (u16) at 290, the comment and private zone sizes
//! (u16) at 334 and 336. A height is `raw · dz`; when the special-points flag is 1, the value
//! z min − 2 marks a point that was not measured (as MountainsMap and SurfaceTopography read
//! it). Inversion 1, 2, 3 negate the heights; 2 also reverses x, 3 reverses y.

use std::path::Path;

use super::bytes::{Le, grid_points};
use super::{Channel, Reading, bad};
use crate::Error;
use crate::units::{Dim, to_si};

/// Signatures of an uncompressed and a compressed SUR file.
const MAGIC: &[u8] = b"DIGITAL SURF";
const MAGIC_COMPRESSED: &[u8] = b"DSCOMPRESSED";
const HEADER: usize = 512;

pub(crate) fn sniff(b: &[u8]) -> bool {
    b.starts_with(MAGIC) || b.starts_with(MAGIC_COMPRESSED)
}

pub(crate) fn read(path: &Path, b: &[u8]) -> Result<Reading, Error> {
    let le = Le { path, b };
    if b.starts_with(MAGIC_COMPRESSED) {
        return Err(bad(
            path,
            "byte 0: compressed SUR (DSCOMPRESSED) is not supported; save the file uncompressed",
        ));
    }
    let objects = le.u16(14, "number of objects")?.max(1);
    let mut channels = Vec::new();
    let mut at = 0;
    for _ in 0..objects {
        let (channel, next) = read_object(&le, at)?;
        channels.push(channel);
        at = next;
    }
    Ok(Reading {
        format: "sur",
        channels,
    })
}

/// A length unit as SUR writes it (µ may be byte 0xB5 or, from DOS code page 437, 0xE6).
fn length_scale(le: &Le, at: usize, what: &str) -> Result<(String, Option<f64>), Error> {
    let unit = le.text(at, 16, what)?.replace('æ', "µ");
    let scale = to_si(1.0, &unit, Dim::Length(1)).ok();
    Ok((unit, scale))
}

/// The object whose header starts at `at`, and where the next one starts.
fn read_object(le: &Le, at: usize) -> Result<(Channel, usize), Error> {
    let path = le.path;
    if le.slice(at, MAGIC.len(), "signature")? != MAGIC {
        return Err(bad(
            path,
            format!("byte {at}: expected the signature 'DIGITAL SURF' of a SUR object"),
        ));
    }
    let special_points = le.u16(at + 86, "special points flag")?;
    let bits = le.u16(at + 98, "bits per point")?;
    if bits != 16 && bits != 32 {
        return Err(bad(
            path,
            format!(
                "byte {}: {bits} bits per point (expected 16 or 32)",
                at + 98
            ),
        ));
    }
    let zmin = le.i32(at + 100, "z min")?;
    let nx = le.i32(at + 108, "nx")?;
    let ny = le.i32(at + 112, "ny")?;
    let count = le.u32(at + 116, "number of points")?;
    if i64::from(nx) * i64::from(ny) != i64::from(count) {
        return Err(bad(
            path,
            format!(
                "byte {}: {count} points, but nx × ny = {nx} × {ny}",
                at + 116
            ),
        ));
    }
    let step = |off: usize, what: &str| -> Result<f64, Error> {
        let v = f64::from(le.f32(at + off, what)?);
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(bad(
                path,
                format!("byte {}: {what} is {v} (expected > 0)", at + off),
            ))
        }
    };
    let (dx, dy, dz) = (step(120, "dx")?, step(124, "dy")?, step(128, "dz")?);
    let name = le.text(at + 164, 16, "z axis name")?;
    let lateral = |off: usize, what: &str| -> Result<f64, Error> {
        let (unit, scale) = length_scale(le, at + off, what)?;
        scale.ok_or_else(|| {
            bad(
                path,
                format!("byte {}: {what} '{unit}' is not a length unit", at + off),
            )
        })
    };
    let (sx, sy) = (lateral(180, "x unit")?, lateral(196, "y unit")?);
    let (z_unit, z_scale) = length_scale(le, at + 212, "z unit")?;
    let inversion = le.u16(at + 290, "inversion")?;
    let comment = le.u16(at + 334, "comment size")? as usize;
    let private = le.u16(at + 336, "private zone size")? as usize;
    let data_at = at + HEADER + comment + private;
    let width = bits as usize / 8;
    let n = grid_points(path, nx.into(), ny.into(), width, data_at, le.b.len())?;
    let (nx, ny) = (nx as usize, ny as usize);
    let sign = if matches!(inversion, 1..=3) {
        -1.0
    } else {
        1.0
    };
    let scale = sign * dz * z_scale.unwrap_or(1.0);
    let missing = (special_points == 1).then(|| i64::from(zmin) - 2);
    let raw = &le.b[data_at..data_at + n * width];
    let mut z: Vec<f64> = if width == 2 {
        raw.chunks_exact(2)
            .map(|c| i64::from(i16::from_le_bytes([c[0], c[1]])))
            .map(|v| {
                if Some(v) == missing {
                    f64::NAN
                } else {
                    v as f64 * scale
                }
            })
            .collect()
    } else {
        raw.chunks_exact(4)
            .map(|c| i64::from(i32::from_le_bytes([c[0], c[1], c[2], c[3]])))
            .map(|v| {
                if Some(v) == missing {
                    f64::NAN
                } else {
                    v as f64 * scale
                }
            })
            .collect()
    };
    match inversion {
        2 => z.chunks_exact_mut(nx).for_each(|row| row.reverse()),
        3 => {
            let rows: Vec<f64> = z.chunks_exact(nx).rev().flatten().copied().collect();
            z = rows;
        }
        _ => {}
    }
    let channel = Channel {
        name: if name.is_empty() { "sur".into() } else { name },
        nx,
        ny,
        dx: dx * sx,
        dy: dy * sy,
        z,
        is_height: z_scale.is_some(),
        unit_in_file: z_unit,
    };
    Ok((channel, data_at + n * width))
}
