//! Synthetic self-affine surfaces with a known power spectrum (paper eq. 2 with a flat
//! roll-off; random phases as in eq. A1).
//!
//! The map is one period of a periodic surface, n × n pixels of size dx. Every Fourier mode
//! k ≠ 0 gets the deterministic amplitude of the target spectrum and a random phase, so the
//! map's periodogram equals the target C(q) mode by mode (no Rayleigh scatter):
//!
//!   C(q) = C0                      for 0 < q < q0   (roll-off plateau),
//!   C(q) = C0 (q/q0)^{−2(1+H)}     for q0 ≤ q ≤ q1,
//!   C(q) = 0                       for q > q1 (and the mean, q = 0, is zero),
//!
//! with C0 fixed so that the map's rms height (or rms slope ξ² = Σ q² C Δq², the discrete form
//! of 2π∫q³C dq) is the requested value. With the normalisation of [`crate::topography`],
//! |H_k| = √(C(q_k) (2π)² N / (dx dy)). Self-conjugate modes (kx, ky ∈ {0, n/2}) are real with
//! a random sign.
//!
//! Random numbers come from SplitMix64 (Steele, Lea & Flood 2014), a few lines of well-known
//! code: the generator only needs reproducible uniform phases for a fixed seed, not the `rand`
//! crate's machinery.

use super::HeightMap;
use crate::error::Error;
use rustfft::FftPlanner;
use rustfft::num_complex::Complex64;
use std::f64::consts::PI;

/// The largest map side n: an n × n map takes 24 n² bytes while it is made (complex modes and
/// heights), 1.6 GB at 8192, and its CSV some 15 n² bytes (1 GB).
pub const MAX_N: usize = 8192;

/// SplitMix64: a 64-bit generator with a 2^64 period that passes BigCrush.
#[derive(Debug, Clone)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1) with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// What fixes the amplitude of the synthetic surface.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Amplitude {
    /// rms height, m.
    RmsHeight(f64),
    /// rms slope ξ (dimensionless).
    RmsSlope(f64),
}

/// A self-affine surface to synthesise.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SynthSpec {
    /// Pixels per side (any size ≥ 4; FFTs of any length are fast when it has small factors).
    pub n: usize,
    /// Pixel size, m.
    pub dx: f64,
    /// Hurst exponent, 0 < H ≤ 1.
    pub hurst: f64,
    /// Roll-off wavenumber q0 (C flat below), 1/m.
    pub q0: f64,
    /// Short-wavelength cut-off q1 (C = 0 above), 1/m.
    pub q1: f64,
    pub amplitude: Amplitude,
    pub seed: u64,
}

impl SynthSpec {
    fn validate(&self) -> Result<(), Error> {
        if !(4..=MAX_N).contains(&self.n) {
            return Err(Error::invalid(
                "map size n",
                self.n,
                "4 <= n <= 8192 pixels per side",
            ));
        }
        if !(self.dx.is_finite() && self.dx > 0.0) {
            return Err(Error::invalid(
                "pixel size",
                self.dx,
                "a finite size > 0 in m",
            ));
        }
        if !(self.hurst > 0.0 && self.hurst <= 1.0) {
            return Err(Error::invalid("Hurst exponent H", self.hurst, "0 < H <= 1"));
        }
        let q_fund = 2.0 * PI / (self.n as f64 * self.dx);
        if !(self.q0.is_finite() && self.q0 > 0.0 && self.q1.is_finite() && self.q1 > self.q0) {
            return Err(Error::invalid(
                "wavenumbers q0, q1",
                format!("q0 = {}, q1 = {}", self.q0, self.q1),
                "0 < q0 < q1",
            ));
        }
        if self.q1 < q_fund {
            return Err(Error::invalid(
                "q1",
                self.q1,
                "q1 at least the map's fundamental 2π/(n dx)",
            ));
        }
        let a = match self.amplitude {
            Amplitude::RmsHeight(a) | Amplitude::RmsSlope(a) => a,
        };
        if !(a.is_finite() && a > 0.0) {
            return Err(Error::invalid(
                "rms height or slope",
                a,
                "a finite value > 0",
            ));
        }
        Ok(())
    }

    /// The unscaled shape of the spectrum (C0 = 1).
    fn shape(&self, q: f64) -> f64 {
        if q <= 0.0 || q > self.q1 {
            0.0
        } else if q < self.q0 {
            1.0
        } else {
            (q / self.q0).powf(-2.0 * (1.0 + self.hurst))
        }
    }

    fn mode_q(&self, ix: usize, iy: usize) -> f64 {
        mode_q(self.n, self.dx, ix, iy)
    }

    /// C0 (m^4) for which the map has the requested rms height or slope.
    pub fn c0(&self) -> f64 {
        let n = self.n;
        let dq = 2.0 * PI / (n as f64 * self.dx);
        let slope = matches!(self.amplitude, Amplitude::RmsSlope(_));
        let mut sum = 0.0;
        for iy in 0..n {
            for ix in 0..n {
                let q = self.mode_q(ix, iy);
                sum += self.shape(q) * if slope { q * q } else { 1.0 };
            }
        }
        let a = match self.amplitude {
            Amplitude::RmsHeight(a) | Amplitude::RmsSlope(a) => a,
        };
        a * a / (sum * dq * dq)
    }

    /// The map's exact power spectrum C(q), m^4 (zero at q = 0 and above q1).
    pub fn c(&self, q: f64) -> f64 {
        self.c0() * self.shape(q)
    }
}

/// The wavenumber |q| (1/m) of Fourier mode (ix, iy) of an n × n map of pixel size dx (indices
/// above n/2 are the negative frequencies).
pub fn mode_q(n: usize, dx: f64, ix: usize, iy: usize) -> f64 {
    let dq = 2.0 * PI / (n as f64 * dx);
    let fx = if ix <= n / 2 {
        ix as f64
    } else {
        ix as f64 - n as f64
    };
    let fy = if iy <= n / 2 {
        iy as f64
    } else {
        iy as f64 - n as f64
    };
    dq * fx.hypot(fy)
}

/// A periodic self-affine height map with random phases (see the module docs).
pub fn self_affine_map(spec: &SynthSpec) -> Result<HeightMap, Error> {
    spec.validate()?;
    let c0 = spec.c0();
    let map = random_phase_map(spec.n, spec.dx, |q| c0 * spec.shape(q), spec.seed);
    let z = &map.z;
    // C0 or the amplitudes leave the floating-point range for extreme inputs (an rms height
    // of 1 m on femtometre pixels): a map of NaN, inf or zeros is refused rather than written.
    if let Some(bad) = z.iter().find(|v| !v.is_finite()) {
        return Err(Error::Numerical {
            what: "synthetic height map",
            detail: format!(
                "a height is {bad} (C0 = {c0:e} m^4); the rms height or slope, pixel size and \
                 wavenumbers are beyond the floating-point range together"
            ),
        });
    }
    if z.iter().all(|&v| v == 0.0) {
        return Err(Error::Numerical {
            what: "synthetic height map",
            detail: format!(
                "every height is 0 (C0 = {c0:e} m^4): the rms height or slope underflows"
            ),
        });
    }
    Ok(map)
}

/// One period (n × n pixels of size dx) of a surface with random phases whose Fourier mode
/// (ix, iy) has the deterministic amplitude of the spectrum `c` (m^4) at the mode's
/// wavenumber [`mode_q`] (1/m), |H_k| = √(C(q_k) (2π)² N / dx²) (module docs); the
/// phases come from SplitMix64 with `seed`, one draw per mode pair whatever its amplitude.
/// The heights are not checked: a caller judges whether they are finite.
pub fn random_phase_map(n: usize, dx: f64, c: impl Fn(f64) -> f64, seed: u64) -> HeightMap {
    let big_n = (n * n) as f64;
    let amp = |q: f64| (c(q) * (2.0 * PI).powi(2) * big_n / (dx * dx)).sqrt();
    let mut rng = SplitMix64::new(seed);
    let mut h = vec![Complex64::new(0.0, 0.0); n * n];
    for iy in 0..n {
        for ix in 0..n {
            let (px, py) = ((n - ix) % n, (n - iy) % n);
            let me = iy * n + ix;
            let partner = py * n + px;
            if partner < me {
                continue;
            }
            let a = amp(mode_q(n, dx, ix, iy));
            if partner == me {
                let sign = if rng.next_u64() & 1 == 0 { 1.0 } else { -1.0 };
                h[me] = Complex64::new(sign * a, 0.0);
            } else {
                let phi = 2.0 * PI * rng.next_f64();
                let v = Complex64::from_polar(a, phi);
                h[me] = v;
                h[partner] = v.conj();
            }
        }
    }
    let mut planner = FftPlanner::new();
    let fft = planner.plan_fft_inverse(n);
    // Rows, then columns (through a transpose-free gather).
    for row in h.chunks_exact_mut(n) {
        fft.process(row);
    }
    let mut col = vec![Complex64::new(0.0, 0.0); n];
    for ix in 0..n {
        for iy in 0..n {
            col[iy] = h[iy * n + ix];
        }
        fft.process(&mut col);
        for iy in 0..n {
            h[iy * n + ix] = col[iy];
        }
    }
    HeightMap {
        nx: n,
        ny: n,
        dx,
        dy: dx,
        z: h.iter().map(|v| v.re / big_n).collect(),
        periodic: true,
    }
}
