//! The guard that keeps NaN and inf out of every report: a table cell or CSV field that reads
//! `NaN`, `inf` or `-inf` is a numerical failure naming its row (the row's first cell: the
//! quantity, or the q or q·d of a data row) and its column (from the first row of several
//! cells, the header). Text is checked whole ([`check_text`], before it is printed) or line by
//! line as it is written ([`Finite`], the writer of every text file). JSON shows a non-finite
//! number as `null`, so a JSON report is checked through a text report of the same numbers.

use crate::error::Error;
use std::io::Write;

/// The cells of a line: split at table borders, `|` and commas, trimmed, empty ones dropped.
fn cells(line: &str) -> Vec<String> {
    line.split(['│', '┆', '|', ','])
        .map(|c| c.trim().to_string())
        .filter(|c| !c.is_empty())
        .collect()
}

/// The check of one report, line by line: remembers the header.
#[derive(Default)]
pub struct Lines {
    header: Vec<String>,
}

impl Lines {
    /// The failure a line shows, if any.
    pub fn check(&mut self, line: &str) -> Result<(), Error> {
        let row = cells(line);
        if self.header.is_empty() && row.len() > 1 {
            self.header = row.clone();
        }
        let bad = row.iter().position(|c| {
            matches!(
                c.to_ascii_lowercase().as_str(),
                "nan" | "inf" | "-inf" | "+inf"
            )
        });
        let Some(i) = bad else {
            return Ok(());
        };
        let column = self
            .header
            .get(i)
            .filter(|_| i > 0)
            .map_or(String::new(), |h| format!(", column {h}"));
        Err(Error::Numerical {
            what: "the report",
            detail: format!(
                "{} is {}{column}; a result that is not finite is not printed",
                row[0], row[i]
            ),
        })
    }
}

/// Refuse a text that shows a number that is not finite (module doc).
pub fn check_text(text: &str) -> Result<(), Error> {
    let mut lines = Lines::default();
    text.lines().try_for_each(|l| lines.check(l))
}

/// A writer that passes text through and fails (an [`std::io::ErrorKind::InvalidData`] error
/// with the guard's message) at the first line that shows a non-finite number; the last line,
/// if it has no newline, is checked by [`Finite::finish`].
pub struct Finite<W: Write> {
    inner: W,
    pending: Vec<u8>,
    lines: Lines,
}

impl<W: Write> Finite<W> {
    pub fn new(inner: W) -> Self {
        Self {
            inner,
            pending: Vec::new(),
            lines: Lines::default(),
        }
    }

    fn check(&mut self, line: &[u8]) -> std::io::Result<()> {
        self.lines
            .check(&String::from_utf8_lossy(line))
            .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, e.to_string()))
    }

    /// Check the last line (without a newline) and flush.
    pub fn finish(mut self) -> std::io::Result<()> {
        let last = std::mem::take(&mut self.pending);
        self.check(&last)?;
        self.inner.flush()
    }
}

impl<W: Write> Write for Finite<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let mut rest = buf;
        while let Some(n) = rest.iter().position(|&b| b == b'\n') {
            self.pending.extend_from_slice(&rest[..n]);
            let line = std::mem::take(&mut self.pending);
            self.check(&line)?;
            rest = &rest[n + 1..];
        }
        self.pending.extend_from_slice(rest);
        self.inner.write_all(buf)?;
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The streamed check finds what the whole-text check finds, across write boundaries, and
    /// the last line without a newline too.
    #[test]
    fn streamed_lines_are_checked_like_the_text() {
        let bad = "q,C\n1e5,2e-20\n2e5,NaN\n";
        let mut out = Vec::new();
        let mut w = Finite::new(&mut out);
        w.write_all(b"q,C\n1e5,2e-2").unwrap();
        w.write_all(b"0\n2e5,Na").unwrap();
        let e = w.write_all(b"N\n").unwrap_err().to_string();
        assert_eq!(e, check_text(bad).unwrap_err().to_string());
        assert!(e.contains("2e5 is NaN, column C"), "{e}");
        let mut w = Finite::new(Vec::new());
        w.write_all(b"q,C\n1e5,inf").unwrap();
        assert!(w.finish().is_err());
        let mut w = Finite::new(Vec::new());
        w.write_all(b"q,C\n1e5,1\n").unwrap();
        assert!(w.finish().is_ok());
    }
}
