//! Tabulated layer kernels (`layer::KernelTable`) against the exact stable forms, over the
//! extreme grid of materials and the whole q·d range including the far field up to 700.

use coatcheck::contact::{Engine, Request};
use coatcheck::layer::{Bilayer, Elastic, KernelTable, Nodes, Stack};
use coatcheck::prec::{Settings, TABLE_RTOL};
use coatcheck::psd::Spectrum;

fn pairs() -> Vec<Bilayer> {
    let mut v = vec![];
    for ratio in [1e-8, 1e-4, 1e-2, 1.0, 1e2, 1e4, 1e8] {
        for (nu0, nu1) in [
            (0.5, 0.5),
            (0.5, 0.3),
            (0.0, 0.5),
            (0.49985, 0.0),
            (0.3, 0.3),
        ] {
            v.push(Bilayer::new(
                Elastic::new(1e6, nu0).unwrap(),
                Elastic::new(1e6 / ratio, nu1).unwrap(),
            ));
        }
    }
    v
}

/// Every tabulated value within 1.5 TABLE_RTOL of the exact one, relative, at 4000 points from
/// q·d = 1e-9 to 700 placed off the panels' interpolation nodes (1.5: the check at build time
/// is relative to a panel's largest value, and these functions vary by < 1.5 across a panel).
#[test]
fn table_matches_exact_kernels() {
    let (lo, hi) = (1e-9f64.ln(), 700f64.ln());
    for layers in pairs() {
        let table = KernelTable::new(layers, 1e-9, 1e4).expect("the kernels are resolved");
        for i in 0..4000 {
            let y = lo + (hi - lo) * (i as f64 + 0.377) / 4000.0;
            let x = y.exp();
            let r = layers.response(x);
            let t = table.squared(x, y);
            for (got, want, what) in [
                (t.k, 1.0 / (r.s * r.s), "S^-2"),
                (t.f2, r.f * r.f, "f^2"),
                (t.g2, r.g * r.g, "g^2"),
            ] {
                if want < 1e-290 {
                    // f², g² underflow near qd = 700; the table must not blow up there.
                    assert!(got < 1e-280, "{layers:?} x {x:e} {what}: {got:e}");
                    continue;
                }
                let err = ((got - want) / want).abs();
                assert!(
                    err <= 1.5 * TABLE_RTOL,
                    "{layers:?} x {x:e} {what}: {got:e} vs {want:e} ({err:.1e})"
                );
            }
            assert_eq!(table.k(x, y), t.k);
        }
    }
}

/// The batched forms (`k_many`, `interface_many`, used at every quadrature node) give the
/// single-point forms' values to the last bit: on ascending nodes with uneven spacing that
/// cross many panels, the far field (q·d > 40) and the bulk limit (q·d > 700).
#[test]
fn batched_kernels_equal_single_points() {
    let d = 1e-5;
    let q: Vec<f64> = (0..3000)
        .map(|i| {
            let s = f64::from(i) + 0.4 * (f64::from(i) * 1.7).sin();
            1e-4 * 1e12f64.powf(s / 3000.0)
        })
        .collect();
    let u: Vec<f64> = q.iter().map(|q| q.ln()).collect();
    for layers in pairs() {
        let table = KernelTable::new(layers, 1e-9, 1e4).expect("the kernels are resolved");
        let (mut k, mut f2, mut g2) = (vec![0.0; 3000], vec![0.0; 3000], vec![0.0; 3000]);
        let at = Nodes {
            q: &q,
            u: &u,
            d,
            ln_d: d.ln(),
        };
        table.k_many(at, &mut k);
        table.interface_many(at, &mut f2, &mut g2);
        for j in 0..q.len() {
            let (x, y) = (q[j] * d, u[j] + d.ln());
            assert_eq!(k[j].to_bits(), table.k(x, y).to_bits(), "S^-2 at x = {x:e}");
            let (f, g) = table.interface(x, y);
            assert_eq!(f2[j].to_bits(), f.to_bits(), "f^2 at x = {x:e}");
            assert_eq!(g2[j].to_bits(), g.to_bits(), "g^2 at x = {x:e}");
        }
    }
}

/// Above q·d = 40 the table uses S = 1 and lines for f e^x, g e^x (module doc): exact to f64
/// rounding against the stable forms all the way to 700, past which both give the bulk limits.
#[test]
fn far_field_is_linear() {
    for layers in pairs() {
        let table = KernelTable::new(layers, 1.0, 1e3).unwrap();
        for x in [40.5, 55.0, 100.0, 333.0, 699.0] {
            let r = layers.response(x);
            let t = table.squared(x, x.ln());
            assert_eq!(t.k, 1.0);
            assert!((r.s - 1.0).abs() <= 4.0 * f64::EPSILON, "{x}: S = {}", r.s);
            for (got, want) in [(t.f2, r.f * r.f), (t.g2, r.g * r.g)] {
                if want < 1e-290 {
                    // Past q·d ≈ 350 the squares underflow, in both.
                    assert!(got < 1e-280, "{x}: {got:e}");
                } else {
                    assert!(
                        ((got - want) / want).abs() < 1e-14,
                        "{x}: {got:e} vs {want:e}"
                    );
                }
            }
        }
        let t = table.squared(800.0, 800f64.ln());
        assert_eq!((t.k, t.f2, t.g2), (1.0, 0.0, 0.0));
    }
}

/// A range wider than the table may span gives no table; the engine then uses the exact kernels,
/// and the two routes agree in the thin-film limit where both reduce to S(0) = E0*/E1*.
#[test]
fn exact_fallback_agrees_with_table() {
    let layers = Bilayer::new(
        Elastic::new(1e6, 0.5).unwrap(),
        Elastic::new(3e6, 0.3).unwrap(),
    );
    assert!(KernelTable::new(layers, 1e-60, 1.0).is_none());
    let spectrum = Spectrum::self_affine(0.8, 1e5, 1e8, None)
        .unwrap()
        .scaled_to_rms_slope(0.5)
        .unwrap();
    let engine = Engine::new(&spectrum, Settings::default());
    // q·d at most 1e-50 (exact kernels) and 1e-22 (table): S = S(0) to far below rounding.
    let exact = engine
        .evaluate(&Stack::new(layers, 1e-58).unwrap(), 1e5, Request::all())
        .unwrap();
    let tabulated = engine
        .evaluate(&Stack::new(layers, 1e-30).unwrap(), 1e5, Request::all())
        .unwrap();
    for (a, b) in [
        (exact.area_fraction, tabulated.area_fraction),
        (
            exact.sigma_rms_top.unwrap(),
            tabulated.sigma_rms_top.unwrap(),
        ),
        (
            exact.sigma_rms_interface.unwrap(),
            tabulated.sigma_rms_interface.unwrap(),
        ),
        (
            exact.e_eff_over_e_film.unwrap(),
            tabulated.e_eff_over_e_film.unwrap(),
        ),
    ] {
        assert!(
            ((a.value - b.value) / b.value).abs() < 1e-13,
            "{a:?} vs {b:?}"
        );
    }
}

/// The engine's interface integrals stop at q·d = 40 and bound the rest by F² there (contact
/// module doc): f² and g² must decrease from 40 on, for every material pair.
#[test]
fn interface_kernels_decrease_beyond_the_cut() {
    for layers in pairs() {
        let table = KernelTable::new(layers, 1.0, 1e3).unwrap();
        let mut last = table.squared(40.0, 40f64.ln());
        let mut x = 40.0;
        while x < 340.0 {
            x *= 1.01;
            let t = table.squared(x, x.ln());
            let r = layers.response(x);
            assert!(t.f2 <= last.f2 && t.g2 <= last.g2, "{layers:?} at {x}");
            assert!(
                r.f * r.f <= last.f2 * (1.0 + 1e-13),
                "{layers:?} exact f at {x}"
            );
            last = t;
        }
    }
}
