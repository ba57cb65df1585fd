//! TOML input helpers shared by the materials library and the scene: values that are numbers or
//! strings with units, where they came from (file line or command-line flag), and errors that
//! name the file, the line and the key on one line.

use crate::error::Error;
use crate::units::{Dim, parse_quantity};
use serde::Deserialize;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// A raw value: a TOML number, a boolean, a string (usually a number with a unit) or a list of
/// strings.
#[derive(Debug, Clone, PartialEq)]
pub enum Raw {
    Number(f64),
    Bool(bool),
    Text(String),
    List(Vec<String>),
}

/// What a [`Raw`] value may be, as a type error says it ("invalid type: boolean `true`,
/// expected …").
const RAW_EXPECTED: &str = "a number, a boolean, a string such as \"10 um\" or a list of strings";

impl<'de> Deserialize<'de> for Raw {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visit;
        impl<'de> serde::de::Visitor<'de> for Visit {
            type Value = Raw;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(RAW_EXPECTED)
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<Raw, E> {
                Ok(Raw::Number(v))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<Raw, E> {
                Ok(Raw::Number(v as f64))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<Raw, E> {
                Ok(Raw::Number(v as f64))
            }
            fn visit_bool<E: serde::de::Error>(self, v: bool) -> Result<Raw, E> {
                Ok(Raw::Bool(v))
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Raw, E> {
                Ok(Raw::Text(v.to_string()))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Raw, A::Error> {
                let mut list = Vec::new();
                while let Some(item) = seq.next_element::<ListItem>()? {
                    list.push(item.0);
                }
                Ok(Raw::List(list))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Raw, A::Error> {
                // The toml crate hands a date-time over as a map with this one private key.
                let what = match map.next_key::<String>()? {
                    Some(k) if k == "$__toml_private_datetime" => "a date-time",
                    _ => "a table",
                };
                Err(serde::de::Error::invalid_type(
                    serde::de::Unexpected::Other(what),
                    &self,
                ))
            }
        }
        d.deserialize_any(Visit)
    }
}

/// One entry of a [`Raw::List`]: a string, with a type error that says so.
struct ListItem(String);

impl<'de> Deserialize<'de> for ListItem {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visit;
        impl serde::de::Visitor<'_> for Visit {
            type Value = ListItem;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a list of strings (each entry in quotes) or numbers")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<ListItem, E> {
                Ok(ListItem(v.to_string()))
            }
            // A number in a list (a range's end, `[0.499, 0.4999]`) is kept as its shortest
            // round-trip text, read back exactly by the unit parser.
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<ListItem, E> {
                Ok(ListItem(format!("{v:e}")))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<ListItem, E> {
                Ok(ListItem(v.to_string()))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<ListItem, E> {
                Ok(ListItem(v.to_string()))
            }
        }
        d.deserialize_any(Visit)
    }
}

/// Where a value came from.
#[derive(Debug, Clone, PartialEq)]
pub enum Origin {
    /// A byte range in the TOML file being read.
    File(Range<usize>),
    /// A command-line flag (e.g. `--thickness`).
    Flag(&'static str),
}

/// A value with its origin.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    pub raw: Raw,
    pub origin: Origin,
}

impl<'de> Deserialize<'de> for Field {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = toml::Spanned::<Raw>::deserialize(d)?;
        Ok(Field {
            origin: Origin::File(s.span()),
            raw: s.into_inner(),
        })
    }
}

impl Field {
    /// A value given on the command line.
    pub fn flag(flag: &'static str, text: &str) -> Self {
        Field {
            raw: Raw::Text(text.to_string()),
            origin: Origin::Flag(flag),
        }
    }

    pub fn is_flag(&self) -> bool {
        matches!(self.origin, Origin::Flag(_))
    }
}

/// A TOML source being read: its path and text (to turn byte offsets into line numbers).
pub struct Source<'a> {
    pub path: &'a Path,
    pub text: &'a str,
}

impl Source<'_> {
    /// 1-based line of a byte offset.
    pub fn line_of(&self, offset: usize) -> usize {
        let end = offset.min(self.text.len());
        1 + self.text.as_bytes()[..end]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
    }

    /// An input error at a byte offset.
    pub fn error_at(&self, offset: usize, msg: String) -> Error {
        Error::Input {
            path: self.path.to_path_buf(),
            line: self.line_of(offset),
            msg,
        }
    }

    /// Parse the text into `T`, turning TOML and serde errors (unknown keys, wrong types,
    /// syntax) into one-line [`Error::Input`]s with the line of the offending key.
    pub fn parse<T: serde::de::DeserializeOwned>(&self) -> Result<T, Error> {
        toml::from_str(self.text).map_err(|e| {
            let line = e.span().map(|s| self.line_of(s.start)).unwrap_or(1);
            let mut msg = one_line(e.message());
            // The TOML parser's "duplicate key" names no key: its span does.
            if msg == "duplicate key"
                && let Some(key) = e.span().and_then(|s| self.text.get(s))
            {
                msg = format!("duplicate key `{}`", one_line(key));
            } else if msg.starts_with("invalid ")
                && let Some(key) = key_path(e)
            {
                msg = format!("{key}: {msg}");
            }
            Error::Input {
                path: self.path.to_path_buf(),
                line,
                msg,
            }
        })
    }
}

/// The dotted key a deserialisation error is about (`film.thickness`), if it names one: the
/// message of a type or value error ("invalid type: …") leaves it out, and its `Display` states it (as "in `KEY`") only without
/// the source text.
fn key_path(mut e: toml::de::Error) -> Option<String> {
    e.set_input(None);
    let text = e.to_string();
    let key = text
        .lines()
        .rev()
        .find_map(|l| l.strip_prefix("in `")?.strip_suffix('`'))?;
    (!key.is_empty()).then(|| key.to_string())
}

/// Collapse a multi-line message into one line.
pub fn one_line(msg: &str) -> String {
    msg.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Context for reporting errors about fields: the scene or material file (if any).
#[derive(Clone, Copy)]
pub struct Ctx<'a> {
    pub file: Option<&'a Source<'a>>,
}

impl Ctx<'_> {
    /// An error about `key` (e.g. `film.thickness`) given at `origin`.
    pub fn error(&self, origin: &Origin, key: &str, msg: impl std::fmt::Display) -> Error {
        match (origin, self.file) {
            (Origin::File(span), Some(src)) => src.error_at(span.start, format!("{key}: {msg}")),
            (Origin::Flag(flag), _) => Error::Value {
                origin: flag.to_string(),
                msg: format!("{key}: {msg}"),
            },
            (Origin::File(_), None) => Error::Value {
                origin: "scene".into(),
                msg: format!("{key}: {msg}"),
            },
        }
    }

    /// The error for a required key that is missing.
    pub fn missing(&self, key: &str, hint: &str) -> Error {
        Error::Value {
            origin: match self.file {
                Some(src) => src.path.display().to_string(),
                None => "scene".into(),
            },
            msg: format!("{key} is missing; {hint}"),
        }
    }

    /// A physical value: a number (SI) or a string with a unit of dimension `dim`.
    pub fn quantity(&self, f: &Field, key: &str, dim: Dim) -> Result<f64, Error> {
        let v = match &f.raw {
            Raw::Number(x) => *x,
            Raw::Text(t) => parse_quantity(t, dim)
                .map_err(|e| self.error(&f.origin, key, format!("{e} (expected {dim})")))?,
            Raw::List(_) => {
                return Err(self.error(
                    &f.origin,
                    key,
                    format!("got a list (expected {dim}, e.g. a string like \"1 MPa\")"),
                ));
            }
            Raw::Bool(b) => {
                return Err(self.error(&f.origin, key, format!("got {b} (expected {dim})")));
            }
        };
        if !v.is_finite() {
            return Err(self.error(&f.origin, key, format!("{v} is not finite")));
        }
        Ok(v)
    }

    /// A physical value that must be > 0.
    pub fn positive(&self, f: &Field, key: &str, dim: Dim) -> Result<f64, Error> {
        let v = self.quantity(f, key, dim)?;
        if v <= 0.0 {
            return Err(self.error(&f.origin, key, format!("{v:e} (expected a value > 0)")));
        }
        Ok(v)
    }

    /// A string value.
    pub fn text<'f>(&self, f: &'f Field, key: &str) -> Result<&'f str, Error> {
        match &f.raw {
            Raw::Text(t) => Ok(t),
            _ => Err(self.error(&f.origin, key, "expected a string")),
        }
    }

    /// A yes/no value: a TOML boolean, or `true`/`false` from a flag.
    pub fn boolean(&self, f: &Field, key: &str) -> Result<bool, Error> {
        match &f.raw {
            Raw::Bool(b) => Ok(*b),
            Raw::Text(t) if t.trim().eq_ignore_ascii_case("true") => Ok(true),
            Raw::Text(t) if t.trim().eq_ignore_ascii_case("false") => Ok(false),
            _ => Err(self.error(&f.origin, key, "expected true or false")),
        }
    }

    /// A list of strings (a TOML array, or a comma-separated string from a flag).
    pub fn list(&self, f: &Field, key: &str) -> Result<Vec<String>, Error> {
        match &f.raw {
            Raw::List(v) => Ok(v.clone()),
            Raw::Text(t) => Ok(t
                .split(',')
                .map(|s| s.trim().to_string())
                .filter(|s| !s.is_empty())
                .collect()),
            Raw::Number(_) | Raw::Bool(_) => {
                Err(self.error(&f.origin, key, "expected a list of names"))
            }
        }
    }

    /// Two physical values `[min, max]`: a TOML list of two numbers (SI) or strings with units,
    /// or `min,max` from a flag; min ≤ max.
    pub fn pair(&self, f: &Field, key: &str, dim: Dim) -> Result<(f64, f64), Error> {
        let items = match &f.raw {
            Raw::List(v) => v.clone(),
            Raw::Text(t) => t.split(',').map(|s| s.trim().to_string()).collect(),
            Raw::Number(_) | Raw::Bool(_) => Vec::new(),
        };
        let [lo, hi] = items.as_slice() else {
            return Err(self.error(
                &f.origin,
                key,
                format!(
                    "expected a range [min, max] of two values ({dim}, e.g. [\"4 MPa\", \"8 MPa\"])"
                ),
            ));
        };
        let at = |t: &String| {
            parse_quantity(t, dim)
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    self.error(
                        &f.origin,
                        key,
                        format!("'{t}' is not a finite value ({dim})"),
                    )
                })
        };
        let (lo, hi) = (at(lo)?, at(hi)?);
        if lo > hi {
            return Err(self.error(
                &f.origin,
                key,
                format!("min {lo:e} > max {hi:e} (expected [min, max])"),
            ));
        }
        Ok((lo, hi))
    }

    /// A path given in the file is relative to the file's directory; one from a flag is
    /// relative to the working directory.
    pub fn path(&self, f: &Field, key: &str) -> Result<PathBuf, Error> {
        let t = PathBuf::from(self.text(f, key)?);
        Ok(match (&f.origin, self.file) {
            (Origin::File(_), Some(src)) if t.is_relative() => {
                src.path.parent().map(|dir| dir.join(&t)).unwrap_or(t)
            }
            _ => t,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_counted_from_one() {
        let src = Source {
            path: Path::new("x.toml"),
            text: "a = 1\nb = 2\n\nc = 3",
        };
        assert_eq!(src.line_of(0), 1);
        assert_eq!(src.line_of(6), 2);
        assert_eq!(src.line_of(13), 4);
    }

    #[test]
    fn quantities_accept_numbers_and_units() {
        let ctx = Ctx { file: None };
        let f = Field::flag("--pressure", "0.1 MPa");
        assert_eq!(
            ctx.quantity(&f, "load.pressure", Dim::Pressure).unwrap(),
            1e5
        );
        let n = Field {
            raw: Raw::Number(2e11),
            origin: Origin::Flag("--x"),
        };
        assert_eq!(ctx.quantity(&n, "x", Dim::Pressure).unwrap(), 2e11);
        let bad = Field::flag("--pressure", "-1 MPa");
        let e = ctx
            .positive(&bad, "load.pressure", Dim::Pressure)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("--pressure") && e.contains("load.pressure"),
            "{e}"
        );
        let inf = Field::flag("--pressure", "inf");
        assert!(ctx.quantity(&inf, "load.pressure", Dim::Pressure).is_err());
    }
}
