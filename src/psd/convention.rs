//! Normalisations of power spectra in files, and their factors to this tool's.
//!
//! This tool (paper eq. A2, notes.md; [`crate::psd::abel`]):
//! - 2D: C(q) = (2π)^−2 ∫d²x ⟨h(x)h(0)⟩ e^{−iq·x}, so h_rms² = ∫d²q C = 2π∫_0^∞ q C dq;
//! - 1D, one-sided (what `coatcheck psd` writes as C1D): h_rms² = ∫_0^∞ C1D dq.
//!
//! [`Convention::Persson`]: the 2D PSD is the paper's (factor 1). Persson's 1D PSD (B.N.J.
//! Persson et al., J. Phys.: Condens. Matter 17 (2005) R1) is two-sided,
//! C1D_P(q) = (2π)^−1 ∫dx ⟨h(x)h(0)⟩ e^{−iqx}, h_rms² = ∫_{−∞}^{∞} C1D_P dq = 2∫_0^∞ C1D_P dq,
//! so C1D = 2 C1D_P.
//!
//! [`Convention::SurfaceTopography`] (the SurfaceTopography library and contact.engineering,
//! Jacobs, Junge, Pastewka, Surf. Topogr. Metrol. Prop. 5 (2017) 013001; their
//! `power_spectrum_from_area` and `power_spectrum_from_profile`):
//! - 2D: from a map of N points over the area A, h̃_k = (A/N) Σ_n h_n e^{−ik·n} and
//!   C_ST(q_k) = |h̃_k|²/A. Parseval, Σ_k |Σ_n h_n e^{−ik·n}|² = N Σ_n h_n², gives
//!   Σ_k C_ST = A ⟨h²⟩; with the cell Δq_x Δq_y = (2π)²/A of the wavevector grid,
//!   ∫d²q C_ST = (2π)² ⟨h²⟩. This tool's periodogram of the same map is
//!   C = A|Σ h e^{−ik·n}|²/((2π)² N²) (module [`crate::topography`]), hence
//!   **C = C_ST/(2π)²**.
//! - 1D: from a scan of n points over the length L, h̃_k = (L/n) Σ h_m e^{−ikm}, C_ST = |h̃_k|²/L
//!   at ±q (the two branches averaged, equal for real heights). Σ_{all k} C_ST = L⟨h²⟩ and
//!   Δq = 2π/L give ∫_{−∞}^{∞} C_ST dq = 2π⟨h²⟩, i.e. h_rms² = (1/π)∫_0^∞ C_ST dq, hence
//!   **C1D = C1D_ST/π**.
//! - contact.engineering's "q/π × 2D PSD" series is y = (q/π) C_ST(q) (in m³, to plot beside
//!   the 1D spectra), hence **C = π y/(q (2π)²) = y/(4π q)**.
//!
//! The test `factors_follow_parseval_on_cosines` checks each factor against periodograms
//! computed in each convention's own definition (discrete Fourier transforms of periodic
//! cosine surfaces whose h_rms and rms slope are known exactly).

use serde::Serialize;
use std::f64::consts::PI;
use std::str::FromStr;

/// The normalisation of a PSD file's C column.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Convention {
    /// This tool's own: the paper's 2D PSD, and the one-sided 1D PSD that `coatcheck psd`
    /// writes.
    #[default]
    Coatcheck,
    /// Persson's: the paper's 2D PSD, and his two-sided 1D PSD.
    Persson,
    /// SurfaceTopography's and contact.engineering's.
    SurfaceTopography,
}

impl Convention {
    /// The factor that turns a 2D PSD in this convention into this tool's.
    pub fn factor_2d(self) -> f64 {
        match self {
            Convention::Coatcheck | Convention::Persson => 1.0,
            Convention::SurfaceTopography => 1.0 / (4.0 * PI * PI),
        }
    }

    /// The factor that turns a 1D PSD in this convention into this tool's one-sided 1D PSD.
    pub fn factor_1d(self) -> f64 {
        match self {
            Convention::Coatcheck => 1.0,
            Convention::Persson => 2.0,
            Convention::SurfaceTopography => 1.0 / PI,
        }
    }

    /// The name users give (`--psd-convention`).
    pub fn name(self) -> &'static str {
        match self {
            Convention::Coatcheck => "coatcheck",
            Convention::Persson => "persson",
            Convention::SurfaceTopography => "surfacetopography",
        }
    }
}

impl FromStr for Convention {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim().to_ascii_lowercase().as_str() {
            "coatcheck" => Ok(Convention::Coatcheck),
            "persson" => Ok(Convention::Persson),
            "surfacetopography" | "contact.engineering" => Ok(Convention::SurfaceTopography),
            _ => Err(format!(
                "'{s}' (expected coatcheck, persson or surfacetopography)"
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// |Σ_m h_m e^{−2πi k·m/n}|² of a row-major map `h` (nx × ny), by direct summation.
    fn dft2_power(h: &[f64], nx: usize, ny: usize, kx: usize, ky: usize) -> f64 {
        let (mut re, mut im) = (0.0, 0.0);
        for iy in 0..ny {
            for ix in 0..nx {
                let phase =
                    -2.0 * PI * ((kx * ix) as f64 / nx as f64 + (ky * iy) as f64 / ny as f64);
                re += h[iy * nx + ix] * phase.cos();
                im += h[iy * nx + ix] * phase.sin();
            }
        }
        re * re + im * im
    }

    /// Signed wavenumber index of DFT bin k of n.
    fn signed(k: usize, n: usize) -> f64 {
        if k <= n / 2 {
            k as f64
        } else {
            k as f64 - n as f64
        }
    }

    #[test]
    fn factors_follow_parseval_on_cosines() {
        // A periodic map of three cosines (none at Nyquist or q = 0) over Lx × Ly: heights and
        // slopes known exactly, h_rms² = Σ a²/2 and ξ² = Σ a² |k|²/2.
        let (nx, ny, lx, ly) = (24usize, 16usize, 3e-4, 2e-4);
        let waves = [(1e-6, 2usize, 0usize), (0.5e-6, 3, 5), (0.25e-6, 7, 2)];
        let kvec = |mx: usize, my: usize| (2.0 * PI * mx as f64 / lx, 2.0 * PI * my as f64 / ly);
        let mut h = vec![0.0; nx * ny];
        for iy in 0..ny {
            for ix in 0..nx {
                let (x, y) = (ix as f64 * lx / nx as f64, iy as f64 * ly / ny as f64);
                h[iy * nx + ix] = waves
                    .iter()
                    .map(|&(a, mx, my)| {
                        let (kx, ky) = kvec(mx, my);
                        a * (kx * x + ky * y).cos()
                    })
                    .sum::<f64>();
            }
        }
        let h2: f64 = waves.iter().map(|w| w.0 * w.0 / 2.0).sum();
        let xi2: f64 = waves
            .iter()
            .map(|&(a, mx, my)| {
                let (kx, ky) = kvec(mx, my);
                a * a * (kx * kx + ky * ky) / 2.0
            })
            .sum();
        // 2D: SurfaceTopography's periodogram C_ST = |(A/N) DFT|²/A, turned into this tool's C
        // and integrated as ∫d²q C over the wavevector grid.
        let (n, area) = ((nx * ny) as f64, lx * ly);
        let cell = (2.0 * PI / lx) * (2.0 * PI / ly);
        let (mut sum_h, mut sum_s) = (0.0, 0.0);
        for ky in 0..ny {
            for kx in 0..nx {
                let c_st = (area / n).powi(2) * dft2_power(&h, nx, ny, kx, ky) / area;
                let c = Convention::SurfaceTopography.factor_2d() * c_st;
                let (qx, qy) = (
                    2.0 * PI * signed(kx, nx) / lx,
                    2.0 * PI * signed(ky, ny) / ly,
                );
                sum_h += c * cell;
                sum_s += c * (qx * qx + qy * qy) * cell;
            }
        }
        assert!((sum_h / h2 - 1.0).abs() < 1e-12, "{sum_h} vs {h2}");
        assert!((sum_s / xi2 - 1.0).abs() < 1e-12, "{sum_s} vs {xi2}");

        // 1D: row 0 of a map of waves along x only; the one-sided C1D integrates to h_rms².
        let scan: Vec<f64> = (0..nx)
            .map(|ix| {
                let x = ix as f64 * lx / nx as f64;
                1e-6 * (2.0 * PI * 2.0 * x / lx).cos() + 0.3e-6 * (2.0 * PI * 9.0 * x / lx).cos()
            })
            .collect();
        let (h2_1d, xi2_1d) = (
            (1e-12 + 0.09e-12) / 2.0,
            (1e-12 * (4.0 * PI / lx).powi(2) + 0.09e-12 * (18.0 * PI / lx).powi(2)) / 2.0,
        );
        let dq = 2.0 * PI / lx;
        let len = lx;
        let mut got = [[0.0; 2]; 2];
        for k in 1..nx / 2 {
            let power = dft2_power(&scan, nx, 1, k, 0);
            let q = k as f64 * dq;
            // SurfaceTopography: C_ST = |(L/n) DFT|²/L (the ±q branches are equal).
            let c_st = (len / nx as f64).powi(2) * power / len;
            // Persson: two-sided (2π)^−1 ∫dx ⟨hh⟩ e^{−iqx}, discretely (2π)^−1 (dx²/L) |DFT|².
            let c_p = (len / nx as f64).powi(2) * power / (2.0 * PI * len);
            for (i, c1d) in [
                Convention::SurfaceTopography.factor_1d() * c_st,
                Convention::Persson.factor_1d() * c_p,
            ]
            .into_iter()
            .enumerate()
            {
                got[i][0] += c1d * dq;
                got[i][1] += c1d * q * q * dq;
            }
        }
        for g in got {
            assert!((g[0] / h2_1d - 1.0).abs() < 1e-12, "{} vs {h2_1d}", g[0]);
            assert!((g[1] / xi2_1d - 1.0).abs() < 1e-12, "{} vs {xi2_1d}", g[1]);
        }
    }

    #[test]
    fn names_round_trip() {
        for c in [
            Convention::Coatcheck,
            Convention::Persson,
            Convention::SurfaceTopography,
        ] {
            assert_eq!(c.name().parse::<Convention>(), Ok(c));
        }
        assert!("st".parse::<Convention>().is_err());
    }
}
