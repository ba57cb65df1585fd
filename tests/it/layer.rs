//! Layer kernels S, f, g against the 100-digit reference (tests/data/kernels_ref.py), their
//! analytic limits, and properties over the extreme ranges.

use coatcheck::layer::{Bilayer, Elastic};
use proptest::prelude::*;

fn pair(e_ratio: f64, nu0: f64, nu1: f64) -> Bilayer {
    Bilayer::new(
        Elastic::new(e_ratio, nu0).unwrap(),
        Elastic::new(1.0, nu1).unwrap(),
    )
}

fn rel(a: f64, b: f64) -> f64 {
    if b == 0.0 {
        a.abs()
    } else {
        ((a - b) / b).abs()
    }
}

/// Every case of the reference grid (qd 1e-8..1e4, E0/E1 1e-8..1e8, ν in {0, 0.25, 0.3,
/// 0.49985, 0.5}) to relative error ≤ `KERNEL_RTOL` (2e-13, the bound outputs quote; the issue
/// asks for 1e-12).
#[test]
fn kernels_match_high_precision_reference() {
    let data = include_str!("../data/kernels_ref.csv");
    let mut worst = [0.0f64; 3];
    let mut n = 0;
    for line in data.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
        let b = pair(v[0], v[1], v[2]);
        let r = b.response(v[3]);
        assert_eq!(r.s, b.s(v[3]), "s() and response().s differ");
        for (k, (got, want)) in [(r.s, v[4]), (r.f, v[5]), (r.g, v[6])]
            .into_iter()
            .enumerate()
        {
            // f and g below 1e-290 are at the f64 underflow edge; compare absolutely there.
            let err = if want.abs() < 1e-290 {
                (got - want).abs() / 1e-290
            } else {
                rel(got, want)
            };
            worst[k] = worst[k].max(err);
            assert!(
                err <= coatcheck::prec::KERNEL_RTOL,
                "{line}: kernel {k} got {got:e}, want {want:e}, rel err {err:e}"
            );
        }
        n += 1;
    }
    assert_eq!(n, 1350);
    eprintln!(
        "worst relative errors S, f, g: {:e} {:e} {:e}",
        worst[0], worst[1], worst[2]
    );
}

#[test]
fn notes_reference_table() {
    // notes.md: rubber (1 MPa, 0.5) on steel (1e11 Pa, 0.5).
    let b = Bilayer::new(
        Elastic::new(1e6, 0.5).unwrap(),
        Elastic::new(1e11, 0.5).unwrap(),
    );
    let table = [
        (0.1, 6.6488081104e-4, 0.99508591419, 0.098526500004),
        (1.0, 0.24059022762, 0.80396367594, 0.45638307583),
        (10.0, 0.99999908899, 9.9878763764e-4, 9.0798876490e-4),
    ];
    for (qd, s, f, g) in table {
        let r = b.response(qd);
        assert!(
            rel(r.s, s) < 1e-10 && rel(r.f, f) < 1e-10 && rel(r.g, g) < 1e-10,
            "qd={qd}: {r:?}"
        );
    }
}

#[test]
fn identical_materials_are_a_half_space() {
    for nu in [0.0, 0.3, 0.5] {
        let b = pair(1.0, nu, nu);
        for qd in [0.0, 1e-8, 1e-3, 0.5, 1.0, 3.0, 30.0, 300.0] {
            let r = b.response(qd);
            let e = (-qd).exp();
            assert!(rel(r.s, 1.0) < 1e-15, "S={}", r.s);
            assert!(rel(r.f, (1.0 + qd) * e) < 1e-14, "f at {qd}");
            assert!(
                rel(r.g, qd * e) < 1e-14 || (qd == 0.0 && r.g == 0.0),
                "g at {qd}"
            );
        }
    }
}

#[test]
fn thin_incompressible_film_on_rigid_base() {
    // G0/G1 = 1e-40 ~ rigid; S -> (2/3)(qd)^3, f -> 1, g -> qd.
    let b = pair(1e-40, 0.5, 0.5);
    for qd in [1e-4, 1e-5, 1e-6] {
        let r = b.response(qd);
        assert!(rel(r.s, 2.0 / 3.0 * qd * qd * qd) < 1e-3, "S={:e}", r.s);
        assert!(rel(r.f, 1.0) < 1e-7);
        assert!(rel(r.g, qd) < 1e-7);
    }
}

#[test]
fn substrate_limit_at_small_qd_and_bulk_limit_at_large_qd() {
    for (e_ratio, nu0, nu1) in [
        (1e-5, 0.5, 0.3),
        (1e4, 0.2, 0.45),
        (1e-8, 0.0, 0.5),
        (1e8, 0.5, 0.0),
    ] {
        let b = pair(e_ratio, nu0, nu1);
        let e0s = b.film.e_star();
        let e1s = b.substrate.e_star();
        // qd = 0 exactly: S = E0*/E1*.
        assert!(rel(b.s(0.0), e0s / e1s) < 1e-14);
        for qd in [1e3, 1e4, 1e300] {
            let r = b.response(qd);
            assert!(
                rel(r.s, 1.0) < 1e-12 && r.f < 1e-300 && r.g < 1e-300,
                "{r:?}"
            );
        }
    }
}

/// The literal eq. (7) loses digits at small qd; the stable form does not (this documents the
/// trap the stable form avoids: the literal error is far above 1e-12 here).
#[test]
fn literal_eq7_loses_digits_where_stable_form_does_not() {
    let (e_ratio, nu0, nu1) = (1e4, 0.5, 0.5);
    let b = pair(e_ratio, nu0, nu1);
    let g_ratio = b.shear_ratio();
    let m = (g_ratio - 1.0) / (g_ratio + 3.0 - 4.0 * nu0);
    let n = 1.0 - 4.0 * (1.0 - nu0) / (1.0 + g_ratio * (3.0 - 4.0 * nu1));
    let qd: f64 = 1e-6;
    let t = (-2.0 * qd).exp();
    let literal = (1.0 + 4.0 * m * qd * t - m * n * t * t)
        / (1.0 - (m + n + 4.0 * m * qd * qd) * t + m * n * t * t);
    let stable = b.s(qd);
    // Second, independent evaluation of the stable form's accuracy: compare with the small-qd
    // expansion S(0) = E0*/E1* to first order (the derivative is O(1) relative).
    assert!(rel(stable, b.film.e_star() / b.substrate.e_star()) < 1e-5);
    assert!(
        rel(literal, stable) > 1e-11,
        "literal form unexpectedly accurate: {literal} vs {stable}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]
    /// Finite, S > 0, f >= 0, g >= 0 and the mirror bound on f, over the extreme ranges.
    #[test]
    fn kernels_are_finite_and_bounded(log_ratio in -8.0f64..8.0, nu0 in 0.0f64..=0.5, nu1 in 0.0f64..=0.5, log_qd in -8.0f64..4.0) {
        let b = pair(10f64.powf(log_ratio), nu0, nu1);
        let qd = 10f64.powf(log_qd);
        let r = b.response(qd);
        prop_assert!(r.s.is_finite() && r.s > 0.0);
        prop_assert!(r.f.is_finite() && r.f >= 0.0);
        prop_assert!(r.g.is_finite() && r.g >= 0.0);
        // f never exceeds the rigid-mirror value 2(1 + qd)e^{-qd} (approached by a soft film on a
        // rigid base at large qd; max over the 100-digit grid: 2 - 2e-8). g has no such bound:
        // a hard film on a soft base carries interface shear far above the half-space value.
        // e^{−qd} as e^{−qd/2}·e^{−qd/2} keeps the bound from underflowing before f does; one
        // subnormal step of slack for the rounding of both into the subnormal range.
        let half = (-0.5 * qd).exp();
        prop_assert!(r.f <= 2.0 * (1.0 + qd) * half * half * (1.0 + 1e-12) + 5e-324);
    }
}

/// The shape the d_min search relies on (`check` module doc, its step widening for
/// substrate-yield): over the extreme grid of material pairs (E0/E1 1e-8..1e8 both ways, ν from 0
/// to exactly 0.5), S(qd) has at most one turn and |f(qd)| never rises, on 2000 points per
/// decade from qd = 1e-8 to 1e3 (S = 1 and f = 0 beyond the bulk limit). Changes within
/// 1e-12 relative (rounding, and the flat limits at both ends) are not counted as a direction.
#[test]
fn s_turns_at_most_once_and_f_never_rises() {
    for ratio in [1e-8, 1e-6, 1e-4, 1e-2, 0.3, 1.0, 3.0, 1e2, 1e4, 1e6, 1e8] {
        for (nu0, nu1) in [
            (0.5, 0.5),
            (0.5, 0.3),
            (0.5, 0.0),
            (0.0, 0.5),
            (0.49985, 0.0),
            (0.3, 0.3),
            (0.0, 0.0),
            (0.25, 0.49985),
        ] {
            let layers = pair(ratio, nu0, nu1);
            let (mut turns, mut dir) = (0, 0i8);
            let mut prev = layers.response(1e-8);
            for i in 1..=22_000 {
                let r = layers.response(10f64.powf(-8.0 + f64::from(i) / 2000.0));
                let ds = r.s - prev.s;
                if ds.abs() > 1e-12 * r.s.abs().max(prev.s.abs()) {
                    let d = if ds > 0.0 { 1 } else { -1 };
                    if dir != 0 && d != dir {
                        turns += 1;
                    }
                    dir = d;
                }
                assert!(
                    r.f.abs() <= prev.f.abs() * (1.0 + 1e-12) + 1e-300,
                    "E0/E1 = {ratio}, nu {nu0}/{nu1}: |f| rises at step {i}: {} -> {}",
                    prev.f,
                    r.f
                );
                prev = r;
            }
            assert!(
                turns <= 1,
                "E0/E1 = {ratio}, nu {nu0}/{nu1}: S turns {turns} times"
            );
        }
    }
}

/// f and g above q·d = 680, where e^{−x}/D leaves the normal range for a stiff film and e^{−x}
/// itself does above 708: against f = 2e^{−x}(1 + x)/(1 + r), g = 2e^{−x}x/(1 + r), the exact
/// forms for ν0 = ν1 = ½ once e^{−2x} is negligible (r = G0/G1), evaluated with mpmath at 40
/// digits (`2*exp(-x)*(1+x)/(1+r)` and `2*exp(-x)*x/(1+r)`). Full relative accuracy while the
/// value is normal; within rounding once it is subnormal; zero only below the subnormal range.
#[test]
fn f_and_g_keep_their_digits_down_to_the_subnormal_range() {
    let cases: [(f64, f64, f64, f64, f64); 12] = [
        (
            1e17,
            1e9,
            680.5,
            3.9545850146543076e-301,
            3.9487822486753576e-301,
        ),
        (
            1e17,
            1e9,
            699.5,
            2.277445744658315e-309,
            2.27419457300284e-309,
        ),
        (1e17, 1e9, 700.5, 8.3902150705495e-310, 8.3782546784318e-310),
        (1e17, 1e9, 705.0, 9.38047759697e-312, 9.367190801504e-312),
        (1e17, 1e9, 720.0, 2.930476e-318, 2.92641e-318),
        (1e17, 1e9, 740.0, 0.0, 0.0),
        (
            1e6,
            1e11,
            680.5,
            3.95454550874507e-293,
            3.948742800735173e-293,
        ),
        (
            1e6,
            1e11,
            699.5,
            2.2774229932028398e-301,
            2.274171854026248e-301,
        ),
        (
            1e6,
            1e11,
            700.5,
            8.390131253139096e-302,
            8.378170980504543e-302,
        ),
        (
            1e6,
            1e11,
            705.0,
            9.380383886934239e-304,
            9.36709722420487e-304,
        ),
        (
            1e6,
            1e11,
            720.0,
            2.9304475126207e-310,
            2.92638309166006e-310,
        ),
        (1e6, 1e11, 740.0, 6.20764e-319, 6.1993e-319),
    ];
    for (e0, e1, x, f, g) in cases {
        let pair = Bilayer::new(
            Elastic::new(e0, 0.5).unwrap(),
            Elastic::new(e1, 0.5).unwrap(),
        );
        let r = pair.response(x);
        assert!((r.s - 1.0).abs() <= 3e-16, "S = {}", r.s);
        for (got, want, what) in [(r.f, f, "f"), (r.g, g, "g")] {
            let tol = 1e-14 * want + 1e-323;
            assert!(
                (got - want).abs() <= tol,
                "{what} at qd = {x}, E0/E1 = {}: {got:e} vs {want:e}",
                e0 / e1
            );
        }
    }
    let far = Bilayer::new(
        Elastic::new(1e6, 0.5).unwrap(),
        Elastic::new(1e11, 0.3).unwrap(),
    )
    .response(800.0);
    assert_eq!((far.s, far.f, far.g), (1.0, 0.0, 0.0));
}
