//! A layer stack's kernels S⁻², f_k², g_k² at many nodes in a short range of u = ln q (the
//! graded region of the contact integrals near q_L: some hundred nodes within about one unit
//! of u), from one Chebyshev interpolant per kernel instead of one recursion per node.
//!
//! Each kernel's logarithm ln|S|, ln|f_k|, ln|g_k| is sampled exactly ([`Stack::response_into`])
//! at the 33 Chebyshev–Lobatto points t_j = cos(πj/32) of the batch's range [u_first, u_last],
//! and its expansion Σ a_k T_k(t) (k = 0 … 32) formed by the discrete cosine sum; the squares
//! are exp(±2 Σ a_k T_k(t)) at the nodes. Logarithms, because an error δ in them is a relative
//! error δ of the value however steeply it decays (a thick layer's e^{−qz}). The batch is
//! interpolated only if every kernel is resolved: its samples finite, normal and of one sign,
//! their logarithms within ±[`MAX_LOG`], and every coefficient of the upper half (k ≥ 16) at
//! most [`TAIL`] times the largest |logarithm| (at least 1): the expansion of a function
//! analytic around the range has converged there, and its truncation error is below that. The trailing coefficients whose magnitudes sum to at most [`CHOP`] are dropped.
//! Otherwise (a kernel through zero or below e^{−50}, as at a deep interface under thick
//! layers, where its stresses are below 1e−21 of the top's) every node is evaluated exactly.
//!
//! Accuracy: within [`BATCH_RTOL`] relative of the exact recursion's squares at every node (tested over
//! q z from 1e−8 to 1e4, ν = ½, neighbour modulus ratios 1e±8 and 1 to 10 layers,
//! `tests/it/stack.rs`), so within [`super::stack::STACK_RTOL`] of the boundary-value problem's
//! solution (the recursion's measured worst error is 4e−13).

use super::stack::{MAX_LAYERS, Stack};
use std::f64::consts::PI;

/// Relative error bound of an interpolated S⁻², f_k² or g_k² against the exact recursion's
/// square at the same node, as asserted by the tests.
pub const BATCH_RTOL: f64 = 5e-12;

/// The fewest nodes a batch must have to be interpolated: the interpolant costs 33 exact
/// evaluations.
pub const BATCH_MIN: usize = 64;

/// The widest range of u = ln q a batch may span to be interpolated.
pub const BATCH_SPAN: f64 = 3.0;

/// Degree of the interpolant: 33 Chebyshev–Lobatto points.
const DEGREE: usize = 32;

/// The largest |ln| of a resolved kernel's samples.
const MAX_LOG: f64 = 50.0;

/// The largest coefficient of the upper half of a resolved expansion, relative to its samples'
/// largest |ln| (at least 1): above the rounding of the cosine sums and the recursion's own
/// steps of ~1e−13 where a layer changes from its thin to its thick form (q d = 1).
const TAIL: f64 = 1e-12;

/// The trailing coefficients dropped sum to at most this (a relative error of the value).
const CHOP: f64 = 5e-13;

/// A Chebyshev expansion Σ_{k < len} a_k T_k(t) on t ∈ [−1, 1].
#[derive(Debug, Clone, Copy)]
struct Series {
    a: [f64; DEGREE + 1],
    len: usize,
}

impl Series {
    /// The interpolant of ln|v| (v at t_j = cos(πj/32), j = 0 … 32), if resolved (module
    /// doc); `cos[m]` = cos(πm/32) for m < 64.
    fn fit(v: &[f64; DEGREE + 1], cos: &[f64; 2 * DEGREE]) -> Option<Self> {
        let sign = v[0].signum();
        let normal = |x: &f64| x.is_normal() && x.signum() == sign;
        if !v.iter().all(normal) {
            return None;
        }
        let l = v.map(|x| x.abs().ln());
        let scale = l.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        if scale > MAX_LOG {
            return None;
        }
        let mut a = [0.0; DEGREE + 1];
        for (k, ak) in a.iter_mut().enumerate() {
            let inner: f64 = (1..DEGREE)
                .map(|j| l[j] * cos[(j * k) % (2 * DEGREE)])
                .sum();
            let ends = 0.5 * (l[0] + l[DEGREE] * cos[(DEGREE * k) % (2 * DEGREE)]);
            let edge = if k == 0 || k == DEGREE { 0.5 } else { 1.0 };
            *ak = edge * (2.0 / DEGREE as f64) * (inner + ends);
        }
        if a[DEGREE / 2..].iter().any(|c| c.abs() > TAIL * scale) {
            return None;
        }
        let mut len = DEGREE + 1;
        let mut dropped = 0.0;
        while len > 1 && dropped + a[len - 1].abs() <= CHOP {
            dropped += a[len - 1].abs();
            len -= 1;
        }
        Some(Self { a, len })
    }

    /// exp(2·sign·Σ a_k T_k(t)) (Clenshaw's recurrence): the square of the value, or of its
    /// inverse for `sign` = −1.
    #[inline]
    fn square_at(&self, t: f64, sign: f64) -> f64 {
        let (mut b1, mut b2) = (0.0, 0.0);
        for &ak in self.a[1..self.len].iter().rev() {
            (b1, b2) = (ak + 2.0 * t * b1 - b2, b1);
        }
        (2.0 * sign * (self.a[0] + t * b1 - b2)).exp()
    }
}

/// Whether the ascending nodes u (= ln q) may be interpolated: at least [`BATCH_MIN`] of them,
/// within [`BATCH_SPAN`].
pub(crate) fn qualifies(u: &[f64]) -> bool {
    match (u.first(), u.last()) {
        (Some(&first), Some(&last)) => {
            u.len() >= BATCH_MIN && last > first && last - first <= BATCH_SPAN
        }
        _ => false,
    }
}

/// S⁻² and every (f_k², g_k²) of `stack` at the ascending nodes u (= ln q, at least
/// [`BATCH_MIN`] of them within [`BATCH_SPAN`]) from the interpolants of the module doc, into
/// `k2` and `fg2` (node-major, N per node; both refilled); false, with nothing written, where
/// the nodes do not qualify or a kernel is not resolved.
pub(crate) fn interpolate(
    stack: &Stack,
    u: &[f64],
    k2: &mut Vec<f64>,
    fg2: &mut Vec<(f64, f64)>,
) -> bool {
    if !qualifies(u) {
        return false;
    }
    let (first, last) = (u[0], u[u.len() - 1]);
    let n = stack.layers().len();
    let (mid, half) = (0.5 * (first + last), 0.5 * (last - first));
    let cos: [f64; 2 * DEGREE] = std::array::from_fn(|m| (PI * m as f64 / DEGREE as f64).cos());
    // Samples: S, then f_k, g_k for every k.
    let mut samples = [[0.0; DEGREE + 1]; 1 + 2 * MAX_LAYERS];
    let mut out = [(0.0, 0.0); MAX_LAYERS];
    for j in 0..=DEGREE {
        let q = (mid + half * cos[j]).exp();
        samples[0][j] = stack.response_into(q, &mut out[..n]);
        for (k, &(f, g)) in out[..n].iter().enumerate() {
            samples[1 + 2 * k][j] = f;
            samples[2 + 2 * k][j] = g;
        }
    }
    let mut series = [Series {
        a: [0.0; DEGREE + 1],
        len: 0,
    }; 1 + 2 * MAX_LAYERS];
    for (sr, v) in series.iter_mut().zip(&samples).take(1 + 2 * n) {
        match Series::fit(v, &cos) {
            Some(fit) => *sr = fit,
            None => return false,
        }
    }
    k2.clear();
    fg2.clear();
    for &uj in u {
        let t = ((uj - mid) / half).clamp(-1.0, 1.0);
        k2.push(series[0].square_at(t, -1.0));
        fg2.extend((0..n).map(|k| {
            let (f, g) = (&series[1 + 2 * k], &series[2 + 2 * k]);
            (f.square_at(t, 1.0), g.square_at(t, 1.0))
        }));
    }
    true
}
