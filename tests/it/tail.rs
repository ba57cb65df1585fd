//! The tail of |τ| for τ = (m + X, Y): closed-form limits (Rayleigh, folded normal, Gaussian
//! around a large mean), the 40-digit reference (tests/data/tail_ref.py, a different integral),
//! monotonicity and the probability/quantile round trip.

use coatcheck::prec::Termination;
use coatcheck::tail::{PEAK_TARGET_RTOL, ShearVector};

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

const EPSILONS: [f64; 8] = [0.1, 1e-3, 1e-6, 1e-20, 1e-50, 1e-100, 1e-200, 1e-300];

/// m = 0, sx = sy = s: P(|τ| > R) = e^{−R²/(2s²)}, so τ* = s√(2 ln(1/ε)) = τ_rms √(ln(1/ε))
/// with τ_rms² = sx² + sy²; through the general (polar) path, to 1e-13.
#[test]
fn rayleigh_closed_form() {
    for s in [1e-3, 1.0, 2.5e5] {
        let v = ShearVector::new(0.0, s, s).unwrap();
        for eps in EPSILONS {
            let t = v.peak(eps).unwrap();
            let tau_rms = (2.0f64).sqrt() * s;
            let want = tau_rms * (1.0 / eps).ln().sqrt();
            assert!(rel(t.value, want) < 1e-13, "{s} {eps}: {t:?} want {want}");
            assert!(t.status == Termination::Converged);
            assert!((t.value - want).abs() <= t.err, "{t:?} vs {want}");
            let l = v.ln_exceedance(0.7 * want).ln_p;
            let lw = -(0.7 * want / s).powi(2) / 2.0;
            assert!(
                (l.value - lw).abs() < 1e-13 * lw.abs().max(1.0),
                "{l:?} {lw}"
            );
        }
    }
}

/// sy = 0 is the folded normal |m + X|: at m = 0 P = erfc(R/(√2 sx)); and a tiny sy (1e-5 sx),
/// through the polar path, gives the same τ* to O(sy²/sx²).
#[test]
fn folded_normal_limit() {
    let v = ShearVector::new(0.0, 2.0, 0.0).unwrap();
    for r in [0.5, 3.0, 10.0, 40.0] {
        let want = libm::erfc(r / (2.0 * 2f64.sqrt()));
        assert!(rel(v.exceedance(r).value, want) < 1e-14, "{r}");
    }
    for m in [0.0, 0.7, 4.0] {
        let folded = ShearVector::new(m, 1.0, 0.0).unwrap();
        let thin = ShearVector::new(m, 1.0, 1e-5).unwrap();
        for eps in EPSILONS {
            let (a, b) = (folded.peak(eps).unwrap(), thin.peak(eps).unwrap());
            assert!(rel(b.value, a.value) < 1e-9, "{m} {eps}: {a:?} {b:?}");
            assert!(a.status == Termination::Converged && b.status == Termination::Converged);
        }
    }
}

/// m ≫ s: |τ| ≈ m + X + Y²/(2m), so τ* − m is the normal upper quantile of X (4.7534243088229
/// sx at ε = 1e-6, from mpmath) up to O(s²/m).
#[test]
fn gaussian_around_a_large_mean() {
    let v = ShearVector::new(1e6, 1.0, 1.0).unwrap();
    let t = v.peak(1e-6).unwrap();
    assert!(
        ((t.value - 1e6) - 4.753_424_308_822_9).abs() < 3e-6,
        "{}",
        t.value - 1e6
    );
}

/// τ* and ln P at 0.9 τ* against the 40-digit reference over m/s 0..10, sx/sy 1e-3..10 and
/// ε = 0.1..1e-300: τ* to 1e-12 relative (the issue asks 1e-10) within its own error estimate,
/// ln P to 1e-12 of max(1, |ln P|) (the relative error of P).
#[test]
fn tail_matches_high_precision_reference() {
    let data = include_str!("../data/tail_ref.csv");
    let (mut worst_t, mut worst_p, mut n) = (0.0f64, 0.0f64, 0);
    for line in data.lines().skip(1) {
        let c: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
        let v = ShearVector::new(c[0], c[1], c[2]).unwrap();
        let t = v.peak(c[3]).unwrap();
        let et = rel(t.value, c[4]);
        assert!(et < 1e-12, "{line}: tau* {t:?}, error {et:e}");
        assert!((t.value - c[4]).abs() <= t.err, "{line}: estimate {t:?}");
        assert!(t.err <= PEAK_TARGET_RTOL * t.value && t.status == Termination::Converged);
        let l = v.ln_exceedance(c[5]).ln_p;
        let ep = (l.value - c[6]).abs() / c[6].abs().max(1.0);
        assert!(ep < 1e-12, "{line}: ln P {l:?}, error {ep:e}");
        assert!((l.value - c[6]).abs() <= l.err, "{line}: estimate {l:?}");
        worst_t = worst_t.max(et);
        worst_p = worst_p.max(ep);
        n += 1;
    }
    assert_eq!(n, 32);
    eprintln!("worst relative error tau* {worst_t:e}, ln P {worst_p:e}");
}

/// P falls as the level rises and τ* rises as ε falls; exceedance(peak(ε)) = ε.
#[test]
fn monotone_and_round_trip() {
    for (m, sx, sy) in [
        (0.0, 1.0, 0.3),
        (2.0, 1.0, 1.0),
        (1.0, 0.1, 2.0),
        (5.0, 1.0, 0.0),
    ] {
        let v = ShearVector::new(m, sx, sy).unwrap();
        let mut last = f64::INFINITY;
        for i in 0..400 {
            let r = m + 0.1 * i as f64;
            let l = v.ln_exceedance(r).ln_p.value;
            assert!(l <= last, "{m} {sx} {sy}: ln P rises at {r}");
            last = l;
        }
        let mut prev = 0.0;
        for eps in EPSILONS {
            let t = v.peak(eps).unwrap().value;
            assert!(t > prev);
            prev = t;
            let back = v.ln_exceedance(t).ln_p.value;
            assert!(
                (back - eps.ln()).abs() < 1e-10,
                "{m} {sx} {sy} {eps}: {back}"
            );
            if eps > 1e-300 {
                assert!(rel(v.exceedance(t).value, eps) < 1e-10);
            }
        }
    }
}

#[test]
fn bad_input_is_named() {
    assert!(ShearVector::new(-1.0, 1.0, 1.0).is_err());
    assert!(ShearVector::new(0.0, f64::NAN, 1.0).is_err());
    let v = ShearVector::new(0.0, 1.0, 1.0).unwrap();
    let e = v.peak(0.7).unwrap_err().to_string();
    assert!(e.contains("exceedance probability"), "{e}");
    let fixed = ShearVector::new(3.0, 0.0, 0.0).unwrap();
    assert_eq!(fixed.peak(1e-6).unwrap().value, 3.0);
}

/// Far beyond the mean, P(|τ| > level) is 0 at once where its Gaussian bound underflows
/// (levels of 1e5 rms and more, as a bond strength against a thick film's shear), and just
/// inside that gap still the Rayleigh value e^{−R²/(2s²)} (subnormal-free, 1e-12 relative).
#[test]
fn exceedance_far_beyond_the_mean_underflows_to_zero() {
    let v = ShearVector::new(0.0, 1.0, 1.0).unwrap();
    let at = v.exceedance(38.0);
    assert!(rel(at.value, (-722.0f64).exp()) < 1e-12, "{at:?}");
    for level in [38.7, 1e3, 2.8e5, 1e12] {
        assert_eq!(v.exceedance(level).value, 0.0);
    }
    let far = ShearVector::new(2000.0, 36.0, 35.9).unwrap();
    assert_eq!(far.exceedance(10e6).value, 0.0);
}

/// The density of |τ| by a second, independent integral: the 2D Gaussian density on the circle
/// of radius R, f(R) = R ∫_0^{2π} φ(R cos θ − m; sx) φ(R sin θ; sy) dθ, by the trapezoid rule
/// (periodic and analytic: with 400 000 points the spacing is below a tenth of the integrand's
/// narrowest width, sy/R ≥ 1e-4 here, and it converges far below 1e-13).
fn density_on_the_circle(m: f64, sx: f64, sy: f64, r: f64) -> f64 {
    let n = 400_000;
    let norm = 1.0 / (2.0 * std::f64::consts::PI * sx * sy);
    let sum: f64 = (0..n)
        .map(|i| {
            let th = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
            let (x, y) = (r * th.cos() - m, r * th.sin());
            norm * (-0.5 * (x * x / (sx * sx) + y * y / (sy * sy))).exp()
        })
        .sum();
    r * sum * 2.0 * std::f64::consts::PI / n as f64
}

/// The density of |τ| (the HTML report's curve): the Rayleigh law R/s² e^{−R²/(2s²)} at m = 0
/// with equal rms (to 1e-12), the circle integral above otherwise (to 1e-11 relative where the
/// density is above 1e-300 of its peak), and an integral of 1 (composite 20-point
/// Gauss–Legendre on geometric panels over [0, m + 40 s_max], to 1e-12), for means from 0 to 10 s and rms ratios to
/// 1e-3, and the folded-normal limit.
#[test]
fn density_is_rayleigh_integrates_to_one_and_matches_the_circle_integral() {
    let s = 2.0;
    let v = ShearVector::new(0.0, s, s).unwrap();
    for r in [1e-3, 0.5, 2.0, 7.0, 30.0] {
        let want = r / (s * s) * (-r * r / (2.0 * s * s)).exp();
        assert!(
            rel(v.density(r), want) < 1e-12,
            "{r}: {} {want}",
            v.density(r)
        );
    }
    let (x, w) = coatcheck::quad::gauss_legendre(20);
    for (m, sx, sy) in [
        (0.0, 1.0, 1.0),
        (0.5, 1.0, 0.4),
        (3.0, 0.7, 1.0),
        (10.0, 1.0, 1.0),
        (2.0, 1.0, 1e-3),
        (1.0, 1.0, 0.0),
    ] {
        let v = ShearVector::new(m, sx, sy).unwrap();
        let hi = m + 40.0 * f64::max(sx, sy);
        // Panels growing geometrically from 1e-9·hi: with sy ≪ sx the density turns to 0 at
        // R = 0 over a width ~sy.
        let mut edges = vec![0.0, 1e-9 * hi];
        while *edges.last().unwrap() < hi {
            let e = (edges.last().unwrap() * 1.05).min(hi);
            edges.push(e);
        }
        let mut total = 0.0;
        for p in edges.windows(2) {
            let (mid, h) = (0.5 * (p[0] + p[1]), 0.5 * (p[1] - p[0]));
            for (xi, wi) in x.iter().zip(&w) {
                total += wi * h * v.density(mid + h * xi);
            }
        }
        assert!(
            (total - 1.0).abs() < 1e-12,
            "({m}, {sx}, {sy}): ∫ = {total}"
        );
        if sx > 0.0 && sy > 0.0 {
            for r in [0.3, 1.0, m.max(0.1), m + 2.0, m + 6.0] {
                let (got, want) = (v.density(r), density_on_the_circle(m, sx, sy, r));
                assert!(
                    rel(got, want) < 1e-11,
                    "({m}, {sx}, {sy}) at {r}: {got} vs {want}"
                );
            }
        }
    }
}
