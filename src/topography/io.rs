//! Reading and writing height data (text tables, SI inside).
//!
//! Line scans ([`read_profile`]): columns `x, z1, z2, …` (x uniformly spaced) or heights only
//! `z1, z2, …` with a given spacing dx; one scan per z column. An optional header names the
//! columns and may carry units in brackets (`x (um), z (nm)`); a first column named `x…`,
//! `pos…` or `dist…` is the position. Without a header the first column is x unless dx is
//! given.
//!
//! Height maps ([`read_height_map`]): a matrix of heights, one row of the map per line (x along
//! the line, y down the file), with the pixel size given in [`MapOptions`] or in the metadata
//! comment that [`write_height_map`] writes:
//! `# coatcheck height map: nx = 256, ny = 256, dx = 1e-6 m, dy = 1e-6 m, periodic = true`.
//! Maps are read line by line (never the whole text at once), so a 4096 × 4096 map costs its
//! heights (128 MiB) and little more.
//!
//! Separators, comments, BOM and CRLF are handled as in [`crate::psd::read`]. Every malformed
//! input is an [`Error::Input`] naming the file, the line and what was expected; heights must
//! be finite (missing points are not interpolated). Writers go through a temporary file in the
//! same directory and a rename, so an output is either complete or absent.

use super::{HeightMap, Profile};
use crate::error::Error;
use crate::psd::read::{Sep, content_lines, decode_utf8, header_fields, name_and_unit};
use crate::units::{Dim, parse_quantity, unit_scale};
use std::io::{BufRead, BufReader};
use std::path::Path;

/// How to read line scans. Values are SI (m); units are strings like `um`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ProfileOptions {
    /// Sample spacing, m (required for heights-only files without metadata).
    pub dx: Option<f64>,
    /// Unit of the x column (overrides the header).
    pub x_unit: Option<String>,
    /// Unit of the heights (overrides the header).
    pub z_unit: Option<String>,
    /// Treat the scans as periodic (default: from the metadata comment, else false).
    pub periodic: Option<bool>,
}

/// How to read a height map.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MapOptions {
    /// Pixel size along x (within a line), m; overrides the metadata.
    pub dx: Option<f64>,
    /// Pixel size along y (between lines), m; default dx.
    pub dy: Option<f64>,
    /// Unit of the heights (default: metadata, else m).
    pub z_unit: Option<String>,
    pub periodic: Option<bool>,
}

/// What a height file holds, as far as its first lines tell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HeightKind {
    Lines,
    Map,
}

/// Key–value metadata from a `# coatcheck …: k = v, …` comment.
#[derive(Debug, Clone, Default, PartialEq)]
struct Meta {
    kind: Option<HeightKind>,
    /// Map size, used only to reserve memory up front.
    nx: Option<usize>,
    ny: Option<usize>,
    dx: Option<f64>,
    dy: Option<f64>,
    periodic: Option<bool>,
    z_unit: Option<String>,
}

fn parse_meta(line: &str, path: &Path, ln: usize) -> Result<Option<Meta>, Error> {
    let t = line.trim_start_matches(['#', '%', '/', ' ']).trim();
    let Some(rest) = t.strip_prefix("coatcheck ") else {
        return Ok(None);
    };
    let Some((what, kv)) = rest.split_once(':') else {
        return Ok(None);
    };
    let mut m = Meta {
        kind: match what.trim() {
            "height map" => Some(HeightKind::Map),
            "line scans" => Some(HeightKind::Lines),
            _ => return Ok(None),
        },
        ..Default::default()
    };
    let bad = |msg: String| Error::Input {
        path: path.to_path_buf(),
        line: ln,
        msg,
    };
    for item in kv.split(',') {
        let Some((k, v)) = item.split_once('=') else {
            continue;
        };
        let (k, v) = (k.trim(), v.trim());
        let length = |v: &str| {
            parse_quantity(v, Dim::Length(1)).map_err(|e| {
                bad(format!(
                    "metadata {k}: {e}; expected a length such as 1e-6 m"
                ))
            })
        };
        match k {
            "dx" => m.dx = Some(length(v)?),
            "dy" => m.dy = Some(length(v)?),
            "periodic" => {
                m.periodic = Some(v.parse().map_err(|_| {
                    bad(format!("metadata periodic = '{v}'; expected true or false"))
                })?)
            }
            "z unit" => m.z_unit = Some(v.to_string()),
            "nx" => m.nx = v.parse().ok(),
            "ny" => m.ny = v.parse().ok(),
            _ => {}
        }
    }
    Ok(Some(m))
}

fn io_err(path: &Path, source: std::io::Error) -> Error {
    Error::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Look at a file's metadata and first content line to tell line scans from a map: the
/// metadata decides; else a header line means line scans; else unknown (`None`).
pub fn sniff(path: &Path) -> Result<Option<HeightKind>, Error> {
    let f = std::fs::File::open(path).map_err(|e| io_err(path, e))?;
    let mut r = BufReader::new(f);
    let mut buf = Vec::new();
    let mut ln = 0;
    loop {
        buf.clear();
        if r.read_until(b'\n', &mut buf).map_err(|e| io_err(path, e))? == 0 {
            return Ok(None);
        }
        ln += 1;
        let text = String::from_utf8_lossy(&buf);
        let line = text.trim_start_matches('\u{feff}').trim();
        if line.is_empty() {
            continue;
        }
        if line.starts_with('#') || line.starts_with('%') || line.starts_with("//") {
            if let Some(m) = parse_meta(line, path, ln)? {
                return Ok(m.kind);
            }
            continue;
        }
        let sep = Sep::detect(line);
        let has_header = sep.split(line).iter().any(|f| sep.number(f).is_none());
        return Ok(has_header.then_some(HeightKind::Lines));
    }
}

/// Read line scans (see the module docs).
pub fn read_profile(path: &Path, opts: &ProfileOptions) -> Result<Profile, Error> {
    let bytes = std::fs::read(path).map_err(|e| io_err(path, e))?;
    let text = decode_utf8(&bytes, path)?;
    parse_profile(text, path, opts)
}

/// Parse line-scan text; `path` only names the file in messages.
pub fn parse_profile(text: &str, path: &Path, opts: &ProfileOptions) -> Result<Profile, Error> {
    let err = |line: usize, msg: String| Error::Input {
        path: path.to_path_buf(),
        line,
        msg,
    };
    let mut meta = Meta::default();
    for (ln, l) in text.split('\n').enumerate() {
        if let Some(m) = parse_meta(l.trim_end_matches('\r'), path, ln + 1)? {
            meta = m;
            break;
        }
    }
    let mut lines = content_lines(text).peekable();
    let Some(&(first_line, first)) = lines.peek() else {
        return Err(err(1, "no data: expected rows of x and z, or of z".into()));
    };
    let sep = Sep::detect(first);
    let header = if sep.split(first).iter().any(|f| sep.number(f).is_none()) {
        lines.next();
        Some(
            header_fields(sep, first)
                .iter()
                .map(|f| name_and_unit(f))
                .collect::<Vec<_>>(),
        )
    } else {
        None
    };
    let dx_given = opts.dx.or(meta.dx);
    let has_x = match &header {
        Some(h) => {
            let n = h[0].0.to_lowercase();
            n.starts_with('x') || n.starts_with("pos") || n.starts_with("dist")
        }
        None => dx_given.is_none(),
    };
    let hline = if header.is_some() { first_line } else { 0 };
    let unit = |flag: &Option<String>, col: usize, what: &str| -> Result<f64, Error> {
        let u = flag
            .clone()
            .or_else(|| header.as_ref().and_then(|h| h.get(col)?.1.clone()))
            .or_else(|| meta.z_unit.clone().filter(|_| what == "z"));
        match u {
            None => Ok(1.0),
            Some(u) => unit_scale(&u, Dim::Length(1)).map_err(|e| {
                err(
                    hline.max(1),
                    format!("unit of {what}: {e}; expected a length unit such as m, um or nm"),
                )
            }),
        }
    };
    let x_scale = if has_x {
        unit(&opts.x_unit, 0, "x")?
    } else {
        1.0
    };
    let z0 = usize::from(has_x);
    let mut cols: Option<usize> = header.as_ref().map(Vec::len);
    let mut x: Vec<(f64, usize)> = Vec::new();
    let mut scans: Vec<Vec<f64>> = Vec::new();
    let mut z_scales: Vec<f64> = Vec::new();
    for (ln, line) in lines {
        let fields = sep.split(line);
        let ncol = *cols.get_or_insert(fields.len());
        if fields.len() != ncol {
            return Err(err(
                ln,
                format!("expected {ncol} columns (as above), found {}", fields.len()),
            ));
        }
        if ncol <= z0 {
            return Err(err(
                ln,
                "expected at least one column of heights (a single column of heights needs dx)"
                    .into(),
            ));
        }
        if scans.is_empty() {
            scans = vec![Vec::new(); ncol - z0];
            z_scales = (z0..ncol)
                .map(|c| unit(&opts.z_unit, c, "z"))
                .collect::<Result<_, _>>()?;
        }
        for (c, f) in fields.iter().enumerate() {
            let v = sep.number(f).ok_or_else(|| {
                err(
                    ln,
                    format!("expected a number in column {}, found '{f}'", c + 1),
                )
            })?;
            if !v.is_finite() {
                return Err(err(
                    ln,
                    format!(
                        "'{f}' in column {}; expected a finite value (missing points are not interpolated)",
                        c + 1
                    ),
                ));
            }
            if c < z0 {
                x.push((v * x_scale, ln));
            } else {
                scans[c - z0].push(v * z_scales[c - z0]);
            }
        }
    }
    let n = scans.first().map_or(0, Vec::len);
    if n < 8 {
        return Err(err(
            first_line,
            format!("found {n} rows of heights; expected at least 8"),
        ));
    }
    let dx = if has_x {
        // Each step must match the median step within 1 % (room for rounded x values); dx is
        // then the mean step over the whole scan.
        let mut steps: Vec<f64> = x.windows(2).map(|w| w[1].0 - w[0].0).collect();
        steps.sort_by(f64::total_cmp);
        let median = steps[steps.len() / 2];
        if median.is_nan() || median <= 0.0 {
            return Err(err(x[1].1, "x must increase down the file".into()));
        }
        for w in x.windows(2) {
            let step = w[1].0 - w[0].0;
            if (step - median).abs() > 1e-2 * median {
                return Err(err(
                    w[1].1,
                    format!(
                        "x steps by {step:e} m here but by {median:e} m elsewhere; expected \
                         equally spaced x"
                    ),
                ));
            }
        }
        let dx = (x[n - 1].0 - x[0].0) / (n - 1) as f64;
        if let Some(d) = opts.dx
            && (d / dx - 1.0).abs() > 1e-3
        {
            return Err(err(
                hline.max(first_line),
                format!("dx = {d:e} m was given but the x column has spacing {dx:e} m"),
            ));
        }
        dx
    } else {
        match dx_given {
            Some(d) if d.is_finite() && d > 0.0 => d,
            _ => {
                return Err(err(
                    first_line,
                    "heights without an x column need the spacing dx (e.g. --dx 0.5um)".into(),
                ));
            }
        }
    };
    Ok(Profile {
        dx,
        scans,
        periodic: opts.periodic.or(meta.periodic).unwrap_or(false),
    })
}

/// Read a height map (see the module docs), line by line.
pub fn read_height_map(path: &Path, opts: &MapOptions) -> Result<HeightMap, Error> {
    let f = std::fs::File::open(path).map_err(|e| io_err(path, e))?;
    let mut r = BufReader::with_capacity(1 << 20, f);
    let err = |line: usize, msg: String| Error::Input {
        path: path.to_path_buf(),
        line,
        msg,
    };
    let mut meta = Meta::default();
    let mut buf = Vec::new();
    let mut z: Vec<f64> = Vec::new();
    let mut nx = 0usize;
    let mut ny = 0usize;
    let mut sep: Option<Sep> = None;
    let mut first_row_line = 0;
    let mut z_scale: Option<f64> = None;
    let mut ln = 0usize;
    loop {
        buf.clear();
        if r.read_until(b'\n', &mut buf).map_err(|e| io_err(path, e))? == 0 {
            break;
        }
        ln += 1;
        let text =
            std::str::from_utf8(&buf).map_err(|_| err(ln, "the file is not UTF-8 text".into()))?;
        let text = if ln == 1 {
            text.trim_start_matches('\u{feff}')
        } else {
            text
        };
        let line = text.trim_end_matches(['\n', '\r']);
        let t = line.trim();
        if t.is_empty() {
            continue;
        }
        if t.starts_with('#') || t.starts_with('%') || t.starts_with("//") {
            if let Some(m) = parse_meta(t, path, ln)? {
                meta = m;
                if let (Some(a), Some(b)) = (meta.nx, meta.ny) {
                    // Reserve exactly (capped at 2^28 heights): no doubling reallocations.
                    z.reserve_exact(a.saturating_mul(b).min(1 << 28));
                }
            }
            continue;
        }
        let s = *sep.get_or_insert_with(|| Sep::detect(line));
        let scale = match z_scale {
            Some(s) => s,
            None => {
                let u = opts.z_unit.clone().or(meta.z_unit.clone());
                let s = match u {
                    None => 1.0,
                    Some(u) => unit_scale(&u, Dim::Length(1)).map_err(|e| {
                        err(
                            ln,
                            format!("unit of the heights: {e}; expected a length unit"),
                        )
                    })?,
                };
                z_scale = Some(s);
                s
            }
        };
        let before = z.len();
        for (c, f) in s.split(line).iter().enumerate() {
            let v = s.number(f).ok_or_else(|| {
                err(
                    ln,
                    format!(
                        "expected a height (number) in column {}, found '{f}'",
                        c + 1
                    ),
                )
            })?;
            if !v.is_finite() {
                return Err(err(
                    ln,
                    format!(
                        "'{f}' in column {}; expected a finite height (missing points are not interpolated)",
                        c + 1
                    ),
                ));
            }
            z.push(v * scale);
        }
        let count = z.len() - before;
        if ny == 0 {
            nx = count;
            first_row_line = ln;
        } else if count != nx {
            return Err(err(
                ln,
                format!("expected {nx} heights (as on line {first_row_line}), found {count}"),
            ));
        }
        ny += 1;
    }
    if nx < 4 || ny < 4 {
        return Err(err(
            ln.max(1),
            format!("a {nx} x {ny} map; expected at least 4 x 4 heights"),
        ));
    }
    let dx = opts.dx.or(meta.dx).ok_or_else(|| {
        err(
            first_row_line,
            "a height map needs its pixel size (e.g. --pixel-size 1um)".into(),
        )
    })?;
    // dy: as given; else dx when dx was given; else the metadata's; else dx.
    let dy = match (opts.dy, opts.dx) {
        (Some(d), _) => d,
        (None, Some(_)) => dx,
        (None, None) => meta.dy.unwrap_or(dx),
    };
    if !(dx.is_finite() && dx > 0.0 && dy.is_finite() && dy > 0.0) {
        return Err(Error::invalid(
            "pixel size",
            format!("dx = {dx}, dy = {dy}"),
            "finite sizes > 0",
        ));
    }
    z.shrink_to_fit();
    Ok(HeightMap {
        nx,
        ny,
        dx,
        dy,
        z,
        periodic: opts.periodic.or(meta.periodic).unwrap_or(false),
    })
}

/// Write a height map (heights in m) with its metadata comment and optional extra comments.
pub fn write_height_map(path: &Path, map: &HeightMap, comments: &[String]) -> Result<(), Error> {
    crate::report::write_with(path, |w| {
        writeln!(
            w,
            "# coatcheck height map: nx = {}, ny = {}, dx = {:e} m, dy = {:e} m, periodic = {}, z unit = m",
            map.nx, map.ny, map.dx, map.dy, map.periodic
        )?;
        for c in comments {
            writeln!(w, "# {c}")?;
        }
        for iy in 0..map.ny {
            let row = map.row(iy);
            for (ix, v) in row.iter().enumerate() {
                if ix > 0 {
                    w.write_all(b",")?;
                }
                write!(w, "{v:e}")?;
            }
            w.write_all(b"\n")?;
        }
        Ok(())
    })
}

/// Write line scans as `x (m), z1 (m), …` with the metadata comment.
pub fn write_profile(path: &Path, p: &Profile, comments: &[String]) -> Result<(), Error> {
    crate::report::write_with(path, |w| {
        writeln!(
            w,
            "# coatcheck line scans: dx = {:e} m, periodic = {}, z unit = m",
            p.dx, p.periodic
        )?;
        for c in comments {
            writeln!(w, "# {c}")?;
        }
        write!(w, "x (m)")?;
        for k in 0..p.scans.len() {
            write!(w, ",z{} (m)", k + 1)?;
        }
        writeln!(w)?;
        let n = p.scans.first().map_or(0, Vec::len);
        for i in 0..n {
            write!(w, "{:e}", i as f64 * p.dx)?;
            for s in &p.scans {
                write!(w, ",{:e}", s[i])?;
            }
            writeln!(w)?;
        }
        Ok(())
    })
}
