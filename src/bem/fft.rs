//! Two-dimensional real FFT filtering on an `ny × nx` row-major grid (rows = y, x fastest).
//!
//! The solver only ever needs "transform, multiply each Fourier coefficient, transform back"
//! (a periodic convolution), so that is the primitive, fused into three passes over memory:
//! 1. a real FFT of every row (`realfft`: `nxc = nx/2 + 1` coefficients per row), written into
//!    strips of `width` adjacent kx columns (strip-major, rows of a strip contiguous);
//! 2. for each strip: a transpose into a buffer that stays in cache, and for each of its
//!    columns a complex FFT of length `ny` along y, the caller's multiplier (kx fixed, all ky in
//!    wrap-around order) and the inverse FFT; the strip is written back in place;
//! 3. a gather of every row from the strips and an inverse real FFT.
//!
//! There is no full transpose: every pass over the half-spectrum reads or writes runs of
//! `width` values, and consecutive rows of a strip are adjacent, so the large-grid passes walk
//! memory in order within each strip. One half-spectrum buffer and the real fields: memory is
//! O(nx·ny). Rows and strips are processed in parallel with rayon. Transforms are
//! unnormalised: the multiplier carries the 1/(nx·ny).

use super::pool::{self, Buf, Pool};
use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex;
use rustfft::num_traits::Zero;
use rustfft::{Fft, FftNum, FftPlanner};
use std::sync::{Arc, Mutex};

/// Target size of a strip (bytes): its transpose buffer stays in a core's L2 cache.
const STRIP_BYTES: usize = 1 << 18;

/// Pad between the columns of a strip's transpose buffer (complex values: one cache line).
const COLUMN_PAD: usize = 4;

/// Columns summed together first by [`Fft2::spectrum_sum`].
const SUM_GROUP: usize = 8;

/// Rows of at most this many elements go to one rayon task (keeps task overhead small).
const CHUNK_ELEMS: usize = 1 << 14;

/// The float type a plan transforms in: `f64`, or `f32` where single precision is enough (the
/// fields read and written are `f64` either way, converted as the rows are read and written).
pub(crate) trait Real: FftNum {
    /// `v` rounded to this type.
    fn of(v: f64) -> Self;

    /// `dst ← src`, rounded to this type.
    fn load(src: &[f64], dst: &mut [Self]);

    /// The row an inverse row transform writes to: the output row itself for `f64`, else
    /// `tmp`, whose values [`Real::store`] then writes to the output row.
    fn out_row<'a>(out: &'a mut [f64], tmp: &'a mut [Self]) -> &'a mut [Self];

    /// `out ← tmp` after a transform into [`Real::out_row`] (nothing to do for `f64`).
    fn store(tmp: &[Self], out: &mut [f64]);

    /// The pool the half spectra of plans in this type are taken from.
    fn spectra() -> &'static Pool<Complex<Self>>;
}

impl Real for f64 {
    fn of(v: f64) -> Self {
        v
    }

    fn load(src: &[f64], dst: &mut [Self]) {
        dst.copy_from_slice(src);
    }

    fn out_row<'a>(out: &'a mut [f64], _: &'a mut [Self]) -> &'a mut [Self] {
        out
    }

    fn store(_: &[Self], _: &mut [f64]) {}

    fn spectra() -> &'static Pool<Complex<Self>> {
        &pool::C64
    }
}

impl Real for f32 {
    fn of(v: f64) -> Self {
        v as f32
    }

    fn load(src: &[f64], dst: &mut [Self]) {
        for (d, s) in dst.iter_mut().zip(src) {
            *d = *s as f32;
        }
    }

    fn out_row<'a>(_: &'a mut [f64], tmp: &'a mut [Self]) -> &'a mut [Self] {
        tmp
    }

    fn store(tmp: &[Self], out: &mut [f64]) {
        for (o, t) in out.iter_mut().zip(tmp) {
            *o = f64::from(*t);
        }
    }

    fn spectra() -> &'static Pool<Complex<Self>> {
        &pool::C32
    }
}

fn zero<T: Real>() -> Complex<T> {
    Complex::zero()
}

/// A planned 2D real FFT filter on a fixed grid, transforming in `T`.
pub(crate) struct Fft2<T: Real = f64> {
    nx: usize,
    ny: usize,
    nxc: usize,
    /// Columns per strip.
    width: usize,
    /// Elements from one strip's start to the next: `width·ny` and a pad of `width`, so that
    /// the runs a row has in the different strips do not fall into the same cache sets.
    stride: usize,
    row_fwd: Arc<dyn RealToComplex<T>>,
    row_inv: Arc<dyn ComplexToReal<T>>,
    col_fwd: Arc<dyn Fft<T>>,
    col_inv: Arc<dyn Fft<T>>,
    /// Half spectrum, strip-major: strip s (columns s·width.., width w) holds (y, j) at
    /// `s·stride + y·w + j`.
    spec: Buf<Complex<T>>,
    /// Work buffers of the parallel tasks, kept from call to call (see [`Lease`]).
    pool: Mutex<Vec<Work<T>>>,
}

/// One task's work buffers: a real row, a block of [`rows_per_chunk`] half-spectrum rows, a
/// strip's transpose buffer and the transforms' scratch (their contents never carry over).
struct Work<T> {
    row: Vec<T>,
    block: Vec<Complex<T>>,
    cols: Vec<Complex<T>>,
    scratch: Vec<Complex<T>>,
}

/// The lengths of the buffers of a [`Work`].
#[derive(Clone, Copy)]
struct WorkShape {
    row: usize,
    block: usize,
    cols: usize,
    scratch: usize,
}

impl WorkShape {
    fn make<T: Real>(self) -> Work<T> {
        Work {
            row: vec![T::zero(); self.row],
            block: vec![zero(); self.block],
            cols: vec![zero(); self.cols],
            scratch: vec![zero(); self.scratch],
        }
    }
}

/// A [`Work`] taken from a plan's pool for one rayon task (made if the pool is empty) and
/// returned to it when the task ends, so that the buffers are allocated and first written once
/// per thread and plan, not once per task and call.
struct Lease<'a, T> {
    pool: &'a Mutex<Vec<Work<T>>>,
    work: Option<Work<T>>,
}

impl<'a, T: Real> Lease<'a, T> {
    fn take(pool: &'a Mutex<Vec<Work<T>>>, make: impl FnOnce() -> Work<T>) -> Self {
        let work = pool.lock().ok().and_then(|mut p| p.pop());
        Self {
            pool,
            work: Some(work.unwrap_or_else(make)),
        }
    }

    fn get(&mut self) -> &mut Work<T> {
        self.work
            .as_mut()
            .expect("a lease holds its work until dropped")
    }
}

impl<T> Drop for Lease<'_, T> {
    fn drop(&mut self) {
        if let (Some(work), Ok(mut pool)) = (self.work.take(), self.pool.lock()) {
            pool.push(work);
        }
    }
}

impl<T: Real> Fft2<T> {
    /// Row length (the grid's nx).
    pub(crate) fn nx(&self) -> usize {
        self.nx
    }

    pub(crate) fn new(nx: usize, ny: usize) -> Self {
        Self::with_width(
            nx,
            ny,
            (STRIP_BYTES / (size_of::<Complex<T>>() * ny.max(1))).clamp(8, 64),
        )
    }

    /// A plan with `width` columns per strip (≥ 1; the results do not depend on it).
    fn with_width(nx: usize, ny: usize, width: usize) -> Self {
        let mut rp = RealFftPlanner::<T>::new();
        let mut cp = FftPlanner::<T>::new();
        let nxc = nx / 2 + 1;
        Self {
            nx,
            ny,
            nxc,
            width,
            stride: width * ny + width,
            row_fwd: rp.plan_fft_forward(nx),
            row_inv: rp.plan_fft_inverse(nx),
            col_fwd: cp.plan_fft_forward(ny),
            col_inv: cp.plan_fft_inverse(ny),
            spec: T::spectra().take(nxc.div_ceil(width) * (width * ny + width), zero()),
            pool: Mutex::new(Vec::new()),
        }
    }

    /// The lengths of a task's work buffers (see [`Work`]).
    fn work_shape(&self) -> WorkShape {
        WorkShape {
            row: self.nx,
            block: self.nxc * rows_per_chunk(self.nx),
            cols: self.width * (self.ny + COLUMN_PAD),
            scratch: self
                .row_fwd
                .get_scratch_len()
                .max(self.row_inv.get_scratch_len())
                .max(self.col_fwd.get_inplace_scratch_len())
                .max(self.col_inv.get_inplace_scratch_len()),
        }
    }

    /// `output = IFFT(m · FFT(input))`, unnormalised, where `multiply(kx, column)` is applied to
    /// every half-spectrum column kx in `0..nxc` (the slice runs over ky in `0..ny`,
    /// wrap-around order). The result must be the spectrum of a real field (Hermitian); the
    /// imaginary parts a real field cannot carry (kx = 0 and, for even nx, kx = nx/2, after the
    /// y transforms) are dropped.
    pub(crate) fn filter<M>(&mut self, input: &[f64], output: &mut [f64], multiply: M)
    where
        M: Fn(usize, &mut [Complex<T>]) + Sync,
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
        M: Fn(usize, &mut [Complex<T>]) + Sync,
    {
        self.filter_scaled_then(input, scale, output, multiply, |_, _, _| []);
    }

    /// [`Self::filter_scaled`], then `finish(y, input_row, output_row)` on every output row while
    /// it is in cache (it may rewrite the row); returns `finish`'s results, one per row in row
    /// order.
    pub(crate) fn filter_scaled_then<M, F, const B: usize>(
        &mut self,
        input: &[f64],
        scale: f64,
        output: &mut [f64],
        multiply: M,
        finish: F,
    ) -> Vec<[f64; B]>
    where
        M: Fn(usize, &mut [Complex<T>]) + Sync,
        F: Fn(usize, &[f64], &mut [f64]) -> [f64; B] + Sync,
    {
        debug_assert_eq!(output.len(), self.nx * self.ny);
        let nx = self.nx;
        self.row_pass(
            input.par_chunks(nx * rows_per_chunk(nx)),
            |chunk: &mut &[f64], k, _, buf| {
                for (b, v) in buf.iter_mut().zip(&chunk[k * nx..(k + 1) * nx]) {
                    *b = T::of(scale * v);
                }
                []
            },
        );
        self.column_pass(multiply);
        self.inverse_row_pass(input, output, finish)
    }

    /// [`Self::filter`] of `input` after `prepare(y, row)` has rewritten each of its rows in
    /// place (as the row is read for its transform), then `finish(y, input_row, output_row)` on
    /// every output row while it is in cache, `finish` being made by `make_finish` from the sums
    /// over the rows (in row order) of `prepare`'s results. Returns those sums and `finish`'s
    /// results, one per row in row order: the same values as `prepare` over the rows, the filter
    /// and `finish` over the rows as separate passes, in one pass over each field.
    pub(crate) fn filter_rows<P, M, G, F, const A: usize, const B: usize>(
        &mut self,
        input: &mut [f64],
        prepare: P,
        output: &mut [f64],
        multiply: M,
        make_finish: G,
    ) -> ([f64; A], Vec<[f64; B]>)
    where
        P: Fn(usize, &mut [f64]) -> [f64; A] + Sync,
        M: Fn(usize, &mut [Complex<T>]) + Sync,
        G: FnOnce([f64; A]) -> F,
        F: Fn(usize, &[f64], &mut [f64]) -> [f64; B] + Sync,
    {
        debug_assert_eq!(output.len(), self.nx * self.ny);
        let nx = self.nx;
        let prepared = self.row_pass(
            input.par_chunks_mut(nx * rows_per_chunk(nx)),
            |chunk: &mut &mut [f64], k, y, buf| {
                let row = &mut chunk[k * nx..(k + 1) * nx];
                let out = prepare(y, row);
                T::load(row, buf);
                out
            },
        );
        let mut sums = [0.0; A];
        for row in &prepared {
            for (s, v) in sums.iter_mut().zip(row) {
                *s += v;
            }
        }
        self.column_pass(multiply);
        let finished = self.inverse_row_pass(input, output, make_finish(sums));
        (sums, finished)
    }

    /// Σ over half-spectrum columns of `visit(kx, column)` (column over ky, wrap-around order)
    /// of the unnormalised FFT of `input`.
    pub(crate) fn spectrum_sum<V>(&mut self, input: &[f64], visit: V) -> f64
    where
        V: Fn(usize, &[Complex<T>]) -> f64 + Sync,
    {
        let nx = self.nx;
        self.row_pass(
            input.par_chunks(nx * rows_per_chunk(nx)),
            |chunk: &mut &[f64], k, _, buf| {
                T::load(&chunk[k * nx..(k + 1) * nx], buf);
                []
            },
        );
        let (ny, nxc, width) = (self.ny, self.nxc, self.width);
        let col_fwd = &self.col_fwd;
        let columns: Vec<f64> = self
            .spec
            .par_chunks(self.stride)
            .enumerate()
            .flat_map_iter(|(s, strip)| {
                let w = width.min(nxc - s * width);
                let mut buf = vec![zero(); w * ny];
                transpose(&strip[..w * ny], w, ny, ny, &mut buf);
                if ny > 1 {
                    col_fwd.process(&mut buf);
                }
                buf.chunks_exact(ny)
                    .enumerate()
                    .map(|(j, col)| visit(s * width + j, col))
                    .collect::<Vec<f64>>()
            })
            .collect();
        // Summed in groups of SUM_GROUP columns, then over the groups, whatever the strip
        // width: the same order of additions on every grid.
        let groups: Vec<f64> = columns
            .chunks(SUM_GROUP)
            .map(|g| g.iter().sum::<f64>())
            .collect();
        (0..groups.len()).into_par_iter().map(|i| groups[i]).sum()
    }

    /// Real FFT of every row into the strips of `self.spec`. `chunks` are the input's runs of
    /// [`rows_per_chunk`] rows; `fill(chunk, k, y, buf)` puts row `k` of a chunk (grid row y)
    /// into the transform buffer `buf`; its results are returned one per row in row order.
    fn row_pass<I, C, R, const A: usize>(&mut self, chunks: C, fill: R) -> Vec<[f64; A]>
    where
        I: Send,
        C: IndexedParallelIterator<Item = I>,
        R: Fn(&mut I, usize, usize, &mut [T]) -> [f64; A] + Sync,
    {
        let (nx, ny, nxc, width) = (self.nx, self.ny, self.nxc, self.width);
        let per_task = rows_per_chunk(nx);
        let shape = self.work_shape();
        debug_assert_eq!(chunks.len(), ny.div_ceil(per_task));
        // Each task's rows occupy one contiguous run of every strip.
        let mut tasks: Vec<Vec<&mut [Complex<T>]>> = (0..ny.div_ceil(per_task))
            .map(|_| Vec::with_capacity(nxc.div_ceil(width)))
            .collect();
        for (s, strip) in self.spec.chunks_mut(self.stride).enumerate() {
            let w = width.min(nxc - s * width);
            for (task, run) in tasks
                .iter_mut()
                .zip(strip[..w * ny].chunks_mut(w * per_task))
            {
                task.push(run);
            }
        }
        let mut results = vec![[0.0; A]; ny];
        let (row_fwd, pool) = (&self.row_fwd, &self.pool);
        let scratch_len = row_fwd.get_scratch_len();
        let make = || shape.make();
        // A task transforms its rows into a block that stays in cache, then copies the block
        // to the strips one contiguous run at a time.
        tasks
            .into_par_iter()
            .zip(chunks)
            .zip(results.par_chunks_mut(per_task))
            .enumerate()
            .for_each_init(
                || Lease::take(pool, make),
                |lease, (ci, ((runs, mut chunk), res))| {
                    let Work {
                        row: buf,
                        block,
                        scratch,
                        ..
                    } = lease.get();
                    let scratch = &mut scratch[..scratch_len];
                    let rows = res.len();
                    for (k, (out, row)) in
                        res.iter_mut().zip(block.chunks_exact_mut(nxc)).enumerate()
                    {
                        *out = fill(&mut chunk, k, ci * per_task + k, buf);
                        row_fwd
                            .process_with_scratch(buf, row, scratch)
                            .expect("buffer lengths are fixed when the plan is made");
                    }
                    for (s, run) in runs.into_iter().enumerate() {
                        let w = run.len() / rows;
                        for (k, dst) in run.chunks_exact_mut(w).enumerate() {
                            dst.copy_from_slice(&block[k * nxc + s * width..][..w]);
                        }
                    }
                },
            );
        results
    }

    /// Per strip: the column FFTs, `multiply` and the inverse column FFTs, in place.
    fn column_pass<M>(&mut self, multiply: M)
    where
        M: Fn(usize, &mut [Complex<T>]) + Sync,
    {
        let (ny, nxc, width) = (self.ny, self.nxc, self.width);
        let (col_fwd, col_inv) = (&self.col_fwd, &self.col_inv);
        let fwd_len = col_fwd.get_inplace_scratch_len();
        let inv_len = col_inv.get_inplace_scratch_len();
        // Columns of the transpose buffer are padded apart for the same reason as the strips.
        let cs = ny + COLUMN_PAD;
        let (shape, pool) = (self.work_shape(), &self.pool);
        let make = || shape.make();
        self.spec
            .par_chunks_mut(self.stride)
            .enumerate()
            .for_each_init(
                || Lease::take(pool, make),
                |lease, (s, strip)| {
                    let Work {
                        cols: buf, scratch, ..
                    } = lease.get();
                    let w = width.min(nxc - s * width);
                    let strip = &mut strip[..w * ny];
                    transpose(strip, w, ny, cs, buf);
                    for (j, col) in buf.chunks_exact_mut(cs).take(w).enumerate() {
                        let col = &mut col[..ny];
                        if ny > 1 {
                            col_fwd.process_with_scratch(col, &mut scratch[..fwd_len]);
                        }
                        multiply(s * width + j, col);
                        if ny > 1 {
                            col_inv.process_with_scratch(col, &mut scratch[..inv_len]);
                        }
                    }
                    for (y, dst) in strip.chunks_exact_mut(w).enumerate() {
                        for (j, o) in dst.iter_mut().enumerate() {
                            *o = buf[j * cs + y];
                        }
                    }
                },
            );
    }

    /// Gather every row from the strips, inverse real FFT it into `output` and apply
    /// `finish(y, input_row, output_row)` to it (`input`: the filtered field); returns
    /// `finish`'s results, one per row in row order.
    fn inverse_row_pass<F, const B: usize>(
        &mut self,
        input: &[f64],
        output: &mut [f64],
        finish: F,
    ) -> Vec<[f64; B]>
    where
        F: Fn(usize, &[f64], &mut [f64]) -> [f64; B] + Sync,
    {
        let (nx, ny, nxc, width, stride) = (self.nx, self.ny, self.nxc, self.width, self.stride);
        let even = nx.is_multiple_of(2);
        let (spec, row_inv, pool) = (&self.spec, &self.row_inv, &self.pool);
        let scratch_len = row_inv.get_scratch_len();
        let shape = self.work_shape();
        let make = || shape.make();
        let per_task = rows_per_chunk(nx);
        let mut results = vec![[0.0; B]; ny];
        // A task copies its rows' contiguous run of every strip into a block that stays in
        // cache, then transforms the rows of the block.
        output
            .par_chunks_mut(nx * per_task)
            .zip(results.par_chunks_mut(per_task))
            .enumerate()
            .for_each_init(
                || Lease::take(pool, make),
                |lease, (ci, (chunk, res))| {
                    let Work {
                        row: tmp,
                        block,
                        scratch,
                        ..
                    } = lease.get();
                    let scratch = &mut scratch[..scratch_len];
                    let rows = res.len();
                    for s in 0..nxc.div_ceil(width) {
                        let w = width.min(nxc - s * width);
                        let run = &spec[s * stride + ci * per_task * w..][..rows * w];
                        for (k, src) in run.chunks_exact(w).enumerate() {
                            block[k * nxc + s * width..][..w].copy_from_slice(src);
                        }
                    }
                    for (k, ((orow, out), row)) in chunk
                        .chunks_exact_mut(nx)
                        .zip(res)
                        .zip(block.chunks_exact_mut(nxc))
                        .enumerate()
                    {
                        row[0].im = T::zero();
                        if even {
                            row[nxc - 1].im = T::zero();
                        }
                        row_inv
                            .process_with_scratch(row, T::out_row(orow, tmp), scratch)
                            .expect(
                                "lengths are fixed by the plan and constrained parts are zeroed",
                            );
                        T::store(tmp, orow);
                        let y = ci * per_task + k;
                        *out = finish(y, &input[y * nx..(y + 1) * nx], orow);
                    }
                },
            );
        results
    }
}

/// Copy a strip of `w` columns stored row by row (`strip[y * w + j]`) into `buf` column by
/// column (`buf[j * cs + y]`, `cs ≥ ny`).
fn transpose<T: Copy>(strip: &[T], w: usize, ny: usize, cs: usize, buf: &mut [T]) {
    for (y, src) in strip.chunks_exact(w).take(ny).enumerate() {
        for (j, v) in src.iter().enumerate() {
            buf[j * cs + y] = *v;
        }
    }
}

fn rows_per_chunk(row_len: usize) -> usize {
    (CHUNK_ELEMS / row_len.max(1)).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rustfft::num_complex::Complex64;

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

    /// Strip widths: one column, strips that do not divide the half spectrum, the default's
    /// lower bound and a single strip.
    const WIDTHS: [usize; 4] = [1, 3, 8, 64];

    #[test]
    fn results_do_not_depend_on_the_strip_width() {
        // Each column is transformed by the same plan whatever the strip it is in, so the
        // results are the same bit for bit.
        let (nx, ny) = (37, 20);
        let field = test_field(nx, ny);
        let multiply = |kx: usize, col: &mut [Complex64]| {
            for (ky, c) in col.iter_mut().enumerate() {
                *c *= 1.0 / (1.0 + (kx * kx + ky * ky) as f64);
            }
        };
        let run = |width| {
            let mut out = vec![0.0; nx * ny];
            Fft2::<f64>::with_width(nx, ny, width).filter(&field, &mut out, multiply);
            out
        };
        let want = run(1);
        for width in WIDTHS {
            let got = run(width);
            assert!(
                got.iter()
                    .zip(&want)
                    .all(|(a, b)| a.to_bits() == b.to_bits())
            );
        }
    }

    #[test]
    fn spectrum_matches_direct_dft() {
        for (&(nx, ny), width) in SIZES.iter().flat_map(|s| WIDTHS.map(move |w| (s, w))) {
            let field = test_field(nx, ny);
            let mut plan = Fft2::<f64>::with_width(nx, ny, width);
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
        for (&(nx, ny), width) in SIZES.iter().flat_map(|s| WIDTHS.map(move |w| (s, w))) {
            let field = test_field(nx, ny);
            let mut plan = Fft2::<f64>::with_width(nx, ny, width);
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
    #[test]
    fn row_callbacks_match_separate_passes() {
        // prepare: x ← 2x − 1 with Σ x of the row; finish: out ← out + y·in with Σ out of the
        // row. The fused calls must give the same fields and per-row sums as the separate
        // passes, bit for bit (the same operations on the same values).
        let multiply = |kx: usize, col: &mut [Complex64]| {
            for (ky, c) in col.iter_mut().enumerate() {
                *c *= 1.0 / (2.0 + (kx * kx + 3 * ky) as f64);
            }
        };
        let prepare = |_: usize, row: &mut [f64]| {
            row.iter_mut().for_each(|x| *x = 2.0 * *x - 1.0);
            [row.iter().sum::<f64>()]
        };
        let finish = |y: usize, inp: &[f64], out: &mut [f64]| {
            for (o, i) in out.iter_mut().zip(inp) {
                *o += y as f64 * i;
            }
            [out.iter().sum::<f64>(), 1.0]
        };
        for (&(nx, ny), width) in SIZES.iter().flat_map(|s| WIDTHS.map(move |w| (s, w))) {
            let mut plan = Fft2::<f64>::with_width(nx, ny, width);
            let field = test_field(nx, ny);
            // Separate passes.
            let mut input = field.clone();
            let prepared: Vec<[f64; 1]> = input
                .chunks_exact_mut(nx)
                .enumerate()
                .map(|(y, row)| prepare(y, row))
                .collect();
            let mut want = vec![0.0; nx * ny];
            plan.filter(&input, &mut want, multiply);
            let want_rows: Vec<[f64; 2]> = want
                .chunks_exact_mut(nx)
                .zip(input.chunks_exact(nx))
                .enumerate()
                .map(|(y, (out, inp))| finish(y, inp, out))
                .collect();
            let sum: f64 = prepared.iter().map(|s| s[0]).sum();
            // Fused.
            let mut fused_input = field.clone();
            let mut got = vec![0.0; nx * ny];
            let (sums, got_rows) =
                plan.filter_rows(&mut fused_input, prepare, &mut got, multiply, |s| {
                    assert_eq!(s[0].to_bits(), sum.to_bits());
                    finish
                });
            assert_eq!(sums[0].to_bits(), sum.to_bits());
            let same =
                |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
            assert!(same(&fused_input, &input), "{nx}x{ny}");
            assert!(same(&got, &want), "{nx}x{ny}");
            assert_eq!(got_rows, want_rows);
            // The scaled filter with a finishing callback.
            let scale = 0.37;
            let scaled: Vec<f64> = field.iter().map(|v| scale * v).collect();
            plan.filter(&scaled, &mut want, multiply);
            let want_rows: Vec<[f64; 2]> = want
                .chunks_exact_mut(nx)
                .zip(field.chunks_exact(nx))
                .enumerate()
                .map(|(y, (out, inp))| finish(y, inp, out))
                .collect();
            let got_rows = plan.filter_scaled_then(&field, scale, &mut got, multiply, finish);
            assert!(same(&got, &want), "{nx}x{ny}");
            assert_eq!(got_rows, want_rows);
        }
    }

    #[test]
    fn single_precision_filter_matches_double_to_f32_rounding() {
        // The same filter in f32 and f64, on every size and strip width: the f32 results agree
        // with the f64 ones to a few f32 roundings (2⁻²⁴ ≈ 6e-8) of the largest value, with the
        // row callbacks seeing the same f64 fields.
        for (&(nx, ny), width) in SIZES.iter().flat_map(|s| WIDTHS.map(move |w| (s, w))) {
            let field = test_field(nx, ny);
            let m = |kx: usize, ky: usize| 1.0 / (2.0 + (kx * kx + 3 * ky) as f64);
            let mut want = vec![0.0; nx * ny];
            Fft2::<f64>::with_width(nx, ny, width).filter(&field, &mut want, |kx, col| {
                for (ky, c) in col.iter_mut().enumerate() {
                    *c *= m(kx, ky);
                }
            });
            let mut input = field.clone();
            let mut got = vec![0.0; nx * ny];
            let (sums, rows) = Fft2::<f32>::with_width(nx, ny, width).filter_rows(
                &mut input,
                |_, row| [row.iter().sum::<f64>()],
                &mut got,
                |kx, col| {
                    for (ky, c) in col.iter_mut().enumerate() {
                        *c *= m(kx, ky) as f32;
                    }
                },
                |_| |_, _: &[f64], out: &mut [f64]| [out.iter().sum::<f64>()],
            );
            let row_sums: f64 = field.chunks_exact(nx).map(|r| r.iter().sum::<f64>()).sum();
            assert_eq!(sums[0], row_sums, "{nx}x{ny}");
            let peak = want.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            for (a, b) in got.iter().zip(&want) {
                assert!((a - b).abs() < 1e-6 * peak, "{nx}x{ny}: {a} vs {b}");
            }
            for (row, out) in rows.iter().zip(got.chunks_exact(nx)) {
                assert_eq!(row[0], out.iter().sum::<f64>());
            }
        }
    }
}
