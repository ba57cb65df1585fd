//! Layer-stack kernels S, f_k, g_k (`layer::stack`) against the high-precision solution of the
//! whole boundary-value problem (tests/data/stack_ref.py) and the limits of notes.md, "Layer
//! stacks".

use coatcheck::layer::stack::{Layer, MAX_LAYERS, STACK_RTOL, Stack};
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

/// Relative difference, or the absolute one against an exact zero.
fn rel(a: f64, b: f64) -> f64 {
    if b == 0.0 {
        a.abs()
    } else {
        ((a - b) / b).abs()
    }
}

/// Every value of the reference (N = 1–4 and 10, neighbour modulus ratios 1e±8, ν = 0 … ½,
/// q z from 1e-8 to 1e4) whose magnitude is at least 1e-30, to `STACK_RTOL` (1e-11) relative.
#[test]
fn stack_matches_high_precision_reference() {
    let data = include_str!("../data/stack_ref.csv");
    let (mut rows, mut values, mut worst) = (0, 0, 0.0f64);
    for line in data.lines().filter(|l| !l.starts_with('#')) {
        let v: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
        let n = v[0] as usize;
        assert_eq!(v.len(), 5 + 5 * n, "{line}");
        let layers = (0..n)
            .map(|k| layer(v[1 + 3 * k], v[2 + 3 * k], v[3 + 3 * k]))
            .collect();
        let o = 1 + 3 * n;
        let stack = Stack::new(layers, el(v[o], v[o + 1])).unwrap();
        let r = stack.response(v[o + 2]);
        let got = std::iter::once(r.s).chain(r.interfaces.iter().flat_map(|&(f, g)| [f, g]));
        for (i, (got, want)) in got.zip(&v[o + 3..]).enumerate() {
            if want.abs() < 1e-30 {
                continue;
            }
            let err = rel(got, *want);
            worst = worst.max(err);
            values += 1;
            assert!(
                err <= STACK_RTOL,
                "{line}: value {i} got {got:e}, want {want:e}, rel err {err:e}"
            );
        }
        rows += 1;
    }
    assert_eq!(rows, 384);
    assert!(values > 2300, "{values} values compared");
    eprintln!("stack kernels: {values} values, worst relative error {worst:e}");
}

/// N = 1 is the bilayer of `layer` (its own forms, tested against a separate 100-digit
/// reference) over E0/E1 1e-8..1e8, ν 0..½ and q d 1e-8..1e4.
#[test]
fn one_layer_reproduces_the_bilayer() {
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
            let stack = Stack::new(
                vec![Layer {
                    material: film,
                    thickness: d,
                }],
                substrate,
            )
            .unwrap();
            for i in 0..=48 {
                let qd = 10f64.powf(-8.0 + 0.25 * f64::from(i));
                let want = bilayer.response(qd);
                let got = stack.response(qd / d);
                let (f, g) = got.interfaces[0];
                for (a, b) in [(got.s, want.s), (f, want.f), (g, want.g)] {
                    // Below 1e-290 (q d > 660) the bilayer rounds to its bulk limit 0.
                    let err = if b.abs() < 1e-290 {
                        (a - b).abs() / 1e-290
                    } else {
                        rel(a, b)
                    };
                    worst = worst.max(err);
                    assert!(
                        err <= 1e-13,
                        "E0/E1 {ratio}, nu {nu0}/{nu1}, qd {qd}: {a:e} vs {b:e} ({err:e})"
                    );
                }
            }
        }
    }
    eprintln!("N = 1 against the bilayer: worst relative difference {worst:e}");
}

fn qs() -> impl Iterator<Item = f64> {
    (0..=48).map(|i| 10f64.powf(-8.0 + 0.25 * f64::from(i)))
}

/// The tolerance for values below 1e-30 (down to 1e-290): they lie at q z > 69, where the
/// rounding of each thick layer's e^{-x}(I + xN) grows like eps·Σ x_k (the kernels' own
/// condition number in z is q z).
const DEEP_RTOL: f64 = 1e-10;

fn tol_at(y: f64, tol: f64) -> Option<f64> {
    if y.abs() >= 1e-30 {
        Some(tol)
    } else if y.abs() >= 1e-290 {
        Some(DEEP_RTOL)
    } else {
        None
    }
}

fn assert_same(a: &Stack, b: &Stack, map: &[usize], tol: f64, what: &str) {
    for q in qs() {
        let (ra, rb) = (a.response(q), b.response(q));
        assert!(
            rel(ra.s, rb.s) <= tol,
            "{what}, q {q}: S {} vs {}",
            ra.s,
            rb.s
        );
        for (k, &j) in map.iter().enumerate() {
            let ((fa, ga), (fb, gb)) = (ra.interfaces[j], rb.interfaces[k]);
            for (x, y) in [(fa, fb), (ga, gb)] {
                if let Some(t) = tol_at(y, tol) {
                    assert!(
                        rel(x, y) <= t,
                        "{what}, q {q}, interface {k}: {x:e} vs {y:e}"
                    );
                }
            }
        }
    }
}

/// A layer split in two identical halves gives the same S and, at the shared interfaces, the
/// same f and g (1e-12 where ≥ 1e-30: the two runs round differently through up to 1e8
/// contrasts; `DEEP_RTOL` below).
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
        assert_same(
            &split,
            &whole,
            &[0, 2, 3],
            1e-12,
            &format!("split layer {e}"),
        );
    }
}

/// A zero-thickness layer anywhere in the stack changes nothing (its interface repeats the one
/// above it): 1e-13 where ≥ 1e-30, `DEEP_RTOL` below.
#[test]
fn zero_thickness_layer_disappears() {
    let sub = el(1e11, 0.5);
    let (a, b) = (layer(1e6, 0.5, 0.01), layer(3e9, 0.35, 0.02));
    let ghost = layer(1e14, 0.0, 0.0);
    let plain = Stack::new(vec![a, b], sub).unwrap();
    let middle = Stack::new(vec![a, ghost, b], sub).unwrap();
    assert_same(&middle, &plain, &[0, 2], 1e-13, "ghost in the middle");
    let bottom = Stack::new(vec![a, b, ghost], sub).unwrap();
    assert_same(&bottom, &plain, &[0, 1], 1e-13, "ghost at the bottom");
    for q in qs() {
        let r = middle.response(q);
        assert!(rel(r.interfaces[1].0, r.interfaces[0].0) <= 1e-13);
        assert!(rel(r.interfaces[1].1, r.interfaces[0].1) <= 1e-13);
    }
}

/// One material throughout, split into ten layers: S = 1, f_k = (1 + q z_k) e^{-q z_k},
/// g_k = q z_k e^{-q z_k}, for ν from 0 to ½ (1e-13 where g_k ≥ 1e-30, `DEEP_RTOL` below).
#[test]
fn homogeneous_stack_is_a_half_space() {
    let mut worst = 0.0f64;
    for nu in [0.0, 0.3, 0.49985, 0.5] {
        let layers: Vec<Layer> = (0..MAX_LAYERS)
            .map(|k| layer(7e6, nu, 1e-6 * (1.0 + k as f64)))
            .collect();
        let stack = Stack::new(layers, el(7e6, nu)).unwrap();
        let depths = stack.depths();
        for i in 0..=60 {
            let q = 10f64.powf(-2.0 + 0.25 * f64::from(i));
            let r = stack.response(q);
            worst = worst.max(rel(r.s, 1.0));
            assert!(rel(r.s, 1.0) <= 1e-13, "nu {nu}, q {q}: S = {}", r.s);
            for (&(f, g), z) in r.interfaces.iter().zip(&depths) {
                let x = q * z;
                let (fw, gw) = ((1.0 + x) * (-x).exp(), x * (-x).exp());
                let Some(tol) = tol_at(gw, 1e-13) else {
                    continue;
                };
                if tol < DEEP_RTOL {
                    worst = worst.max(rel(f, fw)).max(rel(g, gw));
                }
                assert!(
                    rel(f, fw) <= tol && rel(g, gw) <= tol,
                    "nu {nu}, q z {x}: f {f:e} vs {fw:e}, g {g:e} vs {gw:e}"
                );
            }
        }
    }
    eprintln!("homogeneous stack: worst relative error {worst:e}");
}

#[test]
fn invalid_stacks_are_rejected_with_a_reason() {
    let sub = el(1e11, 0.3);
    let ok = layer(1e6, 0.5, 1e-5);
    let msg = |r: Result<Stack, coatcheck::Error>| r.unwrap_err().to_string();
    assert!(msg(Stack::new(vec![], sub)).contains("number of layers"));
    assert!(msg(Stack::new(vec![ok; MAX_LAYERS + 1], sub)).contains("number of layers"));
    for d in [-1e-6, f64::NAN, f64::INFINITY] {
        assert!(
            msg(Stack::new(
                vec![ok, layer(1e6, 0.5, 1.0), Layer { thickness: d, ..ok }],
                sub
            ))
            .contains("layer thickness")
        );
    }
    let bad = Elastic {
        youngs: 1e6,
        poisson: 0.6,
    };
    let e = msg(Stack::new(
        vec![Layer {
            material: bad,
            ..ok
        }],
        sub,
    ));
    assert!(e.contains("Poisson"), "{e}");
    assert!(msg(Stack::new(vec![ok], bad)).contains("Poisson"));
    let s = Stack::new(
        vec![
            ok,
            Layer {
                thickness: 0.0,
                ..ok
            },
        ],
        sub,
    )
    .unwrap();
    assert_eq!(s.depths(), vec![1e-5, 1e-5]);
}

/// The per-node cache of a d_min search (`StackCache`) gives the exact recursion's values to the
/// last bit while one layer after another changes thickness: 10 layers at neighbour modulus
/// ratios 1e±8 with ν = ½ among them, q z from 1e-8 to 1e4, every node asked for twice. On a
/// CPU with AVX2 the cache runs its AVX2 build (`crate::simd`) and the recursion its baseline
/// one: this is also the test that both builds agree to the last bit.
#[test]
fn stack_cache_equals_the_exact_recursion() {
    use coatcheck::layer::stack::StackCache;
    let base: Vec<Layer> = (0..MAX_LAYERS)
        .map(|k| {
            let e = if k % 2 == 0 { 1.0 } else { 1e8 };
            let nu = [0.5, 0.3, 0.0, 0.45, 0.49985][k % 5];
            layer(e, nu, 0.05 + 0.01 * k as f64)
        })
        .collect();
    let sub = el(1e-8, 0.5);
    let mut cache = StackCache::new(Stack::new(base.clone(), sub).unwrap());
    for varied in [0, 0, 3, 3, 9, 1] {
        for d in [1e-9, 0.02, 0.3, 7.0] {
            let mut layers = base.clone();
            layers[varied].thickness = d;
            let stack = Stack::new(layers, sub).unwrap();
            cache.serve(&stack);
            assert!(cache.varied() >= varied);
            for _ in 0..2 {
                for q in (0..=48).map(|i| 10f64.powf(-8.0 + 0.25 * f64::from(i))) {
                    let want = stack.response(q);
                    let (s, got) = cache.response(q);
                    assert_eq!(
                        s.to_bits(),
                        want.s.to_bits(),
                        "layer {varied} at {d}, q {q}"
                    );
                    for (a, b) in got.iter().zip(&want.interfaces) {
                        assert_eq!(
                            a.0.to_bits(),
                            b.0.to_bits(),
                            "f, layer {varied} at {d}, q {q}"
                        );
                        assert_eq!(
                            a.1.to_bits(),
                            b.1.to_bits(),
                            "g, layer {varied} at {d}, q {q}"
                        );
                    }
                    assert_eq!(cache.s(q).to_bits(), want.s.to_bits());
                }
            }
        }
    }
}

/// A layer that changes material, not only thickness, between the stacks a `StackCache` serves
/// (as the corners of a robust check or a library caller reusing an engine may ask): the values
/// are still the exact recursion's, to the last bit. The varied layer's material enters the
/// face to the base the cache keeps per node, so a new material there must not reuse it.
#[test]
fn stack_cache_follows_a_material_change() {
    use coatcheck::layer::stack::StackCache;
    let steel = el(2e11, 0.3);
    let stack = |e_top: f64, nu_top: f64, d_top: f64, e_mid: f64| {
        Stack::new(
            vec![layer(e_top, nu_top, d_top), layer(e_mid, 0.35, 1e-5)],
            steel,
        )
        .unwrap()
    };
    let first = stack(1e6, 0.5, 1e-5, 3e9);
    let mut cache = StackCache::new(first.clone());
    // The d_min search's pattern (the top layer varied), then other materials at each depth.
    let served = [
        stack(1e6, 0.5, 2e-5, 3e9),
        stack(2e6, 0.5, 2e-5, 3e9),
        stack(2e6, 0.3, 5e-6, 3e9),
        stack(2e6, 0.3, 5e-6, 1e10),
        stack(1e6, 0.5, 5e-6, 1e10),
    ];
    for s in std::iter::once(&first).chain(&served) {
        cache.serve(s);
        for q in (0..=32).map(|i| 10f64.powf(3.0 + 0.25 * f64::from(i))) {
            let want = s.response(q);
            let (got_s, got) = cache.response(q);
            assert_eq!(got_s.to_bits(), want.s.to_bits(), "S at q {q}, {s:?}");
            for (a, b) in got.iter().zip(&want.interfaces) {
                assert_eq!(a.0.to_bits(), b.0.to_bits(), "f at q {q}, {s:?}");
                assert_eq!(a.1.to_bits(), b.1.to_bits(), "g at q {q}, {s:?}");
            }
        }
    }
}

/// Where the top layer is far thicker than the wavelength (q·d_1 > 40) the cache takes S as the
/// top layer's half-space's without the layers below: the recursion's S to the last bit, for
/// top layers of ν = 0 … ½ on bases from 1e-8 to 1e8 times as stiff (one or three layers
/// below, thin and thick at that q, a soft layer between stiff ones); and the interface kernels
/// asked for there afterwards are the recursion's too.
#[test]
fn far_top_layer_gives_the_recursions_s() {
    use coatcheck::layer::stack::StackCache;
    for nu in [0.0, 0.3, 0.45, 0.49985, 0.5] {
        for ratio in [1e-8, 1e-3, 1.0, 1e3, 1e8] {
            for below in [
                vec![layer(ratio, 0.35, 1e-3)],
                vec![
                    layer(ratio, 0.2, 1e-6),
                    layer(ratio * 1e-8, 0.5, 0.02),
                    layer(ratio, 0.49, 3.0),
                ],
            ] {
                let mut layers = vec![layer(1.0, nu, 1.0)];
                layers.extend(below);
                let stack = Stack::new(layers, el(ratio * 10.0, 0.3)).unwrap();
                let mut cache = StackCache::new(stack.clone());
                for q in (0..=60).map(|i| 40.000001 * 10f64.powf(f64::from(i) / 24.0)) {
                    let want = stack.response(q);
                    assert_eq!(
                        cache.s(q).to_bits(),
                        want.s.to_bits(),
                        "S at q {q}, {stack:?}"
                    );
                    let (s, got) = cache.response(q);
                    assert_eq!(s.to_bits(), want.s.to_bits());
                    for (a, b) in got.iter().zip(&want.interfaces) {
                        assert_eq!(
                            (a.0.to_bits(), a.1.to_bits()),
                            (b.0.to_bits(), b.1.to_bits())
                        );
                    }
                }
            }
        }
    }
}
