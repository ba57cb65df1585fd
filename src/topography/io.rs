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
//! When the metadata gives nx and ny, the file must hold exactly that grid (a map cut short is
//! an error, not a smaller periodic map). Maps are read line by line, never the whole text at
//! once.
//!
//! Text conventions (comments, line ends, separators, BOM) are those of [`crate::textio`].
//! Every malformed input is an [`Error::Input`] naming the file, the line and what was
//! expected; heights must be finite (missing points are not interpolated).
//!
//! Limits, from the memory a desktop run can spare (about 1 GiB) and a run of seconds: at most
//! [`MAX_HEIGHTS`] = 2²⁶ heights in a map or in all scans of a file (512 MiB of heights; a map's
//! spectrum needs as much again), a line-scan file of at most [`MAX_PROFILE_BYTES`] (read
//! whole) and a map file of at most [`MAX_MAP_BYTES`] (streamed).
//!
//! Writers go through a temporary file in the same directory and a rename, so an output is
//! either complete or absent.

use super::{HeightMap, Profile};
use crate::error::Error;
use crate::textio::{self, Header, LineReader, Sep};
use crate::units::{Dim, parse_quantity, unit_scale};
use std::io::{BufReader, Read, Write};
use std::path::Path;

/// The most heights in a map or in all line scans of one file (2²⁶, 512 MiB as f64).
pub const MAX_HEIGHTS: usize = 1 << 26;
/// The largest line-scan file (read whole): 1 GiB.
pub const MAX_PROFILE_BYTES: u64 = 1 << 30;
/// The largest height-map file (streamed): 4 GiB, 2²⁶ heights of up to 64 characters.
pub const MAX_MAP_BYTES: u64 = 4 << 30;

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
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum HeightKind {
    Lines,
    Map,
}

/// Key–value metadata from a `# coatcheck …: k = v, …` comment.
#[derive(Debug, Clone, Default, PartialEq)]
struct Meta {
    /// The comment's line (0: none).
    line: usize,
    kind: Option<HeightKind>,
    /// Map size: the grid the file must hold.
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
        line: ln,
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
        let count = |v: &str| {
            v.parse::<usize>()
                .ok()
                .filter(|&n| n > 0)
                .ok_or_else(|| bad(format!("metadata {k} = '{v}'; expected a whole number > 0")))
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
            "nx" => m.nx = Some(count(v)?),
            "ny" => m.ny = Some(count(v)?),
            _ => {}
        }
    }
    if let (Some(a), Some(b)) = (m.nx, m.ny)
        && a.saturating_mul(b) > MAX_HEIGHTS
    {
        return Err(bad(format!(
            "metadata grid {a} x {b}; expected at most {MAX_HEIGHTS} heights"
        )));
    }
    Ok(Some(m))
}

fn io_err(path: &Path, source: std::io::Error) -> Error {
    Error::Io {
        path: path.to_path_buf(),
        source,
    }
}

fn open_lines(path: &Path, limit: u64) -> Result<LineReader<'_, impl std::io::BufRead>, Error> {
    let f = std::fs::File::open(path).map_err(|e| io_err(path, e))?;
    Ok(LineReader::new(
        BufReader::with_capacity(1 << 20, f.take(limit)),
        path,
    ))
}

/// Look at a file's metadata and first content line to tell line scans from a map: the
/// metadata decides; else a header line means line scans; else unknown (`None`).
pub fn sniff(path: &Path) -> Result<Option<HeightKind>, Error> {
    let mut r = open_lines(path, MAX_MAP_BYTES)?;
    while let Some((ln, text)) = r.next_line()? {
        let line = text.trim();
        if line.is_empty() {
            continue;
        }
        if textio::is_comment(line) {
            if let Some(m) = parse_meta(line, path, ln)? {
                return Ok(m.kind);
            }
            continue;
        }
        let has_header = Sep::detect(line).is_header(line);
        return Ok(has_header.then_some(HeightKind::Lines));
    }
    Ok(None)
}

/// Read line scans (see the module docs).
pub fn read_profile(path: &Path, opts: &ProfileOptions) -> Result<Profile, Error> {
    let bytes = textio::read_capped(path, MAX_PROFILE_BYTES, "line scans")?;
    let text = textio::decode_utf8(&bytes, path)?;
    parse_profile(text, path, opts)
}

fn input_err(path: &Path, line: usize, msg: String) -> Error {
    Error::Input {
        path: path.to_path_buf(),
        line,
        msg,
    }
}

/// The columns of a line-scan file: its header, whether column 1 is x, and SI factors.
struct Columns {
    sep: Sep,
    header: Option<Header>,
    first_line: usize,
    has_x: bool,
    x_scale: f64,
}

impl Columns {
    /// The SI factor of column `col` (x or z): the flag's unit, else the header's, else (for
    /// z) the metadata's.
    fn scale(
        &self,
        path: &Path,
        flag: &Option<String>,
        meta_unit: Option<&str>,
        col: usize,
        what: &str,
    ) -> Result<f64, Error> {
        let u = flag
            .as_deref()
            .or_else(|| self.header.as_ref()?.unit(col))
            .or(meta_unit);
        match u {
            None => Ok(1.0),
            Some(u) => unit_scale(u, Dim::Length(1)).map_err(|e| {
                let line = self.header.as_ref().map_or(1, |h| h.line);
                input_err(
                    path,
                    line,
                    format!("unit of {what}: {e}; expected a length unit such as m, um or nm"),
                )
            }),
        }
    }
}

/// The x positions (SI, with their lines) and the scans (SI) of a line-scan file's rows.
type ScanData = (Vec<(f64, usize)>, Vec<Vec<f64>>);

fn read_scan_rows<'t>(
    path: &Path,
    cols: &Columns,
    lines: impl Iterator<Item = (usize, &'t str)>,
    opts: &ProfileOptions,
    meta: &Meta,
) -> Result<ScanData, Error> {
    let err = |line: usize, msg: String| input_err(path, line, msg);
    let sep = cols.sep;
    let z0 = usize::from(cols.has_x);
    let mut ncol: Option<usize> = cols.header.as_ref().map(|h| h.names.len());
    let mut x: Vec<(f64, usize)> = Vec::new();
    let mut scans: Vec<Vec<f64>> = Vec::new();
    let mut z_scales: Vec<f64> = Vec::new();
    let mut heights = 0usize;
    for (ln, line) in lines {
        let fields = sep.split(line);
        let ncol = *ncol.get_or_insert(fields.len());
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
                .map(|c| cols.scale(path, &opts.z_unit, meta.z_unit.as_deref(), c, "z"))
                .collect::<Result<_, _>>()?;
        }
        heights += ncol - z0;
        if heights > MAX_HEIGHTS {
            return Err(err(
                ln,
                format!("more than {MAX_HEIGHTS} heights, the limit for line scans"),
            ));
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
                x.push((v * cols.x_scale, ln));
            } else {
                scans[c - z0].push(v * z_scales[c - z0]);
            }
        }
    }
    Ok((x, scans))
}

/// The sample spacing from the x column: each step must match the median step within 1 %
/// (room for rounded x values); dx is then the mean step over the whole scan.
fn spacing_of_x(
    path: &Path,
    x: &[(f64, usize)],
    given: Option<f64>,
    line: usize,
) -> Result<f64, Error> {
    let n = x.len();
    let mut steps: Vec<f64> = x.windows(2).map(|w| w[1].0 - w[0].0).collect();
    steps.sort_by(f64::total_cmp);
    let median = steps[steps.len() / 2];
    if median.is_nan() || median <= 0.0 {
        return Err(input_err(
            path,
            x[1].1,
            "x must increase down the file".into(),
        ));
    }
    for w in x.windows(2) {
        let step = w[1].0 - w[0].0;
        if (step - median).abs() > 1e-2 * median {
            return Err(input_err(
                path,
                w[1].1,
                format!(
                    "x steps by {step:e} m here but by {median:e} m elsewhere; expected \
                     equally spaced x"
                ),
            ));
        }
    }
    let dx = (x[n - 1].0 - x[0].0) / (n - 1) as f64;
    if let Some(d) = given
        && (d / dx - 1.0).abs() > 1e-3
    {
        return Err(input_err(
            path,
            line,
            format!("dx = {d:e} m was given but the x column has spacing {dx:e} m"),
        ));
    }
    Ok(dx)
}

/// Parse line-scan text; `path` only names the file in messages.
pub fn parse_profile(text: &str, path: &Path, opts: &ProfileOptions) -> Result<Profile, Error> {
    let mut meta = Meta::default();
    for (ln, l) in textio::lines(text) {
        if let Some(m) = parse_meta(l, path, ln)? {
            meta = m;
            break;
        }
    }
    let mut lines = textio::content_lines(text).peekable();
    let Some(&(first_line, first)) = lines.peek() else {
        return Err(input_err(
            path,
            1,
            "no data: expected rows of x and z, or of z".into(),
        ));
    };
    let sep = Sep::detect(first);
    let header = sep.is_header(first).then(|| {
        lines.next();
        Header::parse(sep, first, first_line)
    });
    let dx_given = opts.dx.or(meta.dx);
    let has_x = match &header {
        Some(h) => {
            let n = h.names[0].to_lowercase();
            n.starts_with('x') || n.starts_with("pos") || n.starts_with("dist")
        }
        None => dx_given.is_none(),
    };
    let mut cols = Columns {
        sep,
        header,
        first_line,
        has_x,
        x_scale: 1.0,
    };
    if has_x {
        cols.x_scale = cols.scale(path, &opts.x_unit, None, 0, "x")?;
    }
    let (x, scans) = read_scan_rows(path, &cols, lines, opts, &meta)?;
    let n = scans.first().map_or(0, Vec::len);
    if n < 8 {
        return Err(input_err(
            path,
            cols.first_line,
            format!("found {n} rows of heights; expected at least 8"),
        ));
    }
    let dx = if has_x {
        let hline = cols.header.as_ref().map_or(first_line, |h| h.line);
        spacing_of_x(path, &x, opts.dx, hline)?
    } else {
        match dx_given {
            Some(d) if d.is_finite() && d > 0.0 => d,
            _ => {
                return Err(input_err(
                    path,
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

/// Heights read from a map file so far.
struct MapRows {
    z: Vec<f64>,
    nx: usize,
    ny: usize,
    first_row_line: usize,
}

impl MapRows {
    /// Add one line of heights (scaled by `scale`), checking its length against the first
    /// row's and the metadata's grid.
    fn push_row(
        &mut self,
        path: &Path,
        sep: Sep,
        line: &str,
        ln: usize,
        scale: f64,
        meta: &Meta,
    ) -> Result<(), Error> {
        let err = |msg: String| input_err(path, ln, msg);
        if meta.ny.is_some_and(|ny| self.ny == ny) {
            return Err(err(format!(
                "more rows than the metadata's ny = {} (line {})",
                self.ny, meta.line
            )));
        }
        let before = self.z.len();
        for (c, f) in sep.split(line).iter().enumerate() {
            let v = sep.number(f).ok_or_else(|| {
                err(format!(
                    "expected a height (number) in column {}, found '{f}'",
                    c + 1
                ))
            })?;
            if !v.is_finite() {
                return Err(err(format!(
                    "'{f}' in column {}; expected a finite height (missing points are not interpolated)",
                    c + 1
                )));
            }
            if self.z.len() == MAX_HEIGHTS {
                return Err(err(format!(
                    "more than {MAX_HEIGHTS} heights, the limit for a height map"
                )));
            }
            self.z.push(v * scale);
        }
        let count = self.z.len() - before;
        if self.ny == 0 {
            self.nx = count;
            self.first_row_line = ln;
            if let Some(nx) = meta.nx.filter(|&nx| nx != count) {
                return Err(err(format!(
                    "{count} heights in the first row, but the metadata (line {}) says nx = {nx}",
                    meta.line
                )));
            }
        } else if count != self.nx {
            return Err(err(format!(
                "expected {} heights (as on line {}), found {count}",
                self.nx, self.first_row_line
            )));
        }
        self.ny += 1;
        Ok(())
    }
}

/// Read a height map (see the module docs), line by line.
pub fn read_height_map(path: &Path, opts: &MapOptions) -> Result<HeightMap, Error> {
    let mut r = open_lines(path, MAX_MAP_BYTES)?;
    let mut meta = Meta::default();
    let mut rows = MapRows {
        z: Vec::new(),
        nx: 0,
        ny: 0,
        first_row_line: 0,
    };
    let mut sep: Option<Sep> = None;
    let mut z_scale: Option<f64> = None;
    while let Some((ln, line)) = r.next_line()? {
        let t = line.trim();
        if t.is_empty() {
            continue;
        }
        if textio::is_comment(t) {
            if let Some(m) = parse_meta(t, path, ln)? {
                meta = m;
                if let (Some(a), Some(b)) = (meta.nx, meta.ny) {
                    // Reserve exactly (the product is within MAX_HEIGHTS): no doubling.
                    rows.z.reserve_exact(a * b);
                }
            }
            continue;
        }
        let s = *sep.get_or_insert_with(|| Sep::detect(line));
        let scale = match z_scale {
            Some(s) => s,
            None => {
                let u = opts.z_unit.as_deref().or(meta.z_unit.as_deref());
                let s = match u {
                    None => 1.0,
                    Some(u) => unit_scale(u, Dim::Length(1)).map_err(|e| {
                        input_err(
                            path,
                            ln,
                            format!("unit of the heights: {e}; expected a length unit"),
                        )
                    })?,
                };
                *z_scale.insert(s)
            }
        };
        rows.push_row(path, s, line, ln, scale, &meta)?;
    }
    finish_map(path, rows, &meta, opts, r.line)
}

/// Check the grid read against the metadata's and settle the pixel size.
fn finish_map(
    path: &Path,
    rows: MapRows,
    meta: &Meta,
    opts: &MapOptions,
    last_line: usize,
) -> Result<HeightMap, Error> {
    let MapRows {
        mut z,
        nx,
        ny,
        first_row_line,
    } = rows;
    if let Some(want) = meta.ny.filter(|&want| want != ny) {
        return Err(input_err(
            path,
            last_line.max(1),
            format!(
                "the file ends after {ny} rows of heights, but the metadata (line {}) says \
                 ny = {want}: the map is incomplete",
                meta.line
            ),
        ));
    }
    if nx < 4 || ny < 4 {
        return Err(input_err(
            path,
            last_line.max(1),
            format!("a {nx} x {ny} map; expected at least 4 x 4 heights"),
        ));
    }
    let dx = opts.dx.or(meta.dx).ok_or_else(|| {
        input_err(
            path,
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

/// A height map (heights in m) as text, with its metadata comment and optional extra comments
/// (files are written through `report::write_with`).
pub fn write_height_map(
    w: &mut dyn Write,
    map: &HeightMap,
    comments: &[String],
) -> std::io::Result<()> {
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
}

/// Line scans as text, `x (m), z1 (m), …`, with the metadata comment.
pub fn write_profile(w: &mut dyn Write, p: &Profile, comments: &[String]) -> std::io::Result<()> {
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
}
