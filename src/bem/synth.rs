//! A small generator of random self-affine height maps for the solver's tests and benchmark.
//!
//! This is a stop-gap: the project's height-map synthesiser lives in `coatcheck::topography`
//! (measured-data issue) and replaces this module once it is merged. Method: Gaussian white noise
//! on the grid, filtered in Fourier space by √C(q) with the isotropic self-affine spectrum
//! C(q) ∝ q^(−2(1+H)) for q_lo ≤ q ≤ q_hi and C = 0 elsewhere (paper, eq. 2 without roll-off),
//! then scaled to the requested rms slope (spectral definition, [`Surface::rms_slope`]), so the
//! heights are a stationary Gaussian field with that spectrum.

use super::fft::Fft2;
use super::{Surface, wavenumbers};
use crate::error::Error;

/// The spectrum and grid of a synthetic self-affine surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelfAffine {
    /// Points along x and y.
    pub nx: usize,
    pub ny: usize,
    /// Pixel size (m), the same in x and y.
    pub pixel: f64,
    /// Hurst exponent H (0 < H ≤ 1).
    pub hurst: f64,
    /// Lower and upper cut-off wavenumbers (1/m).
    pub q_lo: f64,
    pub q_hi: f64,
    /// Target rms slope ξ (spectral).
    pub rms_slope: f64,
    /// Seed of the random numbers (the same seed gives the same surface).
    pub seed: u64,
}

/// splitmix64: a small, well-mixed 64-bit generator (Steele, Lea, Flood 2014).
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in (0, 1].
    fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 1.0) * (1.0 / (1u64 << 53) as f64)
    }

    /// A pair of independent standard normals (Box–Muller).
    fn normal_pair(&mut self) -> (f64, f64) {
        let r = (-2.0 * self.uniform().ln()).sqrt();
        let phi = 2.0 * std::f64::consts::PI * self.uniform();
        (r * phi.cos(), r * phi.sin())
    }
}

impl SelfAffine {
    /// Generate the surface.
    pub fn generate(&self) -> Result<Surface, Error> {
        if !(self.hurst > 0.0 && self.hurst <= 1.0) {
            return Err(Error::invalid("Hurst exponent", self.hurst, "0 < H <= 1"));
        }
        if !(self.q_lo > 0.0 && self.q_hi > self.q_lo && self.q_hi.is_finite()) {
            return Err(Error::invalid(
                "cut-off wavenumbers",
                format!("{} .. {}", self.q_lo, self.q_hi),
                "0 < q_lo < q_hi",
            ));
        }
        if !(self.rms_slope > 0.0 && self.rms_slope.is_finite()) {
            return Err(Error::invalid(
                "rms slope",
                self.rms_slope,
                "a finite value > 0",
            ));
        }
        let (nx, ny) = (self.nx, self.ny);
        let n = nx * ny;
        let mut rng = SplitMix64(self.seed);
        let mut noise = vec![0.0; n];
        for pair in noise.chunks_mut(2) {
            let (a, b) = rng.normal_pair();
            pair[0] = a;
            if pair.len() > 1 {
                pair[1] = b;
            }
        }
        let (qx, qy) = wavenumbers(nx, ny, self.pixel, self.pixel);
        let exponent = -(1.0 + self.hurst);
        let (q_lo, q_hi) = (self.q_lo, self.q_hi);
        let mut heights = vec![0.0; n];
        Fft2::new(nx, ny).filter(&noise, &mut heights, |kx, col| {
            for (c, q_y) in col.iter_mut().zip(&qy) {
                let q = qx[kx].hypot(*q_y);
                *c *= if q >= q_lo && q <= q_hi {
                    (q / q_lo).powf(exponent)
                } else {
                    0.0
                };
            }
        });
        let mut surface = Surface::new(heights, nx, ny, self.pixel, self.pixel)?;
        let slope = surface.rms_slope();
        if slope == 0.0 {
            return Err(Error::invalid(
                "cut-off wavenumbers",
                format!("{} .. {}", self.q_lo, self.q_hi),
                "a band that contains grid wavenumbers",
            ));
        }
        let scale = self.rms_slope / slope;
        surface.heights.iter_mut().for_each(|h| *h *= scale);
        Ok(surface)
    }
}
