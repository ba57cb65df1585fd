//! Bounds-checked reading of binary instrument files. Every read names the file and the byte
//! offset when the file is too short, and a grid is checked against the bytes the file really
//! holds before anything is allocated for it: a header that claims 10⁹ × 10⁹ points is an
//! error, never an allocation.

use super::bad;
use crate::Error;
use std::path::Path;

/// A file's bytes with its path, for reads that fail with an error naming both.
#[derive(Clone, Copy)]
pub(crate) struct Bytes<'a> {
    path: &'a Path,
    data: &'a [u8],
}

impl<'a> Bytes<'a> {
    pub(crate) fn new(path: &'a Path, data: &'a [u8]) -> Self {
        Bytes { path, data }
    }

    pub(crate) fn len(&self) -> usize {
        self.data.len()
    }

    /// An input error naming the file.
    pub(crate) fn err(&self, msg: impl Into<String>) -> Error {
        bad(self.path, msg)
    }

    /// `n` bytes at `off`, or an error saying what was there to read and where the file ends.
    pub(crate) fn take(&self, off: usize, n: usize, what: &str) -> Result<&'a [u8], Error> {
        match off.checked_add(n) {
            Some(end) if end <= self.data.len() => Ok(&self.data[off..end]),
            _ => Err(self.err(format!(
                "truncated file: {what} at byte {off} needs {n} bytes, the file has {} bytes",
                self.data.len()
            ))),
        }
    }

    fn array<const N: usize>(&self, off: usize, what: &str) -> Result<[u8; N], Error> {
        let mut a = [0u8; N];
        a.copy_from_slice(self.take(off, N, what)?);
        Ok(a)
    }

    pub(crate) fn u8(&self, off: usize, what: &str) -> Result<u8, Error> {
        Ok(self.array::<1>(off, what)?[0])
    }

    pub(crate) fn u16_le(&self, off: usize, what: &str) -> Result<u16, Error> {
        self.array(off, what).map(u16::from_le_bytes)
    }

    pub(crate) fn u16_be(&self, off: usize, what: &str) -> Result<u16, Error> {
        self.array(off, what).map(u16::from_be_bytes)
    }

    pub(crate) fn i16_le(&self, off: usize, what: &str) -> Result<i16, Error> {
        self.array(off, what).map(i16::from_le_bytes)
    }

    pub(crate) fn i16_be(&self, off: usize, what: &str) -> Result<i16, Error> {
        self.array(off, what).map(i16::from_be_bytes)
    }

    pub(crate) fn u32_le(&self, off: usize, what: &str) -> Result<u32, Error> {
        self.array(off, what).map(u32::from_le_bytes)
    }

    pub(crate) fn u32_be(&self, off: usize, what: &str) -> Result<u32, Error> {
        self.array(off, what).map(u32::from_be_bytes)
    }

    pub(crate) fn i32_le(&self, off: usize, what: &str) -> Result<i32, Error> {
        self.array(off, what).map(i32::from_le_bytes)
    }

    pub(crate) fn u64_le(&self, off: usize, what: &str) -> Result<u64, Error> {
        self.array(off, what).map(u64::from_le_bytes)
    }

    pub(crate) fn f32_le(&self, off: usize, what: &str) -> Result<f64, Error> {
        self.array(off, what)
            .map(|b| f64::from(f32::from_le_bytes(b)))
    }

    pub(crate) fn f32_be(&self, off: usize, what: &str) -> Result<f64, Error> {
        self.array(off, what)
            .map(|b| f64::from(f32::from_be_bytes(b)))
    }

    pub(crate) fn f64_le(&self, off: usize, what: &str) -> Result<f64, Error> {
        self.array(off, what).map(f64::from_le_bytes)
    }

    /// `n` bytes at `off` as Latin-1 text, NULs and surrounding blanks removed.
    pub(crate) fn text(&self, off: usize, n: usize, what: &str) -> Result<String, Error> {
        Ok(latin1(self.take(off, n, what)?)
            .trim_matches(|c: char| c == '\0' || c.is_whitespace())
            .to_string())
    }

    /// The bytes of an `nx` × `ny` grid of `elsize`-byte values at `off`, after checking that
    /// the grid is not empty and that the file holds all of it.
    pub(crate) fn grid(
        &self,
        off: usize,
        nx: usize,
        ny: usize,
        elsize: usize,
        what: &str,
    ) -> Result<&'a [u8], Error> {
        if nx == 0 || ny == 0 {
            return Err(self.err(format!(
                "{what} at byte {off}: the header gives an empty grid ({nx} × {ny} points)"
            )));
        }
        let n = nx.checked_mul(ny).and_then(|n| n.checked_mul(elsize));
        let available = self.data.len().saturating_sub(off);
        match n {
            Some(n) if n <= available => Ok(&self.data[off..off + n]),
            _ => Err(self.err(format!(
                "{what} at byte {off}: the header gives {nx} × {ny} points of {elsize} bytes, \
                 but the file holds {available} bytes from there"
            ))),
        }
    }
}

/// Fixed-size values of `raw` converted by `f`, in file order.
pub(crate) fn decode<const N: usize>(raw: &[u8], f: impl Fn([u8; N]) -> f64) -> Vec<f64> {
    raw.chunks_exact(N)
        .map(|c| {
            let mut a = [0u8; N];
            a.copy_from_slice(c);
            f(a)
        })
        .collect()
}

/// Like [`decode`] for a map of `nx`-value rows, with the rows in reverse order (for files
/// that store the bottom line of the image first, or the top line last).
pub(crate) fn decode_flipped<const N: usize>(
    raw: &[u8],
    nx: usize,
    f: impl Fn([u8; N]) -> f64,
) -> Vec<f64> {
    raw.chunks_exact(nx * N)
        .rev()
        .flat_map(|row| decode(row, &f))
        .collect()
}

/// Latin-1 text (every byte one character), as instrument headers are written.
pub(crate) fn latin1(bytes: &[u8]) -> String {
    bytes.iter().map(|&b| char::from(b)).collect()
}

/// Metres per unit of a length unit as instrument files spell it (`~m` is the Nanoscope
/// spelling of µm), or None for a unit that is not a length.
pub(crate) fn length_unit(unit: &str) -> Option<f64> {
    Some(match unit.trim() {
        "m" => 1.0,
        "cm" => 1e-2,
        "mm" => 1e-3,
        "um" | "µm" | "μm" | "~m" | "micron" => 1e-6,
        "nm" => 1e-9,
        "Å" | "A" => 1e-10,
        "pm" => 1e-12,
        _ => return None,
    })
}

/// A pixel size that must be finite and positive; `what` says where it came from.
pub(crate) fn pixel_size(b: &Bytes, value: f64, what: &str) -> Result<f64, Error> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(b.err(format!(
            "{what} is {value}: expected a positive pixel size (the file has no lateral \
             calibration)"
        )))
    }
}
