//! Tests of the minimum-thickness search and its pieces, and of the check rules.

use super::criteria::upper_check;
use super::itp::inverse_quadratic;
use super::min_thickness::{Sample, peak_guard};
use super::*;
use crate::layer::Bilayer;
use crate::prec::Termination;

fn sample(x: f64, u: f64) -> Sample {
    Sample {
        x,
        u,
        kind: Some(CheckKind::BondShear),
    }
}

#[test]
fn peak_guard_resolves_a_smooth_maximum_below_one() {
    let mut n = 0;
    let mut f = |x: f64| {
        n += 1;
        Ok(sample(x, 0.9 - (x - 0.7) * (x - 0.7)))
    };
    let got = peak_guard(
        sample(-0.5, -0.54),
        sample(0.5, 0.86),
        sample(1.5, 0.26),
        &mut f,
    );
    assert_eq!(got.unwrap(), None);
    // A parabola is resolved by its vertex and one confirmation at most.
    assert!(n <= 2, "{n}");
}

#[test]
fn peak_guard_finds_a_peak_above_one_between_samples() {
    // A Gaussian bump of height 1.3 and width 0.08 between samples that see < 0.75.
    let u = |x: f64| 0.2 + 1.1 * (-((x - 0.62) / 0.08f64).powi(2)).exp();
    let mut f = |x: f64| Ok(sample(x, u(x)));
    let (fail, pass) = peak_guard(
        sample(0.3, u(0.3)),
        sample(0.5, u(0.5)),
        sample(0.9, u(0.9)),
        &mut f,
    )
    .unwrap()
    .expect("the bump fails");
    assert!(
        fail.u > 1.0 && pass.u <= 1.0 && pass.x > fail.x,
        "{fail:?} {pass:?}"
    );
}

#[test]
fn inverse_quadratic_is_exact_for_a_quadratic_inverse() {
    // x = 2 + 0.5 y − 0.1 y²: the zero is x = 2.
    let x = |y: f64| 2.0 + 0.5 * y - 0.1 * y * y;
    let pts = [(x(-1.0), -1.0), (x(0.3), 0.3), (x(2.0), 2.0)];
    assert!((inverse_quadratic(&pts).unwrap() - 2.0).abs() < 1e-14);
    assert_eq!(inverse_quadratic(&pts[..2]), None);
}

/// Synthetic utilisations u(ln d) with known crossings.
fn search(u: impl Fn(f64) -> f64) -> MinThickness {
    search_min_thickness(1e-9, 1e-2, |d| {
        Ok(Utilisation {
            value: u(d.ln()),
            rel_err: 0.0,
            kind: Some(CheckKind::BondShear),
        })
    })
    .unwrap()
}

fn assert_crossing(m: &MinThickness, want: f64) {
    let d = m.thickness.unwrap();
    assert!(!m.all_pass_to_floor);
    assert!((d.value - want).abs() <= d.err * 1.0001, "{d:?} vs {want}");
    assert!(d.err <= 0.5 * D_MIN_RTOL * d.value * 1.001, "{d:?}");
}

#[test]
fn monotone_utilisation_crossing() {
    // u = (d0/d)^1.5 fails below d0 = 3.7e-6.
    let m = search(|x| (3.7e-6f64.ln() - x).exp().powf(1.5));
    assert_crossing(&m, 3.7e-6);
    // Eight per decade would take 29 scan samples (3.4 decades, plus the bulk bound); the
    // widened steps cross u < 0.15, and the interpolation with its closing step needs two
    // refinement steps where bisection needs 8.
    assert!(m.evaluations <= 12, "{}", m.evaluations);
}

/// The utilisations' own error enters d_min's estimate: perturbing u by its stated relative
/// error moves d_min by no more than the estimate.
#[test]
fn utilisation_error_widens_the_estimate() {
    let run = |scale: f64, rel_err: f64| {
        search_min_thickness(1e-9, 1e-2, |d| {
            Ok(Utilisation {
                value: scale * (3.7e-6f64.ln() - d.ln()).exp().powf(0.05),
                rel_err,
                kind: Some(CheckKind::BondShear),
            })
        })
        .unwrap()
        .thickness
        .unwrap()
    };
    let exact = run(1.0, 0.0);
    let stated = run(1.0, 1e-3);
    // A shallow crossing (d ln u/d ln d = -0.05): 1e-3 in u is 2 % in d, beyond the bracket.
    assert!(stated.err >= 0.02 * stated.value, "{stated:?}");
    for scale in [1.0 - 1e-3, 1.0 + 1e-3] {
        let moved = run(scale, 0.0);
        assert!(
            (moved.value - exact.value).abs() <= stated.err,
            "{moved:?} {stated:?}"
        );
    }
}

/// |g(qd)| on a dense grid in ln(qd) over [1e-4, 1e3] for a film on a substrate.
fn shear_kernel(film: (f64, f64), substrate: (f64, f64)) -> Vec<(f64, f64)> {
    let e = |(y, nu): (f64, f64)| crate::layer::Elastic::new(y, nu).unwrap();
    let b = Bilayer::new(e(film), e(substrate));
    (0..=3500)
        .map(|i| {
            let t = (1e-4f64).ln() + i as f64 * 7.0 * std::f64::consts::LN_10 / 3500.0;
            (t, b.response(t.exp()).g.abs())
        })
        .collect()
}

/// The premise of the widened scan steps (module docs, step 2): |g| is unimodal in ln(qd)
/// and exceeds each step's `level` of its maximum on a stretch wider than the step, for
/// films softer and stiffer than their substrates and any Poisson ratios; each step's
/// threshold is under level/√2.
#[test]
fn wide_steps_are_narrower_than_the_shear_kernel() {
    let mut narrowest = [f64::INFINITY; WIDE_STEPS.len()];
    for nu0 in [0.0, 0.25, 0.5] {
        for ratio in [1e-3, 1.0, 1e5] {
            for nu1 in [0.0, 0.5] {
                let g = shear_kernel((1e6, nu0), (1e6 * ratio, nu1));
                let (i_max, g_max) = g
                    .iter()
                    .enumerate()
                    .map(|(i, p)| (i, p.1))
                    .max_by(|a, b| a.1.total_cmp(&b.1))
                    .unwrap();
                assert!(i_max > 0 && i_max < g.len() - 1, "{nu0} {ratio} {nu1}");
                // Rising up to the maximum and falling after it (to rounding).
                let tol = 1e-12 * g_max;
                assert!(g[..=i_max].windows(2).all(|w| w[1].1 >= w[0].1 - tol));
                assert!(g[i_max..].windows(2).all(|w| w[1].1 <= w[0].1 + tol));
                for (n, w) in narrowest.iter_mut().zip(WIDE_STEPS) {
                    let above: Vec<f64> = g
                        .iter()
                        .filter(|p| p.1 >= w.level * g_max)
                        .map(|p| p.0)
                        .collect();
                    *n = n.min(above[above.len() - 1] - above[0]);
                }
            }
        }
    }
    // The narrowest, a ν = 0 film on a much stiffer substrate: 1.90 above a quarter of
    // the maximum, 1.32 above half of it.
    for (n, w) in narrowest.into_iter().zip(WIDE_STEPS) {
        let longest = w.decades * std::f64::consts::LN_10;
        assert!(n > 1.05 * longest, "{w:?}: {n} vs {longest}");
        assert!(w.below < w.level / 2f64.sqrt(), "{w:?}");
    }
}

/// The premise of the scan start (module docs, step 1): beyond q·d = 10, |f| and |g|
/// decrease and S⁻² is within 1.8e-6 of 1, for films softer and stiffer than their
/// substrates and any Poisson ratios; the slack covers the latter's effect on A/A0.
#[test]
fn thick_films_only_relax_beyond_the_scan_start() {
    let e = |y: f64, nu: f64| crate::layer::Elastic::new(y, nu).unwrap();
    let mut dev = 0.0f64;
    for nu0 in [0.0, 0.25, 0.5] {
        for ratio in [1e-4, 1e-2, 1.0, 1e2, 1e5] {
            for nu1 in [0.0, 0.5] {
                let b = Bilayer::new(e(1e6, nu0), e(1e6 * ratio, nu1));
                let r: Vec<_> = (0..=2000)
                    .map(|i| b.response(SCAN_START_QD * 10f64.powf(i as f64 / 1000.0)))
                    .collect();
                for w in r.windows(2) {
                    assert!(w[1].f.abs() <= w[0].f.abs() && w[1].g.abs() <= w[0].g.abs());
                }
                dev = r
                    .iter()
                    .map(|x| (x.s.powi(-2) - 1.0).abs())
                    .fold(dev, f64::max);
            }
        }
    }
    assert!(dev <= 1.9e-6, "{dev:e}");
    // A/A0 moves by at most half the relative change of G, the rms stresses by about
    // that of G: the slack covers it five times over, and the search engine's error.
    assert!(5.0 * dev <= THICK_SLACK, "{dev:e}");
}

/// A bond-shear band of the sharpest physical shape (one roughness mode on the narrowest
/// kernel, module docs, step 2) failing at its peak, at every position relative to the
/// widened steps: its upper edge is found.
#[test]
fn a_single_mode_shear_band_is_found_between_wide_steps() {
    let g = shear_kernel((1e6, 0.0), (1e11, 0.5));
    let g_max = g.iter().map(|p| p.1).fold(0.0, f64::max);
    let b = Bilayer::new(
        crate::layer::Elastic::new(1e6, 0.0).unwrap(),
        crate::layer::Elastic::new(1e11, 0.5).unwrap(),
    );
    for k in 0..12 {
        let q0 = 1e5 * 10f64.powf(WIDE_STEPS[0].decades * k as f64 / 12.0);
        let u = |d: f64| 1.05 * b.response(q0 * d).g.abs() / g_max;
        let m = search(|x| u(x.exp()));
        // The upper edge by bisection from the kernel's maximum (q0·d = 2.07) upwards.
        let (mut lo, mut hi) = (2.07 / q0, 100.0 / q0);
        assert!(u(lo) > 1.0 && u(hi) < 1.0);
        while hi / lo > 1.0 + 1e-12 {
            let mid = (lo * hi).sqrt();
            if u(mid) > 1.0 { lo = mid } else { hi = mid }
        }
        assert_crossing(&m, lo);
    }
}

/// Bond-shear utilisations of random few-mode spectra on the narrowest kernel (module docs,
/// step 2), peaking between 1.02 and 1.6: the search agrees with a dense scan at 400
/// points per decade (bisected to 1e-12) on the band's upper edge.
#[test]
fn few_mode_shear_bands_match_a_dense_scan() {
    let e = |y: f64, nu: f64| crate::layer::Elastic::new(y, nu).unwrap();
    let b = Bilayer::new(e(1e6, 0.0), e(1e11, 0.5));
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut rand = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let grid: Vec<f64> = (0..=2800)
        .map(|i| 1e-2 * 10f64.powf(-i as f64 / 400.0))
        .collect();
    for case in 0..24 {
        let modes: Vec<(f64, f64)> = (0..1 + case % 4)
            .map(|_| (1e5 * 10f64.powf(3.0 * rand()), 10f64.powf(-2.0 * rand())))
            .collect();
        let tau = |d: f64| {
            modes
                .iter()
                .map(|&(q, w)| w * b.response(q * d).g.powi(2))
                .sum::<f64>()
                .sqrt()
        };
        let peak = grid.iter().map(|&d| tau(d)).fold(0.0, f64::max);
        let scale = (1.02 + 0.58 * rand()) / peak;
        let u = |d: f64| scale * tau(d);
        let m = search(|x| u(x.exp()));
        // The dense scan's largest failing thickness, then bisection to the edge above it.
        let i = grid.iter().position(|&d| u(d) > 1.0).unwrap();
        assert!(i > 0);
        let (mut lo, mut hi) = (grid[i], grid[i - 1]);
        while hi / lo > 1.0 + 1e-12 {
            let mid = (lo * hi).sqrt();
            if u(mid) > 1.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let d = m.thickness.unwrap();
        assert!(
            (d.value - lo).abs() <= d.err * 1.0001,
            "case {case} {modes:?}: {d:?} vs {lo:e}"
        );
    }
}

#[test]
fn a_flat_low_utilisation_is_crossed_in_wide_steps() {
    // Flat at 0.01 on the thick side, failing below d0 = 3.7e-6.
    let m = search(|x| 0.01 + (3.7e-6f64.ln() - x).exp().powf(1.5));
    let d = m.thickness.unwrap();
    assert!((d.value / 3.7e-6 - 1.0).abs() < 0.01, "{d:?}");
    // Eight per decade down to the crossing would be 29 samples.
    assert!(m.evaluations <= 16, "{}", m.evaluations);
}

#[test]
fn a_failing_band_gives_its_upper_edge() {
    // A broad hump in ln d failing on [1e-7, 2e-5]; passing below and above.
    let (a, b) = (1e-7f64.ln(), 2e-5f64.ln());
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    let m = search(|x| 2.0 - ((x - mid) / half).powi(2));
    assert_crossing(&m, 2e-5);
    // Bisection on the whole range cannot work: both ends pass.
    assert!(2.0 - ((1e-9f64.ln() - mid) / half).powi(2) < 1.0);
}

#[test]
fn a_band_narrower_than_the_scan_step_is_found() {
    // Peak 1.02 midway between two samples (the scan step in ln d is h = ln(1e7)/56);
    // it fails for |ln d − c| < 0.1, a band narrower than the step, so no sample fails.
    let h = 1e7f64.ln() / 56.0;
    let c = (1e-2 * SCAN_START_QD / BULK_QD).ln() - 20.5 * h;
    let m = search(|x| 1.02 - 2.0 * (x - c).powi(2));
    let edge = (c + 0.1).exp();
    assert_crossing(&m, edge);
}

#[test]
fn ends_of_the_search() {
    let m = search(|_| 1.5);
    assert_eq!(m.thickness, None);
    assert_eq!(m.governing, Some(CheckKind::BondShear));
    let m = search(|_| 0.2);
    assert!(m.all_pass_to_floor);
    assert_eq!(m.thickness.unwrap().value, 1e-9);
}

#[test]
fn log_space_hits_both_ends() {
    let v = log_space(1e-6, 1e-3, 4);
    assert_eq!(v.len(), 4);
    assert_eq!(v[0], 1e-6);
    assert_eq!(v[3], 1e-3);
    assert!((v[1] / 1e-5 - 1.0).abs() < 1e-14);
    assert_eq!(log_space(2.0, 3.0, 1), vec![2.0]);
}

#[test]
fn check_names_round_trip() {
    for c in CheckKind::ALL {
        assert_eq!(CheckKind::from_name(c.name()), Some(c));
    }
    assert_eq!(CheckKind::from_name("bond"), None);
}

#[test]
fn upper_checks_margin_and_pass() {
    let c = upper_check(CheckKind::BondShear, Estimate::exact(2.0), 8.0);
    assert!(c.pass && (c.margin.unwrap() - 0.75).abs() < 1e-15 && !c.undecided);
    let c = upper_check(
        CheckKind::BondShear,
        Estimate::new(8.1, 0.2, Termination::Converged),
        8.0,
    );
    assert!(!c.pass && c.undecided && c.margin.unwrap() < 0.0);
}

#[test]
fn itp_closes_a_scan_bracket_in_few_steps_and_never_exceeds_bisection_plus_one() {
    use super::itp::{Bracket, refine};
    // As the search uses it: a bracket one scan step wide, a third point above it.
    let (lo, hi, eps) = (0.2, 0.2 + std::f64::consts::LN_10 / 8.0, 1e-3);
    let bracket = |f: &dyn Fn(f64) -> f64| Bracket {
        x_fail: lo,
        y_fail: f(lo),
        x_pass: hi,
        y_pass: f(hi),
    };
    let bisection = ((hi - lo) / (2.0 * eps)).log2().ceil() as usize;
    // Smooth: y = e^{-x} − e^{-0.3} falls through 0 at x = 0.3.
    let smooth = |x: f64| (-x).exp() - (-0.3f64).exp();
    let mut n = 0;
    let b = refine(bracket(&smooth), Some((0.8, smooth(0.8))), eps, |x| {
        n += 1;
        Ok(smooth(x))
    })
    .unwrap();
    assert!(
        b.x_fail < 0.3 && 0.3 <= b.x_pass && b.x_pass - b.x_fail <= 2.0 * eps,
        "{b:?}"
    );
    assert!(n <= 3, "{n} steps");
    // A step (nothing to interpolate): still bracketed, within bisection's count plus one.
    let step = |x: f64| if x < 0.234_567 { 1.0 } else { -1.0 };
    let mut n = 0;
    let b = refine(bracket(&step), None, eps, |x| {
        n += 1;
        Ok(step(x))
    })
    .unwrap();
    assert!(b.x_fail < 0.234_567 && 0.234_567 <= b.x_pass, "{b:?}");
    assert!(b.x_pass - b.x_fail <= 2.0 * eps);
    assert!(n <= bisection + 1, "{n} > {bisection} + 1");
}

#[test]
fn the_larger_yield_level_governs_and_the_peak_wins_a_tie() {
    use super::criteria::{margin, passes, yield_governing};
    let pick = |peak: f64, mean: f64| yield_governing(("peak", peak), ("mean", mean), |p| p.1).0;
    assert_eq!(pick(2.0, 1.0), "peak");
    assert_eq!(pick(1.0, 2.0), "mean");
    assert_eq!(pick(1.5, 1.5), "peak");
    assert_eq!(margin(3.0, 4.0), 0.25);
    assert!(passes(4.0, 4.0) && !passes(4.0 + 1e-12, 4.0));
}

/// Under the vector rule the search judges each thickness by one step of the peak's solve
/// from the bond limit (`Checker::utilisation`, `tail::ShearVector::peak_from`): its d_min
/// equals the one found by solving the peak at every step, within the two estimates' errors,
/// with the same governing check. Paper scene (rubber on steel, p0 = 0.1 MPa, ε = 1e-6,
/// bond shear and substrate yield), μ = 0.02, 0.5, 1 with bond strengths that put d_min inside
/// the range, the same under a safety factor 1.5, and μ = 0.5 with a bond strength just above
/// the mean friction μp0 = 50 kPa.
#[test]
fn search_with_one_step_peaks_matches_solved_peaks() {
    use crate::layer::Elastic;
    use crate::prec::Settings;
    use crate::psd::Spectrum;
    let spectrum = Spectrum::self_affine(1.0, 1e5, 1e8, None)
        .unwrap()
        .scaled_to_rms_slope(1.0)
        .unwrap();
    let cases = [
        (0.02, 1e6, 1.0),
        (0.5, 2e6, 1.0),
        (1.0, 3e6, 1.0),
        (0.5, 2e6, 1.5),
        (0.5, 5.2e4, 1.0),
    ];
    for (mu, bond, safety_factor) in cases {
        let design = Design {
            layers: Bilayer::new(
                Elastic::new(1e6, 0.5).unwrap(),
                Elastic::new(1e11, 0.5).unwrap(),
            ),
            pressure: 1e5,
            yield_strength: Some(2.5e8),
            bond_strength: bond,
            friction: mu,
            criteria: Criteria {
                shear_tail: Some(ShearTail::Vector),
                epsilon: 1e-6,
                safety_factor,
                checks: Checks::all(),
            },
        };
        let c = Checker::new(&spectrum, design, Settings::default()).unwrap();
        let (fast, solved) = (
            c.min_thickness().unwrap(),
            c.min_thickness_solving_peaks().unwrap(),
        );
        assert_eq!(fast.governing, solved.governing, "{mu} {bond}");
        assert_eq!(fast.all_pass_to_floor, solved.all_pass_to_floor);
        match (fast.thickness, solved.thickness) {
            (Some(a), Some(b)) => assert!(
                (a.value - b.value).abs() <= a.err + b.err,
                "mu {mu}, bond {bond}: {a:?} vs {b:?}"
            ),
            (a, b) => assert_eq!(a, b, "mu {mu}, bond {bond}"),
        }
    }
}
