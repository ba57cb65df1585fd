//! `check --robust` on layer stacks (`coatcheck::check::stack_robust`): for one layer, the
//! film's robust output (`coatcheck::check::robust`, with the closed-form kernels); for two,
//! the robust verdict is the nominal verdict of the scene with the worst corner written out;
//! ranges of zero width give the nominal answer; the d_min range brackets the nominal d_min.

use crate::common::{check_json, run, write_text};
use coatcheck::check::robust::{Param, judge_robust};
use coatcheck::check::stack::{StackDesign, StackLayer};
use coatcheck::check::stack_robust::{self, StackParam};
use coatcheck::check::{Criteria, Design};
use coatcheck::layer::Bilayer;
use coatcheck::material::{Library, Span};
use coatcheck::prec::Settings;
use coatcheck::psd::Spectrum;
use serde_json::Value;

/// NBR over an epoxy primer (its moduli given, so without ranges) on carbon steel: the
/// rubber's and the steel's E and ν have library ranges (16 corners), and both bonds' and the
/// yield strength's.
const SCENE: &str = "\
[roughness]
model = \"self-affine\"
hurst = 0.8
q0 = \"1e4 1/m\"
roll_off = \"5e4 1/m\"
q1 = \"1e7 1/m\"
rms_slope = 0.3
[[layer]]
name = \"rubber\"
material = \"nbr\"
thickness = \"25 um\"
bond = \"chemlok-type\"
[[layer]]
name = \"primer\"
youngs_modulus = \"3 GPa\"
poisson_ratio = 0.35
thickness = \"5 um\"
bond = \"cyanoacrylate\"
[substrate]
material = \"carbon-steel\"
[load]
pressure = \"2 MPa\"
";

/// The scene with the governing corner's values written out as explicit numbers.
fn corner_scene(robust: &Value) -> String {
    let corner = robust["governing_corner"].as_object().unwrap();
    let at = |k: &str| corner[k].as_f64().unwrap();
    SCENE
        .replace(
            "material = \"nbr\"\n",
            &format!(
                "youngs_modulus = {:e}\npoisson_ratio = {:e}\n",
                at("layer[1].youngs_modulus"),
                at("layer[1].poisson_ratio")
            ),
        )
        .replace(
            "bond = \"chemlok-type\"",
            &format!("bond = {:e}", at("layer[1].bond")),
        )
        .replace(
            "bond = \"cyanoacrylate\"",
            &format!("bond = {:e}", at("layer[2].bond")),
        )
        .replace(
            "material = \"carbon-steel\"\n",
            &format!(
                "youngs_modulus = {:e}\npoisson_ratio = {:e}\nyield_strength = {:e}\n",
                at("substrate.youngs_modulus"),
                at("substrate.poisson_ratio"),
                at("substrate.yield_strength")
            ),
        )
}

fn check_at<'a>(checks: &'a Value, name: &str, at: &str) -> &'a Value {
    checks
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == name && c["at"] == at)
        .unwrap()
}

#[test]
fn the_robust_stack_verdict_is_the_nominal_verdict_at_the_worst_corner() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_text(dir.path(), "s.toml", SCENE);
    let v = check_json(&[&scene, "--robust"]);
    let schema: Value = serde_json::from_str(coatcheck::report::CHECK_SCHEMA).unwrap();
    let e = crate::schema::errors(&schema, &v);
    assert!(e.is_empty(), "{}", e.join("\n"));
    let r = &v["robust"];
    assert_eq!(r["corners"], 16);
    let keys: Vec<&str> = r["ranges"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x["key"].as_str().unwrap())
        .collect();
    assert_eq!(
        keys,
        [
            "layer[1].youngs_modulus",
            "layer[1].poisson_ratio",
            "substrate.youngs_modulus",
            "substrate.poisson_ratio",
            "substrate.yield_strength",
            "layer[1].bond",
            "layer[2].bond"
        ]
    );
    let range = &r["min_thickness_range_m"];
    let (lo, hi, nominal) = (
        range["min"].as_f64().unwrap(),
        range["max"].as_f64().unwrap(),
        range["nominal"].as_f64().unwrap(),
    );
    assert!(lo < nominal && nominal < hi, "{range}");
    assert_eq!(nominal, v["min_thickness_m"].as_f64().unwrap());
    // Every check at every interface is no better at its worst corner than nominally.
    for c in r["checks"].as_array().unwrap() {
        let n = check_at(
            &v["checks"],
            c["name"].as_str().unwrap(),
            c["at"].as_str().unwrap(),
        );
        assert!(
            c["margin"].as_f64().unwrap() <= n["margin"].as_f64().unwrap(),
            "{c} {n}"
        );
    }
    // At 25 um, and between the nominal and the worst d_min, where the nominal design passes
    // its min-thickness check and the robust one fails it.
    let between = format!("{}um", 1e6 * (nominal * hi).sqrt());
    for thickness in ["25um", between.as_str()] {
        let given = SCENE.replace(
            "thickness = \"25 um\"",
            &format!("thickness = \"{thickness}\""),
        );
        let scene = write_text(dir.path(), "t.toml", &given);
        let v = check_json(&[&scene, "--robust"]);
        let r = &v["robust"];
        let explicit = write_text(
            dir.path(),
            "corner.toml",
            &corner_scene(r).replace(
                "thickness = \"25 um\"",
                &format!("thickness = \"{thickness}\""),
            ),
        );
        let n = check_json(&[&explicit]);
        assert_eq!(r["verdict"], n["verdict"], "{thickness}");
        let (governing, at) = (
            r["governing_check"].as_str().unwrap(),
            r["governing_at"].as_str().unwrap(),
        );
        assert_eq!(n["governing_check"], governing, "{thickness}");
        let (a, b) = (
            check_at(&r["checks"], governing, at)["margin"]
                .as_f64()
                .unwrap(),
            check_at(&n["checks"], governing, at)["margin"]
                .as_f64()
                .unwrap(),
        );
        assert!(
            (a - b).abs() <= 1e-12 * a.abs().max(1.0),
            "{thickness}: {a} {b}"
        );
        if thickness != "25um" {
            assert_eq!(
                check_at(&v["checks"], "min-thickness", "rubber")["pass"],
                true
            );
            assert_eq!(
                check_at(&r["checks"], "min-thickness", "rubber")["pass"],
                false
            );
            assert_eq!(v["verdict_with_robust"], "fail");
        }
    }
    let table = String::from_utf8_lossy(&run(&["check", &scene, "--robust"]).stdout).into_owned();
    assert!(
        table.contains("robust verdict: ") && table.contains("layer[1].bond"),
        "{table}"
    );
    let csv =
        String::from_utf8_lossy(&run(&["check", &scene, "--robust", "--format", "csv"]).stdout)
            .into_owned();
    let mut lines = csv.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    let cell = |k: &str| row[head.iter().position(|h| *h == k).unwrap()].to_string();
    assert_eq!(
        cell("robust_verdict"),
        v["robust"]["verdict"].as_str().unwrap()
    );
    let max: f64 = cell("robust_min_thickness_m_max").parse().unwrap();
    assert_eq!(max, hi);
}

#[test]
fn ranges_of_zero_width_give_the_nominal_stack_answer() {
    let dir = tempfile::tempdir().unwrap();
    let text = SCENE
        .replace(
            "material = \"nbr\"\n",
            "youngs_modulus = \"6 MPa\"\npoisson_ratio = 0.4995\n",
        )
        .replace("bond = \"chemlok-type\"", "bond = \"7 MPa\"")
        .replace("bond = \"cyanoacrylate\"", "bond = \"20 MPa\"")
        .replace(
            "material = \"carbon-steel\"\n",
            "youngs_modulus = \"200 GPa\"\npoisson_ratio = 0.29\nyield_strength = \"250 MPa\"\n\
             youngs_modulus_range = [\"200 GPa\", \"200 GPa\"]\n",
        );
    let scene = write_text(dir.path(), "s.toml", &text);
    let v = check_json(&[&scene, "--robust"]);
    let r = &v["robust"];
    assert_eq!(r["ranges"], serde_json::json!([]));
    assert_eq!(r["corners"], 1);
    assert_eq!(r["verdict"], v["verdict"]);
    for c in r["checks"].as_array().unwrap() {
        let n = check_at(
            &v["checks"],
            c["name"].as_str().unwrap(),
            c["at"].as_str().unwrap(),
        );
        for key in ["value", "limit", "margin", "pass"] {
            assert_eq!(c[key], n[key], "{key}");
        }
    }
    let m = &r["min_thickness_range_m"];
    assert_eq!(m["min"], v["min_thickness_m"]);
    assert_eq!(m["max"], v["min_thickness_m"]);
}

/// |a − b| ≤ tol·max(|a|, |b|) (equal, None or NaN alike, passes).
fn close(a: Option<f64>, b: Option<f64>, tol: f64, what: &str) {
    let ok = match (a, b) {
        (Some(a), Some(b)) => a == b || (a - b).abs() <= tol * a.abs().max(b.abs()),
        (a, b) => a == b,
    };
    assert!(ok, "{what}: {a:?} vs {b:?}");
}

/// A one-layer stack's robust judgement is the film's: the same corners in the same order, each
/// check's worst corner, value, limit and margin, the verdict, the governing corner and the
/// d_min range (1e-12 relative: the stack's kernels and the film's closed forms agree to
/// ~1e-13).
#[test]
fn one_layer_stack_robust_is_the_films() {
    let lib = Library::builtin().unwrap();
    let (nbr, steel, bond) = (
        lib.material("nbr").unwrap(),
        lib.material("carbon-steel").unwrap(),
        lib.bond("chemlok-type").unwrap(),
    );
    let spectrum = Spectrum::self_affine(0.8, 1e4, 1e7, Some(5e4))
        .unwrap()
        .scaled_to_rms_slope(0.3)
        .unwrap();
    let d = 25e-6;
    let film = Design {
        layers: Bilayer::new(nbr.elastic, steel.elastic),
        pressure: 2e6,
        yield_strength: steel.yield_strength,
        bond_strength: bond.shear_strength,
        friction: 0.0,
        criteria: Criteria::default(),
    };
    let stack = StackDesign {
        layers: vec![StackLayer {
            name: "nbr".into(),
            material: nbr.elastic,
            thickness: d,
            bond_strength: bond.shear_strength,
        }],
        substrate: steel.elastic,
        pressure: 2e6,
        yield_strength: steel.yield_strength,
        friction: 0.0,
        criteria: Criteria::default(),
        thickness_of: 0,
    };
    let ranges = coatcheck::check::robust::ranges(nbr, steel, bond);
    let stack_ranges: Vec<(StackParam, Span)> = ranges
        .iter()
        .map(|&(p, s)| {
            let q = match p {
                Param::FilmYoungsModulus => StackParam::YoungsModulus(0),
                Param::FilmPoissonRatio => StackParam::PoissonRatio(0),
                Param::SubstrateYoungsModulus => StackParam::SubstrateYoungsModulus,
                Param::SubstratePoissonRatio => StackParam::SubstratePoissonRatio,
                Param::YieldStrength => StackParam::YieldStrength,
                Param::BondShearStrength => StackParam::BondStrength(0),
            };
            (q, s)
        })
        .collect();
    assert_eq!(ranges.len(), 6);
    let want = judge_robust(&spectrum, &film, Settings::default(), d, ranges).unwrap();
    let got =
        stack_robust::judge_robust(&spectrum, &stack, Settings::default(), stack_ranges).unwrap();
    let tol = 1e-12;
    assert_eq!((got.corners, want.corners), (16, 16));
    assert!(got.held.is_empty());
    assert_eq!(got.pass, want.pass);
    assert_eq!(got.governing.as_ref().map(|g| g.0), want.governing);
    assert_eq!(got.corner, want.corner);
    assert_eq!(got.checks.len(), want.checks.len());
    for (g, w) in got.checks.iter().zip(&want.checks) {
        let (gr, wr) = (&g.check.result, &w.result);
        assert_eq!((gr.kind, gr.pass), (wr.kind, wr.pass));
        assert_eq!(g.corner, w.corner, "{:?}", gr.kind);
        close(Some(gr.value.value), Some(wr.value.value), tol, "value");
        close(gr.limit, wr.limit, tol, "limit");
        close(gr.margin, wr.margin, 1e-9, "margin");
    }
    let (gm, wm) = (got.min_thickness.unwrap(), want.min_thickness.unwrap());
    close(gm.min, wm.min, tol, "d_min range min");
    close(gm.max, wm.max, tol, "d_min range max");
}

/// A stack with more than `MAX_VARIED` elastic ranges (natural rubber on NBR on an epoxy primer
/// on carbon steel: 8) varies the 6 that change the largest utilisation most over their 64
/// corners and holds the other 2 at the end where that utilisation is larger (each range
/// screened here at its two ends with the others nominal); every check at its worst corner is
/// no better than nominally.
#[test]
fn a_deep_stack_holds_its_least_influential_ranges() {
    use coatcheck::check::stack::StackChecker;
    use coatcheck::check::stack_robust::MAX_VARIED;
    let lib = Library::builtin().unwrap();
    let m = |n: &str| lib.material(n).unwrap();
    let (nr, nbr, primer, steel) = (
        m("natural-rubber"),
        m("nbr"),
        m("epoxy-primer"),
        m("carbon-steel"),
    );
    let layer = |name: &str, e, d| StackLayer {
        name: name.into(),
        material: e,
        thickness: d,
        bond_strength: 5e6,
    };
    let design = StackDesign {
        layers: vec![
            layer("skin", nr.elastic, 10e-6),
            layer("lining", nbr.elastic, 10e-6),
            layer("primer", primer.elastic, 5e-6),
        ],
        substrate: steel.elastic,
        pressure: 2e6,
        yield_strength: steel.yield_strength,
        friction: 0.0,
        criteria: Criteria::default(),
        thickness_of: 0,
    };
    let mut ranges = Vec::new();
    for (k, mat) in [nr, nbr, primer].iter().enumerate() {
        ranges.push((
            StackParam::YoungsModulus(k),
            mat.ranges.youngs_modulus.unwrap(),
        ));
        ranges.push((
            StackParam::PoissonRatio(k),
            mat.ranges.poisson_ratio.unwrap(),
        ));
    }
    ranges.push((
        StackParam::SubstrateYoungsModulus,
        steel.ranges.youngs_modulus.unwrap(),
    ));
    ranges.push((
        StackParam::SubstratePoissonRatio,
        steel.ranges.poisson_ratio.unwrap(),
    ));
    let spectrum = Spectrum::self_affine(0.8, 1e4, 1e7, Some(5e4))
        .unwrap()
        .scaled_to_rms_slope(0.3)
        .unwrap();
    let settings = Settings::default();
    let largest = |d: &StackDesign| {
        let row = StackChecker::new(&spectrum, d.clone(), settings)
            .unwrap()
            .evaluate(d.layers[0].thickness)
            .unwrap();
        row.checks
            .iter()
            .map(|c| c.result.value.value / c.result.limit.unwrap())
            .fold(0.0, f64::max)
    };
    let screened: Vec<(f64, f64)> = ranges
        .iter()
        .map(|&(p, s)| {
            let at = |v: f64| {
                let mut d = design.clone();
                p.set(&mut d, v).unwrap();
                largest(&d)
            };
            let (lo, hi) = (at(s.min), at(s.max));
            ((hi - lo).abs(), if hi > lo { s.max } else { s.min })
        })
        .collect();
    let r = stack_robust::judge_robust(&spectrum, &design, settings, ranges.clone()).unwrap();
    assert_eq!(r.corners, 1 << MAX_VARIED);
    assert_eq!(r.held.len(), ranges.len() - MAX_VARIED);
    let varied_least = (0..ranges.len())
        .filter(|i| !r.held.iter().any(|(h, _)| h == i))
        .map(|i| screened[i].0)
        .fold(f64::INFINITY, f64::min);
    for &(i, v) in &r.held {
        assert!(screened[i].0 <= varied_least, "held {i}: {:?}", screened);
        assert_eq!(v, screened[i].1, "held {i} at its worse end");
        assert_eq!(r.corner[i], v);
    }
    let nominal = StackChecker::new(&spectrum, design.clone(), settings)
        .unwrap()
        .run()
        .unwrap();
    for (w, n) in r.checks.iter().zip(&nominal.checks) {
        assert_eq!((w.check.result.kind, &w.check.at), (n.result.kind, &n.at));
        assert!(w.check.result.margin <= n.result.margin, "{w:?} {n:?}");
    }
}
