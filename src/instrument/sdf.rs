//! ISO 25178-71 surface data file (SDF), text (`aISO-1.0`) and binary (`bISO-1.0`).
//!
//! Text: the signature line, then `Key = value` lines up to a line `*` (NumPoints, points per
//! profile, along x; NumProfiles, along y; Xscale, Yscale, Zscale in metres; DataType 0–7;
//! Compression 0), then NumPoints × NumProfiles values separated by blanks, profile after
//! profile, up to the next `*`; `BAD` marks a point that was not measured. Binary: after the
//! 8-byte signature a packed little-endian header (ManufacID 10 bytes, CreateDate and ModDate
//! 12 each, NumPoints and NumProfiles u16, Xscale, Yscale, Zscale, Zresolution f64,
//! Compression, DataType, CheckType u8: 81 bytes from the start), then the values, of DataType
//! 0–7: u8, u16, u32, f32, i8, i16, i32, f64. A height is value · Zscale; the largest unsigned
//! and the most negative signed 16- and 32-bit integers and NaN mark points not measured.

use std::path::Path;

use super::bytes::{Le, grid_points};
use super::{Channel, Reading, bad, bad_line};
use crate::Error;

const TEXT: &[u8] = b"aISO-1.0";
const BINARY: &[u8] = b"bISO-1.0";
/// Bytes before the values of a binary SDF.
const BINARY_HEADER: usize = 81;

pub(crate) fn sniff(b: &[u8]) -> bool {
    b.starts_with(TEXT) || b.starts_with(BINARY)
}

/// The header fields that matter.
struct Header {
    nx: usize,
    ny: usize,
    scales: [f64; 3],
    data_type: u8,
}

pub(crate) fn read(path: &Path, b: &[u8]) -> Result<Reading, Error> {
    let (h, z) = if b.starts_with(BINARY) {
        read_binary(path, b)?
    } else if b.starts_with(TEXT) {
        read_text(path, b)?
    } else {
        return Err(bad_line(
            path,
            1,
            "expected the SDF signature 'aISO-1.0' (text) or 'bISO-1.0' (binary)",
        ));
    };
    let [dx, dy, dz] = h.scales;
    let missing = |v: f64| match h.data_type {
        1 => v == f64::from(u16::MAX),
        2 => v == f64::from(u32::MAX),
        5 => v == f64::from(i16::MIN),
        6 => v == f64::from(i32::MIN),
        _ => false,
    };
    let z = z
        .into_iter()
        .map(|v| {
            if missing(v) || v.is_nan() {
                f64::NAN
            } else {
                v * dz
            }
        })
        .collect();
    Ok(Reading {
        format: "sdf",
        channels: vec![Channel {
            name: "sdf".into(),
            nx: h.nx,
            ny: h.ny,
            dx,
            dy,
            z,
            unit_in_file: "m".into(),
            is_height: true,
        }],
    })
}

/// Checks the pixel sizes and height step; `line` (0 in a binary file) and `at` say where.
fn check_scales(path: &Path, scales: [f64; 3], line: usize, at: &str) -> Result<(), Error> {
    for (name, v) in ["Xscale", "Yscale", "Zscale"].iter().zip(scales) {
        if !(v.is_finite() && v > 0.0) {
            return Err(bad_line(
                path,
                line,
                format!("{at}{name} = {v} (expected a finite value > 0)"),
            ));
        }
    }
    Ok(())
}

fn read_binary(path: &Path, b: &[u8]) -> Result<(Header, Vec<f64>), Error> {
    let le = Le { path, b };
    let nx = le.u16(42, "NumPoints")?;
    let ny = le.u16(44, "NumProfiles")?;
    let scales = [
        le.f64(46, "Xscale")?,
        le.f64(54, "Yscale")?,
        le.f64(62, "Zscale")?,
    ];
    check_scales(path, scales, 0, "byte 46: ")?;
    let compression = le.slice(78, 1, "Compression")?[0];
    let data_type = le.slice(79, 1, "DataType")?[0];
    if compression != 0 {
        return Err(bad(
            path,
            format!(
                "byte 78: Compression = {compression} (expected 0; compressed SDF is not supported)"
            ),
        ));
    }
    let width = match data_type {
        0 | 4 => 1,
        1 | 5 => 2,
        2 | 3 | 6 => 4,
        7 => 8,
        t => {
            return Err(bad(
                path,
                format!("byte 79: DataType = {t} (expected 0 to 7)"),
            ));
        }
    };
    let n = grid_points(path, nx.into(), ny.into(), width, BINARY_HEADER, b.len())?;
    let raw = &b[BINARY_HEADER..BINARY_HEADER + n * width];
    let z = raw
        .chunks_exact(width)
        .map(|c| match data_type {
            0 => f64::from(c[0]),
            1 => f64::from(u16::from_le_bytes([c[0], c[1]])),
            2 => f64::from(u32::from_le_bytes([c[0], c[1], c[2], c[3]])),
            3 => f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]])),
            4 => f64::from(c[0] as i8),
            5 => f64::from(i16::from_le_bytes([c[0], c[1]])),
            6 => f64::from(i32::from_le_bytes([c[0], c[1], c[2], c[3]])),
            _ => f64::from_le_bytes(c.try_into().expect("8 bytes")),
        })
        .collect();
    let header = Header {
        nx: nx.into(),
        ny: ny.into(),
        scales,
        data_type,
    };
    Ok((header, z))
}

fn read_text(path: &Path, b: &[u8]) -> Result<(Header, Vec<f64>), Error> {
    let text = std::str::from_utf8(b).map_err(|e| {
        bad(
            path,
            format!("byte {}: a text SDF must be ASCII", e.valid_up_to()),
        )
    })?;
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l.trim()));
    lines.next();
    let mut get = std::collections::HashMap::new();
    let mut header_end = None;
    for (no, line) in lines.by_ref() {
        if line == "*" {
            header_end = Some(no);
            break;
        }
        if let Some((k, v)) = line.split_once('=') {
            get.insert(k.trim().to_string(), (no, v.trim().to_string()));
        }
    }
    let header_end = header_end.ok_or_else(|| {
        bad_line(
            path,
            text.lines().count(),
            "the header never ends: expected a line '*' after it",
        )
    })?;
    let field = |key: &str| -> Result<(usize, &str), Error> {
        get.get(key)
            .map(|(no, v)| (*no, v.as_str()))
            .ok_or_else(|| bad_line(path, header_end, format!("the header has no {key}")))
    };
    let int = |key: &str| -> Result<usize, Error> {
        let (no, v) = field(key)?;
        v.parse::<usize>()
            .map_err(|_| bad_line(path, no, format!("{key} = '{v}' (expected an integer)")))
    };
    let float = |key: &str| -> Result<f64, Error> {
        let (no, v) = field(key)?;
        v.parse::<f64>()
            .map_err(|_| bad_line(path, no, format!("{key} = '{v}' (expected a number)")))
    };
    let (nx, ny) = (int("NumPoints")?, int("NumProfiles")?);
    let scales = [float("Xscale")?, float("Yscale")?, float("Zscale")?];
    check_scales(path, scales, header_end, "")?;
    let data_type = int("DataType")?;
    if data_type > 7 {
        return Err(bad_line(
            path,
            field("DataType")?.0,
            format!("DataType = {data_type} (expected 0 to 7)"),
        ));
    }
    if get.contains_key("Compression") && int("Compression")? != 0 {
        return Err(bad_line(
            path,
            field("Compression")?.0,
            "compressed SDF is not supported (expected Compression = 0)",
        ));
    }
    // Each value takes at least two bytes of text (a digit and a blank).
    let n = grid_points(path, nx as i64, ny as i64, 2, 0, b.len() + 1)?;
    let mut z = Vec::with_capacity(n);
    let mut last = header_end;
    for (no, line) in lines {
        last = no;
        if line == "*" {
            break;
        }
        for tok in line.split_whitespace() {
            if z.len() == n {
                return Err(bad_line(
                    path,
                    no,
                    format!("more than NumPoints × NumProfiles = {n} values"),
                ));
            }
            let v = if tok.eq_ignore_ascii_case("BAD") {
                f64::NAN
            } else {
                tok.parse::<f64>()
                    .map_err(|_| bad_line(path, no, format!("'{tok}' is not a number (or BAD)")))?
            };
            z.push(v);
        }
    }
    if z.len() != n {
        return Err(bad_line(
            path,
            last,
            format!(
                "{} values, the header says NumPoints × NumProfiles = {nx} × {ny} \
                 (truncated file?)",
                z.len()
            ),
        ));
    }
    let header = Header {
        nx,
        ny,
        scales,
        data_type: data_type as u8,
    };
    Ok((header, z))
}
