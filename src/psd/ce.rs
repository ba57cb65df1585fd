//! Power-spectrum downloads from contact.engineering (its "Power spectrum" analysis, saved as
//! CSV or TXT), read with their own column names and series.
//!
//! Layouts (contact.engineering's download functions for plotted series):
//! - **CSV**: `;`-separated, one header line `Subject type;Subject name;Creator;Instrument
//!   name;Instrument type;Instrument parameters;Function name;Data series;Wavevector (1/m);PSD
//!   (m³)` (optionally `;standard error of PSD (m³);comment`), then one row per point of every
//!   series of every measurement, with fields in double quotes where they hold a `;`.
//! - **TXT**: `#` comment lines: the function's name, per measurement a headline
//!   (`# topography: NAME` or `# surface: NAME`) underlined with `=`, then per series its name
//!   underlined with `-`, a line `# Columns: Wavevector (1/m), PSD (m³)[, …]` and rows of
//!   space-separated numbers, several series one after another (so one q appears once per
//!   series).
//!
//! The series of a measurement are "1D PSD along x", "1D PSD along y" (1D PSDs, m³) and
//! "q/π × 2D PSD" (a 2D PSD times q/π, m³), each also "(incl. unreliable data)"; a surface's
//! average has "1D PSD along x". All are in SurfaceTopography's normalisation
//! ([`crate::psd::convention`]). A series is chosen by its name, or by `SUBJECT: NAME` when the
//! file holds several measurements; by default the 2D series, else "1D PSD along x", of the
//! only measurement.

use crate::error::Error;
use std::path::Path;

/// One series of a download: raw numbers as written (in `x_unit`, `y_unit`) with their lines.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub subject: String,
    pub name: String,
    pub x_unit: Option<String>,
    pub y_unit: Option<String>,
    /// (x, y, 1-based line).
    pub rows: Vec<(f64, f64, usize)>,
}

impl Series {
    /// "q/π × 2D PSD": a 2D PSD times q/π (else a 1D PSD).
    pub fn is_2d(&self) -> bool {
        self.name.contains("2D PSD")
    }

    fn label(&self) -> String {
        format!("{}: {}", self.subject, self.name)
    }
}

/// Whether `text` is a contact.engineering download: the CSV header or the TXT series header.
pub fn detect(text: &str) -> bool {
    let first = text.lines().find(|l| !l.trim().is_empty()).unwrap_or("");
    is_csv_header(first) || text.lines().any(|l| l.starts_with("# Columns: "))
}

fn is_csv_header(line: &str) -> bool {
    let fields = split_csv(line);
    fields.iter().any(|f| f == "Data series") && fields.iter().any(|f| f == "Subject name")
}

/// Split a `;`-separated line, honouring double quotes (`""` is a quote inside quotes).
fn split_csv(line: &str) -> Vec<String> {
    let mut out = vec![String::new()];
    let mut quoted = false;
    let mut chars = line.trim_end_matches('\r').chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                chars.next();
                out.last_mut().expect("never empty").push('"');
            }
            ('"', _) => quoted = !quoted,
            (';', false) => out.push(String::new()),
            (c, _) => out.last_mut().expect("never empty").push(c),
        }
    }
    out
}

/// `Name (unit)` → (name, unit).
fn name_and_unit(field: &str) -> (String, Option<String>) {
    let f = field.trim();
    match (f.rfind('('), f.ends_with(')')) {
        (Some(i), true) => (
            f[..i].trim().to_string(),
            Some(f[i + 1..f.len() - 1].trim().to_string()),
        ),
        _ => (f.to_string(), None),
    }
}

fn err(path: &Path, line: usize, msg: String) -> Error {
    Error::Input {
        path: path.to_path_buf(),
        line,
        msg,
    }
}

fn number(path: &Path, line: usize, text: &str, what: &str) -> Result<f64, Error> {
    text.trim().parse::<f64>().map_err(|_| {
        err(
            path,
            line,
            format!("expected a number for {what}, found '{}'", text.trim()),
        )
    })
}

/// Every series of a download, in file order.
pub fn read(text: &str, path: &Path) -> Result<Vec<Series>, Error> {
    let first = text.lines().position(|l| !l.trim().is_empty()).unwrap_or(0);
    if is_csv_header(text.lines().nth(first).unwrap_or("")) {
        read_csv(text, path, first)
    } else {
        read_txt(text, path)
    }
}

fn read_csv(text: &str, path: &Path, header_at: usize) -> Result<Vec<Series>, Error> {
    let mut lines = text.lines().enumerate().skip(header_at);
    let (_, header) = lines.next().expect("the header was found");
    let names = split_csv(header);
    let col = |want: &str| names.iter().position(|n| n == want);
    let (subject, series) = (
        col("Subject name").expect("detected"),
        col("Data series").expect("detected"),
    );
    let (x, y) = (series + 1, series + 2);
    let hline = header_at + 1;
    if names.len() <= y {
        return Err(err(
            path,
            hline,
            "expected the wavevector and PSD columns after 'Data series'".into(),
        ));
    }
    let (_, x_unit) = name_and_unit(&names[x]);
    let (_, y_unit) = name_and_unit(&names[y]);
    let mut out: Vec<Series> = Vec::new();
    for (i, line) in lines {
        if line.trim().is_empty() {
            continue;
        }
        let ln = i + 1;
        let f = split_csv(line);
        if f.len() <= y {
            return Err(err(
                path,
                ln,
                format!("expected {} fields, found {}", names.len(), f.len()),
            ));
        }
        let row = (
            number(path, ln, &f[x], "the wavevector")?,
            number(path, ln, &f[y], "the PSD")?,
            ln,
        );
        match out
            .iter_mut()
            .find(|s| s.subject == f[subject] && s.name == f[series])
        {
            Some(s) => s.rows.push(row),
            None => out.push(Series {
                subject: f[subject].clone(),
                name: f[series].clone(),
                x_unit: x_unit.clone(),
                y_unit: y_unit.clone(),
                rows: vec![row],
            }),
        }
    }
    Ok(out)
}

/// The text of a comment line, without `#` and one space.
fn comment(line: &str) -> Option<&str> {
    let t = line.trim_end_matches('\r').strip_prefix('#')?;
    Some(t.strip_prefix(' ').unwrap_or(t))
}

fn underlined(next: Option<&str>, with: char) -> bool {
    next.and_then(comment)
        .is_some_and(|t| !t.is_empty() && t.chars().all(|c| c == with))
}

fn read_txt(text: &str, path: &Path) -> Result<Vec<Series>, Error> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out: Vec<Series> = Vec::new();
    let mut subject = String::new();
    let mut open: Option<Series> = None;
    for (i, line) in lines.iter().enumerate() {
        let next = lines.get(i + 1).copied();
        if let Some(c) = comment(line) {
            if underlined(next, '=') {
                subject = c.split_once(": ").map_or(c, |(_, name)| name).to_string();
            } else if underlined(next, '-') {
                out.extend(open.take());
                open = Some(Series {
                    subject: subject.clone(),
                    name: c.to_string(),
                    x_unit: None,
                    y_unit: None,
                    rows: Vec::new(),
                });
            } else if let (Some(cols), Some(s)) = (c.strip_prefix("Columns: "), open.as_mut()) {
                let mut fields = cols.split(", ");
                s.x_unit = fields.next().and_then(|f| name_and_unit(f).1);
                s.y_unit = fields.next().and_then(|f| name_and_unit(f).1);
            }
            continue;
        }
        if line.trim().is_empty() {
            continue;
        }
        let ln = i + 1;
        let Some(s) = open.as_mut() else {
            return Err(err(
                path,
                ln,
                "numbers before any series header ('# NAME' underlined with '-')".into(),
            ));
        };
        let mut f = line.split_whitespace();
        let (Some(a), Some(b)) = (f.next(), f.next()) else {
            return Err(err(
                path,
                ln,
                "expected two numbers (wavevector and PSD)".into(),
            ));
        };
        s.rows.push((
            number(path, ln, a, "the wavevector")?,
            number(path, ln, b, "the PSD")?,
            ln,
        ));
    }
    out.extend(open);
    Ok(out)
}

/// The series named `want` (`NAME` or `SUBJECT: NAME`), or by default the 2D series, else
/// "1D PSD along x", of the only measurement. Errors list the series the file holds.
pub fn choose(all: Vec<Series>, want: Option<&str>, path: &Path) -> Result<Series, Error> {
    let list = || {
        all.iter()
            .map(|s| format!("'{}'", s.label()))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let matches: Vec<&Series> = match want {
        Some(w) => all
            .iter()
            .filter(|s| s.name == w.trim() || s.label() == w.trim())
            .collect(),
        None => {
            let mut subjects: Vec<&str> = all.iter().map(|s| s.subject.as_str()).collect();
            subjects.dedup();
            if subjects.len() > 1 {
                return Err(err(
                    path,
                    1,
                    format!(
                        "a contact.engineering download with {} measurements; choose a series \
                         with --series 'SUBJECT: NAME' (the file holds {})",
                        subjects.len(),
                        list()
                    ),
                ));
            }
            let default = |name: &str| all.iter().filter(|s| s.name == name).collect::<Vec<_>>();
            let two_d = default("q/π × 2D PSD");
            if two_d.is_empty() {
                default("1D PSD along x")
            } else {
                two_d
            }
        }
    };
    match matches[..] {
        [one] => Ok(one.clone()),
        [] => Err(err(
            path,
            1,
            format!(
                "no series {} in this contact.engineering download (it holds {})",
                want.map_or("'q/π × 2D PSD' or '1D PSD along x'".into(), |w| format!(
                    "'{w}'"
                )),
                list()
            ),
        )),
        _ => Err(err(
            path,
            1,
            format!(
                "series '{}' is in several measurements; choose one with --series 'SUBJECT: NAME' \
                 (the file holds {})",
                want.unwrap_or_default(),
                list()
            ),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_fields_honour_quotes() {
        assert_eq!(
            split_csv("a;\"b;c\";\"d \"\"e\"\"\";"),
            vec!["a", "b;c", "d \"e\"", ""]
        );
        assert_eq!(
            name_and_unit("Wavevector (1/m)"),
            ("Wavevector".into(), Some("1/m".into()))
        );
    }
}
