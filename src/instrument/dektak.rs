//! Bruker Dektak CSV export (stylus profilometer, one profile): Latin-1 text, comma-separated;
//! a metadata block (`Scan Parameters`, then `Key,value` lines and further blocks such as
//! `Analytical Results`) up to a line `Scan Data`; then a header line naming the position and
//! height columns with their units (e.g. `Lateral um,Raw Micrometer,`) and one `x,z` line per
//! point. The pixel size is the mean step of the x column, which must be uniform up to the
//! rounding of the printed positions (see `uniform_step`).

use std::path::Path;

use super::bytes::latin1;
use super::{Reading, bad_line, uniform_step};
use crate::Error;

const MAGIC: &str = "Scan Parameters";

pub(crate) fn sniff(b: &[u8]) -> bool {
    b.strip_prefix(b"\xef\xbb\xbf".as_slice())
        .unwrap_or(b)
        .starts_with(MAGIC.as_bytes())
}

/// Metres per unit of a column header's unit word (e.g. `um` in `Lateral um`,
/// `Micrometer` in `Raw Micrometer`), and the word.
fn column_unit(header: &str) -> Option<(f64, String)> {
    header
        .split(|c: char| c.is_whitespace() || "()[]".contains(c))
        .find_map(|w| {
            let scale = match w.to_lowercase().as_str() {
                "m" | "meter" | "meters" => 1.0,
                "mm" | "millimeter" | "millimeters" => 1e-3,
                "um" | "µm" | "μm" | "micrometer" | "micrometers" | "micron" | "microns" => 1e-6,
                "nm" | "nanometer" | "nanometers" => 1e-9,
                "å" | "a" | "angstrom" | "angstroms" => 1e-10,
                _ => return None,
            };
            Some((scale, w.to_string()))
        })
}

pub(crate) fn read(path: &Path, b: &[u8]) -> Result<Reading, Error> {
    let text = latin1(b);
    let mut lines = text
        .split('\n')
        .map(|l| l.trim_end_matches('\r').trim())
        .enumerate()
        .map(|(i, l)| (i + 1, l));
    if lines
        .next()
        .is_none_or(|(_, l)| l.trim_start_matches('\u{feff}') != MAGIC)
    {
        return Err(bad_line(
            path,
            1,
            format!("expected '{MAGIC}' (a Dektak CSV export)"),
        ));
    }
    let total = text.split('\n').count();
    if !lines.by_ref().any(|(_, l)| l == "Scan Data") {
        return Err(bad_line(
            path,
            total,
            "no line 'Scan Data' before the end (truncated file?)",
        ));
    }
    let (hno, header) = lines
        .by_ref()
        .find(|(_, l)| !l.is_empty())
        .ok_or_else(|| bad_line(path, total, "no column header after 'Scan Data'"))?;
    let cols: Vec<&str> = header.split(',').collect();
    let unit = |i: usize, what: &str| {
        cols.get(i).and_then(|c| column_unit(c)).ok_or_else(|| {
            bad_line(
                path,
                hno,
                format!(
                    "the {what} column's header '{}' names no length unit",
                    cols.get(i).unwrap_or(&"")
                ),
            )
        })
    };
    let ((sx, _), (sz, z_unit)) = (unit(0, "position")?, unit(1, "height")?);
    let (mut x, mut z, mut rows) = (Vec::new(), Vec::new(), Vec::new());
    let mut fields = None;
    for (no, line) in lines {
        if line.is_empty() {
            continue;
        }
        let count = line.split(',').count();
        let first = *fields.get_or_insert(count);
        if count != first {
            return Err(bad_line(
                path,
                no,
                format!("{count} fields, the lines above have {first} (truncated file?)"),
            ));
        }
        rows.push(no);
        let mut f = line.split(',');
        let mut num = |what: &str| -> Result<f64, Error> {
            let t = f.next().unwrap_or("").trim();
            t.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad_line(path, no, format!("{what} '{t}' is not a number")))
        };
        x.push(num("x")?);
        z.push(num("z")?);
    }
    let n = x.len();
    let dx = uniform_step(&x).map_err(|i| {
        bad_line(
            path,
            rows.get(i).copied().unwrap_or(total),
            format!(
                "{n} points: x must increase in uniform steps (at least 2 points); this point \
                 is off the grid of step (x_last − x_first)/(n − 1)"
            ),
        )
    })?;
    Ok(super::profile_reading(
        "dektak",
        cols[1].trim().to_string(),
        dx * sx,
        z.into_iter().map(|v| v * sz).collect(),
        z_unit,
    ))
}
