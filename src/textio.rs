//! Text tables as users have them: reading with limits, line ends, comments, separators,
//! header lines and the units in them. Shared by the spectrum reader ([`crate::psd::read`]) and
//! the height readers ([`crate::topography::io`]).
//!
//! Conventions:
//! - text is UTF-8, with or without a byte-order mark; a NUL byte means the file is not text;
//! - a line ends at `\n`, `\r\n` or a lone `\r` (old Mac files); lines are numbered from 1;
//! - comment lines start with `#`, `%` or `//`; blank lines are skipped;
//! - the separator is detected on the first content line: tab, then `;`, then `,`, else runs
//!   of whitespace. With tab, `;` or whitespace separators a decimal comma (`1,5e-20`) is read
//!   as a decimal point; fields may be wrapped in double quotes;
//! - a first content line with a field that is not a number is a header; its fields are a
//!   name and an optional unit in brackets, `q (1/um)` or `z [nm]`.
//!
//! Limits: a file read whole may hold at most the byte count its reader states, and a line
//! read by [`LineReader`] at most [`MAX_LINE_BYTES`]; beyond either the read stops with an
//! error naming the file, so an endless input (`/dev/zero`, a pipe) can neither hang the tool
//! nor fill the memory.

use crate::error::Error;
use std::io::{BufRead, Read};
use std::path::Path;

/// The longest line [`LineReader`] accepts: 64 MiB (a row of 2²¹ heights of 32 characters).
pub const MAX_LINE_BYTES: usize = 64 << 20;

fn io_err(path: &Path, source: std::io::Error) -> Error {
    Error::Io {
        path: path.to_path_buf(),
        source,
    }
}

fn not_text(path: &Path, line: usize, offset: u64) -> Error {
    Error::Input {
        path: path.to_path_buf(),
        line,
        msg: format!("a NUL byte at byte offset {offset}: the file is not a text table"),
    }
}

/// Read a whole file of at most `limit` bytes, stopping at the first NUL byte (not text) or
/// once the limit is passed; `what` names the content in the message.
pub fn read_capped(path: &Path, limit: u64, what: &str) -> Result<Vec<u8>, Error> {
    let f = std::fs::File::open(path).map_err(|e| io_err(path, e))?;
    let mut r = f.take(limit + 1);
    let mut bytes = Vec::new();
    let mut chunk = vec![0u8; 1 << 16];
    loop {
        let n = r.read(&mut chunk).map_err(|e| io_err(path, e))?;
        if n == 0 {
            return Ok(bytes);
        }
        if let Some(i) = chunk[..n].iter().position(|&b| b == 0) {
            let line = 1 + line_ends(&bytes) + line_ends(&chunk[..i]);
            return Err(not_text(path, line, (bytes.len() + i) as u64));
        }
        bytes.extend_from_slice(&chunk[..n]);
        if bytes.len() as u64 > limit {
            return Err(Error::Input {
                path: path.to_path_buf(),
                line: 1 + line_ends(&bytes[..limit as usize]),
                msg: format!(
                    "the file is larger than {} MiB, the limit for {what}",
                    limit >> 20
                ),
            });
        }
    }
}

/// The number of line ends (`\n`, `\r\n` or lone `\r`) in `bytes`.
fn line_ends(bytes: &[u8]) -> usize {
    bytes
        .iter()
        .enumerate()
        .filter(|&(i, &b)| b == b'\n' || (b == b'\r' && bytes.get(i + 1) != Some(&b'\n')))
        .count()
}

/// Bytes as UTF-8 text without a BOM; invalid UTF-8 is an error naming its line.
pub fn decode_utf8<'a>(bytes: &'a [u8], path: &Path) -> Result<&'a str, Error> {
    let text = std::str::from_utf8(bytes).map_err(|e| Error::Input {
        path: path.to_path_buf(),
        line: 1 + line_ends(&bytes[..e.valid_up_to()]),
        msg: "the file is not UTF-8 text".into(),
    })?;
    Ok(text.strip_prefix('\u{feff}').unwrap_or(text))
}

/// The lines of a text (1-based number, text without its line end), split at `\n`, `\r\n`
/// and lone `\r`.
pub fn lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    let mut rest = Some(text);
    std::iter::from_fn(move || {
        let t = rest?;
        match t.find(['\n', '\r']) {
            Some(i) => {
                let end = if t[i..].starts_with("\r\n") {
                    i + 2
                } else {
                    i + 1
                };
                rest = Some(&t[end..]);
                Some(&t[..i])
            }
            None => {
                rest = None;
                Some(t)
            }
        }
    })
    .enumerate()
    .map(|(i, l)| (i + 1, l))
}

/// Whether a (trimmed) line is a comment.
pub fn is_comment(line: &str) -> bool {
    line.starts_with('#') || line.starts_with('%') || line.starts_with("//")
}

/// The content lines of a text (see [`lines`]), skipping blank and comment lines.
pub fn content_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    lines(text).filter(|(_, l)| {
        let t = l.trim();
        !(t.is_empty() || is_comment(t))
    })
}

/// Reads a text file line by line (line ends as in [`lines`]) without holding more than one
/// line, each at most [`MAX_LINE_BYTES`].
pub struct LineReader<'p, R> {
    inner: R,
    path: &'p Path,
    /// The line just read (1-based; 0 before the first).
    pub line: usize,
    offset: u64,
    skip_lf: bool,
    buf: Vec<u8>,
}

impl<'p, R: BufRead> LineReader<'p, R> {
    pub fn new(inner: R, path: &'p Path) -> Self {
        Self {
            inner,
            path,
            line: 0,
            offset: 0,
            skip_lf: false,
            buf: Vec::new(),
        }
    }

    /// The next line (its 1-based number and its text without the line end, and without a
    /// BOM on line 1); `None` at the end of the file.
    pub fn next_line(&mut self) -> Result<Option<(usize, &str)>, Error> {
        self.buf.clear();
        let mut started = false;
        loop {
            let avail = self.inner.fill_buf().map_err(|e| io_err(self.path, e))?;
            if avail.is_empty() {
                if !started {
                    return Ok(None);
                }
                break;
            }
            started = true;
            if std::mem::take(&mut self.skip_lf) && avail[0] == b'\n' {
                self.inner.consume(1);
                self.offset += 1;
                started = false;
                continue;
            }
            let end = avail.iter().position(|&b| b == b'\n' || b == b'\r');
            let take = end.unwrap_or(avail.len());
            if let Some(i) = avail[..take].iter().position(|&b| b == 0) {
                let at = self.offset + (self.buf.len() + i) as u64;
                return Err(not_text(self.path, self.line + 1, at));
            }
            self.buf.extend_from_slice(&avail[..take]);
            let used = take + usize::from(end.is_some());
            self.skip_lf = end.is_some_and(|i| avail[i] == b'\r');
            self.inner.consume(used);
            self.offset += used as u64;
            if self.buf.len() > MAX_LINE_BYTES {
                return Err(Error::Input {
                    path: self.path.to_path_buf(),
                    line: self.line + 1,
                    msg: format!(
                        "a line longer than {} MiB, the limit for one line of a text table",
                        MAX_LINE_BYTES >> 20
                    ),
                });
            }
            if end.is_some() {
                break;
            }
        }
        self.line += 1;
        let text = std::str::from_utf8(&self.buf).map_err(|_| Error::Input {
            path: self.path.to_path_buf(),
            line: self.line,
            msg: "the file is not UTF-8 text".into(),
        })?;
        Ok(Some(if self.line == 1 {
            (1, text.trim_start_matches('\u{feff}'))
        } else {
            (self.line, text)
        }))
    }
}

/// The field separator of a table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sep {
    Char(char),
    Whitespace,
}

impl Sep {
    /// Detect from the first content line: tab, `;`, `,`, else whitespace.
    pub fn detect(line: &str) -> Self {
        for c in ['\t', ';', ','] {
            if line.contains(c) {
                return Sep::Char(c);
            }
        }
        Sep::Whitespace
    }

    /// Split a line into trimmed fields (surrounding double quotes removed).
    pub fn split<'a>(&self, line: &'a str) -> Vec<&'a str> {
        match self {
            Sep::Char(c) => line.split(*c).map(unquote).collect(),
            Sep::Whitespace => line.split_whitespace().map(unquote).collect(),
        }
    }

    /// Fields `a` and `b` of a line as [`Sep::split`] gives them, when it has at least `need`
    /// (> a, b) fields; without collecting the line.
    pub fn pick<'a>(
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
    pub fn number(&self, field: &str) -> Option<f64> {
        match field.parse::<f64>() {
            Ok(v) => Some(v),
            Err(_) if *self != Sep::Char(',') && field.contains(',') && !field.contains('.') => {
                field.replacen(',', ".", 1).parse().ok()
            }
            Err(_) => None,
        }
    }

    /// Whether a first content line is a header: one of its fields is not a number.
    pub fn is_header(&self, line: &str) -> bool {
        self.split(line).iter().any(|f| self.number(f).is_none())
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

/// A header line: column names and their bracketed units.
#[derive(Debug, Clone, PartialEq)]
pub struct Header {
    /// 1-based line number.
    pub line: usize,
    pub names: Vec<String>,
    pub units: Vec<Option<String>>,
}

impl Header {
    /// Parse a header line (`q (1/m), C (m^4)`); with a whitespace separator a bracketed unit
    /// stays with its name (`q (1/m)  C (m^4)` is two fields, not four).
    pub fn parse(sep: Sep, line: &str, line_no: usize) -> Self {
        let (names, units) = header_fields(sep, line)
            .iter()
            .map(|f| name_and_unit(f))
            .unzip();
        Self {
            line: line_no,
            names,
            units,
        }
    }

    /// The unit written for column `i`, if any.
    pub fn unit(&self, i: usize) -> Option<&str> {
        self.units.get(i)?.as_deref()
    }
}

/// A header field split into its name and bracketed unit: `q (1/um)` → ("q", Some("1/um")).
fn name_and_unit(field: &str) -> (String, Option<String>) {
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

fn header_fields(sep: Sep, line: &str) -> Vec<String> {
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

    /// `lines` and `LineReader` split alike at every kind of line end, including a `\r\n`
    /// cut between two reads of the buffered reader, and number the lines alike.
    #[test]
    fn line_ends_lf_crlf_and_cr_alike() {
        let text = "a\nb\r\nc\rd\r\r\ne\n\nf";
        let want = ["a", "b", "c", "d", "", "e", "", "f"];
        let got: Vec<&str> = lines(text).map(|(_, l)| l).collect();
        assert_eq!(got, want);
        assert_eq!(line_ends(text.as_bytes()), want.len() - 1);
        for cap in 1..6 {
            let r = std::io::BufReader::with_capacity(cap, text.as_bytes());
            let mut lr = LineReader::new(r, Path::new("t"));
            let mut got = Vec::new();
            while let Some((n, l)) = lr.next_line().unwrap() {
                assert_eq!(n, got.len() + 1);
                got.push(l.to_string());
            }
            assert_eq!(got, want, "buffer {cap}");
            assert_eq!(lr.line, want.len());
        }
    }

    #[test]
    fn a_nul_byte_is_not_text() {
        let r = std::io::BufReader::new(&b"1 2\n3\0"[..]);
        let mut lr = LineReader::new(r, Path::new("t"));
        assert_eq!(lr.next_line().unwrap(), Some((1, "1 2")));
        let e = lr.next_line().unwrap_err().to_string();
        assert!(e.contains("t:2:") && e.contains("byte offset 5"), "{e}");
    }
}
