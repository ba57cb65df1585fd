//! Reading a roughness spectrum from a text file as users have them.
//!
//! The file is a table of numbers with an optional header line:
//! - comment lines start with `#`, `%` or `//`; blank lines are skipped; a UTF-8 BOM and
//!   Windows (CRLF) line ends are accepted;
//! - the separator is detected on the first non-comment line: tab, then `;`, then `,`, else
//!   runs of whitespace. With tab, `;` or whitespace separators a decimal comma (`1,5e-20`) is
//!   read as a decimal point;
//! - a first line with a field that is not a number is the header. Header fields name the
//!   column and may carry its unit in brackets: `q (1/m)`, `q [1/um]`, `C (m^4)`, `C [um^4]`,
//!   `PSD (nm^3)`. Units in [`ReadOptions`] (command-line flags) override the header's, with a
//!   warning when they differ;
//! - the columns are chosen by name or 1-based index ([`Column`]); by default the first header
//!   field named like a wavenumber (`q…`, `k…`, `wavenumber`, `wavevector`) and the first named
//!   like a spectrum (`C…`, `PSD…`, `power…`), else columns 1 and 2. A column that looks like a
//!   spatial frequency or a wavelength is refused: q here is the angular wavenumber 2π/λ.
//!
//! The C column is a 2D PSD in m^4 (the theory's C(q), notes.md) unless its unit is a length
//! cubed or [`ReadOptions::kind`] says [`PsdKind::OneD`]: then it is the one-sided 1D PSD of a
//! line scan in m^3 (h_rms² = ∫_0^∞ C1D dq) and is converted to the isotropic 2D PSD with the
//! exact inverse Abel transform ([`crate::psd::abel`]).
//!
//! Data are checked, not repaired: a non-number, a non-positive or non-finite q or C, a
//! duplicate q, too few columns or fewer than two points is an [`Error::Input`] naming the file,
//! the line and what was expected. Unsorted q is sorted, with a warning.

use crate::error::Error;
use crate::psd::Tabulated;
use crate::psd::abel::{self, Conversion};
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
}

/// Read a spectrum file into a validated 2D [`Tabulated`] spectrum (SI: q in 1/m, C in m^4),
/// with warnings (sorting, unit overrides, 1D→2D conversion) for the caller to print.
pub fn read_spectrum(path: &Path, opts: &ReadOptions) -> Result<(Tabulated, Vec<String>), Error> {
    let bytes = std::fs::read(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let text = decode_utf8(&bytes, path)?;
    parse_spectrum(text, path, opts)
}

/// Bytes as UTF-8 text without a BOM; invalid UTF-8 is an error naming its line.
pub(crate) fn decode_utf8<'a>(bytes: &'a [u8], path: &Path) -> Result<&'a str, Error> {
    let text = std::str::from_utf8(bytes).map_err(|e| Error::Input {
        path: path.to_path_buf(),
        line: 1 + bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count(),
        msg: "the file is not UTF-8 text".into(),
    })?;
    Ok(text.strip_prefix('\u{feff}').unwrap_or(text))
}

/// The field separator of a table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Sep {
    Char(char),
    Whitespace,
}

impl Sep {
    /// Detect from the first content line: tab, `;`, `,`, else whitespace.
    pub(crate) fn detect(line: &str) -> Self {
        for c in ['\t', ';', ','] {
            if line.contains(c) {
                return Sep::Char(c);
            }
        }
        Sep::Whitespace
    }

    /// Split a line into trimmed fields (surrounding double quotes removed).
    pub(crate) fn split<'a>(&self, line: &'a str) -> Vec<&'a str> {
        match self {
            Sep::Char(c) => line.split(*c).map(unquote).collect(),
            Sep::Whitespace => line.split_whitespace().map(unquote).collect(),
        }
    }

    /// Fields `a` and `b` of a line as [`Sep::split`] gives them, when it has at least `need`
    /// (> a, b) fields; without collecting the line (the rows of a 1000-line file).
    pub(crate) fn pick<'a>(
        &self,
        line: &'a str,
        a: usize,
        b: usize,
        need: usize,
    ) -> Option<(&'a str, &'a str)> {
        fn first<'a>(
            mut fields: impl Iterator<Item = &'a str>,
            a: usize,
            b: usize,
            need: usize,
        ) -> Option<(&'a str, &'a str)> {
            let (mut fa, mut fb) = ("", "");
            for i in 0..need {
                let f = unquote(fields.next()?);
                if i == a {
                    fa = f;
                }
                if i == b {
                    fb = f;
                }
            }
            Some((fa, fb))
        }
        match self {
            Sep::Char(c) => first(line.split(*c), a, b, need),
            Sep::Whitespace => first(line.split_whitespace(), a, b, need),
        }
    }

    /// Parse a number; a decimal comma is accepted when the separator is not a comma.
    pub(crate) fn number(&self, field: &str) -> Option<f64> {
        match field.parse::<f64>() {
            Ok(v) => Some(v),
            Err(_) if *self != Sep::Char(',') && field.contains(',') && !field.contains('.') => {
                field.replacen(',', ".", 1).parse().ok()
            }
            Err(_) => None,
        }
    }
}

/// A field trimmed, with surrounding double quotes removed.
fn unquote(f: &str) -> &str {
    let f = f.trim();
    f.strip_prefix('"')
        .and_then(|g| g.strip_suffix('"'))
        .unwrap_or(f)
        .trim()
}

/// The content lines of a text (1-based line number, text without line end), skipping blank
/// and comment lines.
pub(crate) fn content_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.split('\n')
        .enumerate()
        .map(|(i, l)| (i + 1, l.strip_suffix('\r').unwrap_or(l)))
        .filter(|(_, l)| {
            let t = l.trim();
            !(t.is_empty() || t.starts_with('#') || t.starts_with('%') || t.starts_with("//"))
        })
}

/// A header field split into its name and bracketed unit: `q (1/um)` → ("q", Some("1/um")).
pub(crate) fn name_and_unit(field: &str) -> (String, Option<String>) {
    for (open, close) in [('(', ')'), ('[', ']')] {
        if let (Some(a), Some(b)) = (field.find(open), field.rfind(close))
            && b > a
        {
            return (
                field[..a].trim().to_string(),
                Some(field[a + 1..b].trim().to_string()),
            );
        }
    }
    (field.trim().to_string(), None)
}

/// Header fields of a whitespace-separated header, with a bracketed unit glued back to its
/// name (`q (1/m)  C (m^4)` is two fields, not four).
pub(crate) fn header_fields(sep: Sep, line: &str) -> Vec<String> {
    let raw = sep.split(line);
    if sep != Sep::Whitespace {
        return raw.into_iter().map(str::to_string).collect();
    }
    let mut out: Vec<String> = Vec::new();
    for f in raw {
        match out.last_mut() {
            Some(prev) if f.starts_with('(') || f.starts_with('[') => {
                prev.push(' ');
                prev.push_str(f);
            }
            _ => out.push(f.to_string()),
        }
    }
    out
}

struct Header {
    line: usize,
    names: Vec<String>,
    units: Vec<Option<String>>,
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

/// Parse spectrum text (see [`read_spectrum`]); `path` only names the file in messages.
pub fn parse_spectrum(
    text: &str,
    path: &Path,
    opts: &ReadOptions,
) -> Result<(Tabulated, Vec<String>), Error> {
    let err = |line: usize, msg: String| Error::Input {
        path: path.to_path_buf(),
        line,
        msg,
    };
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut warnings = Vec::new();
    let mut lines = content_lines(text).peekable();
    let Some(&(first_line, first)) = lines.peek() else {
        return Err(err(
            1,
            "no data: expected a header line and rows of q and C values".into(),
        ));
    };
    let sep = Sep::detect(first);
    let header = if sep.split(first).iter().any(|f| sep.number(f).is_none()) {
        lines.next();
        let fields = header_fields(sep, first);
        let (names, units) = fields.iter().map(|f| name_and_unit(f)).unzip();
        Some(Header {
            line: first_line,
            names,
            units,
        })
    } else {
        None
    };

    // Column choice.
    let resolve = |col: &Option<Column>,
                   what: &str,
                   looks: fn(&str) -> bool,
                   default: usize|
     -> Result<(usize, bool), Error> {
        match (col, &header) {
            (Some(Column::Index(i)), Some(h)) if *i > h.names.len() => Err(err(
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
                        err(
                            h.line,
                            format!(
                                "no column named '{name}' for {what}; the header has: {}",
                                h.names.join(", ")
                            ),
                        )
                    })
            }
            (Some(Column::Name(name)), None) => Err(err(
                first_line,
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
    };
    let (qi, q_named) = resolve(&opts.q_col, "q", looks_like_q, 0)?;
    let (ci, c_named) = resolve(&opts.c_col, "C", looks_like_c, 1)?;
    if qi == ci {
        return Err(err(
            header.as_ref().map_or(first_line, |h| h.line),
            format!(
                "q and C are both read from column {}; choose different columns",
                qi + 1
            ),
        ));
    }
    if let Some(h) = &header {
        for (i, named, what) in [(qi, q_named, "q"), (ci, c_named, "C")] {
            let Some(name) = h.names.get(i) else {
                return Err(err(
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
                    path.display(),
                    h.line,
                    i + 1
                ));
            }
        }
        if opts.q_col.is_none() && looks_like_frequency_or_wavelength(&h.names[qi]) {
            return Err(err(
                h.line,
                format!(
                    "column '{}' looks like a spatial frequency or wavelength; expected the \
                     wavenumber q = 2π/λ (convert it, or choose the q column explicitly)",
                    h.names[qi]
                ),
            ));
        }
    }

    // Units: flags override the header.
    let header_unit = |i: usize| header.as_ref().and_then(|h| h.units[i].clone());
    let hline = header.as_ref().map_or(first_line, |h| h.line);
    let pick_unit = |flag: &Option<String>,
                     from_header: Option<String>,
                     what: &str,
                     warnings: &mut Vec<String>| {
        match (flag, from_header) {
            (Some(f), Some(h)) => {
                if f.replace(' ', "") != h.replace(' ', "") {
                    warnings.push(format!(
                        "{}:{hline}: the header gives {what} in '{h}'; using '{f}' as requested",
                        path.display()
                    ));
                }
                Some(f.clone())
            }
            (Some(f), None) => Some(f.clone()),
            (None, h) => h,
        }
    };
    let q_unit = pick_unit(&opts.q_unit, header_unit(qi), "q", &mut warnings);
    let c_unit = pick_unit(&opts.c_unit, header_unit(ci), "C", &mut warnings);
    let q_scale = match &q_unit {
        None => 1.0,
        Some(u) => unit_scale(u, Dim::Length(-1)).map_err(|e| {
            err(
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
                return Err(err(
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
            return Err(err(
                hline,
                format!(
                    "C is in '{}', a {} unit, but a {} PSD was requested",
                    c_unit.unwrap_or_default(),
                    if u == PsdKind::OneD {
                        "1D (m^3)"
                    } else {
                        "2D (m^4)"
                    },
                    if k == PsdKind::OneD { "1D" } else { "2D" }
                ),
            ));
        }
        (Some(k), _) => k,
        (None, Some(u)) => u,
        (None, None) => PsdKind::TwoD,
    };

    // Rows.
    let need = qi.max(ci) + 1;
    let mut rows: Vec<(f64, f64, usize)> = Vec::new();
    let mut last_line = first_line;
    for (ln, line) in lines {
        last_line = ln;
        let Some((q_text, c_text)) = sep.pick(line, qi, ci, need) else {
            return Err(err(
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
                err(
                    ln,
                    format!(
                        "expected a number for {what} in column {}, found '{field}'",
                        i + 1
                    ),
                )
            })?;
            if !(v.is_finite() && v > 0.0) {
                return Err(err(
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
            return Err(err(
                ln,
                format!(
                    "q = {q_text}, C = {c_text} are q = {q:e} 1/m, C = {c:e} m^4 in SI units, \
                     outside the floating-point range; expected values that are finite and > 0 in SI"
                ),
            ));
        }
        rows.push((q, c, ln));
    }
    if rows.len() < 2 {
        return Err(err(
            last_line,
            format!(
                "found {} data row(s); expected at least 2 rows of q and C",
                rows.len()
            ),
        ));
    }
    if let Some(w) = rows.windows(2).find(|w| w[1].0 <= w[0].0) {
        let (a, b) = (w[0].2, w[1].2);
        rows.sort_by(|x, y| x.0.total_cmp(&y.0));
        if let Some(d) = rows.windows(2).find(|w| w[1].0 == w[0].0) {
            let (l1, l2) = (d[0].2.min(d[1].2), d[0].2.max(d[1].2));
            return Err(err(
                l2,
                format!(
                    "duplicate q = {:e} 1/m (also on line {l1}); expected distinct q values",
                    d[0].0
                ),
            ));
        }
        warnings.push(format!(
            "{}:{b}: q is not increasing (line {b} after line {a}); the rows were sorted by q",
            path.display()
        ));
    }
    let (q, c): (Vec<f64>, Vec<f64>) = rows.iter().map(|r| (r.0, r.1)).unzip();
    let line_of = |i: usize| rows[i].2;

    let spectrum = match kind {
        PsdKind::TwoD => Tabulated::new(q, c).map_err(|e| err(line_of(0), e.to_string()))?,
        PsdKind::OneD => {
            let n = q.len();
            let conv = abel::c2d_from_c1d(&q, &c, opts.conversion).map_err(|e| {
                let first = q
                    .iter()
                    .position(|&x| x >= 0.5 * q[n - 1])
                    .unwrap_or(n - 2)
                    .min(n - 2);
                err(line_of(first), format!("1D PSD: {e}"))
            })?;
            if let Some(i) = conv
                .c
                .iter()
                .position(|e| !(e.value.is_finite() && e.value > 0.0))
            {
                return Err(err(
                    line_of(i),
                    format!(
                        "the 1D→2D conversion gives C = {:.3e} m^4 at q = {:.4e} 1/m; expected \
                         C > 0 (a 1D PSD of an isotropic surface cannot rise this steeply to the right)",
                        conv.c[i].value, conv.q[i]
                    ),
                ));
            }
            match conv.method {
                Conversion::InverseAbel => warnings.push(format!(
                    "{}: 1D PSD (m^3, one-sided) converted to the isotropic 2D PSD by the exact \
                     inverse Abel transform; beyond q = {:.4e} 1/m C1D was continued as q^{:.3}, \
                     which C in the last octave depends on (max quadrature error {:.1e})",
                    path.display(),
                    q[n - 1],
                    conv.tail_exponent.unwrap_or(f64::NAN),
                    conv.max_rel_err()
                )),
                Conversion::PiQShortcut => warnings.push(format!(
                    "{}: 1D PSD converted with the shortcut C = C1D/(πq), exact only for H = 1 \
                     (27 % too high for H = 0.5)",
                    path.display()
                )),
            }
            conv.into_tabulated()
                .map_err(|e| err(line_of(0), e.to_string()))?
        }
    };
    Ok((spectrum, warnings))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pick_gives_the_fields_split_gives() {
        let lines = [
            "1e5,2e-20",
            " 1e5 , \"2e-20\" ,x",
            "1e5;2,5e-20;;",
            "a\tb\t\tc",
            "  1e5   2e-20  3 ",
            "\"q\" \"C\"",
            "",
            ",",
            "1e5",
        ];
        for line in lines {
            for sep in [
                Sep::Char(','),
                Sep::Char(';'),
                Sep::Char('\t'),
                Sep::Whitespace,
            ] {
                let all = sep.split(line);
                for need in 1..5 {
                    for (a, b) in (0..need).flat_map(|a| (0..need).map(move |b| (a, b))) {
                        let got = sep.pick(line, a, b, need);
                        let want = (all.len() >= need).then(|| (all[a], all[b]));
                        assert_eq!(got, want, "{line:?} {sep:?} need {need} ({a}, {b})");
                    }
                }
            }
        }
    }
}
