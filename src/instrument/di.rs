//! Bruker (Veeco, Digital Instruments) Nanoscope files (`.spm`, `.001`, …; "DI"), version 4.3
//! and later, as the Nanoscope file-format description lays them out: a Latin-1 text header of
//! `\Key: value` lines in sections opened by `\*Name` (the first `\*File list`, the last
//! `\*File list end`), then binary channels at the offsets the header gives.
//!
//! Each `\*Ciao image list` section is a channel: `Samps/line` × `Number of lines` points,
//! little-endian integers of `Bytes/pixel` bytes (always 4 from version 9.2 when the data
//! length allows) at `Data offset`, row by row from the top line (the rows are reversed here,
//! as Gwyddion and SurfaceTopography orient the image); `Scan Size` is the physical size
//! (`Slow Axis Size` of the scan list, where given, the size along y). The channel's name is
//! the soft scale of `@2:Image Data` (e.g. `S [Height] "Height"` → "Height").
//!
//! Values: `@2:Z scale: V [Sens. Zsens] (… V/LSB) 2.910461 V` gives the hard value h (V) per
//! full range of the integers, so one count is h / 256^(bytes/pixel) V; the soft scale
//! `\@Sens. Zsens: V 20.82646 nm/V` of the scanner or scan list converts volts into the
//! channel's unit. A channel whose unit is a length (the soft scale's numerator) holds heights;
//! other channels (phase, amplitude) keep their values in their own unit.

use super::bounded::{Bytes, decode_flipped, latin1, length_unit};
use super::{Channel, Reading};
use crate::Error;
use std::path::Path;

/// From this software version on, the data are 32-bit integers whatever `Bytes/pixel` says.
const VERSION_32BIT: u32 = 0x0920_0000;

const FILE_LIST: [&str; 2] = ["file list", "ec file list"];
const SCANNER: [&str; 2] = ["scanner list", "microscope list"];
const SCAN: [&str; 4] = ["ciao scan list", "afm list", "stm list", "nc afm list"];
const IMAGE: [&str; 5] = [
    "ciao image list",
    "afm image list",
    "stm image list",
    "ncafm image list",
    "image list",
];

/// A Nanoscope file starts with the section `\*File list` (or `\*EC File list`).
pub fn is_di(bytes: &[u8]) -> bool {
    let head = latin1(&bytes[..bytes.len().min(16)]).to_lowercase();
    FILE_LIST
        .iter()
        .any(|s| head.starts_with(&format!("\\*{s}")))
}

/// One header entry: key (lower case), value and 1-based line.
struct Entry {
    key: String,
    value: String,
    line: usize,
}

/// A header section: its name (lower case), 1-based line and entries.
struct Section {
    name: String,
    line: usize,
    entries: Vec<Entry>,
}

impl Section {
    fn get(&self, key: &str) -> Option<&Entry> {
        self.entries.iter().find(|e| e.key == key)
    }
}

/// An error at a header line.
fn at(path: &Path, line: usize, msg: impl Into<String>) -> Error {
    Error::Input {
        path: path.to_path_buf(),
        line,
        msg: msg.into(),
    }
}

fn header(path: &Path, bytes: &[u8]) -> Result<Vec<Section>, Error> {
    let mut sections: Vec<Section> = Vec::new();
    let mut lines = 0;
    for (i, raw) in bytes.split(|&c| c == b'\n').enumerate() {
        lines = i + 1;
        let line = latin1(raw);
        let line = line.trim();
        let n = i + 1;
        if line.is_empty() {
            continue;
        }
        if line.eq_ignore_ascii_case("\\*file list end") {
            return if sections.is_empty() {
                Err(at(path, n, "no sections before the end of the header"))
            } else {
                Ok(sections)
            };
        }
        if line.starts_with("?*") {
            return Err(at(path, n, "data stored as text are not supported"));
        }
        if let Some(name) = line.strip_prefix("\\*") {
            let name = name.to_lowercase();
            if sections.is_empty() && !FILE_LIST.contains(&name.as_str()) {
                return Err(at(
                    path,
                    n,
                    "expected the header to start with '\\*File list'",
                ));
            }
            sections.push(Section {
                name,
                line: n,
                entries: Vec::new(),
            });
        } else if let (Some(kv), Some(s)) = (line.strip_prefix('\\'), sections.last_mut()) {
            let (key, value) = kv.split_once(": ").unwrap_or((kv, ""));
            s.entries.push(Entry {
                key: key.trim().to_lowercase(),
                value: value.trim().to_string(),
                line: n,
            });
        } else {
            return Err(at(
                path,
                n,
                "expected a header line starting with '\\' (or '\\*File list end')",
            ));
        }
    }
    Err(at(path, lines, "the file ends before '\\*File list end'"))
}

/// A `@`-value `V [soft] (hard scale) value unit`, split into its type, soft scale name and
/// value with unit (the hard scale in parentheses is not needed).
fn parse_value(value: &str) -> Option<(char, Option<&str>, &str)> {
    let mut chars = value.trim().chars();
    let kind = chars.next()?;
    let mut rest = chars.as_str().trim();
    let mut soft = None;
    if let Some(r) = rest.strip_prefix('[') {
        let end = r.find(']')?;
        soft = Some(r[..end].trim()).filter(|s| !s.is_empty());
        rest = r[end + 1..].trim();
    }
    if rest.starts_with('(') {
        let mut depth = 0;
        let end = rest.char_indices().find_map(|(i, c)| {
            depth += i32::from(c == '(') - i32::from(c == ')');
            (depth == 0).then_some(i)
        })?;
        rest = rest[end + 1..].trim();
    }
    Some((kind, soft, rest))
}

/// "2.910461 V" → (2.910461, "V").
fn number_and_unit(s: &str) -> Option<(f64, &str)> {
    let s = s.trim();
    let (num, unit) = s.split_once(char::is_whitespace).unwrap_or((s, ""));
    Some((num.parse().ok()?, unit.trim()))
}

/// Factor from `from` to `to` when both are the same base unit with SI prefixes (mV → V).
fn prefix_factor(from: &str, to: &str) -> Option<f64> {
    let split = |u: &str| -> (f64, String) {
        let mut c = u.chars();
        let p = match c.next() {
            Some('m') => 1e-3,
            Some('u' | 'µ' | 'μ' | '~') => 1e-6,
            Some('n') => 1e-9,
            Some('p') => 1e-12,
            Some('k') => 1e3,
            _ => return (1.0, u.to_string()),
        };
        let base = c.as_str();
        if base.is_empty() {
            (1.0, u.to_string())
        } else {
            (p, base.to_string())
        }
    };
    let ((pf, bf), (pt, bt)) = (split(from), split(to));
    if from == to {
        Some(1.0)
    } else {
        (bf == bt).then(|| pf / pt)
    }
}

/// What the global sections say: software version, grid of the scan and slow-axis size.
struct Globals<'a> {
    version: u32,
    scan_grid: Option<(usize, usize)>,
    /// Fast and slow scan sizes, m, where the scan list gives a `Slow Axis Size`.
    slow_axis: Option<(f64, f64)>,
    /// Soft scales: the scanner lists, then the scan lists.
    soft: Vec<&'a Entry>,
}

/// A size with a length unit ("500 nm", "10 ~m") in m.
fn size_m(path: &Path, e: &Entry) -> Result<f64, Error> {
    number_and_unit(&e.value)
        .and_then(|(v, u)| Some(v * length_unit(u)?))
        .ok_or_else(|| {
            at(
                path,
                e.line,
                format!("expected a length, found '{}'", e.value),
            )
        })
}

fn globals<'a>(path: &Path, sections: &'a [Section]) -> Result<Globals<'a>, Error> {
    let in_kind = |kinds: &[&str]| -> Vec<&'a Section> {
        sections
            .iter()
            .filter(|s| kinds.contains(&s.name.as_str()))
            .collect()
    };
    let (files, scanners, scans) = (in_kind(&FILE_LIST), in_kind(&SCANNER), in_kind(&SCAN));
    let find = |list: &[&'a Section], key: &str| list.iter().find_map(|s| s.get(key));
    let version = find(&files, "version")
        .and_then(|e| u32::from_str_radix(e.value.trim_start_matches("0x"), 16).ok())
        .unwrap_or(0);
    let mode = sections.iter().find_map(|s| s.get("operating mode"));
    if let Some(m) = mode.filter(|m| m.value == "Force") {
        return Err(at(path, m.line, "force curves are not supported"));
    }
    if let Some(c) = find(&files, "start context") {
        if c.value == "FOL" {
            return Err(at(path, c.line, "force curves are not supported"));
        }
        if c.value.ends_with("VAR") && mode.is_none_or(|m| m.value != "Force Volume") {
            return Err(at(
                path,
                c.line,
                "unevenly spaced profiles are not supported",
            ));
        }
    }
    let count = |key: &str| find(&scans, key).and_then(|e| e.value.parse::<usize>().ok());
    let scan_grid = count("samps/line").zip(count("lines"));
    let slow_axis = match (find(&scans, "scan size"), find(&scans, "slow axis size")) {
        (Some(fast), Some(slow)) => {
            let unit = fast.value.split_whitespace().last().unwrap_or("");
            let first = fast.value.split_whitespace().next().unwrap_or("");
            let fast_m = number_and_unit(&format!("{first} {unit}"))
                .and_then(|(v, u)| Some(v * length_unit(u)?))
                .ok_or_else(|| at(path, fast.line, "expected a scan size with a length unit"))?;
            Some((fast_m, size_m(path, slow)?))
        }
        _ => None,
    };
    let soft = scanners
        .iter()
        .chain(&scans)
        .flat_map(|s| s.entries.iter().filter(|e| e.key.starts_with('@')))
        .collect();
    Ok(Globals {
        version,
        scan_grid,
        slow_axis,
        soft,
    })
}

/// A channel's value per count and unit from its `@2:Z scale` and the soft scale it names;
/// whether that unit is a length (then the factor gives m).
fn z_scale(
    path: &Path,
    image: &Section,
    g: &Globals,
    bytes_per_pixel: usize,
) -> Result<(f64, String, bool), Error> {
    let e = image
        .get("@4:z scale")
        .or_else(|| image.get("@2:z scale"))
        .ok_or_else(|| {
            let msg = "the image section has no '@2:Z scale' (versions before 4.3 are not read)";
            at(path, image.line, msg)
        })?;
    let malformed = || {
        at(
            path,
            e.line,
            format!("cannot read the Z scale '{}'", e.value),
        )
    };
    let (_, soft_name, hard) = parse_value(&e.value).ok_or_else(malformed)?;
    let (hard_value, hard_unit) = number_and_unit(hard).ok_or_else(malformed)?;
    let per_count = hard_value / 256f64.powi(bytes_per_pixel as i32);
    let soft = soft_name.and_then(|n| {
        let key = format!("@{}", n.to_lowercase());
        g.soft.iter().find(|s| s.key == key)
    });
    let Some(soft) = soft else {
        return Ok(match length_unit(hard_unit) {
            Some(m) => (per_count * m, hard_unit.to_string(), true),
            None => (per_count, hard_unit.to_string(), false),
        });
    };
    let bad_soft = || {
        at(
            path,
            soft.line,
            format!("cannot read the soft scale '{}'", soft.value),
        )
    };
    let (kind, _, value) = parse_value(&soft.value).ok_or_else(bad_soft)?;
    let (factor, unit) = number_and_unit(value).ok_or_else(bad_soft)?;
    if kind != 'V' {
        return Err(bad_soft());
    }
    let Some((num, den)) = unit.split_once('/') else {
        return Ok((per_count * factor, hard_unit.to_string(), false));
    };
    let convert = prefix_factor(hard_unit, den).ok_or_else(|| {
        at(
            path,
            e.line,
            format!(
                "the Z scale is in '{hard_unit}' but its soft scale (line {}) is per '{den}'",
                soft.line
            ),
        )
    })?;
    let value = per_count * convert * factor;
    Ok(match length_unit(num) {
        Some(m) => (value * m, num.to_string(), true),
        None => (value, num.to_string(), false),
    })
}

/// The name of an image section's channel: the soft scale of `@2:Image Data`, else its value.
fn image_name(image: &Section) -> String {
    ["@2:image data", "@3:image data", "@4:image data"]
        .iter()
        .find_map(|k| image.get(k))
        .and_then(|e| {
            let (_, soft, value) = parse_value(&e.value)?;
            Some(soft.unwrap_or(value.trim_matches('"')).to_string())
        })
        .or_else(|| image.get("image data").map(|e| e.value.clone()))
        .unwrap_or_else(|| "image".to_string())
}

fn channel(b: &Bytes, path: &Path, image: &Section, g: &Globals) -> Result<Channel, Error> {
    let entry = |key: &str| {
        image.get(key).ok_or_else(|| {
            at(
                path,
                image.line,
                format!("the image section has no '{key}'"),
            )
        })
    };
    let count = |key: &str| -> Result<usize, Error> {
        let e = entry(key)?;
        e.value.parse().map_err(|_| {
            at(
                path,
                e.line,
                format!("expected a count, found '{}'", e.value),
            )
        })
    };
    let (mut nx, mut ny) = (count("samps/line")?, count("number of lines")?);
    let (offset, length) = (count("data offset")?, count("data length")?);
    let bpp = match image.get("bytes/pixel") {
        Some(_) => count("bytes/pixel")?,
        None => 2,
    };
    if bpp != 2 && bpp != 4 {
        let line = entry("bytes/pixel")?.line;
        return Err(at(
            path,
            line,
            format!("{bpp} bytes per pixel, expected 2 or 4"),
        ));
    }
    let size = entry("scan size")?;
    let words: Vec<&str> = size.value.split_whitespace().collect();
    let unit = words.last().and_then(|u| length_unit(u));
    let numbers: Vec<f64> = words.iter().map_while(|w| w.parse().ok()).collect();
    let (mut sx, mut sy) = match (numbers.as_slice(), unit) {
        ([x], Some(u)) => (x * u, x * u),
        ([x, y, ..], Some(u)) => (x * u, y * u),
        _ => {
            let msg = format!(
                "expected a scan size like '500 500 nm', found '{}'",
                size.value
            );
            return Err(at(path, size.line, msg));
        }
    };
    if let Some((fast, slow)) = g.slow_axis {
        (sx, sy) = (fast, slow);
    }
    let elsize = if g.version >= VERSION_32BIT && length / 4 >= nx.saturating_mul(ny) {
        4
    } else {
        bpp
    };
    if let Some((gx, gy)) = g.scan_grid {
        let need = |x: usize, y: usize| x.saturating_mul(y).saturating_mul(elsize);
        let fits_global =
            length == need(gx, gy) || (need(nx, ny) > length && length >= need(gx, gy));
        if length != need(nx, ny) && fits_global {
            if g.slow_axis.is_none() {
                sx *= gx as f64 / nx as f64;
                sy *= gy as f64 / ny as f64;
            }
            (nx, ny) = (gx, gy);
        } else if g.slow_axis.is_some() && non_square(image) && ny < gy {
            sy *= ny as f64 / gy as f64;
        }
    }
    if nx.saturating_mul(ny).saturating_mul(elsize) > length {
        let line = entry("data length")?.line;
        let msg = format!("data length {length} is less than {nx} × {ny} points of {elsize} bytes");
        return Err(at(path, line, msg));
    }
    let (dx, dy) = (sx / nx as f64, sy / ny as f64);
    if !(dx.is_finite() && dx > 0.0 && dy.is_finite() && dy > 0.0) {
        let msg = format!(
            "pixel size {dx} × {dy} m from scan size '{}', expected positive",
            size.value
        );
        return Err(at(path, size.line, msg));
    }
    let raw = b.grid(offset, nx, ny, elsize, "image data")?;
    let (per_count, unit_in_file, is_height) = z_scale(path, image, g, bpp)?;
    let z: Vec<f64> = if elsize == 2 {
        decode_flipped(raw, nx, |a| f64::from(i16::from_le_bytes(a)) * per_count)
    } else {
        decode_flipped(raw, nx, |a| f64::from(i32::from_le_bytes(a)) * per_count)
    };
    Ok(Channel {
        name: image_name(image),
        nx,
        ny,
        dx,
        dy,
        z,
        unit_in_file,
        is_height,
    })
}

/// An image section whose `Aspect Ratio` is not 1:1.
fn non_square(image: &Section) -> bool {
    image.get("aspect ratio").is_some_and(|e| {
        e.value != "1:1"
            && e.value
                .split(':')
                .next()
                .and_then(|r| r.trim().parse::<f64>().ok())
                .is_some_and(|r| r > 0.0 && r != 1.0)
    })
}

/// Read a Nanoscope file: one channel per image section, heights in m for the channels whose
/// unit is a length, other channels in their own unit.
pub fn read_di(path: &Path, bytes: &[u8]) -> Result<Reading, Error> {
    let b = Bytes::new(path, bytes);
    if !is_di(bytes) {
        return Err(at(
            path,
            1,
            "not a Nanoscope file: expected '\\*File list' on line 1",
        ));
    }
    let sections = header(path, bytes)?;
    let g = globals(path, &sections)?;
    let channels = sections
        .iter()
        .filter(|s| IMAGE.contains(&s.name.as_str()))
        .map(|s| channel(&b, path, s, &g))
        .collect::<Result<Vec<_>, _>>()?;
    if channels.is_empty() {
        return Err(at(
            path,
            1,
            "the header has no image section ('\\*Ciao image list')",
        ));
    }
    Ok(Reading {
        format: "di",
        channels,
    })
}
