//! Tangential-load kernels of a layer stack (g_t,k, f_t,k, h_k: `Stack::tangential`) against
//! the high-precision solution of the whole boundary-value problem
//! (tests/data/stack_tangential_ref.py), the film's kernels and the splitting identity.

use coatcheck::layer::stack::{InterfaceShear, Layer, STACK_RTOL, Stack};
use coatcheck::layer::{Bilayer, Elastic};

fn el(e: f64, nu: f64) -> Elastic {
    Elastic::new(e, nu).unwrap()
}

fn layer(e: f64, nu: f64, d: f64) -> Layer {
    Layer {
        material: el(e, nu),
        thickness: d,
    }
}

/// |got − want| over max(|want|, floor).
fn err(got: f64, want: f64, floor: f64) -> f64 {
    (got - want).abs() / want.abs().max(floor)
}

/// Every value of the reference whose magnitude is at least 1e-30 within `STACK_RTOL` (1e-11):
/// f_t,k and h_k relative; g_t,k relative, or, where it is below 1e-2 h_k (near its zeros, which
/// the reference includes at and 1 ± 1e-6 around each), absolute in units of 1e-2 h_k.
#[test]
fn stack_tangential_kernels_match_high_precision_reference() {
    let data = include_str!("../data/stack_tangential_ref.csv");
    let (mut rows, mut values, mut near_zero) = (0, 0, 0);
    let mut worst = [0.0f64; 3];
    for line in data.lines().filter(|l| !l.starts_with('#')) {
        let v: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
        let n = v[0] as usize;
        assert_eq!(v.len(), 4 + 6 * n, "{line}");
        let layers = (0..n)
            .map(|k| layer(v[1 + 3 * k], v[2 + 3 * k], v[3 + 3 * k]))
            .collect();
        let o = 1 + 3 * n;
        let stack = Stack::new(layers, el(v[o], v[o + 1])).unwrap();
        let got = stack.tangential(v[o + 2]);
        for (k, (g, want)) in got.iter().zip(v[o + 3..].chunks(3)).enumerate() {
            let floor = 1e-2 * want[2].abs();
            if want[0].abs() < floor && want[0].abs() >= 1e-30 {
                near_zero += 1;
            }
            for (j, (got, want, floor)) in [
                (g.g_t, want[0], floor),
                (g.f_t, want[1], 0.0),
                (g.h, want[2], 0.0),
            ]
            .into_iter()
            .enumerate()
            {
                if want.abs() < 1e-30 {
                    continue;
                }
                let e = err(got, want, floor);
                worst[j] = worst[j].max(e);
                values += 1;
                assert!(
                    e <= STACK_RTOL,
                    "{line}: interface {k}, kernel {j}: got {got:e}, want {want:e}, error {e:e}"
                );
            }
        }
        rows += 1;
    }
    assert_eq!(rows, 214);
    assert!(values > 1000, "{values} values compared");
    assert!(
        near_zero >= 10,
        "only {near_zero} values near a zero of g_t,k"
    );
    eprintln!(
        "stack tangential kernels: {values} values ({near_zero} near a zero of g_t,k); worst g_t, f_t, h: {:e} {:e} {:e}",
        worst[0], worst[1], worst[2]
    );
}

fn qs() -> impl Iterator<Item = f64> {
    (0..=48).map(|i| 10f64.powf(-8.0 + 0.25 * f64::from(i)))
}

/// N = 1 is the film's g_t, f_t, h ([`Bilayer::tangential`], tested against its own 50-digit
/// reference) over E0/E1 1e-8..1e8, ν 0..½ and q d 1e-8..1e4: f_t, h to 1e-13 relative, g_t
/// to 1e-13 of max(|g_t|, e^{-qd}/100) (absolute near its zero, as the film's bound).
#[test]
fn one_layer_reproduces_the_film() {
    let mut worst = 0.0f64;
    for ratio in [1e-8, 1e-5, 1e-2, 0.3, 1.0, 7.0, 1e3, 1e6, 1e8] {
        for (nu0, nu1) in [
            (0.5, 0.5),
            (0.5, 0.3),
            (0.0, 0.5),
            (0.3, 0.0),
            (0.49985, 0.25),
        ] {
            let (film, substrate) = (el(ratio, nu0), el(1.0, nu1));
            let bilayer = Bilayer::new(film, substrate);
            let d = 2e-6;
            let stack = Stack::new(vec![layer(ratio, nu0, d)], substrate).unwrap();
            for qd in qs() {
                let want = bilayer.tangential(qd);
                let got = stack.tangential(qd / d)[0];
                let floor = 1e-2 * (-qd).exp();
                for (a, b, fl) in [
                    (got.g_t, want.g_t, floor),
                    (got.f_t, want.f_t, 0.0),
                    (got.h, want.h, 0.0),
                ] {
                    if b.abs() < 1e-290 {
                        assert!(a.abs() < 1e-280, "{a:e} vs {b:e}");
                        continue;
                    }
                    let e = err(a, b, fl);
                    worst = worst.max(e);
                    assert!(
                        e <= 1e-13,
                        "E0/E1 {ratio}, nu {nu0}/{nu1}, qd {qd}: {got:?} vs {want:?} ({e:e})"
                    );
                }
            }
        }
    }
    eprintln!("N = 1 against the film's tangential kernels: worst {worst:e}");
}

fn assert_close(a: &InterfaceShear, b: &InterfaceShear, tol: f64, what: &str) {
    let floor = 1e-2 * b.h.abs();
    for (x, y, fl) in [(a.g_t, b.g_t, floor), (a.f_t, b.f_t, 0.0), (a.h, b.h, 0.0)] {
        if y.abs() < 1e-30 {
            continue;
        }
        assert!(err(x, y, fl) <= tol, "{what}: {a:?} vs {b:?}");
    }
}

/// A layer split in two identical halves gives, at the shared interfaces, the same g_t, f_t, h
/// (1e-12 where ≥ 1e-30; g_t absolute in units of h/100 near its zeros), for split layers from
/// rubber to far stiffer than the steel substrate, ν = ½ among them.
#[test]
fn two_identical_layers_equal_one_of_summed_thickness() {
    let sub = el(2e11, 0.3);
    for (e, nu) in [(1e6, 0.5), (3e9, 0.35), (10.0, 0.0), (1e13, 0.5)] {
        let top = layer(5e8, 0.46, 0.3);
        let split = Stack::new(
            vec![
                top,
                layer(e, nu, 0.25),
                layer(e, nu, 0.45),
                layer(1e5, 0.5, 1.0),
            ],
            sub,
        )
        .unwrap();
        let whole = Stack::new(vec![top, layer(e, nu, 0.7), layer(1e5, 0.5, 1.0)], sub).unwrap();
        for q in qs() {
            let (a, b) = (split.tangential(q), whole.tangential(q));
            for (j, k) in [(0, 0), (2, 1), (3, 2)] {
                assert_close(
                    &a[j],
                    &b[k],
                    1e-12,
                    &format!("split {e}, q {q}, interface {k}"),
                );
            }
        }
    }
}

/// One material throughout, in ten layers: the half-space's g_t = (1 − q z)e^{−q z},
/// f_t = q z e^{−q z}, h = e^{−q z} at every depth (notes.md), ν from 0 to ½.
#[test]
fn homogeneous_stack_is_a_half_space() {
    for nu in [0.0, 0.3, 0.5] {
        let layers: Vec<Layer> = (0..10)
            .map(|k| layer(7e6, nu, 1e-6 * (1.0 + k as f64)))
            .collect();
        let stack = Stack::new(layers, el(7e6, nu)).unwrap();
        let depths = stack.depths();
        for q in (0..=40).map(|i| 10f64.powf(-2.0 + 0.25 * f64::from(i))) {
            for (got, z) in stack.tangential(q).iter().zip(&depths) {
                let x = q * z;
                let e = (-x).exp();
                let want = InterfaceShear {
                    g_t: (1.0 - x) * e,
                    f_t: x * e,
                    h: e,
                };
                assert_close(got, &want, 1e-13, &format!("nu {nu}, q z {x}"));
            }
        }
    }
}

/// The mean friction passes every interface unchanged: at q = 0, g_t,k = h_k = 1 and
/// f_t,k = 0 exactly, and as q → 0 (q z_N = 1e-9 over the stiffest layer's modulus ratio, as
/// the film's limit test) g_t,k, h_k → 1 and f_t,k/(q z_k) → 1 (equilibrium of a uniform shear
/// mode) within 1e-7, for a three-layer stack at contrasts up to 1e4 and ν = 0 … ½. So the
/// interface shear's mean under sliding is μ p0 along x at every interface.
#[test]
fn uniform_shear_passes_every_interface() {
    let sub = el(2e11, 0.3);
    let stacks = [
        vec![
            layer(1e6, 0.5, 1e-5),
            layer(3e9, 0.35, 1e-5),
            layer(1e7, 0.0, 2e-5),
        ],
        vec![
            layer(1e10, 0.3, 1e-6),
            layer(1e6, 0.5, 3e-5),
            layer(2e11, 0.5, 1e-6),
        ],
    ];
    for layers in stacks {
        let stack = Stack::new(layers, sub).unwrap();
        for t in stack.tangential(0.0) {
            assert_eq!((t.g_t, t.f_t, t.h), (1.0, 0.0, 1.0));
        }
        let depths = stack.depths();
        let q = 1e-9 / 1e4 / depths[2];
        for (t, z) in stack.tangential(q).iter().zip(&depths) {
            assert!((t.g_t - 1.0).abs() < 1e-7, "{t:?}");
            assert!((t.h - 1.0).abs() < 1e-7, "{t:?}");
            assert!((t.f_t / (q * z) - 1.0).abs() < 1e-7, "{t:?}");
        }
    }
}

/// g_t − h, which the sliding spectra need (the friction-driven shear across the sliding
/// direction), formed literally from a one-layer stack's kernels, against the film's stable
/// form (`Bilayer::shear_undecayed`): the literal difference loses about 1e-16/|g_t − h|
/// relative where both are near 1. Measured and bounded here (rubber on steel, qd 1e-6..10):
/// within 4e-16 absolute of the stable form.
#[test]
fn literal_difference_of_g_t_and_h() {
    let (film, substrate) = (el(1e6, 0.5), el(2e11, 0.3));
    let bilayer = Bilayer::new(film, substrate);
    let d = 1e-5;
    let stack = Stack::new(vec![layer(1e6, 0.5, d)], substrate).unwrap();
    let mut worst = 0.0f64;
    for i in 0..=28 {
        let qd = 10f64.powf(-6.0 + 0.25 * f64::from(i));
        let t = stack.tangential(qd / d)[0];
        let want = bilayer.shear_undecayed(qd).diff * (-qd).exp();
        let abs = (t.g_t - t.h - want).abs();
        worst = worst.max(abs);
        assert!(abs <= 4e-16, "qd {qd}: {} vs {want:e}", t.g_t - t.h);
    }
    eprintln!("literal g_t - h against the stable form: worst absolute {worst:e}");
}
