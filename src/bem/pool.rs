//! Work buffers kept from solve to solve.
//!
//! The periodic solver's full-grid work fields (the direction, the responses, the Green
//! function, the FFT half spectra, …) are as large as the grid, and glibc serves blocks of
//! 128 KiB and more by `mmap` and unmaps them when they are freed, so a buffer allocated afresh
//! is first written through one page fault per page again. A buffer taken from a [`Pool`] is
//! given back when dropped and kept (up to [`KEEP_BYTES`] over all pools) for the next one of
//! its type: the coarse levels of a solve use the start of the buffers of the grid solved
//! before, and the next solve of a run (the thickness search of `check --verify`, the runs of a
//! benchmark) and the interface fields reuse those of the last solve. Only the memory is
//! reused: [`Pool::take`] fills the buffer with the value asked for, as `vec!` would.

use rustfft::num_complex::Complex;
use std::ops::{Deref, DerefMut};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Bytes kept over all pools at most (a quarter of the 2 GB a 4096² solve may use, so what is
/// kept never takes a solve or the fields it is followed by over it).
const KEEP_BYTES: usize = 512 << 20;

/// Bytes kept now, over all pools.
static KEPT: AtomicUsize = AtomicUsize::new(0);

/// Buffers of one element type that are not in use.
pub(crate) struct Pool<T: 'static> {
    kept: Mutex<Vec<Vec<T>>>,
}

pub(crate) static F64: Pool<f64> = Pool::new();
pub(crate) static F32: Pool<f32> = Pool::new();
pub(crate) static BOOL: Pool<bool> = Pool::new();
pub(crate) static C64: Pool<Complex<f64>> = Pool::new();
pub(crate) static C32: Pool<Complex<f32>> = Pool::new();

/// Bytes of a buffer's allocation.
fn bytes<T>(v: &Vec<T>) -> usize {
    v.capacity() * size_of::<T>()
}

impl<T: Copy> Pool<T> {
    const fn new() -> Self {
        Self {
            kept: Mutex::new(Vec::new()),
        }
    }

    /// A buffer of `n` values `fill`: the kept one of the smallest capacity that holds them, or
    /// else the largest kept one (grown) or a new one.
    pub(crate) fn take(&'static self, n: usize, fill: T) -> Buf<T> {
        let mut v = self
            .kept
            .lock()
            .ok()
            .and_then(|mut kept| {
                let fits = kept
                    .iter()
                    .enumerate()
                    .filter(|(_, v)| v.capacity() >= n)
                    .min_by_key(|(_, v)| v.capacity())
                    .map(|(i, _)| i);
                let largest = || {
                    kept.iter()
                        .enumerate()
                        .max_by_key(|(_, v)| v.capacity())
                        .map(|(i, _)| i)
                };
                let i = fits.or_else(largest)?;
                Some(kept.swap_remove(i))
            })
            .unwrap_or_default();
        KEPT.fetch_sub(bytes(&v), Ordering::Relaxed);
        v.clear();
        v.resize(n, fill);
        Buf { pool: self, v }
    }
}

/// A buffer taken from a [`Pool`], given back when dropped (kept if the pools' total stays
/// within [`KEEP_BYTES`], freed otherwise).
pub(crate) struct Buf<T: 'static> {
    pool: &'static Pool<T>,
    v: Vec<T>,
}

impl<T> Deref for Buf<T> {
    type Target = [T];

    fn deref(&self) -> &[T] {
        &self.v
    }
}

impl<T> DerefMut for Buf<T> {
    fn deref_mut(&mut self) -> &mut [T] {
        &mut self.v
    }
}

impl<T> Drop for Buf<T> {
    fn drop(&mut self) {
        let v = std::mem::take(&mut self.v);
        let size = bytes(&v);
        if size == 0 {
            return;
        }
        let room = KEPT.fetch_update(Ordering::Relaxed, Ordering::Relaxed, |kept| {
            (kept + size <= KEEP_BYTES).then_some(kept + size)
        });
        if room.is_ok() {
            match self.pool.kept.lock() {
                Ok(mut kept) => kept.push(v),
                Err(_) => {
                    KEPT.fetch_sub(size, Ordering::Relaxed);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    static TEST: Pool<u64> = Pool::new();

    #[test]
    fn buffers_are_refilled_and_their_memory_reused() {
        let mut a = TEST.take(1000, 7);
        assert!(a.iter().all(|&v| v == 7));
        a[3] = 9;
        let at = a.as_ptr();
        drop(a);
        // The kept buffer serves a smaller request, filled afresh.
        let b = TEST.take(10, 0);
        assert_eq!(b.as_ptr(), at);
        assert_eq!(&b[..], &[0; 10]);
        // A larger one while it is in use is a new buffer.
        let c = TEST.take(2000, 1);
        assert_ne!(c.as_ptr(), at);
        assert_eq!(c.len(), 2000);
    }
}
