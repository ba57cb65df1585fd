//! Spectra shared by the tests and the benchmark examples (which include this file by path).

use coatcheck::psd::{Spectrum, Tabulated};

/// A measured-like tabulated PSD: self-affine (H = 0.8) with roll-off at 3e4 1/m and a 3 %
/// ripple, `n` points from 1e4 to 1e8 1/m, rms slope 0.5.
pub fn measured_like(n: usize) -> Spectrum {
    let q: Vec<f64> = (0..n)
        .map(|i| 1e4 * 1e4f64.powf(i as f64 / (n - 1) as f64))
        .collect();
    let c: Vec<f64> = q
        .iter()
        .map(|&q| {
            let base = if q < 3e4 {
                1.0
            } else {
                (q / 3e4).powf(-2.0 * 1.8)
            };
            base * (1.0 + 0.03 * (7.0 * q.ln()).sin())
        })
        .collect();
    Spectrum::Tabulated(Tabulated::new(q, c).expect("valid table"))
        .scaled_to_rms_slope(0.5)
        .expect("positive slope")
}
