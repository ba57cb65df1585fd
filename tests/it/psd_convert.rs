//! The exact 1D ↔ 2D PSD relation (`psd::abel`): analytic pairs, the Abel round
//! trip, and line scans of a synthetic map against the map's own 2D PSD.

use coatcheck::psd::Spectrum;
use coatcheck::psd::abel::{Conversion, c1d_at, c1d_of_spectrum, c2d_from_c1d};
use coatcheck::topography::Profile;
use coatcheck::topography::spectrum::{PsdOptions, map_psd, profile_psd};
use coatcheck::topography::synth::{Amplitude, SynthSpec, self_affine_map};
use std::f64::consts::PI;

/// C(k) = (1 + k²/k0²)^−(1+H) and its closed-form one-sided 1D PSD
/// C1D(q) = 2√π Γ(H+½)/Γ(H+1) · √(k0² + q²) · (1 + q²/k0²)^−(1+H).
fn lorentz(h: f64, k0: f64) -> (impl Fn(f64) -> f64, impl Fn(f64) -> f64) {
    let g = statrs::function::gamma::gamma;
    let a = 2.0 * PI.sqrt() * g(h + 0.5) / g(h + 1.0);
    let c2 = move |k: f64| (1.0 + (k / k0).powi(2)).powf(-(1.0 + h));
    let c1 = move |q: f64| a * (k0 * k0 + q * q).sqrt() * (1.0 + (q / k0).powi(2)).powf(-(1.0 + h));
    (c2, c1)
}

#[test]
fn forward_transform_of_a_gaussian_is_closed_form() {
    // C(k) = e^{−k²/2s²} ⇒ C1D(q) = 2√(2π) s e^{−q²/2s²}; tolerance 1e-12 relative.
    let s = 3e5;
    let knots: Vec<f64> = (0..=24).map(|i| s * (1e-3 + 0.5 * i as f64)).collect();
    for i in 0..40 {
        let q = s * (0.01 + 0.15 * i as f64);
        let e = c1d_at(|k| (-(k * k) / (2.0 * s * s)).exp(), &knots, q);
        let exact = 2.0 * (2.0 * PI).sqrt() * s * (-(q * q) / (2.0 * s * s)).exp();
        let r = (e.value / exact - 1.0).abs();
        assert!(r < 1e-12, "q = {q:e}: {r:e}");
        // The error estimate is honest (covers the error) and small against the peak.
        assert!((e.value - exact).abs() <= e.err + 1e-15 * exact);
        assert!(
            e.err < 1e-12 * 2.0 * (2.0 * PI).sqrt() * s,
            "estimate {:e}",
            e.err
        );
    }
}

#[test]
fn forward_transform_of_a_power_law_with_roll_off_is_closed_form() {
    let (c2, c1) = lorentz(0.8, 1e5);
    let knots: Vec<f64> = (0..=90).map(|i| 1e2 * 2f64.powi(i / 2)).collect();
    for i in 0..30 {
        let q = 1e3 * 10f64.powf(i as f64 / 6.0);
        let r = (c1d_at(&c2, &knots, q).value / c1(q) - 1.0).abs();
        assert!(r < 1e-12, "q = {q:e}: {r:e}");
    }
}

#[test]
fn inverse_of_the_closed_form_pair_converges() {
    // Sampled closed-form C1D, n points per decade over five decades: the inverse Abel
    // transform gives C back to the interpolation error of the tabulated C1D, which falls
    // like h^2.5 (measured 1.6e-3, 2.8e-4, 4.9e-5 at 10, 20, 40 per decade).
    let (c2, c1) = lorentz(0.8, 1e5);
    for (ppd, tol) in [(10usize, 2.5e-3), (20, 4e-4), (40, 8e-5)] {
        let q: Vec<f64> = (0..=5 * ppd)
            .map(|i| 1e3 * 10f64.powf(i as f64 / ppd as f64))
            .collect();
        let f: Vec<f64> = q.iter().map(|&x| c1(x)).collect();
        let conv = c2d_from_c1d(&q, &f, Conversion::InverseAbel).unwrap();
        assert!(conv.max_rel_err() < 1e-10);
        let worst = conv
            .c
            .iter()
            .zip(&q)
            .map(|(e, &x)| (e.value / c2(x) - 1.0).abs())
            .fold(0.0, f64::max);
        assert!(worst < tol, "{ppd} per decade: {worst:e}");
    }
}

#[test]
fn abel_round_trip_of_a_gaussian() {
    // Forward numerically, then back: C(k) = e^{−k²/2s²}, tabulated 40 per decade on
    // [0.01 s, 6.3 s]; compared on [0.01 s, 3 s] (beyond the last point C1D is continued as a
    // power law, which a Gaussian is not, so the last octave is left out). Tolerance 2e-3.
    let s = 1e6;
    let knots: Vec<f64> = (0..=24).map(|i| s * (1e-4 + 0.5 * i as f64)).collect();
    let c2 = |k: f64| (-(k * k) / (2.0 * s * s)).exp();
    let q: Vec<f64> = (0..=112)
        .map(|i| s * 0.01 * 10f64.powf(i as f64 / 40.0))
        .collect();
    let f: Vec<f64> = q.iter().map(|&x| c1d_at(c2, &knots, x).value).collect();
    let conv = c2d_from_c1d(&q, &f, Conversion::InverseAbel).unwrap();
    let mut worst: f64 = 0.0;
    for (e, &x) in conv.c.iter().zip(&q) {
        if x <= 3.0 * s {
            worst = worst.max((e.value / c2(x) - 1.0).abs());
        }
    }
    eprintln!("Gaussian round trip: {worst:e}");
    assert!(worst < 2e-3, "{worst:e}");
}

#[test]
fn abel_round_trip_of_a_self_affine_spectrum() {
    // The paper-style model with roll-off (H = 0.8, q0 = 1e4, q_r = 1e5, q1 = 1e8), 40 per
    // decade: back within 2e-3 away from the roll-off kink (where C′ jumps) and the cut-off.
    let sp = Spectrum::self_affine(0.8, 1e4, 1e8, Some(1e5)).unwrap();
    let q: Vec<f64> = (0..160)
        .map(|i| 1e4 * 10f64.powf(i as f64 / 40.0))
        .collect();
    let f: Vec<f64> = q.iter().map(|&x| c1d_of_spectrum(&sp, x).value).collect();
    let conv = c2d_from_c1d(&q, &f, Conversion::InverseAbel).unwrap();
    let mut worst: f64 = 0.0;
    for (e, &x) in conv.c.iter().zip(&q) {
        if !(0.7e5..=1.5e5).contains(&x) && x < 1e7 {
            worst = worst.max((e.value / sp.c(x) - 1.0).abs());
        }
    }
    eprintln!("self-affine round trip: {worst:e}");
    assert!(worst < 2e-3, "{worst:e}");
}

#[test]
fn line_scans_of_a_map_convert_to_the_maps_2d_psd() {
    // 512² periodic self-affine map (H = 0.7, roll-off at 8 q_L, roughness to the corners).
    // Its rows as line scans → 1D PSD → exact inverse Abel; compared with the map's radially
    // averaged 2D PSD and with the generator's exact C, for q from 2 q_r = 16 q_L up to half
    // the 4-pixel cut-off, 64 q_L (the rows' 1D PSD is truncated at the y Nyquist wavenumber
    // 256 q_L, a < 1 % effect there). Tolerance 5 %.
    let n = 512;
    let dx = 1e-6;
    let ql = 2.0 * PI / (n as f64 * dx);
    let sp = SynthSpec {
        n,
        dx,
        hurst: 0.7,
        q0: 8.0 * ql,
        q1: 2000.0 * ql,
        amplitude: Amplitude::RmsSlope(0.3),
        seed: 11,
    };
    let m = self_affine_map(&sp).unwrap();
    let opts = PsdOptions {
        cutoff_pixels: 4.0,
        points_per_decade: 20,
        ..Default::default()
    };
    let map = map_psd(&m, &opts).unwrap();
    let lines = profile_psd(
        &Profile {
            dx,
            scans: (0..n).map(|iy| m.row(iy).to_vec()).collect(),
            periodic: true,
        },
        &opts,
    )
    .unwrap();
    let map_c = Spectrum::Tabulated(map.c2d.clone());
    let (mut vs_map, mut vs_exact, mut points): (f64, f64, usize) = (0.0, 0.0, 0);
    for (q, c) in lines.c2d.q().iter().zip(lines.c2d.c_values()) {
        if *q >= 2.0 * sp.q0 && *q <= 0.5 * lines.summary.q_max {
            vs_map = vs_map.max((c / map_c.c(*q) - 1.0).abs());
            vs_exact = vs_exact.max((c / sp.c(*q) - 1.0).abs());
            points += 1;
        }
    }
    eprintln!("line scans → 2D vs map: {vs_map:.4}, vs exact: {vs_exact:.4} ({points} points)");
    assert!(points >= 10, "{points}");
    assert!(vs_map < 0.05 && vs_exact < 0.05, "{vs_map} {vs_exact}");
}

/// One row of a periodic self-affine map (H, roll-off at 8 q_L, roughness to the corners) as a
/// single line scan, and the generator's exact 2D PSD.
fn single_scan(hurst: f64, seed: u64) -> (Profile, SynthSpec) {
    let (n, dx) = (1024, 1e-6);
    let ql = 2.0 * PI / (n as f64 * dx);
    let sp = SynthSpec {
        n,
        dx,
        hurst,
        q0: 8.0 * ql,
        q1: 1000.0 * ql,
        amplitude: Amplitude::RmsSlope(0.3),
        seed,
    };
    let m = self_affine_map(&sp).unwrap();
    let row = m.row(seed as usize % n).to_vec();
    let p = Profile {
        dx,
        scans: vec![row],
        periodic: true,
    };
    (p, sp)
}

/// A single line scan (the commonest measurement) gives a positive, finite 2D PSD: the noisy
/// C1D is fitted as non-increasing before the inverse Abel transform. One row of a 1024²
/// self-affine map, H = 0.3, 0.5, 0.7, 1, six seeds each, default options (Hann window not
/// needed: the rows are periodic), compared with the generator's exact C on [2 q_r, q_max/2]:
/// the mean of ln(C/C_exact) over points and seeds lies within ±0.35 (measured −0.10 to −0.24,
/// mostly the −E ln of the periodogram's scatter), and the rms slope² over that range within
/// 35 % in every scan (measured: at most 28 %). A single scan cannot do better: a bin of m
/// modes scatters by 1/√m.
#[test]
fn one_line_scan_converts_to_a_positive_2d_psd_near_the_true_one() {
    for hurst in [0.3, 0.5, 0.7, 1.0] {
        let (mut sum_ln, mut points) = (0.0, 0);
        for seed in 1..=6 {
            let (p, sp) = single_scan(hurst, seed);
            let psd = profile_psd(&p, &PsdOptions::default()).unwrap();
            let (lo, hi) = (2.0 * sp.q0, 0.5 * psd.summary.q_max);
            for (q, c) in psd.c2d.q().iter().zip(psd.c2d.c_values()) {
                assert!(
                    c.is_finite() && *c > 0.0,
                    "H {hurst} seed {seed}: C({q:e}) = {c:e}"
                );
                if *q >= lo && *q <= hi {
                    sum_ln += (c / sp.c(*q)).ln();
                    points += 1;
                }
            }
            let kept = Spectrum::Tabulated(psd.c2d.restricted(Some(lo), Some(hi)).unwrap());
            let (a, b) = kept.support();
            let exact = Spectrum::self_affine(hurst, a, b, None)
                .unwrap()
                .scaled(sp.c(a));
            let err = kept.slope_sq().value / exact.slope_sq().value - 1.0;
            assert!(
                err.abs() < 0.35,
                "H {hurst} seed {seed}: slope² off by {err:.3}"
            );
        }
        let bias = sum_ln / points as f64;
        eprintln!("H = {hurst}: mean ln(C/C_exact) = {bias:.3} over {points} points");
        assert!(
            points >= 50 && bias.abs() < 0.35,
            "H {hurst}: {bias} ({points})"
        );
    }
}

/// A real stylus profile (Bruker Dektak, 9600 samples, tilted) as a single scan: a PSD with
/// positive, finite C from the command line (exit 0), where the exact transform of the binned
/// C1D gave C < 0.
#[test]
fn a_real_single_stylus_profile_gives_a_psd() {
    let o = crate::common::run(&["psd", "tests/data/dektak-1-profile.csv", "--format", "json"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let j = crate::common::json(&o);
    let c = j["c_m4"].as_array().expect("C values");
    assert!(c.len() >= 20, "{}", c.len());
    for v in c {
        let v = v.as_f64().expect("a number");
        assert!(v.is_finite() && v > 0.0, "{v}");
    }
}
