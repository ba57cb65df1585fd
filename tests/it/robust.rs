//! `check --robust`: the design at the worst corner of its materials' ranges, against the
//! nominal check of a scene with that corner's values written out; ranges of zero width; the
//! d_min range; bad ranges; the materials listing and every output format.

use crate::common::{check_json, json, run, write_text};
use serde_json::Value;

/// NBR on carbon steel with a rubber-tearing bond: every property has a library range.
const SCENE: &str = "\
[roughness]
model = \"self-affine\"
hurst = 0.8
q0 = \"1e4 1/m\"
roll_off = \"5e4 1/m\"
q1 = \"1e7 1/m\"
rms_slope = 0.3
[film]
material = \"nbr\"
thickness = \"25 um\"
[substrate]
material = \"carbon-steel\"
[bond]
material = \"chemlok-type\"
[load]
pressure = \"2 MPa\"
";

/// The scene with the governing corner's values written out as explicit numbers.
fn corner_scene(robust: &Value) -> String {
    let corner = robust["governing_corner"].as_object().unwrap();
    let mut text = SCENE.to_string();
    for (section, key) in [
        ("film", "youngs_modulus"),
        ("film", "poisson_ratio"),
        ("substrate", "youngs_modulus"),
        ("substrate", "poisson_ratio"),
        ("substrate", "yield_strength"),
        ("bond", "shear_strength"),
    ] {
        let v = corner[&format!("{section}.{key}")].as_f64().unwrap();
        text = text.replace(
            &format!("[{section}]\n"),
            &format!("[{section}]\n{key} = {v:e}\n"),
        );
    }
    ["nbr", "carbon-steel", "chemlok-type"]
        .iter()
        .fold(text, |t, m| t.replace(&format!("material = \"{m}\"\n"), ""))
}

fn check_named<'a>(checks: &'a Value, name: &str) -> &'a Value {
    checks
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == name)
        .unwrap()
}

#[test]
fn the_robust_verdict_is_the_nominal_verdict_at_the_worst_corner() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_text(dir.path(), "s.toml", SCENE);
    let v = check_json(&[&scene, "--robust"]);
    let r = &v["robust"];
    assert_eq!(r["corners"], 16);
    assert_eq!(r["ranges"].as_array().unwrap().len(), 6);
    let range = r["min_thickness_range_m"].clone();
    let (lo, hi, nominal) = (
        range["min"].as_f64().unwrap(),
        range["max"].as_f64().unwrap(),
        range["nominal"].as_f64().unwrap(),
    );
    assert!(lo < nominal && nominal < hi, "{range}");
    assert_eq!(nominal, v["min_thickness_m"].as_f64().unwrap());
    // At 25 um, and between the nominal and the worst d_min, where the nominal design passes
    // its min-thickness check and the robust one fails it.
    let between = format!("{}um", 1e6 * (nominal * hi).sqrt());
    for thickness in ["25um", between.as_str()] {
        let v = check_json(&[&scene, "--robust", "--thickness", thickness]);
        let r = &v["robust"];
        let explicit = write_text(dir.path(), "corner.toml", &corner_scene(r));
        let n = check_json(&[&explicit, "--thickness", thickness]);
        assert_eq!(r["verdict"], n["verdict"], "{thickness}");
        let governing = r["governing_check"].as_str().unwrap();
        assert_eq!(n["governing_check"], governing, "{thickness}");
        let (a, b) = (
            check_named(&r["checks"], governing)["margin"]
                .as_f64()
                .unwrap(),
            check_named(&n["checks"], governing)["margin"]
                .as_f64()
                .unwrap(),
        );
        assert!(
            (a - b).abs() <= 1e-12 * a.abs().max(1.0),
            "{thickness}: {a} {b}"
        );
        assert_eq!(
            v["verdict_with_robust"],
            if v["verdict"] == "pass" && r["verdict"] == "pass" {
                "pass"
            } else {
                "fail"
            }
        );
        if thickness != "25um" {
            assert_eq!(check_named(&v["checks"], "min-thickness")["pass"], true);
            assert_eq!(check_named(&r["checks"], "min-thickness")["pass"], false);
            assert_eq!(v["verdict_with_robust"], "fail");
        }
    }
}

#[test]
fn ranges_of_zero_width_give_the_nominal_answer() {
    let dir = tempfile::tempdir().unwrap();
    // Explicit values have no range; a zero-width range given for one changes nothing.
    let text = SCENE
        .replace("material = \"nbr\"\n", "youngs_modulus = \"6 MPa\"\npoisson_ratio = 0.4995\nyoungs_modulus_range = [\"6 MPa\", \"6 MPa\"]\n")
        .replace("material = \"carbon-steel\"\n", "youngs_modulus = \"200 GPa\"\npoisson_ratio = 0.29\nyield_strength = \"250 MPa\"\n")
        .replace("material = \"chemlok-type\"\n", "shear_strength = \"5 MPa\"\n");
    let scene = write_text(dir.path(), "s.toml", &text);
    let v = check_json(&[&scene, "--robust"]);
    let r = &v["robust"];
    assert_eq!(r["ranges"], serde_json::json!([]));
    assert_eq!(r["corners"], 1);
    assert_eq!(r["verdict"], v["verdict"]);
    for c in r["checks"].as_array().unwrap() {
        let n = check_named(&v["checks"], c["name"].as_str().unwrap());
        for key in ["value", "limit", "margin", "pass"] {
            assert_eq!(c[key], n[key], "{key}");
        }
    }
    let m = &r["min_thickness_range_m"];
    assert_eq!(m["min"], v["min_thickness_m"]);
    assert_eq!(m["max"], v["min_thickness_m"]);
}

#[test]
fn bad_ranges_are_errors_naming_the_file_line_and_key() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "[film]\n",
            "[film]\nyoungs_modulus_range = [\"8 MPa\", \"4 MPa\"]\n",
            9,
            "film.youngs_modulus_range: min 8e6 > max 4e6",
        ),
        (
            "[film]\n",
            "[film]\nyoungs_modulus_range = [\"-4 MPa\", \"8 MPa\"]\n",
            9,
            "film.youngs_modulus_range: -4e6 (expected values > 0)",
        ),
        (
            "[film]\n",
            "[film]\npoisson_ratio_range = [0.45, 0.55]\n",
            9,
            "film.poisson_ratio_range: invalid Poisson ratio",
        ),
        (
            "[substrate]\n",
            "[substrate]\npoisson_ratio_range = [-1.2, 0.3]\n",
            12,
            "substrate.poisson_ratio_range: invalid Poisson ratio",
        ),
        (
            "[bond]\n",
            "[bond]\nshear_strength_range = [\"6 MPa\", \"9 MPa\"]\n",
            14,
            "bond.shear_strength_range: [6e6, 9e6] does not hold the nominal value 5e6",
        ),
    ];
    for (from, to, line, needle) in cases {
        let scene = write_text(dir.path(), "bad.toml", &SCENE.replace(from, to));
        let o = run(&["check", &scene, "--robust"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(
            err.contains(&format!(
                "bad.toml:{line}: {}",
                needle.split(':').next().unwrap()
            )),
            "{err}"
        );
        assert!(err.contains(needle), "{err}");
    }
    let scene = write_text(dir.path(), "s.toml", SCENE);
    let o = run(&[
        "check",
        &scene,
        "--robust",
        "--yield-strength-range",
        "300MPa,200MPa",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--yield-strength-range") && err.contains("min 3e8 > max 2e8"),
        "{err}"
    );
}

#[test]
fn the_materials_listing_shows_the_ranges_and_their_sources() {
    let o = run(&["materials"]);
    assert_eq!(o.status.code(), Some(0));
    let text = String::from_utf8_lossy(&o.stdout);
    // (Cells wrap at spaces: the needles are the unwrapped pieces.)
    for needle in [
        "Ranges (check --robust",
        "0.49867",
        "0.49978",
        "241.0 MPa to 276.0",
    ] {
        assert!(text.contains(needle), "{needle}");
    }
    let v = json(&run(&["materials", "--format", "json"]));
    let nbr = v["materials"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["name"] == "nbr")
        .unwrap();
    assert_eq!(
        nbr["youngs_modulus_range_pa"],
        serde_json::json!([4e6, 8e6])
    );
    let epoxy = v["bonds"]
        .as_array()
        .unwrap()
        .iter()
        .find(|b| b["name"] == "epoxy")
        .unwrap();
    assert_eq!(epoxy["shear_strength_range_pa"], Value::Null);
}

#[test]
fn every_format_reports_the_robust_verdict_beside_the_nominal_one() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_text(
        dir.path(),
        "s.toml",
        &SCENE.replace("[load]\n", "[criteria]\nrobust = true\n[load]\n"),
    );
    let schema: Value = serde_json::from_str(coatcheck::report::CHECK_SCHEMA).unwrap();
    let v = check_json(&[&scene]);
    let e = crate::schema::errors(&schema, &v);
    assert!(e.is_empty(), "{}", e.join("\n"));
    let r = &v["robust"];
    let table = String::from_utf8_lossy(&run(&["check", &scene]).stdout).into_owned();
    assert!(
        table.contains("robust verdict: ") && table.contains("governing corner"),
        "{table}"
    );
    assert!(table.contains("d_min over the corners: "), "{table}");
    let csv =
        String::from_utf8_lossy(&run(&["check", &scene, "--format", "csv"]).stdout).into_owned();
    let mut lines = csv.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    let at = |k: &str| row[head.iter().position(|h| *h == k).unwrap()].to_string();
    assert_eq!(at("robust_verdict"), r["verdict"].as_str().unwrap());
    let max: f64 = at("robust_min_thickness_m_max").parse().unwrap();
    assert_eq!(max, r["min_thickness_range_m"]["max"].as_f64().unwrap());
    let html = dir.path().join("r.html");
    let o = run(&["check", &scene, "--report", html.to_str().unwrap()]);
    assert!(o.status.code().is_some_and(|c| c < 2));
    let page = std::fs::read_to_string(&html).unwrap();
    assert!(
        page.contains("robust (worst corner of the materials&#39; ranges)")
            || page.contains("robust (worst corner of the materials' ranges)"),
        "headline"
    );
    assert!(page.contains("d_min over the corners of the ranges"));
    // --robust=false on the command line turns the scene's switch off.
    let v = check_json(&[&scene, "--robust=false"]);
    assert!(v.get("robust").is_none());
}
