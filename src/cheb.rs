//! Piecewise Chebyshev interpolation of degree [`DEGREE`], shared by the layer-kernel table
//! (`layer::KernelTable`) and the erf table (`special`): the interpolant through the Chebyshev
//! points of a panel, stored as monomials in the panel's local variable t ∈ [−1, 1] and evaluated
//! by Estrin's scheme.

use std::f64::consts::PI;

/// Polynomial degree per panel.
pub const DEGREE: usize = 13;
/// Coefficients (and interpolation points) per panel.
pub const N: usize = DEGREE + 1;

/// The Chebyshev points t_j = cos(π(j + ½)/N) on [−1, 1].
pub fn nodes() -> [f64; N] {
    std::array::from_fn(|j| (PI * (j as f64 + 0.5) / N as f64).cos())
}

/// Monomial coefficients (in t) of the Chebyshev polynomials T_0..T_{N−1}.
fn chebyshev_monomials() -> [[f64; N]; N] {
    let mut t = [[0.0; N]; N];
    t[0][0] = 1.0;
    t[1][1] = 1.0;
    for n in 2..N {
        for k in 0..N {
            let up = if k > 0 { 2.0 * t[n - 1][k - 1] } else { 0.0 };
            t[n][k] = up - t[n - 2][k];
        }
    }
    t
}

/// Interpolation at the Chebyshev points t_j = cos(π(j + ½)/N): the discrete cosine transform
/// to Chebyshev coefficients (which decay fast for smooth functions), then each T_k expanded
/// in monomials. The coefficients are formed before the expansion so that rounding in the
/// transform is not multiplied by the large monomial coefficients of T_k.
pub struct Interpolation {
    cosines: [[f64; N]; N],
    monomials: [[f64; N]; N],
}

impl Interpolation {
    pub fn new() -> Self {
        Self {
            cosines: std::array::from_fn(|k| {
                let scale = if k == 0 { 1.0 } else { 2.0 } / N as f64;
                std::array::from_fn(|j| scale * (PI * k as f64 * (j as f64 + 0.5) / N as f64).cos())
            }),
            monomials: chebyshev_monomials(),
        }
    }

    /// Monomial coefficients in t of the interpolant through `values` at [`nodes`].
    pub fn coefficients(&self, values: &[f64; N]) -> [f64; N] {
        let mut mono = [0.0; N];
        for (row, t_k) in self.cosines.iter().zip(&self.monomials) {
            let a: f64 = row.iter().zip(values).map(|(c, v)| c * v).sum();
            for (m, c) in mono.iter_mut().zip(t_k) {
                *m += a * c;
            }
        }
        mono
    }
}

/// The panel polynomial at t by Estrin's scheme (pairs, then powers t², t⁴, t⁸): a dependency
/// chain of depth 5 instead of Horner's 13, which is what the evaluation time is made of.
#[inline(always)]
pub fn poly(c: &[f64; N], t: f64) -> f64 {
    let t2 = t * t;
    let t4 = t2 * t2;
    let t8 = t4 * t4;
    let p = |i: usize| c[i] + c[i + 1] * t;
    let low = (p(0) + t2 * p(2)) + t4 * (p(4) + t2 * p(6));
    let high = (p(8) + t2 * p(10)) + t4 * p(12);
    low + t8 * high
}

impl Default for Interpolation {
    fn default() -> Self {
        Self::new()
    }
}
