//! Scene ranges in `[[layer]]` tables (`youngs_modulus_range`, `poisson_ratio_range`,
//! `shear_strength_range` of the layer's bond) for `check --robust` on a stack: they replace
//! the library's, the robust d_min range's ends are the nominal d_min of the scenes with each
//! end written out, and a bad range is an error at its line (exit 2).

use crate::common::{check_json, run, write_text};
use serde_json::Value;
use std::path::Path;

/// Rubber over an epoxy primer on steel, every value explicit (no library range): the rubber
/// and the primer given by their moduli, the bonds by their strengths, the substrate by its
/// moduli and yield strength.
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
youngs_modulus = \"6 MPa\"
poisson_ratio = 0.4995
thickness = \"25 um\"
bond = \"7 MPa\"
[[layer]]
name = \"primer\"
youngs_modulus = \"3 GPa\"
poisson_ratio = 0.35
thickness = \"5 um\"
bond = \"20 MPa\"
[substrate]
youngs_modulus = \"200 GPa\"
poisson_ratio = 0.29
yield_strength = \"250 MPa\"
[load]
pressure = \"2 MPa\"
";

/// `text` with `line` added after the first occurrence of `after`.
fn with(text: &str, after: &str, line: &str) -> String {
    text.replacen(after, &format!("{after}{line}\n"), 1)
}

/// The nominal d_min of `text` (m).
fn d_min(dir: &Path, text: &str) -> f64 {
    let scene = write_text(dir, "nominal.toml", text);
    check_json(&[&scene])["min_thickness_m"].as_f64().unwrap()
}

/// `a` and `b` agree to 1e-12 relative (the same search on the same design).
fn same(a: f64, b: f64, what: &str) {
    assert!((a - b).abs() <= 1e-12 * b.abs(), "{what}: {a:e} vs {b:e}");
}

/// One scene range at a time: the robust d_min range is the nominal d_min of the scene with
/// the property at each end of the range (an elastic constant: the larger and the smaller of
/// the two; a bond's strength: its maximum gives the least d_min, its minimum the largest).
#[test]
fn a_layer_range_moves_the_robust_d_min_range_to_its_ends() {
    let dir = tempfile::tempdir().unwrap();
    let nominal = d_min(dir.path(), SCENE);
    let cases = [
        (
            "bond = \"7 MPa\"\n",
            "shear_strength_range = [\"5 MPa\", \"9 MPa\"]",
            "layer[1].bond",
            ["bond = \"5 MPa\"\n", "bond = \"9 MPa\"\n"],
        ),
        (
            "youngs_modulus = \"6 MPa\"\n",
            "youngs_modulus_range = [\"4 MPa\", \"8 MPa\"]",
            "layer[1].youngs_modulus",
            [
                "youngs_modulus = \"4 MPa\"\n",
                "youngs_modulus = \"8 MPa\"\n",
            ],
        ),
        (
            "youngs_modulus = \"3 GPa\"\n",
            "youngs_modulus_range = [\"1 GPa\", \"3 GPa\"]",
            "layer[2].youngs_modulus",
            [
                "youngs_modulus = \"1 GPa\"\n",
                "youngs_modulus = \"3 GPa\"\n",
            ],
        ),
        (
            "poisson_ratio = 0.4995\n",
            "poisson_ratio_range = [0.45, 0.5]",
            "layer[1].poisson_ratio",
            ["poisson_ratio = 0.45\n", "poisson_ratio = 0.5\n"],
        ),
    ];
    for (after, range, key, ends) in cases {
        let scene = write_text(dir.path(), "s.toml", &with(SCENE, after, range));
        let r = &check_json(&[&scene, "--robust"])["robust"];
        let ranges = r["ranges"].as_array().unwrap();
        assert_eq!(ranges.len(), 1, "{key}: {ranges:?}");
        assert_eq!(ranges[0]["key"], key);
        let at: Vec<f64> = ends
            .iter()
            .map(|e| d_min(dir.path(), &SCENE.replacen(after, e, 1)))
            .collect();
        let m = &r["min_thickness_range_m"];
        let (lo, hi) = (m["min"].as_f64().unwrap(), m["max"].as_f64().unwrap());
        same(lo, at[0].min(at[1]), key);
        same(hi, at[0].max(at[1]), key);
        assert_eq!(m["nominal"].as_f64().unwrap(), nominal);
        assert!(lo <= nominal && nominal <= hi, "{key}: {m}");
        assert!(lo < hi, "{key}: the range moves d_min ({m})");
        if key == "layer[1].bond" {
            // The weaker bond needs the thicker rubber.
            same(hi, at[0], key);
            assert!(at[0] > nominal && at[1] < nominal, "{at:?} {nominal}");
        }
    }
}

/// A scene's range replaces the library's: NBR's E range 4–8 MPa and the Chemlok-type bond's
/// 5–10 MPa narrowed in the scene narrow the robust d_min range (within the library's) and are
/// the ranges reported.
#[test]
fn a_layer_range_replaces_the_librarys() {
    let dir = tempfile::tempdir().unwrap();
    let library = SCENE
        .replacen(
            "youngs_modulus = \"6 MPa\"\npoisson_ratio = 0.4995\n",
            "material = \"nbr\"\n",
            1,
        )
        .replacen("bond = \"7 MPa\"", "bond = \"chemlok-type\"", 1);
    let narrowed = with(
        &with(
            &library,
            "material = \"nbr\"\n",
            "youngs_modulus_range = [\"5 MPa\", \"7 MPa\"]",
        ),
        "bond = \"chemlok-type\"\n",
        "shear_strength_range = [\"5 MPa\", \"7 MPa\"]",
    );
    let wide = check_json(&[&write_text(dir.path(), "a.toml", &library), "--robust"]);
    let narrow = check_json(&[&write_text(dir.path(), "b.toml", &narrowed), "--robust"]);
    let span = |v: &Value, key: &str| {
        let r = v["robust"]["ranges"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["key"] == key)
            .unwrap_or_else(|| panic!("{key}"))
            .clone();
        (r["min"].as_f64().unwrap(), r["max"].as_f64().unwrap())
    };
    assert_eq!(span(&wide, "layer[1].youngs_modulus"), (4e6, 8e6));
    assert_eq!(span(&wide, "layer[1].bond"), (5e6, 10e6));
    assert_eq!(span(&narrow, "layer[1].youngs_modulus"), (5e6, 7e6));
    assert_eq!(span(&narrow, "layer[1].bond"), (5e6, 7e6));
    // The library's other ranges stay (NBR's ν).
    assert_eq!(
        span(&narrow, "layer[1].poisson_ratio"),
        span(&wide, "layer[1].poisson_ratio")
    );
    let m = |v: &Value, end: &str| v["robust"]["min_thickness_range_m"][end].as_f64().unwrap();
    assert!(m(&narrow, "min") > m(&wide, "min"), "{narrow} {wide}");
    assert!(m(&narrow, "max") < m(&wide, "max"), "{narrow} {wide}");
    assert_eq!(
        narrow["robust"]["min_thickness_range_m"]["nominal"],
        wide["robust"]["min_thickness_range_m"]["nominal"]
    );
}

/// A bad layer range is an error naming the file, the line and the key, with what was
/// expected (exit 2), as a film's.
#[test]
fn bad_layer_ranges_are_errors_naming_the_file_line_and_key() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "bond = \"20 MPa\"\n",
            "youngs_modulus_range = [\"4 GPa\", \"2 GPa\"]",
            "layer[2].youngs_modulus_range: min 4e9 > max 2e9",
        ),
        (
            "bond = \"7 MPa\"\n",
            "youngs_modulus_range = [\"-4 MPa\", \"8 MPa\"]",
            "layer[1].youngs_modulus_range: -4e6 (expected values > 0)",
        ),
        (
            "bond = \"7 MPa\"\n",
            "poisson_ratio_range = [0.45, 0.55]",
            "layer[1].poisson_ratio_range: invalid Poisson ratio",
        ),
        (
            "bond = \"7 MPa\"\n",
            "shear_strength_range = [\"8 MPa\", \"9 MPa\"]",
            "layer[1].shear_strength_range: [8e6, 9e6] does not hold the nominal value 7e6",
        ),
        (
            "bond = \"20 MPa\"\n",
            "shear_strength_range = \"20 MPa\"",
            "layer[2].shear_strength_range: expected a range [min, max] of two values",
        ),
        (
            "bond = \"20 MPa\"\n",
            "shear_strength_range = [\"10 um\", \"30 MPa\"]",
            "layer[2].shear_strength_range: '10 um' is not a finite value",
        ),
    ];
    for (after, range, needle) in cases {
        let text = with(SCENE, after, range);
        let line = text.lines().position(|l| l == range).unwrap() + 1;
        let scene = write_text(dir.path(), "bad.toml", &text);
        let o = run(&["check", &scene, "--robust"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(
            err.contains(&format!("bad.toml:{line}: {needle}")),
            "{needle}: {err}"
        );
    }
}
