//! Filling small holes of non-measured points (NaN) by harmonic interpolation.
//!
//! A hole is a 4-connected set of non-measured points. Holes of at most [`MAX_HOLE`] points
//! (dropouts: single pixels, short runs) are filled with the discrete harmonic function that
//! takes the measured heights around them as boundary values: each filled point is the mean of
//! its measured or filled 4-neighbours (in a line scan, of its 2 neighbours: linear
//! interpolation), solved by Gauss–Seidel sweeps. Larger holes and missing bands are left for
//! the largest complete rectangle ([`crate::topography`]) to cut away.
//!
//! Effect on the spectrum, measured on non-periodic 563 × 484 cuts of self-affine maps
//! (H = 0.8, q0 = 1e4, q1 = 1e6 1/m, 1 µm pixels) with 117, 2000 and 20 000 randomly punched
//! single-point holes (0.04 %, 0.7 %, 7 %): below q1/2 the filled map's C differs from the
//! intact map's by 0.000, 0.0002 and 0.002 in rms ln(C/C_true), its h_rms within the kept range
//! by < 1e-4 and its rms slope by 0.0 %, 0.06 % and 0.3 % (it smooths the holes' own
//! short-wavelength content). The largest complete rectangle of the same maps kept 8–10 %,
//! 0.6 % and 0.1 % of the points, its q_min rose 5- to 50-fold and its h_rms within the kept
//! range fell to 25–32 %, 15 % and 2 % of the true value. The test
//! `filling_dropouts_keeps_the_spectrum` pins the 0.7 % case.

/// The largest hole filled, in points.
pub const MAX_HOLE: usize = 16;

/// Fill the holes of at most [`MAX_HOLE`] points of the row-major `nx` × `ny` grid `z` in place;
/// returns the number of points filled.
pub fn fill_small_holes(z: &mut [f64], nx: usize, ny: usize) -> usize {
    let neighbours = |k: usize| {
        let (ix, iy) = (k % nx, k / nx);
        [
            (ix > 0).then(|| k - 1),
            (ix + 1 < nx).then(|| k + 1),
            (iy > 0).then(|| k - nx),
            (iy + 1 < ny).then(|| k + nx),
        ]
        .into_iter()
        .flatten()
    };
    let mut seen = vec![false; z.len()];
    let mut filled = 0;
    for start in 0..z.len() {
        if z[start].is_finite() || seen[start] {
            continue;
        }
        // The hole around `start`, up to one point more than fits.
        let mut hole = vec![start];
        seen[start] = true;
        let mut i = 0;
        let mut large = false;
        while i < hole.len() {
            for n in neighbours(hole[i]) {
                if !z[n].is_finite() && !seen[n] {
                    seen[n] = true;
                    hole.push(n);
                }
            }
            i += 1;
            if hole.len() > MAX_HOLE {
                large = true;
            }
        }
        if large {
            continue;
        }
        let boundary: Vec<f64> = hole
            .iter()
            .flat_map(|&k| neighbours(k))
            .filter_map(|n| z[n].is_finite().then_some(z[n]))
            .collect();
        if boundary.is_empty() {
            continue;
        }
        let start_value = boundary.iter().sum::<f64>() / boundary.len() as f64;
        let scale = boundary
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()))
            .max(f64::MIN_POSITIVE);
        let mut value: Vec<f64> = vec![start_value; hole.len()];
        let index = |k: usize| hole.iter().position(|&h| h == k);
        for _ in 0..10_000 {
            let mut change = 0.0f64;
            for j in 0..hole.len() {
                let (mut s, mut c) = (0.0, 0.0);
                for n in neighbours(hole[j]) {
                    s += match index(n) {
                        Some(m) => value[m],
                        None => z[n],
                    };
                    c += 1.0;
                }
                let v = s / c;
                change = change.max((v - value[j]).abs());
                value[j] = v;
            }
            if change <= 1e-14 * scale {
                break;
            }
        }
        for (&k, &v) in hole.iter().zip(&value) {
            z[k] = v;
        }
        filled += hole.len();
    }
    filled
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::psd::Spectrum;
    use crate::topography::HeightMap;
    use crate::topography::spectrum::{PsdOptions, map_psd};
    use crate::topography::synth::{Amplitude, SplitMix64, SynthSpec, self_affine_map};

    #[test]
    fn filling_dropouts_keeps_the_spectrum() {
        let big = self_affine_map(&SynthSpec {
            n: 1024,
            dx: 1e-6,
            hurst: 0.8,
            q0: 1e4,
            q1: 1e6,
            amplitude: Amplitude::RmsHeight(1e-6),
            seed: 3,
        })
        .unwrap();
        let (nx, ny) = (563usize, 484usize);
        let z: Vec<f64> = (0..ny)
            .flat_map(|iy| big.z[iy * 1024..iy * 1024 + nx].to_vec())
            .collect();
        let map = |z: Vec<f64>| HeightMap {
            nx,
            ny,
            dx: 1e-6,
            dy: 1e-6,
            z,
            periodic: false,
        };
        let truth = map_psd(&map(z.clone()), &PsdOptions::default()).unwrap();
        let mut rng = SplitMix64::new(103);
        let mut holed = z;
        for _ in 0..2000 {
            holed[(rng.next_u64() % (nx * ny) as u64) as usize] = f64::NAN;
        }
        // The rectangle alone would keep under 1 % of the points.
        let r = crate::topography::largest_rectangle(&holed, nx, ny);
        assert!(((r.w * r.h) as f64) < 0.01 * (nx * ny) as f64);
        let filled = fill_small_holes(&mut holed, nx, ny);
        assert!((1900..=2000).contains(&filled), "{filled}");
        assert!(holed.iter().all(|v| v.is_finite()));
        let got = map_psd(&map(holed), &PsdOptions::default()).unwrap();
        let s = Spectrum::Tabulated(got.c2d.clone());
        let (mut sq, mut n) = (0.0, 0);
        for (&q, &c) in truth.c2d.q().iter().zip(truth.c2d.c_values()) {
            if q <= 5e5 {
                sq += (s.c(q) / c).ln().powi(2);
                n += 1;
            }
        }
        // Measured: 0.0002 rms in ln C, h_rms < 1e-4, rms slope 0.06 % low.
        assert!((sq / n as f64).sqrt() < 1e-3, "{}", (sq / n as f64).sqrt());
        let rel = |a: f64, b: f64| (a / b - 1.0).abs();
        assert!(rel(got.summary.h_rms_kept, truth.summary.h_rms_kept) < 1e-4);
        assert!(rel(got.summary.rms_slope, truth.summary.rms_slope) < 2e-3);
    }

    #[test]
    fn a_plane_is_filled_exactly_and_large_holes_are_left() {
        // A plane is harmonic: its interior holes are filled to rounding (at the border the
        // mean of fewer neighbours is not, and only finiteness is asked).
        let (nx, ny) = (20, 12);
        let plane = |k: usize| 0.3 * (k % nx) as f64 - 0.7 * (k / nx) as f64 + 2.0;
        let mut z: Vec<f64> = (0..nx * ny).map(plane).collect();
        let interior = [25, 26, 27, 45, 3 * nx + 2];
        for k in interior.into_iter().chain([0, nx * ny - 1]) {
            z[k] = f64::NAN;
        }
        // A 5 × 4 block: 20 points, too large.
        let block = |k: usize| (6..10).contains(&(k / nx)) && (10..15).contains(&(k % nx));
        for k in (0..nx * ny).filter(|&k| block(k)) {
            z[k] = f64::NAN;
        }
        assert_eq!(fill_small_holes(&mut z, nx, ny), 7);
        for (k, v) in z.iter().enumerate() {
            if block(k) {
                assert!(v.is_nan());
            } else if k == 0 || k == nx * ny - 1 {
                assert!(v.is_finite());
            } else {
                assert!((v - plane(k)).abs() < 1e-12, "{k}: {v}");
            }
        }
        // A scan: linear interpolation across a 3-point gap.
        let mut scan = vec![0.0, 1.0, f64::NAN, f64::NAN, f64::NAN, 5.0, 6.0];
        assert_eq!(fill_small_holes(&mut scan, 7, 1), 3);
        for (i, v) in scan.iter().enumerate() {
            assert!((v - i as f64).abs() < 1e-12, "{i}: {v}");
        }
    }
}
