//! Persson's theory on layer stacks (`Engine::evaluate_stack`) and stack scenes: the limits of
//! notes.md ("Layer stacks": two identical adjacent layers are one layer of the summed
//! thickness; one layer is the film), extreme contrasts, up to ten layers, and an independent
//! high-precision evaluation of the integrals.

use coatcheck::contact::{Contact, Engine, Request, StackContact};
use coatcheck::layer::stack::{Layer, Stack as LayerStack};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::{Estimate, Settings};
use coatcheck::psd::Spectrum;

fn paper_spectrum() -> Spectrum {
    Spectrum::self_affine(1.0, 1e5, 1e8, None)
        .unwrap()
        .scaled_to_rms_slope(1.0)
        .unwrap()
}

fn el(e: f64, nu: f64) -> Elastic {
    Elastic::new(e, nu).unwrap()
}

fn layers(spec: &[(f64, f64, f64)], substrate: Elastic) -> LayerStack {
    LayerStack::new(
        spec.iter()
            .map(|&(e, nu, d)| Layer {
                material: el(e, nu),
                thickness: d,
            })
            .collect(),
        substrate,
    )
    .unwrap()
}

/// |a − b| within the sum of both error estimates (and a 1e-12 relative floor for two exact
/// computations of one number by different kernels).
fn agree(what: &str, a: &Estimate, b: &Estimate) {
    let tol = a.err + b.err + 1e-12 * b.value.abs();
    assert!(
        (a.value - b.value).abs() <= tol,
        "{what}: {} ± {} vs {} ± {}",
        a.value,
        a.err,
        b.value,
        b.err
    );
}

fn film(e0: Elastic, sub: Elastic, d: f64, engine: &Engine) -> Contact {
    let s = Stack::new(Bilayer::new(e0, sub), d).unwrap();
    engine.evaluate(&s, 1e5, Request::all()).unwrap()
}

/// Two identical adjacent layers equal one layer of the summed thickness: A/A0, G1, σ_rms at
/// the top, E_eff and the bottom interface's σ_rms, τ_rms against the Bilayer's (closed-form
/// kernels, another code path); and a one-layer stack equals the film.
#[test]
fn split_layer_equals_one_layer() {
    let engine = Engine::new(&paper_spectrum(), Settings::default());
    let (rubber, steel) = (el(1e6, 0.5), el(2e11, 0.3));
    let one = film(rubber, steel, 10e-6, &engine);
    let check = |c: &StackContact| {
        agree("G1", &c.top.g1, &one.g1);
        agree("A/A0", &c.top.area_fraction, &one.area_fraction);
        agree(
            "sigma top",
            c.top.sigma_rms_top.as_ref().unwrap(),
            one.sigma_rms_top.as_ref().unwrap(),
        );
        agree(
            "E_eff",
            c.top.e_eff_over_e_film.as_ref().unwrap(),
            one.e_eff_over_e_film.as_ref().unwrap(),
        );
        let bottom = c.interfaces.last().unwrap();
        agree(
            "sigma bottom",
            bottom.sigma_rms.as_ref().unwrap(),
            one.sigma_rms_interface.as_ref().unwrap(),
        );
        agree(
            "tau bottom",
            bottom.tau_rms.as_ref().unwrap(),
            one.tau_rms_interface.as_ref().unwrap(),
        );
    };
    for split in [[4e-6, 6e-6], [9.99e-6, 1e-8]] {
        let s = layers(&[(1e6, 0.5, split[0]), (1e6, 0.5, split[1])], steel);
        check(&engine.evaluate_stack(&s, 1e5, Request::all()).unwrap());
    }
    let s = layers(&[(1e6, 0.5, 10e-6)], steel);
    check(&engine.evaluate_stack(&s, 1e5, Request::all()).unwrap());
}

fn run(args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_coatcheck"))
        .args(args)
        .output()
        .expect("binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

const PAPER: &str = include_str!("../../examples/paper-rubber-on-steel.toml");

/// The paper's scene with its [film] and [bond] as `layers` (TOML text) instead.
fn with_layers(layers: &str) -> String {
    let film =
        "[film]\nmaterial = \"paper-rubber\"   # E = 1 MPa, nu = 0.5\nthickness = \"10 um\"\n";
    let bond = "[bond]\nmaterial = \"epoxy\"          # 10 MPa shear (paper)\n";
    assert!(PAPER.contains(film) && PAPER.contains(bond));
    PAPER.replace(film, layers).replace(bond, "")
}

fn write(dir: &tempfile::TempDir, name: &str, text: &str) -> String {
    let p = dir.path().join(name);
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

/// A one-layer [[layer]] scene is the [film] scene: byte-identical reports (table and JSON).
#[test]
fn one_layer_scene_is_the_film_scene() {
    let dir = tempfile::tempdir().unwrap();
    let film = write(&dir, "film.toml", PAPER);
    let one = write(
        &dir,
        "one.toml",
        &with_layers(
            "[[layer]]\nname = \"rubber\"\nmaterial = \"paper-rubber\"\nthickness = \"10 um\"\n\
             bond = \"epoxy\"\n",
        ),
    );
    for format in ["table", "json"] {
        let a = run(&["check", &film, "--format", format]);
        let b = run(&["check", &one, "--format", format]);
        assert_eq!(a.0, 0, "{}", a.2);
        assert_eq!((a.0, &a.1), (b.0, &b.1), "{format}");
    }
}

/// Stack scenes from the outside: every interface in the JSON with errors, the checks at each
/// bonded interface against its own bond, and bad stacks rejected naming the key.
#[test]
fn stack_scene_json_and_errors() {
    let dir = tempfile::tempdir().unwrap();
    let two = "[[layer]]\nname = \"rubber\"\nmaterial = \"paper-rubber\"\nthickness = \"10 um\"\n\
               bond = \"5 MPa\"\n[[layer]]\nname = \"primer\"\nyoungs_modulus = \"3 GPa\"\n\
               poisson_ratio = 0.35\nthickness = \"10 um\"\nbond = \"epoxy\"\n";
    let scene = write(&dir, "two.toml", &with_layers(two));
    let (code, out, err) = run(&["check", &scene, "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let inter = v["interfaces"].as_array().unwrap();
    assert_eq!(inter.len(), 2);
    for (i, (name, depth)) in inter.iter().zip([("rubber", 1e-5), ("primer", 2e-5)]) {
        assert_eq!(i["name"], name);
        assert!((i["depth_m"].as_f64().unwrap() - depth).abs() < 1e-20);
        for k in ["sigma_rms_pa", "tau_rms_pa", "tau_peak_pa", "sigma_peak_pa"] {
            let (x, e) = (
                i[k].as_f64().unwrap(),
                i[format!("{k}_err")].as_f64().unwrap(),
            );
            assert!(x > 0.0 && e > 0.0 && e < 1e-8 * x, "{k}: {x} ± {e}");
        }
    }
    let bonds: Vec<(String, f64)> = v["checks"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["name"] == "bond-shear")
        .map(|c| {
            (
                c["at"].as_str().unwrap().to_string(),
                c["limit"].as_f64().unwrap(),
            )
        })
        .collect();
    assert_eq!(bonds, [("rubber".into(), 5e6), ("primer".into(), 1e7)]);
    // The top-level interface keys are the bottom interface's.
    assert_eq!(v["tau_rms_interface_pa"], inter[1]["tau_rms_pa"]);
    let bad = [
        (
            two.replace("bond = \"epoxy\"\n", ""),
            "layer[2].bond is missing",
        ),
        (
            two.replace("name = \"primer\"", "name = \"rubber\""),
            "layer[2].name",
        ),
        (
            two.replace(
                "thickness = \"10 um\"\nbond = \"epoxy\"",
                "thickness = \"-1 um\"\nbond = \"epoxy\"",
            ),
            "layer[2].thickness",
        ),
        (
            two.replace("poisson_ratio = 0.35\n", ""),
            "layer[2].youngs_modulus and layer[2].poisson_ratio",
        ),
        (
            format!("{two}[film]\nthickness = \"1 um\"\n"),
            "film.thickness: contradicts the [[layer]]",
        ),
        (
            two.replace("bond = \"5 MPa\"", "bond = \"glue\""),
            "layer[1].bond",
        ),
    ];
    for (text, want) in bad {
        let scene = write(&dir, "bad.toml", &with_layers(&text));
        let (code, _, err) = run(&["check", &scene]);
        assert_eq!(code, 2, "{want}: {err}");
        assert!(err.contains(want), "{want}: {err}");
    }
    let (code, _, err) = run(&[
        "check",
        &write(&dir, "two.toml", &with_layers(two)),
        "--thickness-of",
        "skin",
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("no layer is named 'skin'") && err.contains("rubber, primer"),
        "{err}"
    );
}

/// A three-layer stack at extreme contrasts (1e-8 and 1e8 between neighbours, ν = ½
/// everywhere): finite results with finite error estimates at every interface.
#[test]
fn extreme_contrast_is_finite() {
    let engine = Engine::new(&paper_spectrum(), Settings::default());
    for spec in [
        [(1e6, 0.5, 3e-6), (1e14, 0.5, 1e-6), (1e6, 0.5, 3e-6)],
        [(1e14, 0.5, 1e-7), (1e6, 0.5, 5e-6), (1e14, 0.5, 1e-6)],
    ] {
        let sub = if spec[2].0 > 1e10 {
            el(1e6, 0.5)
        } else {
            el(1e14, 0.5)
        };
        let c = engine
            .evaluate_stack(&layers(&spec, sub), 1e5, Request::all())
            .unwrap();
        let mut all = vec![c.top.g1, c.top.area_fraction, c.top.sigma_rms_top.unwrap()];
        for i in &c.interfaces {
            all.push(i.sigma_rms.unwrap());
            all.push(i.tau_rms.unwrap());
        }
        for e in all {
            assert!(e.value.is_finite() && e.value > 0.0, "{spec:?}: {e:?}");
            assert!(
                e.err.is_finite() && e.err <= 1e-6 * e.value,
                "{spec:?}: {e:?}"
            );
        }
    }
}

/// Ten layers work (and give the one-layer answer when they are all the film's material);
/// eleven are refused.
#[test]
fn ten_layers() {
    let engine = Engine::new(&paper_spectrum(), Settings::default());
    let steel = el(2e11, 0.3);
    let ten: Vec<(f64, f64, f64)> = (0..10).map(|_| (1e6, 0.5, 1e-6)).collect();
    let c = engine
        .evaluate_stack(&layers(&ten, steel), 1e5, Request::all())
        .unwrap();
    let one = film(el(1e6, 0.5), steel, 10e-6, &engine);
    agree("A/A0", &c.top.area_fraction, &one.area_fraction);
    agree(
        "tau bottom",
        c.interfaces[9].tau_rms.as_ref().unwrap(),
        one.tau_rms_interface.as_ref().unwrap(),
    );
    let mixed: Vec<(f64, f64, f64)> = (0..10)
        .map(|k| {
            if k % 2 == 0 {
                (1e6, 0.5, 2e-6)
            } else {
                (3e9, 0.35, 1e-6)
            }
        })
        .collect();
    let c = engine
        .evaluate_stack(&layers(&mixed, steel), 1e5, Request::all())
        .unwrap();
    for i in &c.interfaces {
        let t = i.tau_rms.unwrap();
        assert!(t.value > 0.0 && t.err <= 1e-8 * t.value, "{t:?}");
    }
    let eleven: Vec<Layer> = (0..11)
        .map(|_| Layer {
            material: el(1e6, 0.5),
            thickness: 1e-6,
        })
        .collect();
    assert!(LayerStack::new(eleven, steel).is_err());
}

/// d_min of a split layer: the top rubber layer's d_min above 100 nm of the same rubber plus
/// those 100 nm is the film's d_min, within the two searches' error estimates.
#[test]
fn split_layer_min_thickness() {
    use coatcheck::check::stack::{StackChecker, StackDesign, StackLayer};
    use coatcheck::check::{Checker, Criteria, Design};
    let spectrum = paper_spectrum();
    let (rubber, steel) = (el(1e6, 0.5), el(2e11, 0.3));
    let criteria = Criteria::default();
    let design = Design {
        layers: Bilayer::new(rubber, steel),
        pressure: 1e5,
        yield_strength: Some(2.5e8),
        bond_strength: 1e6,
        friction: 0.0,
        criteria,
    };
    let film = Checker::new(&spectrum, design, Settings::default()).unwrap();
    let want = film.min_thickness().unwrap().thickness.unwrap();
    let layer = |d: f64| StackLayer {
        name: format!("rubber {d}"),
        material: rubber,
        thickness: d,
        bond_strength: 1e6,
    };
    let stack = StackDesign {
        layers: vec![layer(10e-6), layer(1e-7)],
        substrate: steel,
        pressure: 1e5,
        yield_strength: Some(2.5e8),
        friction: 0.0,
        criteria,
        thickness_of: 0,
    };
    let got = StackChecker::new(&spectrum, stack, Settings::default())
        .unwrap()
        .min_thickness()
        .unwrap()
        .thickness
        .unwrap();
    assert!(
        (got.value + 1e-7 - want.value).abs() <= got.err + want.err,
        "{} + 1e-7 vs {} (± {}, {})",
        got.value,
        want.value,
        got.err,
        want.err
    );
}

/// Against a 30/40-digit mpmath evaluation of the same integrals with the kernels of an
/// independent solve of the whole boundary-value problem (`tests/data/stack_contact_ref.py`,
/// which checks its two quadratures against each other to 1e-20): G1, A/A0, σ_rms at the top
/// and σ_rms, τ_rms at every interface within 1e-8 relative and within their own error
/// estimates (which must bound the true error), on three stacks: rubber/epoxy/steel,
/// PTFE/rubber/steel and a three-layer stack with 1e8 contrasts, ν = ½.
#[test]
fn stack_integrals_match_mpmath() {
    let engine = Engine::new(&paper_spectrum(), Settings::default());
    let num = |s: &str| -> f64 { s.parse().unwrap() };
    for line in include_str!("../data/stack_contact_ref.csv")
        .lines()
        .skip(1)
    {
        let v: Vec<&str> = line.split(',').collect();
        let spec: Vec<(f64, f64, f64)> = v[2]
            .split('|')
            .map(|l| {
                let p: Vec<f64> = l.split(';').map(num).collect();
                (p[0], p[1], p[2])
            })
            .collect();
        let s = layers(&spec, el(num(v[3]), num(v[4])));
        let c = engine
            .evaluate_stack(&s, num(v[5]), Request::all())
            .unwrap();
        let mut got = vec![c.top.g1, c.top.area_fraction, c.top.sigma_rms_top.unwrap()];
        for i in &c.interfaces {
            got.push(i.sigma_rms.unwrap());
            got.push(i.tau_rms.unwrap());
        }
        let want: Vec<f64> = v[6..9]
            .iter()
            .copied()
            .chain(v[9].split('|'))
            .map(num)
            .collect();
        assert_eq!(got.len(), want.len());
        for (k, (g, w)) in got.iter().zip(&want).enumerate() {
            let diff = (g.value - w).abs();
            assert!(diff <= 1e-8 * w, "{} #{k}: {} vs {w}", v[0], g.value);
            assert!(
                diff <= g.err,
                "{} #{k}: {} ± {} vs {w}",
                v[0],
                g.value,
                g.err
            );
        }
    }
}

/// The exact solver on a stack: a rubber layer split in two (4 + 6 µm) on steel gives the
/// contact of the 10 µm film (`bem::solve` with the Bilayer's kernels) and, at the bottom
/// interface, its interface fields, to 1e-7 of the peak pressure (the solver's tolerance); at
/// the upper interface the normal stress has mean p0 and the shear is finite and non-zero.
#[test]
fn exact_solver_on_a_split_layer() {
    use coatcheck::bem::{self, BemSettings, Surface};
    use std::f64::consts::PI;
    let (n, l) = (32usize, 1e-4);
    let mut h = Vec::with_capacity(n * n);
    for iy in 0..n {
        for ix in 0..n {
            let (x, y) = (ix as f64 / n as f64, iy as f64 / n as f64);
            h.push(
                1e-7 * (2.0 * PI * (x + 2.0 * y)).cos()
                    + 4e-8 * (2.0 * PI * (5.0 * x - 3.0 * y)).sin(),
            );
        }
    }
    let surface = Surface::new(h, n, n, l / n as f64, l / n as f64).unwrap();
    let settings = BemSettings {
        gap_tol: 1e-12,
        ..BemSettings::default()
    };
    let (rubber, steel) = (el(1e6, 0.5), el(2e11, 0.3));
    let film = Stack::new(Bilayer::new(rubber, steel), 10e-6).unwrap();
    let p0 = 2e4;
    let want = bem::solve(&surface, &film, p0, &settings).unwrap();
    let want_fields = bem::interface_fields(&want, &film).unwrap();
    let split = layers(&[(1e6, 0.5, 4e-6), (1e6, 0.5, 6e-6)], steel);
    let got = bem::solve_stack(&surface, &split, p0, &settings).unwrap();
    let fields = bem::stack_interface_fields(&got, &split).unwrap();
    assert_eq!(fields.len(), 2);
    let scale = want.pressure.iter().fold(0.0f64, |m, p| m.max(*p));
    let close = |a: &[f64], b: &[f64], what: &str| {
        for (x, y) in a.iter().zip(b) {
            assert!((x - y).abs() <= 1e-7 * scale, "{what}: {x} vs {y}");
        }
    };
    close(&got.pressure, &want.pressure, "pressure");
    close(
        &fields[1].normal,
        &want_fields.normal,
        "normal at the bottom",
    );
    close(
        &fields[1].shear_x,
        &want_fields.shear_x,
        "shear_x at the bottom",
    );
    close(
        &fields[1].shear_y,
        &want_fields.shear_y,
        "shear_y at the bottom",
    );
    assert!((fields[0].normal_stats.mean - p0).abs() <= 1e-9 * p0);
    assert!(fields[0].shear_stats.rms > 0.0 && fields[0].shear_stats.rms.is_finite());
}

/// The interface tail's cut (src/contact/evaluate.rs, "Interface tail", with z_k for d) assumes
/// f_k² and g_k² do not increase beyond q·z_k = 20: checked on 4000 log-spaced q per interface
/// up to q·z_k = 700 for the stacks of these tests.
#[test]
fn interface_kernels_decrease_beyond_the_cut() {
    let steel = el(2e11, 0.3);
    let mixed: Vec<(f64, f64, f64)> = (0..10)
        .map(|k| {
            if k % 2 == 0 {
                (1e6, 0.5, 2e-6)
            } else {
                (3e9, 0.35, 1e-6)
            }
        })
        .collect();
    let stacks = [
        layers(&[(1e6, 0.5, 1e-5), (3e9, 0.35, 1e-5)], steel),
        layers(&[(5e8, 0.46, 5e-6), (2e6, 0.4998, 1e-4)], el(2e11, 0.29)),
        layers(
            &[(1e6, 0.5, 3e-6), (1e14, 0.5, 1e-6), (1e6, 0.5, 3e-6)],
            el(1e14, 0.5),
        ),
        layers(
            &[(1e14, 0.5, 1e-7), (1e6, 0.5, 5e-6), (1e14, 0.5, 1e-6)],
            el(1e6, 0.5),
        ),
        layers(&mixed, steel),
    ];
    for s in &stacks {
        for (k, z) in s.depths().into_iter().enumerate() {
            let mut last = (f64::INFINITY, f64::INFINITY);
            for i in 0..4000 {
                let x = 20.0 * 35f64.powf(i as f64 / 3999.0);
                let (f, g) = s.response(x / z).interfaces[k];
                let now = (f * f, g * g);
                assert!(
                    now.0 <= last.0 * (1.0 + 1e-12) && now.1 <= last.1 * (1.0 + 1e-12),
                    "{:?} interface {k} at q z = {x}: {now:?} after {last:?}",
                    s.layers()
                );
                last = now;
            }
        }
    }
}

/// One engine evaluating stacks whose top layer changes thickness and then modulus (its
/// per-node cache reused between them) gives what fresh engines give, to the last bit.
#[test]
fn engine_reused_across_materials_equals_fresh_engines() {
    let steel = el(2e11, 0.3);
    let reused = Engine::new(&paper_spectrum(), Settings::default());
    for (e_top, d_top) in [(1e6, 10e-6), (1e6, 20e-6), (4e6, 20e-6), (4e6, 10e-6)] {
        let s = layers(&[(e_top, 0.5, d_top), (3e9, 0.35, 10e-6)], steel);
        let got = reused.evaluate_stack(&s, 1e5, Request::all()).unwrap();
        let fresh = Engine::new(&paper_spectrum(), Settings::default());
        let want = fresh.evaluate_stack(&s, 1e5, Request::all()).unwrap();
        assert_eq!(got, want, "top layer E = {e_top}, d = {d_top}");
    }
}
