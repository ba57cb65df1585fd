//! The periodic solver's convolutions with the influence kernel K (the kernel grid: K(q)/N on
//! the transposed half spectrum, 0 at q = 0): the displacement u = K p with the gap statistics
//! and the response r = K t of a new direction (`passes`). They are formed in single precision
//! at the start of the iteration, while the gap is large, and in double precision after it, so
//! that every verdict is taken on a double-precision displacement.

use super::fft::{Fft2, Real};
use super::passes::{self, GapSums};
use rayon::prelude::*;
use rustfft::num_complex::Complex;

/// Gap level (relative to h_rms) above which the iteration forms its convolutions in single
/// precision: their rounding, about 1e-7 of u (a few h_rms), is then below 1e-2 of the gap
/// being reduced. Once the rms gap and the penetration are both below it (or the iteration
/// would stop), the rest of the iteration, and every verdict, runs in double precision from a
/// freshly computed displacement.
const SINGLE_ABOVE: f64 = 1e-4;

/// Largest ratio of the kernel's largest to its smallest value (q ≠ 0) for which the start runs
/// in single precision: f32 rounding of a direction's other modes, ≈ 1e-7 of it, reaches K t
/// amplified by that ratio, and at 1e6 it costs more iterations than it saves (a full-contact
/// sinusoid: 2 iterations at a ratio of 1e4, 19 at 1e6, against 2 in double precision). The
/// half-space on an n² grid spans n/√2 (2896 at 4096²); thin stiff-backed films span far more
/// and solve in double precision throughout.
const SINGLE_RANGE: f64 = 1e4;

/// Multiplication by the kernel on the half spectrum, in `T` (for `f64`, `c · k` exactly).
fn multiply<T: Real>(kernel: &[f64], ny: usize) -> impl Fn(usize, &mut [Complex<T>]) + Sync + '_ {
    move |kx, col| {
        for (c, k) in col.iter_mut().zip(&kernel[kx * ny..(kx + 1) * ny]) {
            *c = *c * T::of(*k);
        }
    }
}

/// max K / min K over the kernel grid's wavevectors q ≠ 0 (its zero entry is q = 0).
fn kernel_range(kernel: &[f64]) -> f64 {
    let (low, high) = kernel
        .par_iter()
        .filter(|&&k| k > 0.0)
        .fold(
            || (f64::INFINITY, 0.0f64),
            |(l, h), &k| (l.min(k), h.max(k)),
        )
        .reduce(
            || (f64::INFINITY, 0.0),
            |(l1, h1), (l2, h2)| (l1.min(l2), h1.max(h2)),
        );
    high / low
}

/// The kernel with its double-precision plan and, during the single-precision start, its
/// single-precision plan.
pub(super) struct Convolutions<'k> {
    kernel: &'k [f64],
    ny: usize,
    double: Fft2<f64>,
    /// `None` once the start has ended, or from the outset if the kernel spans more than
    /// [`SINGLE_RANGE`].
    single: Option<Fft2<f32>>,
    /// Iterations made in single precision.
    single_steps: usize,
}

impl<'k> Convolutions<'k> {
    pub(super) fn new(kernel: &'k [f64], nx: usize, ny: usize) -> Self {
        Self {
            kernel,
            ny,
            double: Fft2::new(nx, ny),
            single: (kernel_range(kernel) <= SINGLE_RANGE).then(|| Fft2::new(nx, ny)),
            single_steps: 0,
        }
    }

    /// The periodic real-space influence matrix's first column into `green`: the response to a
    /// unit pressure at pixel 0, in double precision. `unit` must be all zero; it is so again
    /// on return.
    pub(super) fn first_column(&mut self, unit: &mut [f64], green: &mut [f64]) {
        unit[0] = 1.0;
        self.double
            .filter(unit, green, multiply::<f64>(self.kernel, self.ny));
        unit[0] = 0.0;
    }

    /// Whether the single-precision start is on.
    pub(super) fn single(&self) -> bool {
        self.single.is_some()
    }

    /// Ends the single-precision start after `iterations` steps; the caller forms the
    /// displacement again, in double precision.
    pub(super) fn end_single(&mut self, iterations: usize) {
        self.single = None;
        self.single_steps = iterations;
    }

    /// Ends the single-precision start if the iteration would stop (`stopping`) or the rms gap
    /// and the penetration are both at most [`SINGLE_ABOVE`]·h_rms; true if it ended now.
    pub(super) fn end_single_at(
        &mut self,
        stopping: bool,
        (gap_rms, penetration, h_rms): (f64, f64, f64),
        iterations: usize,
    ) -> bool {
        let ends = self.single() && (stopping || gap_rms.max(penetration) <= SINGLE_ABOVE * h_rms);
        if ends {
            self.end_single(iterations);
        }
        ends
    }

    /// Whether the answer after `iterations` steps comes from a double-precision step (or from
    /// none at all).
    pub(super) fn last_step_double(&self, iterations: usize) -> bool {
        self.single_steps == 0 || iterations > self.single_steps
    }

    /// [`passes::fresh`] with this kernel, in the current precision.
    pub(super) fn fresh(
        &mut self,
        pressure: (&[f64], f64),
        graw: &mut [f64],
        fields: (&[f64], &[bool], &[f64]),
    ) -> GapSums {
        let (kernel, ny) = (self.kernel, self.ny);
        match self.single.as_mut() {
            Some(plan) => passes::fresh(plan, pressure, graw, multiply(kernel, ny), fields),
            None => passes::fresh(
                &mut self.double,
                pressure,
                graw,
                multiply(kernel, ny),
                fields,
            ),
        }
    }

    /// [`passes::conjugate`] with this kernel, in the current precision.
    pub(super) fn conjugate(
        &mut self,
        tr: (&mut [f64], &mut [f64]),
        zc: (&[f64], f64, &[bool]),
        n_c: f64,
        beta: f64,
    ) -> f64 {
        let (kernel, ny) = (self.kernel, self.ny);
        match self.single.as_mut() {
            Some(plan) => passes::conjugate(plan, tr, multiply(kernel, ny), zc, n_c, beta),
            None => passes::conjugate(&mut self.double, tr, multiply(kernel, ny), zc, n_c, beta),
        }
    }
}
