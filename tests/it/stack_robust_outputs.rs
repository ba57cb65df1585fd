//! `check --robust` in the JUnit XML (a film's and a stack's: one more case per check, at its
//! worst corner, failing exactly where the JSON's robust check fails, its message naming the
//! corner) and in a stack's HTML report (the robust verdict in the headline, the ranges, each
//! check at its worst corner and the d_min range in "how far to trust these numbers").

use crate::common::{json, run};
use serde_json::Value;
use std::path::Path;

/// Rubber (NBR, with its library ranges) over an epoxy primer on steel, the rubber's bond a
/// scene range whose lower end the rubber's interface shear exceeds (set in the tests).
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
bond = \"7 MPa\"
[[layer]]
name = \"primer\"
youngs_modulus = \"3 GPa\"
poisson_ratio = 0.35
thickness = \"5 um\"
bond = \"20 MPa\"
[substrate]
material = \"carbon-steel\"
[load]
pressure = \"2 MPa\"
";

/// The scene with the rubber's bond ranging from 90 % of its nominal interface shear (so that
/// bond-shear at rubber fails at its worst corner) to 9 MPa.
fn failing_at_the_corner(dir: &Path) -> String {
    let nominal = dir.join("nominal.toml");
    std::fs::write(&nominal, SCENE).unwrap();
    let v = json(&run(&[
        "check",
        nominal.to_str().unwrap(),
        "--format",
        "json",
    ]));
    let shear = v["checks"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == "bond-shear" && c["at"] == "rubber")
        .unwrap()["value"]
        .as_f64()
        .unwrap();
    assert!(shear < 7e6, "the nominal design passes: {shear}");
    let text = SCENE.replacen(
        "bond = \"7 MPa\"\n",
        &format!(
            "bond = \"7 MPa\"\nshear_strength_range = [{:e}, 9e6]\n",
            0.9 * shear
        ),
        1,
    );
    let p = dir.join("s.toml");
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

/// The text of the `<testcase>` named `name` (to the next case or the end of its suite).
fn case<'a>(xml: &'a str, name: &str) -> &'a str {
    let start = xml
        .find(&format!("<testcase name=\"{name}\""))
        .unwrap_or_else(|| panic!("no case {name}: {xml}"));
    let case = &xml[start + 1..];
    let end = case
        .find("<testcase ")
        .or_else(|| case.find("</testsuite>"))
        .unwrap_or(case.len());
    &case[..end]
}

/// The check's case name: `bond-shear at rubber`, or `bond-shear` for a film.
fn name(c: &Value) -> String {
    match c["at"].as_str() {
        Some(at) => format!("{} at {at}", c["name"].as_str().unwrap()),
        None => c["name"].as_str().unwrap().to_string(),
    }
}

/// `check SCENE --robust --junit`: a case per nominal check and per robust check, each failing
/// where its JSON check fails; a failing robust case names its corner's keys.
fn junit_matches_json(scene: &str) -> (Value, String) {
    let dir = tempfile::tempdir().unwrap();
    let xml = dir.path().join("junit.xml");
    let o = run(&["check", scene, "--robust", "--junit", xml.to_str().unwrap()]);
    assert!(o.status.code().is_some_and(|c| c <= 1), "{o:?}");
    let v = json(&run(&["check", scene, "--robust", "--format", "json"]));
    let xml = std::fs::read_to_string(&xml).unwrap();
    let report = quick_junit::Report::deserialize_from_str(&xml).expect("valid JUnit XML");
    let (nominal, robust) = (
        v["checks"].as_array().unwrap(),
        v["robust"]["checks"].as_array().unwrap(),
    );
    assert_eq!(
        report.test_suites[0].test_cases.len(),
        nominal.len() + robust.len()
    );
    for c in nominal {
        let text = case(&xml, &name(c));
        assert_eq!(text.contains("<failure"), c["pass"] == false, "{text}");
    }
    let keys: Vec<&str> = v["robust"]["ranges"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["key"].as_str().unwrap())
        .collect();
    for c in robust {
        let text = case(&xml, &format!("{} (robust)", name(c)));
        assert_eq!(text.contains("<failure"), c["pass"] == false, "{text}");
        if c["pass"] == false {
            assert!(
                text.contains("at the worst corner of the materials&apos; ranges")
                    || text.contains("at the worst corner of the materials' ranges"),
                "{text}"
            );
            for k in &keys {
                let value = c["corner"][k].as_f64().unwrap();
                assert!(text.contains(&format!("{k} = {value:e}")), "{k}: {text}");
            }
        }
    }
    (v, xml)
}

#[test]
fn junit_has_a_robust_case_per_check_of_a_stack() {
    let dir = tempfile::tempdir().unwrap();
    let scene = failing_at_the_corner(dir.path());
    let (v, xml) = junit_matches_json(&scene);
    assert_eq!(v["verdict"], "pass");
    assert_eq!(v["robust"]["verdict"], "fail");
    assert!(
        case(&xml, "bond-shear at rubber (robust)").contains("<failure"),
        "{xml}"
    );
    assert!(!case(&xml, "bond-shear at rubber").contains("<failure"));
}

#[test]
fn junit_has_a_robust_case_per_check_of_a_film() {
    let (v, _) = junit_matches_json("examples/nbr-gasket-fretting.toml");
    assert_eq!(v["robust"]["checks"].as_array().unwrap().len(), 3);
    // Without --robust, no robust case.
    let dir = tempfile::tempdir().unwrap();
    let xml = dir.path().join("junit.xml");
    run(&[
        "check",
        "examples/nbr-gasket-fretting.toml",
        "--junit",
        xml.to_str().unwrap(),
    ]);
    assert!(!std::fs::read_to_string(&xml).unwrap().contains("(robust)"));
}

/// The stack's HTML report with `--robust`: the robust verdict in the headline, and the ranges,
/// every check at its worst corner with its utilisation, and the d_min range of the layer
/// `thickness_of` among the uncertainty; the same numbers as the JSON.
#[test]
fn the_stack_report_has_its_robust_section() {
    let dir = tempfile::tempdir().unwrap();
    let scene = failing_at_the_corner(dir.path());
    let html = dir.path().join("r.html");
    let o = run(&[
        "check",
        &scene,
        "--robust",
        "--report",
        html.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{o:?}");
    let page = std::fs::read_to_string(&html).unwrap();
    let v = json(&run(&["check", &scene, "--robust", "--format", "json"]));
    assert!(
        page.contains("robust (worst corner of the materials&#39; ranges): FAIL"),
        "{page}"
    );
    let governing = format!(
        "robust verdict FAIL (nominal PASS), governed by {} at {}",
        v["robust"]["governing_check"].as_str().unwrap(),
        v["robust"]["governing_at"].as_str().unwrap()
    );
    assert!(page.contains(&governing), "{governing}");
    assert!(!page.contains("their spread is not propagated"));
    for r in v["robust"]["ranges"].as_array().unwrap() {
        assert!(page.contains(r["key"].as_str().unwrap()), "{r}");
    }
    for c in v["robust"]["checks"].as_array().unwrap() {
        let u = 100.0 * c["utilisation"].as_f64().unwrap();
        let pass = if c["pass"] == true { "PASS" } else { "FAIL" };
        let want = format!("{} {u:.1} % ({pass})", name(c));
        assert!(page.contains(&want), "{want}");
    }
    assert!(page.contains("d_min of layer &#39;rubber&#39; over the corners of the ranges"));
}
