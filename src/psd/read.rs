//! Minimal reader of a two-column PSD file (q [1/m], C [m^4]), standing in for the full reader
//! of issue 4 (same path and signature) until that lands on main.
//!
//! Lines starting with `#` and blank lines are skipped; a first line that is not numeric is a
//! header; fields are separated by commas, semicolons, tabs or spaces. Every value is checked
//! (finite, positive, q strictly increasing, at least two points); errors name file and line.

use crate::error::Error;
use crate::psd::Tabulated;
use std::path::Path;

/// How to read a spectrum file (the minimal reader has no options).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReadOptions {}

/// Read a spectrum file into a validated [`Tabulated`] spectrum, with warnings.
pub fn read_spectrum(path: &Path, _opts: &ReadOptions) -> Result<(Tabulated, Vec<String>), Error> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let err = |line: usize, msg: String| Error::Input {
        path: path.to_path_buf(),
        line,
        msg,
    };
    let (mut q, mut c) = (Vec::new(), Vec::new());
    let mut last_line = 1;
    let mut seen_data_or_header = false;
    for (i, line) in text.lines().enumerate() {
        let n = i + 1;
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        last_line = n;
        let fields: Vec<&str> = t
            .split(|ch: char| ch == ',' || ch == ';' || ch.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        let nums: Vec<Option<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
        if !seen_data_or_header && nums.iter().any(Option::is_none) {
            seen_data_or_header = true;
            continue; // header
        }
        seen_data_or_header = true;
        if fields.len() < 2 {
            return Err(err(
                n,
                format!("expected two columns (q, C), found {}", fields.len()),
            ));
        }
        let (Some(qi), Some(ci)) = (nums[0], nums[1]) else {
            return Err(err(n, format!("expected two numbers (q, C), found '{t}'")));
        };
        if !(qi.is_finite() && qi > 0.0) {
            return Err(err(n, format!("q = {qi}: expected a finite q > 0")));
        }
        if !(ci.is_finite() && ci > 0.0) {
            return Err(err(n, format!("C = {ci}: expected a finite C > 0")));
        }
        if let Some(&prev) = q.last() {
            if qi == prev {
                return Err(err(
                    n,
                    format!("duplicate q = {qi}: expected strictly increasing q"),
                ));
            }
            if qi < prev {
                return Err(err(
                    n,
                    format!("q = {qi} after {prev}: expected strictly increasing q"),
                ));
            }
        }
        q.push(qi);
        c.push(ci);
    }
    if q.len() < 2 {
        return Err(err(
            last_line,
            format!("{} data point(s): expected at least 2", q.len()),
        ));
    }
    let t = Tabulated::new(q, c).map_err(|e| err(last_line, e.to_string()))?;
    Ok((t, Vec::new()))
}
