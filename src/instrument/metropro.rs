//! Zygo MetroPro `.dat` files (Zygo interferometers), as the MetroPro Reference Guide
//! (0347M) lays them out: a big-endian header (834 bytes for header formats 1 and 2, 4096 for
//! format 3), then the intensity buckets (16-bit counts, `ac_n_buckets` frames of
//! `ac_org_width` × `ac_org_height`), then the connected phase (32-bit integers, `cn_org_width`
//! × `cn_org_height`), both row by row from the top line of the camera image.
//!
//! Heights from phase counts: z = sign · S · O · λ / R · count, with S the interferometric
//! scale factor, O the obliquity factor, λ the wavelength in metres and R the phase
//! resolution (4096, 32768 or 131072 counts per wave for `phase_res` 0, 1, 2); a negative
//! `sign` field flips the surface. Counts ≥ 2147483640 mark non-measured points. The pixel
//! size is `lateral_res` (m), the same along x and y.

use super::bounded::{Bytes, decode, pixel_size};
use super::{Channel, Reading};
use crate::Error;
use std::path::Path;

const MAGIC: [[u8; 4]; 3] = [
    [0x88, 0x1b, 0x03, 0x6f],
    [0x88, 0x1b, 0x03, 0x70],
    [0x88, 0x1b, 0x03, 0x71],
];

/// Phase counts at or above this mark non-measured points.
const INVALID_PHASE: i32 = 2_147_483_640;

/// A MetroPro file starts with one of the three header-format magic numbers.
pub fn is_metropro(bytes: &[u8]) -> bool {
    bytes.len() >= 4 && MAGIC.iter().any(|m| bytes[..4] == *m)
}

/// Read a MetroPro `.dat` file: the height map from the connected phase (channel "metropro",
/// heights in m) and one channel per intensity bucket ("intensity", counts as stored).
pub fn read_metropro(path: &Path, bytes: &[u8]) -> Result<Reading, Error> {
    let b = Bytes::new(path, bytes);
    if !is_metropro(bytes) {
        return Err(b.err(
            "not a Zygo MetroPro file: expected the magic number 881b036f, 881b0370 or \
             881b0371 at byte 0",
        ));
    }
    let header_size = b.u32_be(6, "header size")? as usize;
    let expected = if bytes[3] == 0x71 { 4096 } else { 834 };
    if header_size != expected {
        return Err(b.err(format!(
            "byte 6: header size {header_size}, expected {expected} for header format {}",
            bytes[3] - 0x6e
        )));
    }
    let dim = |off: usize, what: &str| b.u16_be(off, what).map(usize::from);
    let (ac_w, ac_h) = (dim(52, "intensity width")?, dim(54, "intensity height")?);
    let buckets = dim(56, "intensity buckets")?;
    let (cn_w, cn_h) = (dim(68, "phase width")?, dim(70, "phase height")?);
    let scale = b.f32_be(164, "interferometric scale factor")?;
    let wavelength = b.f32_be(168, "wavelength")?;
    let obliquity = b.f32_be(176, "obliquity factor")?;
    let lateral = b.f32_be(184, "lateral resolution")?;
    let resolution = match b.i16_be(218, "phase resolution")? {
        0 => 4096.0,
        1 => 32768.0,
        2 => 131072.0,
        r => {
            return Err(b.err(format!(
                "byte 218: phase resolution code {r}, expected 0, 1 or 2"
            )));
        }
    };
    let sign = if b.i16_be(232, "sign")? != 0 {
        -1.0
    } else {
        1.0
    };
    let dx = pixel_size(&b, lateral, "lateral resolution (byte 184)")?;
    let z_scale = sign * scale * obliquity * wavelength / resolution;
    if !(z_scale.is_finite() && z_scale != 0.0) {
        return Err(b.err(format!(
            "bytes 164–180: scale factor {scale}, wavelength {wavelength} m and obliquity \
             {obliquity} give a height per count of {z_scale}, expected a finite nonzero value"
        )));
    }
    let frame = ac_w * ac_h * 2;
    let intensity: &[u8] = if frame == 0 || buckets == 0 {
        &[]
    } else {
        b.grid(header_size, ac_w * ac_h, buckets, 2, "intensity data")?
    };
    let phase_off = header_size + intensity.len();
    let raw = b.grid(phase_off, cn_w, cn_h, 4, "phase data")?;
    let z = decode(raw, |a| {
        let c = i32::from_be_bytes(a);
        if c >= INVALID_PHASE {
            f64::NAN
        } else {
            f64::from(c) * z_scale
        }
    });
    let mut channels = vec![Channel {
        name: "metropro".to_string(),
        nx: cn_w,
        ny: cn_h,
        dx,
        dy: dx,
        z,
        unit_in_file: "m".to_string(),
        is_height: true,
    }];
    for (k, raw) in intensity.chunks_exact(frame.max(1)).enumerate() {
        channels.push(Channel {
            name: if buckets == 1 {
                "intensity".to_string()
            } else {
                format!("intensity {}", k + 1)
            },
            nx: ac_w,
            ny: ac_h,
            dx,
            dy: dx,
            z: decode(raw, |a| f64::from(u16::from_be_bytes(a))),
            unit_in_file: "counts".to_string(),
            is_height: false,
        });
    }
    Ok(Reading {
        format: "metropro",
        channels,
    })
}
