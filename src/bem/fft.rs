//! Two-dimensional real FFT filtering on an `ny × nx` row-major grid (rows = y, x fastest).
//!
//! The solver only ever needs "transform, multiply each Fourier coefficient, transform back"
//! (a periodic convolution), so that is the primitive, fused into three passes over memory:
//! 1. a real FFT of every row (`realfft`: `nxc = nx/2 + 1` coefficients per row);
//! 2. for each strip of `STRIP` adjacent kx columns: gather the strip (a small transpose that
//!    stays in cache), complex FFTs of length `ny` along y, the caller's multiplier on every
//!    column (kx fixed, all ky in wrap-around order), inverse FFTs, and a write-out in
//!    strip-major order;
//! 3. a gather of every row from the strips and an inverse real FFT.
//!
//! There is no full transpose and no full spectrum array: two half-spectrum buffers (rows and
//! strips) and the real fields, so memory is O(nx·ny). Rows and strips are processed in
//! parallel with rayon. Transforms are unnormalised: the multiplier carries the 1/(nx·ny).

use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

/// Columns per strip: 8 complex values (128 bytes) per row read, strip buffer of
/// 8·ny complex values (128 KiB at ny = 1024, inside L2).
const STRIP: usize = 8;

/// Rows of at most this many elements go to one rayon task (keeps task overhead small).
const CHUNK_ELEMS: usize = 1 << 14;

const ZERO: Complex64 = Complex64::new(0.0, 0.0);

/// A planned 2D real FFT filter on a fixed grid.
pub(crate) struct Fft2 {
    nx: usize,
    ny: usize,
    nxc: usize,
    row_fwd: Arc<dyn RealToComplex<f64>>,
    row_inv: Arc<dyn ComplexToReal<f64>>,
    col_fwd: Arc<dyn Fft<f64>>,
    col_inv: Arc<dyn Fft<f64>>,
    /// Row spectra, `ny × nxc` row-major.
    rows: Vec<Complex64>,
    /// Filtered spectra, strip-major: strip s (columns s·STRIP.., width w) holds (y, j) at
    /// `s·STRIP·ny + y·w + j`.
    strips: Vec<Complex64>,
}

impl Fft2 {
    pub(crate) fn new(nx: usize, ny: usize) -> Self {
        let mut rp = RealFftPlanner::<f64>::new();
        let mut cp = FftPlanner::<f64>::new();
        let nxc = nx / 2 + 1;
        Self {
            nx,
            ny,
            nxc,
            row_fwd: rp.plan_fft_forward(nx),
            row_inv: rp.plan_fft_inverse(nx),
            col_fwd: cp.plan_fft_forward(ny),
            col_inv: cp.plan_fft_inverse(ny),
            rows: vec![ZERO; ny * nxc],
            strips: vec![ZERO; ny * nxc],
        }
    }

    /// `output = IFFT(m · FFT(input))`, unnormalised, where `multiply(kx, column)` is applied to
    /// every half-spectrum column kx in `0..nxc` (the slice runs over ky in `0..ny`,
    /// wrap-around order). The result must be the spectrum of a real field (Hermitian); the
    /// imaginary parts a real field cannot carry (kx = 0 and, for even nx, kx = nx/2, after the
    /// y transforms) are dropped.
    pub(crate) fn filter<M>(&mut self, input: &[f64], output: &mut [f64], multiply: M)
    where
        M: Fn(usize, &mut [Complex64]) + Sync,
    {
        self.filter_scaled(input, 1.0, output, multiply);
    }

    /// [`Self::filter`] of `scale · input`, the scaling done as the rows are read (the same
    /// values as filtering a scaled copy, without the pass over memory that makes it).
    pub(crate) fn filter_scaled<M>(
        &mut self,
        input: &[f64],
        scale: f64,
        output: &mut [f64],
        multiply: M,
    ) where
        M: Fn(usize, &mut [Complex64]) + Sync,
    {
        debug_assert_eq!(output.len(), self.nx * self.ny);
        self.row_pass(input, scale);
        let (ny, nxc) = (self.ny, self.nxc);
        let rows = &self.rows;
        let (col_fwd, col_inv) = (&self.col_fwd, &self.col_inv);
        let scratch_len = col_fwd
            .get_inplace_scratch_len()
            .max(col_inv.get_inplace_scratch_len());
        self.strips
            .par_chunks_mut(STRIP * ny)
            .enumerate()
            .for_each_init(
                || (vec![ZERO; STRIP * ny], vec![ZERO; scratch_len]),
                |(buf, scratch), (s, out)| {
                    let c0 = s * STRIP;
                    let w = out.len() / ny;
                    let buf = &mut buf[..w * ny];
                    gather_strip(rows, nxc, ny, c0, w, buf);
                    if ny > 1 {
                        col_fwd.process_with_scratch(buf, scratch);
                    }
                    for (j, col) in buf.chunks_exact_mut(ny).enumerate() {
                        multiply(c0 + j, col);
                    }
                    if ny > 1 {
                        col_inv.process_with_scratch(buf, scratch);
                    }
                    for y in 0..ny {
                        for (j, o) in out[y * w..(y + 1) * w].iter_mut().enumerate() {
                            *o = buf[j * ny + y];
                        }
                    }
                },
            );
        let (nx, even) = (self.nx, self.nx.is_multiple_of(2));
        let strips = &self.strips;
        let row_inv = &self.row_inv;
        let per_task = rows_per_chunk(nx);
        output
            .par_chunks_mut(nx * per_task)
            .enumerate()
            .for_each_init(
                || (vec![ZERO; nxc], row_inv.make_scratch_vec()),
                |(row, scratch), (ci, chunk)| {
                    for (k, orow) in chunk.chunks_exact_mut(nx).enumerate() {
                        let y = ci * per_task + k;
                        for (s, dst) in row.chunks_mut(STRIP).enumerate() {
                            let w = dst.len();
                            let base = s * STRIP * ny + y * w;
                            dst.copy_from_slice(&strips[base..base + w]);
                        }
                        row[0].im = 0.0;
                        if even {
                            row[nxc - 1].im = 0.0;
                        }
                        row_inv.process_with_scratch(row, orow, scratch).expect(
                            "lengths are fixed by the plan and constrained parts are zeroed",
                        );
                    }
                },
            );
    }

    /// Σ over half-spectrum columns of `visit(kx, column)` (column over ky, wrap-around order)
    /// of the unnormalised FFT of `input`.
    pub(crate) fn spectrum_sum<V>(&mut self, input: &[f64], visit: V) -> f64
    where
        V: Fn(usize, &[Complex64]) -> f64 + Sync,
    {
        self.row_pass(input, 1.0);
        let (ny, nxc) = (self.ny, self.nxc);
        let rows = &self.rows;
        let col_fwd = &self.col_fwd;
        (0..nxc.div_ceil(STRIP))
            .into_par_iter()
            .map(|s| {
                let c0 = s * STRIP;
                let w = STRIP.min(nxc - c0);
                let mut buf = vec![ZERO; w * ny];
                gather_strip(rows, nxc, ny, c0, w, &mut buf);
                if ny > 1 {
                    col_fwd.process(&mut buf);
                }
                buf.chunks_exact(ny)
                    .enumerate()
                    .map(|(j, col)| visit(c0 + j, col))
                    .sum::<f64>()
            })
            .sum()
    }

    /// Real FFT of every row of `scale · input` into `self.rows`.
    fn row_pass(&mut self, input: &[f64], scale: f64) {
        let (nx, nxc) = (self.nx, self.nxc);
        debug_assert_eq!(input.len(), nx * self.ny);
        let per_task = rows_per_chunk(nx);
        let row_fwd = &self.row_fwd;
        self.rows
            .par_chunks_mut(nxc * per_task)
            .zip(input.par_chunks(nx * per_task))
            .for_each_init(
                || (vec![0.0; nx], row_fwd.make_scratch_vec()),
                |(buf, scratch), (out, inp)| {
                    for (o, i) in out.chunks_exact_mut(nxc).zip(inp.chunks_exact(nx)) {
                        for (b, v) in buf.iter_mut().zip(i) {
                            *b = scale * v;
                        }
                        row_fwd
                            .process_with_scratch(buf, o, scratch)
                            .expect("buffer lengths are fixed when the plan is made");
                    }
                },
            );
    }
}

/// Copy columns `c0..c0 + w` of the `ny × nxc` row spectra into `buf`, column-major
/// (`buf[j * ny + y]`).
fn gather_strip(
    rows: &[Complex64],
    nxc: usize,
    ny: usize,
    c0: usize,
    w: usize,
    buf: &mut [Complex64],
) {
    for y in 0..ny {
        let src = &rows[y * nxc + c0..y * nxc + c0 + w];
        for (j, v) in src.iter().enumerate() {
            buf[j * ny + y] = *v;
        }
    }
}

fn rows_per_chunk(row_len: usize) -> usize {
    (CHUNK_ELEMS / row_len.max(1)).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Direct O(N²) DFT of one coefficient, the independent reference.
    fn dft(field: &[f64], nx: usize, ny: usize, kx: usize, ky: usize) -> Complex64 {
        let mut s = Complex64::new(0.0, 0.0);
        for y in 0..ny {
            for x in 0..nx {
                let ph = -2.0
                    * std::f64::consts::PI
                    * ((kx * x) as f64 / nx as f64 + (ky * y) as f64 / ny as f64);
                s += field[y * nx + x] * Complex64::new(ph.cos(), ph.sin());
            }
        }
        s
    }

    fn test_field(nx: usize, ny: usize) -> Vec<f64> {
        (0..nx * ny)
            .map(|i| ((i * 7919) % 101) as f64 / 50.0 - 1.0)
            .collect()
    }

    const SIZES: [(usize, usize); 6] = [(8, 6), (7, 5), (16, 1), (1, 9), (12, 12), (37, 20)];

    #[test]
    fn spectrum_matches_direct_dft() {
        for &(nx, ny) in &SIZES {
            let field = test_field(nx, ny);
            let mut plan = Fft2::new(nx, ny);
            // Visit each coefficient by weighting it with a distinct number: the sum of
            // Re(c)·a + Im(c)·b over all (kx, ky) must match the direct DFT's.
            let weight = |kx: usize, ky: usize| (1.0 + kx as f64 * 0.37, 0.5 + ky as f64 * 0.11);
            let got = plan.spectrum_sum(&field, |kx, col| {
                col.iter()
                    .enumerate()
                    .map(|(ky, c)| {
                        let (a, b) = weight(kx, ky);
                        c.re * a + c.im * b
                    })
                    .sum()
            });
            let mut want = 0.0;
            for kx in 0..nx / 2 + 1 {
                for ky in 0..ny {
                    let c = dft(&field, nx, ny, kx, ky);
                    let (a, b) = weight(kx, ky);
                    want += c.re * a + c.im * b;
                }
            }
            assert!(
                (got - want).abs() < 1e-11 * want.abs().max(1.0),
                "{nx}x{ny}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn identity_filter_round_trips_and_shift_filter_shifts() {
        for &(nx, ny) in &SIZES {
            let field = test_field(nx, ny);
            let mut plan = Fft2::new(nx, ny);
            let inv_n = 1.0 / (nx * ny) as f64;
            let mut back = vec![0.0; nx * ny];
            plan.filter(&field, &mut back, |_, col| {
                col.iter_mut().for_each(|c| *c *= inv_n)
            });
            for (a, b) in back.iter().zip(&field) {
                assert!((a - b).abs() < 1e-14, "{nx}x{ny}");
            }
            // Multiplying by e^{-i qx·dx} (a one-pixel shift in x, exact for any field when
            // the Nyquist column is real, i.e. odd nx) and by e^{-i qy·dy} in y.
            if nx % 2 == 1 && ny % 2 == 1 {
                plan.filter(&field, &mut back, |kx, col| {
                    for (ky, c) in col.iter_mut().enumerate() {
                        let ph = -2.0
                            * std::f64::consts::PI
                            * (kx as f64 / nx as f64 + ky as f64 / ny as f64);
                        *c *= Complex64::new(ph.cos(), ph.sin()) * inv_n;
                    }
                });
                for y in 0..ny {
                    for x in 0..nx {
                        let want = field[((y + ny - 1) % ny) * nx + (x + nx - 1) % nx];
                        assert!((back[y * nx + x] - want).abs() < 1e-13, "{nx}x{ny}");
                    }
                }
            }
        }
    }
}
