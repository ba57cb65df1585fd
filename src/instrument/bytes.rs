//! Little-endian fields of binary instrument files, each read with a bounds check whose error
//! names the file, the byte offset and the field; and the size check made before a grid of
//! points is allocated.

use std::path::Path;

use super::bad;
use crate::Error;

/// A binary file's content, read field by field (little-endian).
pub(crate) struct Le<'a> {
    pub(crate) path: &'a Path,
    pub(crate) b: &'a [u8],
}

macro_rules! field {
    ($name:ident, $t:ty) => {
        pub(crate) fn $name(&self, at: usize, what: &str) -> Result<$t, Error> {
            let s = self.slice(at, std::mem::size_of::<$t>(), what)?;
            Ok(<$t>::from_le_bytes(
                s.try_into().expect("slice of the type's size"),
            ))
        }
    };
}

impl<'a> Le<'a> {
    /// `len` bytes at `at`, or an error naming the field and where the file ends.
    pub(crate) fn slice(&self, at: usize, len: usize, what: &str) -> Result<&'a [u8], Error> {
        at.checked_add(len)
            .and_then(|end| self.b.get(at..end))
            .ok_or_else(|| {
                bad(
                    self.path,
                    format!(
                        "byte {at}: {what} needs {len} bytes, the file ends at byte {} \
                         (truncated file?)",
                        self.b.len()
                    ),
                )
            })
    }

    field!(u16, u16);
    field!(i32, i32);
    field!(u32, u32);
    field!(f32, f32);
    field!(f64, f64);

    /// A fixed-size text field: up to the first NUL, trailing blanks removed (Latin-1 bytes
    /// such as `\xb5` for µ decoded as Latin-1).
    pub(crate) fn text(&self, at: usize, len: usize, what: &str) -> Result<String, Error> {
        let s = self.slice(at, len, what)?;
        let s = s.split(|&c| c == 0).next().unwrap_or_default();
        Ok(latin1(s).trim().to_string())
    }
}

/// Bytes as text: UTF-8 where valid, else Latin-1 (one char per byte).
pub(crate) fn latin1(b: &[u8]) -> String {
    match std::str::from_utf8(b) {
        Ok(s) => s.to_string(),
        Err(_) => b.iter().map(|&c| c as char).collect(),
    }
}

/// Number of points of an `nx` × `ny` grid of `width`-byte values starting at byte `at`,
/// checked against the `len` bytes available, before anything is allocated.
pub(crate) fn grid_points(
    path: &Path,
    nx: i64,
    ny: i64,
    width: usize,
    at: usize,
    len: usize,
) -> Result<usize, Error> {
    if nx < 1 || ny < 1 {
        return Err(bad(
            path,
            format!("the grid is {nx} × {ny} points (expected at least 1 × 1)"),
        ));
    }
    let need = (nx as u128) * (ny as u128) * width as u128;
    let have = len.saturating_sub(at) as u128;
    if need > have {
        return Err(bad(
            path,
            format!(
                "byte {at}: a grid of {nx} × {ny} points needs {need} bytes of data, the file \
                 has {have} (truncated file, or sizes in the header are wrong)"
            ),
        ));
    }
    Ok((nx * ny) as usize)
}
