//! Preconditioner of the periodic solver's conjugate gradients: the inverse of the influence
//! operator on the full grid, a Fourier multiplier 1/K(q), applied to the gap on the contact set
//! (an FFT-based preconditioner in the sense of Vollebregt's bound-constrained CG, JOTA 162,
//! 2014, 931–953, and J. Comput. Phys. 257, 2014, 333–351).
//!
//! With K(q) ∝ 1/q the unpreconditioned operator's condition number on a contact patch grows
//! with the patch size in pixels, and so do the iterations; 1/K(q) undoes that scaling, so the
//! preconditioned operator is close to the identity on the interior of each patch. The direction
//! is z = P₀ M P g: the gap g on the contact set (P), filtered by M = 1/K (q = 0 excluded), then
//! made mean-free on the contact set (P₀: the load is fixed, so directions carry no net force).
//! M is symmetric and non-negative, and P₀ M P₀ on the contact set too, so Σ g·z ≥ 0 and the
//! Fletcher–Reeves coefficient β = Σ g·z / Σ g'·z' of preconditioned CG applies.
//!
//! The filter runs in single precision (`f32` transforms and multiplier; the gap is read and z
//! written in `f64`, and the sums over them are formed in `f64`). A preconditioner only has to
//! be close to the inverse operator: M's relative rounding (≈ 1e-7) perturbs the directions,
//! not the problem solved, and the stopping test is taken on the gap, computed in `f64`, so the
//! iteration converges to the same tolerance. It halves the memory the filter streams.

use super::fft::Fft2;
use super::passes::GapSums;
use super::pool::{self, Buf};
use super::sum;

/// The multiplier M = 1/K on the half-spectrum grid (same layout as the kernel), including the
/// 1/N of the inverse FFT, in `f32`, and the single-precision plan it is applied with.
pub(super) struct Preconditioner {
    multiplier: Buf<f32>,
    ny: usize,
    plan: Fft2<f32>,
}

impl Preconditioner {
    /// From the kernel grid of the solver (K(q)/N on the transposed half spectrum, 0 at q = 0).
    pub(super) fn new(kernel: &[f64], nx: usize, ny: usize) -> Self {
        let inv_n = 1.0 / (nx * ny) as f64;
        let m = |k: f64| if k > 0.0 { inv_n * inv_n / k } else { 0.0 };
        let mut multiplier = pool::F32.take(kernel.len(), 0.0);
        for (mi, &k) in multiplier.iter_mut().zip(kernel) {
            *mi = m(k) as f32;
        }
        Self {
            multiplier,
            ny,
            plan: Fft2::new(nx, ny),
        }
    }

    /// z ← M (P g), using `scratch` for P g; returns (Σ_c g·(z − z̄), z̄) with z̄ the mean of z
    /// on the contact set, i.e. the preconditioned residual's product with the gap and the shift
    /// that makes it mean-free there. The gap g = graw − ḡ is masked in the forward row pass of
    /// the convolution, the sums are formed in its inverse row pass (per row, in row order).
    pub(super) fn apply(
        &mut self,
        (graw, contact, sums): (&[f64], &[bool], &GapSums),
        scratch: &mut [f64],
        z: &mut [f64],
    ) -> (f64, f64) {
        let (m, ny, nx, gbar) = (&self.multiplier, self.ny, self.plan.nx(), sums.gbar);
        let (_, rows) = self.plan.filter_rows(
            scratch,
            |y, row| {
                let o = y * nx;
                for ((si, gr), c) in row
                    .iter_mut()
                    .zip(&graw[o..o + nx])
                    .zip(&contact[o..o + nx])
                {
                    *si = if *c { gr - gbar } else { 0.0 };
                }
                [0.0; 0]
            },
            z,
            |kx, col| {
                for (c, k) in col.iter_mut().zip(&m[kx * ny..(kx + 1) * ny]) {
                    *c *= *k;
                }
            },
            |_| {
                |y, grow: &[f64], zrow: &mut [f64]| {
                    // grow is the masked gap (0 off the contact set).
                    let (mut gz, mut zs, mut gs) = (0.0, 0.0, 0.0);
                    let flags = &contact[y * nx..(y + 1) * nx];
                    for ((zi, gi), c) in zrow.iter().zip(grow).zip(flags) {
                        if *c {
                            gz += gi * zi;
                            zs += zi;
                            gs += gi;
                        }
                    }
                    [gz, zs, gs]
                }
            },
        );
        let zbar = sum(&rows, 1) / sums.n_c;
        (sum(&rows, 0) - zbar * sum(&rows, 2), zbar)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bem::{Surface, kernel_grid};
    use std::f64::consts::PI;

    /// Relative agreement of the single-precision filter with exact values: a few f32 roundings
    /// (2⁻²⁴ ≈ 6e-8) per FFT level on these small grids.
    const F32_TOL: f64 = 2e-6;

    /// A 24 × 16 grid with unequal pixels and the half-space compliance 2/(q E*).
    fn setup() -> (
        usize,
        usize,
        crate::bem::pool::Buf<f64>,
        impl Fn(f64) -> f64,
    ) {
        let (nx, ny, dx, dy) = (24, 16, 1e-6, 1.5e-6);
        let s = Surface::new(vec![0.0; nx * ny], nx, ny, dx, dy).unwrap();
        let compliance = |q: f64| 2.0 / (q * 3e6);
        let kernel = kernel_grid(&s, &compliance).unwrap();
        (nx, ny, kernel, compliance)
    }

    /// Gap statistics of a full contact set of `n` points with ḡ = 0 (what `apply` reads).
    fn all(n: usize) -> GapSums {
        GapSums {
            n_c: n as f64,
            gbar: 0.0,
            g2: 0.0,
            pen: 0.0,
            gt: 0.0,
        }
    }

    #[test]
    fn on_the_full_contact_it_inverts_the_influence_operator() {
        // One oblique grid mode g = cos(q·x) with everything in contact: K z must give g back
        // (z = g / K(q) exactly, the mean being 0 already).
        let (nx, ny, kernel, compliance) = setup();
        let (kx, ky) = (3.0, 2.0);
        let q = 2.0 * PI * (kx / (nx as f64 * 1e-6)).hypot(ky / (ny as f64 * 1.5e-6));
        let g: Vec<f64> = (0..nx * ny)
            .map(|i| {
                let (x, y) = ((i % nx) as f64, (i / nx) as f64);
                1e-9 * (2.0 * PI * (kx * x / nx as f64 + ky * y / ny as f64)).cos()
            })
            .collect();
        let contact = vec![true; nx * ny];
        let mut pre = Preconditioner::new(&kernel, nx, ny);
        let (mut scratch, mut z) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
        let (gz, zbar) = pre.apply((&g, &contact, &all(nx * ny)), &mut scratch, &mut z);
        // The filter runs in f32: agreement to F32_TOL, not to f64 rounding.
        let peak = 1e-9 / compliance(q);
        assert!(zbar.abs() < F32_TOL * peak, "{zbar:e}");
        for (zi, gi) in z.iter().zip(&g) {
            assert!((zi - gi / compliance(q)).abs() < F32_TOL * peak);
        }
        let expect: f64 = g.iter().map(|gi| gi * gi / compliance(q)).sum();
        assert!(
            (gz - expect).abs() < F32_TOL * expect,
            "{gz:e} vs {expect:e}"
        );
    }

    #[test]
    fn a_unit_gap_pixel_is_filtered_to_the_direct_sum() {
        // M applied to a unit gap at one pixel, read at that pixel, is M's diagonal, the direct
        // sum (1/N) Σ_q 1/K(q) over the full spectrum.
        let (nx, ny, kernel, compliance) = setup();
        let mut pre = Preconditioner::new(&kernel, nx, ny);
        let mut direct = 0.0;
        for ky in 0..ny {
            for kx in 0..nx {
                if kx == 0 && ky == 0 {
                    continue;
                }
                let sx = if kx <= nx / 2 {
                    kx as f64
                } else {
                    kx as f64 - nx as f64
                };
                let sy = if ky <= ny / 2 {
                    ky as f64
                } else {
                    ky as f64 - ny as f64
                };
                let q = 2.0 * PI * (sx / (nx as f64 * 1e-6)).hypot(sy / (ny as f64 * 1.5e-6));
                direct += 1.0 / compliance(q);
            }
        }
        direct /= (nx * ny) as f64;
        let j = 5 * nx + 7;
        let mut g = vec![0.0; nx * ny];
        g[j] = 1.0;
        let contact = vec![true; nx * ny];
        let (mut scratch, mut z) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
        pre.apply((&g, &contact, &all(nx * ny)), &mut scratch, &mut z);
        assert!(
            (z[j] - direct).abs() < F32_TOL * direct,
            "{} vs {direct}",
            z[j]
        );
    }
}
