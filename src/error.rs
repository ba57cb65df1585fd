//! The library's error type. `main` maps it to messages and exit codes in one place.

use std::path::PathBuf;

/// Errors of the library. Every variant is an input or numerical failure that the command
/// line reports with exit code 2.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A value outside its physical domain (names the quantity and what was expected).
    #[error("invalid {what}: {got} (expected {expected})")]
    Invalid {
        what: &'static str,
        got: String,
        expected: &'static str,
    },
    /// A malformed input file, with the line (1-based) where it went wrong.
    #[error("{}:{line}: {msg}", path.display())]
    Input {
        path: PathBuf,
        line: usize,
        msg: String,
    },
    /// A bad or missing value that has no file line: a command-line flag (`origin` is the
    /// flag) or a key missing from a scene (`origin` is the scene file).
    #[error("{origin}: {msg}")]
    Value { origin: String, msg: String },
    /// A file that could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    /// A computation that could not produce a trustworthy number.
    #[error("numerical failure in {what}: {detail}")]
    Numerical { what: &'static str, detail: String },
}

impl Error {
    pub fn invalid(
        what: &'static str,
        got: impl std::fmt::Display,
        expected: &'static str,
    ) -> Self {
        Error::Invalid {
            what,
            got: got.to_string(),
            expected,
        }
    }
}
