//! The interface stresses of a friction traction on a solved contact (not in the paper; notes.md,
//! "Sliding friction"): the film's top carries μ p(x) along x besides the solved pressure p
//! (uncoupled approximation: p is the frictionless solution). Per Fourier mode with wavevector at
//! angle φ to x (cos φ = q_x/q, sin φ = q_y/q) the interface carries, per unit of the mode's
//! friction traction ([`crate::layer::tangential`]),
//! σ_xz: g_t cos²φ + h sin²φ, σ_yz: (g_t − h) cos φ sin φ, both in phase, and σ_zz (tension):
//! f_t cos φ in quadrature (cos(k·r) → sin(k·r), the multiplier −i on e^{ik·r}). The q = 0 mode
//! (the mean friction μ p0) passes unchanged to σ_xz (g_t = h = 1). The σ_zz operator (odd in q_x)
//! is set to zero on the x Nyquist column and the σ_yz one (odd in q_x and in q_y) on both Nyquist
//! lines, as the static shear is ([`super::interface_fields_with`]): a real field's Nyquist mode
//! cannot carry an odd operator.

use super::fft::Fft2;
use super::wavenumbers;
use crate::error::Error;
use crate::layer::Stack;
use rayon::prelude::*;
use rustfft::num_complex::Complex64;

/// The friction-driven interface stresses (Pa), to be added to the static fields.
#[derive(Debug, Clone, PartialEq)]
pub struct FrictionFields {
    /// σ_xz at z = d (includes the mean μ p0).
    pub shear_x: Vec<f64>,
    /// σ_yz at z = d.
    pub shear_y: Vec<f64>,
    /// Normal stress at z = d, compression positive (mean 0).
    pub normal: Vec<f64>,
}

/// The interface stresses of the traction μ p along x on the film's top, for the pressure field
/// `pressure` (Pa, compression positive, row-major `ny × nx`, pixel sizes `dx`, `dy`).
pub fn friction_fields(
    pressure: &[f64],
    dims: (usize, usize),
    pixel: (f64, f64),
    stack: &Stack,
    mu: f64,
) -> Result<FrictionFields, Error> {
    let (layers, d) = (stack.layers, stack.thickness);
    friction_fields_with(pressure, dims, pixel, mu, |q| {
        let t = layers.tangential(q * d);
        [t.g_t, t.f_t, t.h]
    })
}

/// The interface stresses of the traction μ p along x on the top surface at an interface whose
/// kernels at wavenumber q > 0 (1/m) are `kernels(q) = [g_t, f_t, h]` (module doc), for the
/// pressure field `pressure` (Pa, compression positive, row-major `ny × nx`, pixel sizes `dx`,
/// `dy`).
pub fn friction_fields_with<K>(
    pressure: &[f64],
    (nx, ny): (usize, usize),
    (dx, dy): (f64, f64),
    mu: f64,
    kernels: K,
) -> Result<FrictionFields, Error>
where
    K: Fn(f64) -> [f64; 3] + Sync,
{
    if !(mu.is_finite() && mu >= 0.0) {
        return Err(Error::invalid(
            "friction coefficient",
            mu,
            "a finite value >= 0",
        ));
    }
    let n = nx * ny;
    let (qx, qy) = wavenumbers(nx, ny, dx, dy);
    let nxc = nx / 2 + 1;
    // (g_t cos²φ + h sin²φ, (g_t − h) cos φ sin φ, f_t cos φ) per half-spectrum entry.
    let mut mult = vec![[0.0; 3]; nxc * ny];
    mult.par_chunks_mut(ny).enumerate().for_each(|(kx, col)| {
        for (ky, m) in col.iter_mut().enumerate() {
            let q = qx[kx].hypot(qy[ky]);
            *m = if q == 0.0 {
                [1.0, 0.0, 0.0]
            } else {
                let [g_t, f_t, h] = kernels(q);
                let (c, s) = (qx[kx] / q, qy[ky] / q);
                [g_t * c * c + h * s * s, (g_t - h) * c * s, f_t * c]
            };
        }
    });
    let scale = mu / n as f64;
    let nyq_x = nx.is_multiple_of(2).then_some(nx / 2);
    let nyq_y = ny.is_multiple_of(2).then_some(ny / 2);
    let mut plan = Fft2::<f64>::new(nx, ny);
    let mut out = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    for (j, field) in out.iter_mut().enumerate() {
        plan.filter(pressure, field, |kx, col| {
            for (ky, (c, m)) in col
                .iter_mut()
                .zip(&mult[kx * ny..(kx + 1) * ny])
                .enumerate()
            {
                *c *= match j {
                    0 => Complex64::new(m[0] * scale, 0.0),
                    // (g_t − h) cos φ sin φ is odd in q_x and in q_y.
                    1 if Some(kx) == nyq_x || Some(ky) == nyq_y => Complex64::new(0.0, 0.0),
                    1 => Complex64::new(m[1] * scale, 0.0),
                    // Compression positive: −σ_zz, and −i on e^{ik·r}: +i.
                    _ if Some(kx) == nyq_x => Complex64::new(0.0, 0.0),
                    _ => Complex64::new(0.0, m[2] * scale),
                };
            }
        });
    }
    let [shear_x, shear_y, normal] = out;
    Ok(FrictionFields {
        shear_x,
        shear_y,
        normal,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layer::{Bilayer, Elastic};
    use std::f64::consts::PI;

    /// A single pressure mode p0 + a cos(k·r) (k a grid wavevector at an oblique angle) against
    /// the kernels' definitions: σ_xz = μ[p0 + a(g_t c² + h s²) cos], σ_yz = μ a (g_t − h) c s
    /// cos, normal (compression) = −μ a f_t c sin, to 1e-12 of μ(p0 + a).
    #[test]
    fn single_mode_matches_the_kernels() {
        let (nx, ny, dx, dy) = (32, 16, 1e-6, 2e-6);
        let (kx, ky) = (3usize, 2usize);
        let (qx, qy) = (
            2.0 * PI * kx as f64 / (nx as f64 * dx),
            2.0 * PI * ky as f64 / (ny as f64 * dy),
        );
        let (p0, a, mu) = (1e5, 4e4, 0.6);
        let stack = Stack {
            layers: Bilayer::new(
                Elastic::new(1e6, 0.5).unwrap(),
                Elastic::new(2e11, 0.3).unwrap(),
            ),
            thickness: 3e-6,
        };
        let phase = |i: usize, j: usize| qx * i as f64 * dx + qy * j as f64 * dy;
        let p: Vec<f64> = (0..ny)
            .flat_map(|j| (0..nx).map(move |i| (i, j)))
            .map(|(i, j)| p0 + a * phase(i, j).cos())
            .collect();
        let f = friction_fields(&p, (nx, ny), (dx, dy), &stack, mu).unwrap();
        let q = qx.hypot(qy);
        let t = stack.layers.tangential(q * stack.thickness);
        let (c, s) = (qx / q, qy / q);
        let tol = 1e-12 * mu * (p0 + a);
        for j in 0..ny {
            for i in 0..nx {
                let k = j * nx + i;
                let (co, si) = (phase(i, j).cos(), phase(i, j).sin());
                let want = [
                    mu * (p0 + a * (t.g_t * c * c + t.h * s * s) * co),
                    mu * a * (t.g_t - t.h) * c * s * co,
                    -mu * a * t.f_t * c * si,
                ];
                let got = [f.shear_x[k], f.shear_y[k], f.normal[k]];
                for (g, w) in got.iter().zip(want) {
                    assert!((g - w).abs() <= tol, "({i}, {j}): {got:?} vs {want:?}");
                }
            }
        }
    }
}
