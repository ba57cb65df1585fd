//! Reading a roughness spectrum from a text file as users have them.
//!
//! The file is a table of numbers with an optional header line, read as [`crate::textio`]
//! describes (comments, line ends, separators, decimal commas). Header fields name the column
//! and may carry its unit in brackets: `q (1/m)`, `q [1/um]`, `C (m^4)`, `C [um^4]`,
//! `PSD (nm^3)`. Units in [`ReadOptions`] (command-line flags) override the header's, with a
//! warning when they differ.
//!
//! Column choice:
//! - by name or 1-based index ([`Column`]); by default the first header field named like a wavenumber (`q…`, `k…`, `wavenumber`, `wavevector`) and the first named
//!   like a spectrum (`C…`, `PSD…`, `power…`), else columns 1 and 2;
//! - a column that looks like a spatial frequency or a wavelength is refused: q here is the
//!   angular wavenumber 2π/λ.
//!
//! The C column is a 2D PSD in m^4 (the theory's C(q), notes.md) unless its unit is a length
//! cubed or [`ReadOptions::kind`] says [`PsdKind::OneD`]: then it is the one-sided 1D PSD of a
//! line scan in m^3 (h_rms² = ∫_0^∞ C1D dq) and is converted to the isotropic 2D PSD with the
//! exact inverse Abel transform ([`crate::psd::abel`]).
//!
//! Data are checked, not repaired: a non-number, a non-positive or non-finite q or C, a
//! duplicate q, too few columns or fewer than two points is an [`Error::Input`] naming the file,
//! the line and what was expected. Unsorted q is sorted, with a warning.
//!
//! Limits: a file of at most [`MAX_FILE_BYTES`] (64 MiB, about a million rows) with at most
//! [`MAX_POINTS`] points, and a 1D PSD of at most [`MAX_POINTS_1D`] points: its conversion
//! costs O(n²) quadratures (each point integrates over all points above it).

use crate::error::Error;
use crate::psd::Tabulated;
use crate::psd::abel::{self, Conversion};
use crate::psd::ce;
use crate::psd::convention::Convention;
use crate::textio::{self, Header, Sep};
use crate::units::{Dim, unit_scale};
use std::path::Path;
use std::str::FromStr;

/// A column chosen by 1-based index or by header name (case-insensitive, with or without
/// its bracketed unit).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Column {
    /// 1-based column number.
    Index(usize),
    Name(String),
}

impl FromStr for Column {
    type Err = Error;
    /// `"2"` is column 2 (1-based); anything else is a header name.
    fn from_str(s: &str) -> Result<Self, Error> {
        let t = s.trim();
        if t.is_empty() {
            return Err(Error::invalid(
                "column",
                "''",
                "a 1-based column number or a header name",
            ));
        }
        match t.parse::<usize>() {
            Ok(0) => Err(Error::invalid(
                "column",
                0,
                "a 1-based column number (1 is the first column)",
            )),
            Ok(i) => Ok(Column::Index(i)),
            Err(_) => Ok(Column::Name(t.to_string())),
        }
    }
}

/// Whether the C column is a 2D PSD (m^4) or a one-sided 1D PSD from line scans (m^3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PsdKind {
    TwoD,
    OneD,
}

/// How to read a spectrum file. `Default` reads a 2D PSD in SI units (or the header's units)
/// from the auto-detected columns.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReadOptions {
    pub q_col: Option<Column>,
    pub c_col: Option<Column>,
    /// Unit of q (e.g. `1/um`); overrides the header's.
    pub q_unit: Option<String>,
    /// Unit of C (e.g. `um^4`, or `nm^3` for a 1D PSD); overrides the header's.
    pub c_unit: Option<String>,
    /// 2D or 1D PSD; `None`: from the C unit's dimension, else 2D.
    pub kind: Option<PsdKind>,
    /// How a 1D PSD is converted (the exact inverse Abel transform by default).
    pub conversion: Conversion,
    /// The file's normalisation; `None`: this tool's, or SurfaceTopography's for a
    /// contact.engineering download.
    pub convention: Option<Convention>,
    /// contact.engineering downloads: the series to read (`NAME` or `SUBJECT: NAME`).
    pub series: Option<String>,
}

/// The largest spectrum file read: 64 MiB.
pub const MAX_FILE_BYTES: u64 = 64 << 20;
/// The most points a spectrum file may hold.
pub const MAX_POINTS: usize = 1_000_000;
/// The most points of a 1D PSD (converted to 2D in O(n²)).
pub const MAX_POINTS_1D: usize = 10_000;

/// Read a spectrum file into a validated 2D [`Tabulated`] spectrum (SI: q in 1/m, C in m^4),
/// with warnings (sorting, unit overrides, 1D→2D conversion) for the caller to print.
pub fn read_spectrum(path: &Path, opts: &ReadOptions) -> Result<(Tabulated, Vec<String>), Error> {
    let bytes = textio::read_capped(path, MAX_FILE_BYTES, "a spectrum")?;
    let text = textio::decode_utf8(&bytes, path)?;
    parse_spectrum(text, path, opts)
}

fn looks_like_q(name: &str) -> bool {
    let n = name.to_lowercase();
    n.starts_with('q')
        || n == "k"
        || n.starts_with("k_")
        || n.contains("wavenumber")
        || n.contains("wave number")
        || n.contains("wavevector")
        || n.contains("wave vector")
}

fn looks_like_c(name: &str) -> bool {
    let n = name.to_lowercase();
    n.starts_with('c') || n.contains("psd") || n.contains("power")
}

fn looks_like_frequency_or_wavelength(name: &str) -> bool {
    let n = name.to_lowercase();
    n.contains("freq") || n.contains("wavelength") || n.contains("lambda") || n == "f"
}

/// What the parse knows about the file: its name, first content line and header.
struct Ctx<'a> {
    path: &'a Path,
    first_line: usize,
    header: Option<Header>,
}

impl Ctx<'_> {
    fn err(&self, line: usize, msg: String) -> Error {
        Error::Input {
            path: self.path.to_path_buf(),
            line,
            msg,
        }
    }

    /// The header's line, else the first content line.
    fn hline(&self) -> usize {
        self.header.as_ref().map_or(self.first_line, |h| h.line)
    }

    /// The 0-based column of q or C, and whether it was chosen (by the options or a name that
    /// looks right) rather than defaulted.
    fn column(
        &self,
        col: &Option<Column>,
        what: &str,
        looks: fn(&str) -> bool,
        default: usize,
    ) -> Result<(usize, bool), Error> {
        match (col, &self.header) {
            (Some(Column::Index(i)), Some(h)) if *i > h.names.len() => Err(self.err(
                h.line,
                format!(
                    "column {i} for {what} requested, but the header has only {} columns",
                    h.names.len()
                ),
            )),
            (Some(Column::Index(i)), _) => Ok((i - 1, true)),
            (Some(Column::Name(name)), Some(h)) => {
                let want = name.to_lowercase();
                h.names
                    .iter()
                    .zip(&h.units)
                    .position(|(n, u)| {
                        n.to_lowercase() == want
                            || u.as_ref()
                                .is_some_and(|u| format!("{n} ({u})").to_lowercase() == want)
                    })
                    .map(|i| (i, true))
                    .ok_or_else(|| {
                        self.err(
                            h.line,
                            format!(
                                "no column named '{name}' for {what}; the header has: {}",
                                h.names.join(", ")
                            ),
                        )
                    })
            }
            (Some(Column::Name(name)), None) => Err(self.err(
                self.first_line,
                format!(
                    "column '{name}' for {what} requested by name, but the file has no header line \
                     (use a 1-based column number)"
                ),
            )),
            (None, Some(h)) => Ok(h
                .names
                .iter()
                .position(|n| looks(n))
                .map(|i| (i, true))
                .unwrap_or((default, false))),
            (None, None) => Ok((default, true)),
        }
    }

    /// The 0-based columns (q, C), with warnings for columns not named like q or C.
    fn columns(
        &self,
        opts: &ReadOptions,
        warnings: &mut Vec<String>,
    ) -> Result<(usize, usize), Error> {
        let (qi, q_named) = self.column(&opts.q_col, "q", looks_like_q, 0)?;
        let (ci, c_named) = self.column(&opts.c_col, "C", looks_like_c, 1)?;
        if qi == ci {
            return Err(self.err(
                self.hline(),
                format!(
                    "q and C are both read from column {}; choose different columns",
                    qi + 1
                ),
            ));
        }
        let Some(h) = &self.header else {
            return Ok((qi, ci));
        };
        for (i, named, what) in [(qi, q_named, "q"), (ci, c_named, "C")] {
            let Some(name) = h.names.get(i) else {
                return Err(self.err(
                    h.line,
                    format!(
                        "the header has {} column(s), expected at least {} (for {what})",
                        h.names.len(),
                        i + 1
                    ),
                ));
            };
            if !named {
                warnings.push(format!(
                    "{}:{}: no header name looks like {what}; reading {what} from column {} ('{name}')",
                    self.path.display(),
                    h.line,
                    i + 1
                ));
            }
        }
        if opts.q_col.is_none() && looks_like_frequency_or_wavelength(&h.names[qi]) {
            return Err(self.err(
                h.line,
                format!(
                    "column '{}' looks like a spatial frequency or wavelength; expected the \
                     wavenumber q = 2π/λ (convert it, or choose the q column explicitly)",
                    h.names[qi]
                ),
            ));
        }
        Ok((qi, ci))
    }

    /// The unit of column `i`: the flag's, else the header's (a warning when they differ).
    fn unit(
        &self,
        flag: &Option<String>,
        i: usize,
        what: &str,
        warnings: &mut Vec<String>,
    ) -> Option<String> {
        let from_header = self.header.as_ref().and_then(|h| h.unit(i));
        match (flag, from_header) {
            (Some(f), Some(h)) => {
                if f.replace(' ', "") != h.replace(' ', "") {
                    warnings.push(format!(
                        "{}:{}: the header gives {what} in '{h}'; using '{f}' as requested",
                        self.path.display(),
                        self.hline()
                    ));
                }
                Some(f.clone())
            }
            (Some(f), None) => Some(f.clone()),
            (None, h) => h.map(str::to_string),
        }
    }

    /// The SI factors of q and C and whether C is a 2D or a 1D PSD.
    fn scales(
        &self,
        opts: &ReadOptions,
        (qi, ci): (usize, usize),
        warnings: &mut Vec<String>,
    ) -> Result<(f64, f64, PsdKind), Error> {
        let hline = self.hline();
        let q_unit = self.unit(&opts.q_unit, qi, "q", warnings);
        let c_unit = self.unit(&opts.c_unit, ci, "C", warnings);
        let q_scale = match &q_unit {
            None => 1.0,
            Some(u) => unit_scale(u, Dim::Length(-1)).map_err(|e| {
                self.err(
                    hline,
                    format!("unit of q: {e}; expected a wavenumber unit such as 1/m or 1/um"),
                )
            })?,
        };
        let (c_scale, unit_kind) = match &c_unit {
            None => (1.0, None),
            Some(u) => {
                if let Ok(s) = unit_scale(u, Dim::Length(4)) {
                    (s, Some(PsdKind::TwoD))
                } else if let Ok(s) = unit_scale(u, Dim::Length(3)) {
                    (s, Some(PsdKind::OneD))
                } else {
                    return Err(self.err(
                        hline,
                        format!(
                            "unit of C '{u}' is neither a length^4 (2D PSD, e.g. m^4, um^4) nor a \
                             length^3 (1D PSD, e.g. m^3, nm^3)"
                        ),
                    ));
                }
            }
        };
        let kind = match (opts.kind, unit_kind) {
            (Some(k), Some(u)) if k != u => {
                let name = |k: PsdKind| match k {
                    PsdKind::OneD => "1D",
                    PsdKind::TwoD => "2D",
                };
                let unit = if u == PsdKind::OneD { "m^3" } else { "m^4" };
                return Err(self.err(
                    hline,
                    format!(
                        "C is in '{}', a {} ({unit}) unit, but a {} PSD was requested",
                        c_unit.unwrap_or_default(),
                        name(u),
                        name(k)
                    ),
                ));
            }
            (Some(k), _) => k,
            (None, Some(u)) => u,
            (None, None) => PsdKind::TwoD,
        };
        Ok((q_scale, c_scale, kind))
    }
}

/// One data row in SI: q, C and the row's line.
type Row = (f64, f64, usize);

/// Read the data rows: q and C from columns `qi`, `ci`, scaled to SI, checked finite and > 0.
fn read_rows<'t>(
    ctx: &Ctx,
    sep: Sep,
    lines: impl Iterator<Item = (usize, &'t str)>,
    (qi, ci): (usize, usize),
    (q_scale, c_scale): (f64, f64),
) -> Result<Vec<Row>, Error> {
    let need = qi.max(ci) + 1;
    let mut rows: Vec<Row> = Vec::new();
    let mut last_line = ctx.first_line;
    for (ln, line) in lines {
        last_line = ln;
        let Some((q_text, c_text)) = sep.pick(line, qi, ci, need) else {
            return Err(ctx.err(
                ln,
                format!(
                    "expected at least {need} columns (q in column {}, C in column {}), found {}",
                    qi + 1,
                    ci + 1,
                    sep.split(line).len()
                ),
            ));
        };
        let value = |i: usize, field: &str, what: &str| -> Result<f64, Error> {
            let v = sep.number(field).ok_or_else(|| {
                ctx.err(
                    ln,
                    format!(
                        "expected a number for {what} in column {}, found '{field}'",
                        i + 1
                    ),
                )
            })?;
            if !(v.is_finite() && v > 0.0) {
                return Err(ctx.err(
                    ln,
                    format!(
                        "{what} = {field} in column {}; expected a finite value > 0",
                        i + 1
                    ),
                ));
            }
            Ok(v)
        };
        let q = value(qi, q_text, "q")? * q_scale;
        let c = value(ci, c_text, "C")? * c_scale;
        if !(q.is_finite() && q > 0.0 && c.is_finite() && c > 0.0) {
            return Err(ctx.err(
                ln,
                format!(
                    "q = {q_text}, C = {c_text} are q = {q:e} 1/m, C = {c:e} m^4 in SI units, \
                     outside the floating-point range; expected values that are finite and > 0 in SI"
                ),
            ));
        }
        if rows.len() == MAX_POINTS {
            return Err(ctx.err(
                ln,
                format!("more than {MAX_POINTS} points, the limit for a spectrum file"),
            ));
        }
        rows.push((q, c, ln));
    }
    if rows.len() < 2 {
        return Err(ctx.err(
            last_line,
            format!(
                "found {} data row(s); expected at least 2 rows of q and C",
                rows.len()
            ),
        ));
    }
    Ok(rows)
}

/// Rows in increasing q: sorted with a warning if they were not; a duplicate q is an error.
fn sort_rows(ctx: &Ctx, rows: &mut [Row], warnings: &mut Vec<String>) -> Result<(), Error> {
    let Some(w) = rows.windows(2).find(|w| w[1].0 <= w[0].0) else {
        return Ok(());
    };
    let (a, b) = (w[0].2, w[1].2);
    rows.sort_by(|x, y| x.0.total_cmp(&y.0));
    if let Some(d) = rows.windows(2).find(|w| w[1].0 == w[0].0) {
        let (l1, l2) = (d[0].2.min(d[1].2), d[0].2.max(d[1].2));
        return Err(ctx.err(
            l2,
            format!(
                "duplicate q = {:e} 1/m (also on line {l1}); expected distinct q values",
                d[0].0
            ),
        ));
    }
    warnings.push(format!(
        "{}:{b}: q is not increasing (line {b} after line {a}); the rows were sorted by q",
        ctx.path.display()
    ));
    Ok(())
}

/// A 1D PSD's rows converted to the isotropic 2D PSD, with the conversion's warning.
fn convert_1d(
    ctx: &Ctx,
    rows: &[Row],
    conversion: Conversion,
    warnings: &mut Vec<String>,
) -> Result<Tabulated, Error> {
    let (q, c): (Vec<f64>, Vec<f64>) = rows.iter().map(|r| (r.0, r.1)).unzip();
    let n = q.len();
    if n > MAX_POINTS_1D {
        return Err(ctx.err(
            rows[MAX_POINTS_1D].2,
            format!(
                "{n} points of a 1D PSD; its conversion to 2D takes at most {MAX_POINTS_1D} \
                 (bin or thin the data)"
            ),
        ));
    }
    let line_of = |i: usize| rows[i].2;
    let conv = abel::c2d_from_c1d(&q, &c, conversion).map_err(|e| {
        let first = q
            .iter()
            .position(|&x| x >= 0.5 * q[n - 1])
            .unwrap_or(n - 2)
            .min(n - 2);
        ctx.err(line_of(first), format!("1D PSD: {e}"))
    })?;
    if let Some(i) = conv
        .c
        .iter()
        .position(|e| !(e.value.is_finite() && e.value > 0.0))
    {
        return Err(ctx.err(
            line_of(i),
            format!(
                "the 1D→2D conversion gives C = {:.3e} m^4 at q = {:.4e} 1/m; expected \
                 C > 0 (a 1D PSD of an isotropic surface cannot rise this steeply to the right)",
                conv.c[i].value, conv.q[i]
            ),
        ));
    }
    warnings.push(match conv.method {
        Conversion::InverseAbel => format!(
            "{}: 1D PSD (m^3, one-sided) converted to the isotropic 2D PSD by the exact \
             inverse Abel transform; beyond q = {:.4e} 1/m C1D was continued as q^{:.3}, \
             which C in the last octave depends on (max quadrature error {:.1e})",
            ctx.path.display(),
            q[n - 1],
            conv.tail_exponent.unwrap_or(f64::NAN),
            conv.max_rel_err()
        ),
        Conversion::PiQShortcut => format!(
            "{}: 1D PSD converted with the shortcut C = C1D/(πq), exact only for H = 1 \
             (27 % too high for H = 0.5)",
            ctx.path.display()
        ),
    });
    conv.into_tabulated()
        .map_err(|e| ctx.err(line_of(0), e.to_string()))
}

/// Parse spectrum text (see [`read_spectrum`]); `path` only names the file in messages.
pub fn parse_spectrum(
    text: &str,
    path: &Path,
    opts: &ReadOptions,
) -> Result<(Tabulated, Vec<String>), Error> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if ce::detect(text) {
        return parse_ce(text, path, opts);
    }
    if opts.series.is_some() {
        return Err(Error::Input {
            path: path.to_path_buf(),
            line: 1,
            msg: "a series was chosen, but this is not a contact.engineering download (it has \
                  one series)"
                .into(),
        });
    }
    let mut warnings = Vec::new();
    let mut lines = textio::content_lines(text).peekable();
    let Some(&(first_line, first)) = lines.peek() else {
        return Err(Error::Input {
            path: path.to_path_buf(),
            line: 1,
            msg: "no data: expected a header line and rows of q and C values".into(),
        });
    };
    let sep = Sep::detect(first);
    let header = sep.is_header(first).then(|| {
        lines.next();
        Header::parse(sep, first, first_line)
    });
    let ctx = Ctx {
        path,
        first_line,
        header,
    };
    let cols = ctx.columns(opts, &mut warnings)?;
    let (q_scale, c_scale, kind) = ctx.scales(opts, cols, &mut warnings)?;
    let stated = [(&opts.q_unit, cols.0), (&opts.c_unit, cols.1)]
        .iter()
        .any(|(flag, i)| {
            flag.is_some() || ctx.header.as_ref().is_some_and(|h| h.unit(*i).is_some())
        });
    let convention = opts.convention.unwrap_or_default();
    let factor = match kind {
        PsdKind::TwoD => convention.factor_2d(),
        PsdKind::OneD => convention.factor_1d(),
    };
    let mut rows = read_rows(&ctx, sep, lines, cols, (q_scale, c_scale * factor))?;
    sort_rows(&ctx, &mut rows, &mut warnings)?;
    if convention != Convention::Coatcheck {
        warnings.push(format!(
            "{}: C read in the {} normalisation and multiplied by {factor:.6e} into this tool's \
             (see --psd-convention)",
            path.display(),
            convention.name()
        ));
    }
    let (t, warnings) = finish(&ctx, rows, kind, opts.conversion, warnings)?;
    if !stated {
        plausible_si(&ctx, &t)?;
    }
    Ok((t, warnings))
}

/// Sorted rows in SI (this tool's normalisation) as a 2D spectrum: as they are, or converted
/// from a 1D PSD.
fn finish(
    ctx: &Ctx,
    rows: Vec<Row>,
    kind: PsdKind,
    conversion: Conversion,
    mut warnings: Vec<String>,
) -> Result<(Tabulated, Vec<String>), Error> {
    let spectrum = match kind {
        PsdKind::TwoD => {
            let (q, c) = rows.iter().map(|r| (r.0, r.1)).unzip();
            Tabulated::new(q, c).map_err(|e| ctx.err(rows[0].2, e.to_string()))?
        }
        PsdKind::OneD => convert_1d(ctx, &rows, conversion, &mut warnings)?,
    };
    Ok((spectrum, warnings))
}

/// Wavenumbers a file without units is accepted with, read as 1/m: wavelengths from about
/// 0.06 nm to 6 m.
pub const Q_SI: (f64, f64) = (1.0, 1e11);

/// What a file without units must hold, in messages ([`Q_SI`] and
/// [`crate::topography::plausible::H_RMS_SI`]; a unit test holds them together).
const EXPECTED_SI: &str = "q within 1e0 to 1e11 1/m and h_rms within 1e-11 to 1e-2 m; give the \
     units: a header 'q (1/um), C (um^4)', or --q-unit 1/um --c-unit um^4 (roughness.q_unit, \
     roughness.c_unit)";

/// A spectrum from a file that states no units, read as SI: its q-range within [`Q_SI`] and
/// its h_rms within [`crate::topography::plausible::H_RMS_SI`], else an error that suggests the
/// unit flags.
fn plausible_si(ctx: &Ctx, t: &Tabulated) -> Result<(), Error> {
    let (lo, hi) = (t.q()[0], t.q()[t.q().len() - 1]);
    let s = crate::psd::Spectrum::Tabulated(t.clone());
    let (h, xi) = (s.h_rms_sq().value.sqrt(), s.slope_sq().value.sqrt());
    let h_si = crate::topography::plausible::H_RMS_SI;
    let inside = |v: f64, (a, b): (f64, f64)| !v.is_finite() || (a..=b).contains(&v);
    if inside(lo, Q_SI) && inside(hi, Q_SI) && inside(h, h_si) {
        return Ok(());
    }
    Err(ctx.err(
        ctx.hline(),
        format!(
            "the file states no units, and read as SI its q runs from {lo:.3e} to {hi:.3e} 1/m, \
             h_rms = {h:.3e} m, rms slope = {xi:.3e}; expected {EXPECTED_SI}"
        ),
    ))
}

/// A contact.engineering download ([`ce`]): its chosen series, in SurfaceTopography's
/// normalisation, as this tool's 2D spectrum.
fn parse_ce(
    text: &str,
    path: &Path,
    opts: &ReadOptions,
) -> Result<(Tabulated, Vec<String>), Error> {
    let bad = |line: usize, msg: String| Error::Input {
        path: path.to_path_buf(),
        line,
        msg,
    };
    if let Some(c) = opts
        .convention
        .filter(|&c| c != Convention::SurfaceTopography)
    {
        return Err(bad(
            1,
            format!(
                "a contact.engineering download is in the surfacetopography normalisation, \
                 not {} (drop --psd-convention or give surfacetopography)",
                c.name()
            ),
        ));
    }
    if opts.q_col.is_some() || opts.c_col.is_some() {
        return Err(bad(
            1,
            "a contact.engineering download is read by its series (--series), not by columns"
                .into(),
        ));
    }
    let s = ce::choose(ce::read(text, path)?, opts.series.as_deref(), path)?;
    let line = s.rows.first().map_or(1, |r| r.2);
    let x_unit = opts.q_unit.clone().or(s.x_unit.clone());
    let y_unit = opts.c_unit.clone().or(s.y_unit.clone());
    let scale = |u: &Option<String>, dim: Dim, what: &str| -> Result<f64, Error> {
        match u {
            None => Ok(1.0),
            Some(u) => {
                unit_scale(u, dim).map_err(|e| bad(line, format!("unit of {what} '{u}': {e}")))
            }
        }
    };
    let q_scale = scale(&x_unit, Dim::Length(-1), "the wavevector")?;
    let y_scale = scale(&y_unit, Dim::Length(3), "the PSD (m³ in every series)")?;
    let st = Convention::SurfaceTopography;
    let mut rows: Vec<Row> = Vec::with_capacity(s.rows.len());
    for &(x, y, ln) in &s.rows {
        let q = x * q_scale;
        // "q/π × 2D PSD": y = (q/π) C_ST, so C = π y/(q (2π)²); a 1D series: C1D = C1D_ST/π.
        let c = if s.is_2d() {
            std::f64::consts::PI * y * y_scale / q * st.factor_2d()
        } else {
            y * y_scale * st.factor_1d()
        };
        if !(q.is_finite() && q > 0.0 && c.is_finite() && c > 0.0) {
            return Err(bad(
                ln,
                format!("wavevector {x:e}, PSD {y:e}; expected finite values > 0"),
            ));
        }
        rows.push((q, c, ln));
    }
    let ctx = Ctx {
        path,
        first_line: line,
        header: None,
    };
    let mut warnings = Vec::new();
    sort_rows(&ctx, &mut rows, &mut warnings)?;
    warnings.push(format!(
        "{}: contact.engineering download, series '{}: {}' ({} points) read in the \
         surfacetopography normalisation ({})",
        path.display(),
        s.subject,
        s.name,
        rows.len(),
        if s.is_2d() {
            "C = y/(4πq)"
        } else {
            "C1D = C1D_ST/π, then converted to 2D"
        }
    ));
    let kind = if s.is_2d() {
        PsdKind::TwoD
    } else {
        PsdKind::OneD
    };
    finish(&ctx, rows, kind, opts.conversion, warnings)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_si_message_quotes_the_bounds() {
        let h = crate::topography::plausible::H_RMS_SI;
        assert!(EXPECTED_SI.contains(&format!("{:e} to {:e} m", h.0, h.1)));
        assert!(EXPECTED_SI.contains(&format!("{:e} to {:e} 1/m", Q_SI.0, Q_SI.1)));
    }
}
