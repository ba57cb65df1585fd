//! Keysight/Agilent (Molecular Imaging) `.mi` image files (PicoView AFMs), laid out as
//! Gwyddion's `mifile.c` reads them: a text header of lines with a 14-character key column
//! (`xPixels       256`), indented lines being continuations; `bufferLabel` opens the
//! description of a channel (`bufferRange`, `bufferUnit`); the line with the key `data` ends
//! the header and says how the channels are stored (`BINARY`: i16, `BINARY_32`: i32, both
//! little-endian). The channels follow back to back, `yPixels` rows of `xPixels` values, the
//! last row being the top line of the image (reversed here).
//!
//! Values: count · `bufferRange` / 2¹⁵ (i16) or / 2³¹ (i32), in `bufferUnit`; a channel whose
//! unit is a length holds heights. `xLength` and `yLength` are the scan size in m.

use super::bounded::{Bytes, decode_flipped, length_unit};
use super::{Channel, Reading};
use crate::Error;
use std::path::Path;

const KEY_WIDTH: usize = 14;

/// An MI file starts with the key `fileType`.
pub fn is_mi(bytes: &[u8]) -> bool {
    bytes.starts_with(b"fileType")
}

/// A header entry: value and 1-based line.
type Entry = (String, usize);

/// The header's global entries, its channel descriptions and the offset of the data.
struct Header {
    global: Vec<(String, Entry)>,
    buffers: Vec<Vec<(String, Entry)>>,
    data_offset: usize,
}

fn at(path: &Path, line: usize, msg: impl Into<String>) -> Error {
    Error::Input {
        path: path.to_path_buf(),
        line,
        msg: msg.into(),
    }
}

fn header(path: &Path, bytes: &[u8]) -> Result<Header, Error> {
    let mut h = Header {
        global: Vec::new(),
        buffers: Vec::new(),
        data_offset: 0,
    };
    let (mut off, mut lines) = (0, 0);
    for (i, raw) in bytes.split_inclusive(|&c| c == b'\n').enumerate() {
        off += raw.len();
        lines = i + 1;
        let line = String::from_utf8_lossy(raw);
        let line = line.trim_end_matches(['\r', '\n']);
        if line.starts_with(' ') || line.trim().is_empty() {
            continue;
        }
        let split = line
            .char_indices()
            .nth(KEY_WIDTH)
            .map_or(line.len(), |(k, _)| k);
        let key = line[..split].trim().to_string();
        let entry = (line[split..].trim().to_string(), i + 1);
        if key == "data" {
            h.global.push((key, entry));
            h.data_offset = off;
            return Ok(h);
        }
        if key == "bufferLabel" {
            h.buffers.push(Vec::new());
        }
        match h.buffers.last_mut() {
            Some(b) => b.push((key, entry)),
            None => h.global.push((key, entry)),
        }
    }
    Err(at(
        path,
        lines,
        "the file ends before the 'data' line that ends the header",
    ))
}

fn get<'a>(
    path: &Path,
    list: &'a [(String, Entry)],
    key: &str,
    line: usize,
) -> Result<&'a Entry, Error> {
    list.iter()
        .find(|(k, _)| k == key)
        .map(|(_, e)| e)
        .ok_or_else(|| {
            at(
                path,
                line,
                format!("no '{key}' in the header from this line"),
            )
        })
}

fn number<T: std::str::FromStr>(path: &Path, e: &Entry, what: &str) -> Result<T, Error> {
    e.0.parse()
        .map_err(|_| at(path, e.1, format!("expected {what}, found '{}'", e.0)))
}

/// Read an MI image file: one channel per buffer, heights in m for the channels whose unit is a
/// length, other channels in their own unit.
pub fn read_mi(path: &Path, bytes: &[u8]) -> Result<Reading, Error> {
    if !is_mi(bytes) {
        return Err(at(
            path,
            1,
            "not an MI file: expected the key 'fileType' on line 1",
        ));
    }
    let h = header(path, bytes)?;
    let g = |key: &str| get(path, &h.global, key, 1);
    let file_type = g("fileType")?;
    if file_type.0 != "Image" {
        let msg = format!(
            "file type '{}', expected Image (spectroscopy files are not read)",
            file_type.0
        );
        return Err(at(path, file_type.1, msg));
    }
    let data = g("data")?;
    let (elsize, full_scale) = match data.0.as_str() {
        "BINARY" | "" => (2, 32768.0),
        "BINARY_32" => (4, 2147483648.0),
        other => {
            let msg = format!("data stored as '{other}', expected BINARY or BINARY_32");
            return Err(at(path, data.1, msg));
        }
    };
    let nx: usize = number(path, g("xPixels")?, "a count")?;
    let ny: usize = number(path, g("yPixels")?, "a count")?;
    let b = Bytes::new(path, bytes);
    let step = |key: &str, n: usize| -> Result<f64, Error> {
        let e = g(key)?;
        let d = number::<f64>(path, e, "a length in m")? / n as f64;
        if d.is_finite() && d > 0.0 {
            Ok(d)
        } else {
            Err(at(
                path,
                e.1,
                format!("pixel size {d} m, expected positive"),
            ))
        }
    };
    let (dx, dy) = (step("xLength", nx)?, step("yLength", ny)?);
    if h.buffers.is_empty() {
        return Err(at(
            path,
            data.1,
            "the header describes no channel ('bufferLabel')",
        ));
    }
    let mut channels = Vec::with_capacity(h.buffers.len());
    let mut off = h.data_offset;
    for buf in &h.buffers {
        let label = &buf[0].1;
        let range: f64 = number(path, get(path, buf, "bufferRange", label.1)?, "a number")?;
        let unit = get(path, buf, "bufferUnit", label.1)?.0.clone();
        let raw = b.grid(off, nx, ny, elsize, &format!("channel '{}'", label.0))?;
        off += raw.len();
        let to_m = length_unit(&unit);
        let per_count = range / full_scale * to_m.unwrap_or(1.0);
        let z = if elsize == 2 {
            decode_flipped(raw, nx, |a| f64::from(i16::from_le_bytes(a)) * per_count)
        } else {
            decode_flipped(raw, nx, |a| f64::from(i32::from_le_bytes(a)) * per_count)
        };
        channels.push(Channel {
            name: label.0.clone(),
            nx,
            ny,
            dx,
            dy,
            z,
            unit_in_file: unit,
            is_height: to_m.is_some(),
        });
    }
    Ok(Reading {
        format: "mi",
        channels,
    })
}
