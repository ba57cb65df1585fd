//! `coatcheck check` and `coatcheck materials` as a user runs them: verdicts and exit codes of
//! the bundled examples, and every bad-input case of issue 3 (one-line error naming file, line
//! and field; exit code 2; no output file written).

use std::path::PathBuf;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_coatcheck");

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .expect("run coatcheck")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

const GOOD_PSD: &str = "q (1/m),C (m^4)\n1e5,1e-20\n1e6,1e-23\n1e7,1e-26\n1e8,1e-29\n";

/// A valid scene that reads `s.csv` next to it.
const PSD_SCENE: &str = "\
[roughness]
psd = \"s.csv\"
[film]
material = \"paper-rubber\"
thickness = \"10 um\"
[substrate]
material = \"paper-steel\"
[bond]
material = \"epoxy\"
[load]
pressure = \"0.1 MPa\"
";

/// A valid model scene.
const MODEL_SCENE: &str = "\
[roughness]
model = \"self-affine\"
hurst = 1
q0 = \"1e5 1/m\"
q1 = \"1e8 1/m\"
rms_slope = 1
[film]
material = \"paper-rubber\"
thickness = \"10 um\"
[substrate]
material = \"paper-steel\"
[bond]
material = \"epoxy\"
[load]
pressure = \"0.1 MPa\"
";

/// Run `check` on a scene (and PSD) written to a fresh directory, with `--output`; assert exit
/// code 2, one line on stderr that contains every `needle`, and no output file.
fn bad(scene: &str, csv: Option<&str>, extra: &[&str], needles: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let scene_path = dir.path().join("scene.toml");
    std::fs::write(&scene_path, scene).unwrap();
    if let Some(csv) = csv {
        std::fs::write(dir.path().join("s.csv"), csv).unwrap();
    }
    let out = dir.path().join("out.json");
    let mut args = vec![
        "check",
        scene_path.to_str().unwrap(),
        "--format",
        "json",
        "--output",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let o = run(&args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(
        o.stdout.is_empty(),
        "stdout: {}",
        String::from_utf8_lossy(&o.stdout)
    );
    assert_eq!(err.lines().count(), 1, "not one line: {err}");
    assert!(err.starts_with("coatcheck: "), "{err}");
    for n in needles {
        assert!(err.contains(n), "'{n}' not in: {err}");
    }
    assert!(!out.exists(), "an output file was written");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn missing_files() {
    let o = run(&["check", "no/such/scene.toml"]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(err.starts_with("coatcheck: no/such/scene.toml:"), "{err}");
    assert_eq!(err.lines().count(), 1);
    bad(PSD_SCENE, None, &[], &["s.csv"]);
}

#[test]
fn malformed_or_empty_csv() {
    bad(
        PSD_SCENE,
        Some("q,C\n1e5,1e-20\n1e6,abc\n"),
        &[],
        &["s.csv:3:"],
    );
    bad(PSD_SCENE, Some(""), &[], &["s.csv"]);
    bad(PSD_SCENE, Some("q,C\n"), &[], &["s.csv"]);
    bad(PSD_SCENE, Some("q,C\n1e5,1e-20\n"), &[], &["s.csv"]);
}

#[test]
fn bad_csv_values_name_the_line() {
    let cases = [
        ("q,C\n1e5,1e-20\n1e6,0\n1e7,1e-26\n", "s.csv:3:"),
        ("q,C\n1e5,1e-20\n1e6,-1e-23\n1e7,1e-26\n", "s.csv:3:"),
        ("q,C\n1e5,1e-20\n1e6,1e-23\n-1e7,1e-26\n", "s.csv:4:"),
        ("q,C\n1e5,1e-20\ninf,1e-23\n", "s.csv:3:"),
        ("q,C\n1e5,1e-20\n1e6,NaN\n1e7,1e-26\n", "s.csv:3:"),
        ("q,C\n1e5,1e-20\n1e6,1e-23\n1e6,1e-24\n", "s.csv:4:"),
    ];
    for (csv, needle) in cases {
        bad(PSD_SCENE, Some(csv), &[], &[needle]);
    }
}

/// q not increasing: the PSD reader (issue 4) sorts the rows and warns, naming file and line,
/// in the report; the check then runs on the sorted data.
#[test]
fn unsorted_q_is_sorted_with_a_warning_naming_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("scene.toml");
    std::fs::write(&scene, PSD_SCENE).unwrap();
    std::fs::write(
        dir.path().join("s.csv"),
        "q,C\n1e5,1e-20\n1e7,1e-26\n1e6,1e-23\n1e8,1e-29\n",
    )
    .unwrap();
    let o = run(&["check", scene.to_str().unwrap(), "--format", "json"]);
    let err = stderr(&o);
    assert!(
        o.status.code() == Some(0) || o.status.code() == Some(1),
        "{err}"
    );
    // The reader's warning is part of the report (every format), not only of standard error.
    let v = json_of(&o);
    let warnings = v["warnings"].as_array().unwrap();
    assert!(
        warnings
            .iter()
            .any(|w| w.as_str().unwrap().contains("s.csv:4:")),
        "{warnings:?}"
    );
}

#[test]
fn unknown_material_lists_close_names() {
    let s = MODEL_SCENE.replace("\"paper-rubber\"", "\"natural-rubbr\"");
    bad(
        &s,
        None,
        &[],
        &[
            "scene.toml:8:",
            "film.material",
            "natural-rubbr",
            "natural-rubber",
        ],
    );
    bad(
        MODEL_SCENE,
        None,
        &["--bond", "superglue"],
        &["--bond", "superglue", "bond.material"],
    );
}

#[test]
fn negative_or_invalid_values() {
    let s = MODEL_SCENE.replace("\"10 um\"", "\"-10 um\"");
    bad(&s, None, &[], &["scene.toml:9:", "film.thickness"]);
    bad(
        MODEL_SCENE,
        None,
        &["--thickness", "-5um"],
        &["--thickness", "film.thickness"],
    );
    let s = MODEL_SCENE.replace("\"0.1 MPa\"", "\"-0.1 MPa\"");
    bad(&s, None, &[], &["scene.toml:15:", "load.pressure"]);
    bad(
        MODEL_SCENE,
        None,
        &["--pressure", "0"],
        &["--pressure", "load.pressure"],
    );
    bad(
        MODEL_SCENE,
        None,
        &["--epsilon", "2"],
        &["--epsilon", "criteria.epsilon"],
    );
    bad(
        MODEL_SCENE,
        None,
        &["--checks", "bond"],
        &["--checks", "unknown check 'bond'"],
    );
    bad(
        MODEL_SCENE,
        None,
        &["--sweep-thickness", "1um:0:5"],
        &["--sweep-thickness"],
    );
}

#[test]
fn unknown_unit_names_field_and_unit() {
    let s = MODEL_SCENE.replace("\"10 um\"", "\"10 furlong\"");
    bad(
        &s,
        None,
        &[],
        &["scene.toml:9:", "film.thickness", "unknown unit 'furlong'"],
    );
    let s = MODEL_SCENE.replace("\"0.1 MPa\"", "\"0.1 um\"");
    bad(
        &s,
        None,
        &[],
        &["scene.toml:15:", "load.pressure", "pressure"],
    );
}

#[test]
fn contradictory_scenes_name_both_keys() {
    let s = MODEL_SCENE.replace("[roughness]\n", "[roughness]\npsd = \"s.csv\"\n");
    bad(
        &s,
        Some(GOOD_PSD),
        &[],
        &["roughness.psd", "roughness.model"],
    );
    // One property of a named material is an override; both moduli contradict the name.
    let s = MODEL_SCENE.replace(
        "material = \"paper-rubber\"\n",
        "material = \"paper-rubber\"\nyoungs_modulus = \"2 MPa\"\npoisson_ratio = 0.4\n",
    );
    bad(
        &s,
        None,
        &[],
        &[
            "scene.toml:9:",
            "film.youngs_modulus",
            "film.material",
            "override one property",
        ],
    );
    let s = MODEL_SCENE.replace("rms_slope = 1\n", "rms_slope = 1\nrms_height = \"1 um\"\n");
    bad(
        &s,
        None,
        &[],
        &["roughness.rms_height", "roughness.rms_slope"],
    );
    let s = MODEL_SCENE.replace("hurst = 1\n", "hurst = 1\nwidth = \"1e4 1/m\"\n");
    bad(
        &s,
        None,
        &[],
        &["scene.toml:4:", "roughness.width", "self-affine"],
    );
}

#[test]
fn unknown_keys_are_named_with_their_line() {
    let s = MODEL_SCENE.replace("thickness = ", "thicknes = ");
    bad(&s, None, &[], &["scene.toml:9:", "thicknes"]);
    let s = format!("{MODEL_SCENE}[lod]\npressure = 1\n");
    bad(&s, None, &[], &["scene.toml:16:", "lod"]);
    let s = MODEL_SCENE.replace("[load]", "[load");
    bad(&s, None, &[], &["scene.toml:14:"]);
}

#[test]
fn missing_keys_are_named() {
    let s = MODEL_SCENE.replace("[load]\npressure = \"0.1 MPa\"\n", "");
    bad(&s, None, &[], &["load.pressure", "missing"]);
    let s = MODEL_SCENE.replace("material = \"epoxy\"\n", "");
    bad(&s, None, &[], &["bond.material", "missing"]);
}

#[test]
fn help_documents_the_exit_codes() {
    let o = run(&["check", "--help"]);
    assert_eq!(o.status.code(), Some(0));
    let text = String::from_utf8_lossy(&o.stdout);
    for needle in [
        "Exit codes:",
        "0  every enabled check passes",
        "1  a check fails",
        "2  bad input",
    ] {
        assert!(text.contains(needle), "{needle}");
    }
}

#[test]
fn materials_lists_the_library() {
    let o = run(&["materials"]);
    assert_eq!(o.status.code(), Some(0));
    let text = String::from_utf8_lossy(&o.stdout);
    for name in [
        "natural-rubber",
        "epdm",
        "ptfe",
        "carbon-steel",
        "glass",
        "epoxy",
        "paper-steel",
    ] {
        assert!(text.contains(name), "{name}");
    }
}

/// Path of a bundled example.
pub fn example(name: &str) -> String {
    root()
        .join("examples")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

fn json_of(o: &Output) -> serde_json::Value {
    serde_json::from_slice(&o.stdout).expect("stdout is one JSON object")
}

#[test]
fn examples_give_their_verdicts_and_exit_codes() {
    for (name, code) in [
        ("paper-rubber-on-steel.toml", 0),
        ("measured-rolloff.toml", 0),
        ("waviness-thin-film.toml", 1),
    ] {
        let o = run(&["check", &example(name)]);
        let text = String::from_utf8_lossy(&o.stdout);
        assert_eq!(o.status.code(), Some(code), "{name}: {text}{}", stderr(&o));
        let verdict = if code == 0 {
            "verdict: PASS"
        } else {
            "verdict: FAIL"
        };
        assert!(text.contains(verdict), "{name}: {text}");
        for needle in [
            "A/A0",
            "tau_rms interface",
            "bond-shear",
            "substrate-yield",
            "min-thickness",
        ] {
            assert!(text.contains(needle), "{name}: {needle}");
        }
    }
}

#[test]
fn json_has_the_required_keys_with_error_siblings() {
    let o = run(&[
        "check",
        &example("paper-rubber-on-steel.toml"),
        "--format",
        "json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = json_of(&o);
    assert_eq!(v["verdict"], "pass");
    for key in [
        "area_fraction",
        "mean_contact_pressure_pa",
        "sigma_rms_top_pa",
        "sigma_rms_interface_pa",
        "tau_rms_interface_pa",
        "tau_peak_pa",
        "sigma_peak_interface_pa",
        "e_eff_over_e_film",
        "min_thickness_m",
    ] {
        let x = v[key].as_f64().unwrap_or_else(|| panic!("{key}"));
        let err = v[format!("{key}_err")]
            .as_f64()
            .unwrap_or_else(|| panic!("{key}_err"));
        assert!(
            x.is_finite() && err >= 0.0 && err < 0.01 * x.abs(),
            "{key}: {x} ± {err}"
        );
    }
    let a = v["area_fraction"].as_f64().unwrap();
    assert!((a - 0.0927).abs() < 5e-5, "{a}");
    assert!(v["governing_check"].is_string());
    let checks = v["checks"].as_array().unwrap();
    let names: Vec<&str> = checks.iter().map(|c| c["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["bond-shear", "substrate-yield", "min-thickness"]);
    for c in checks {
        assert!(
            c["value"].is_f64() && c["limit"].is_f64() && c["pass"].is_boolean(),
            "{c}"
        );
    }
}

#[test]
fn only_the_requested_checks_run() {
    let o = run(&[
        "check",
        &example("paper-rubber-on-steel.toml"),
        "--format",
        "json",
        "--checks",
        "bond-shear",
    ]);
    let v = json_of(&o);
    let checks = v["checks"].as_array().unwrap();
    assert_eq!(checks.len(), 1);
    assert_eq!(checks[0]["name"], "bond-shear");
    assert!(v["min_thickness_m"].is_null());
}

#[test]
fn no_passing_thickness_is_null_and_exit_1() {
    // A 0.5 MPa "yield strength" is below the bulk film's mean contact pressure (≈ 0.65 MPa).
    let o = run(&[
        "check",
        &example("paper-rubber-on-steel.toml"),
        "--format",
        "json",
        "--yield-strength",
        "0.5 MPa",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let v = json_of(&o);
    assert_eq!(v["verdict"], "fail");
    assert!(v["min_thickness_m"].is_null());
    let o = run(&[
        "check",
        &example("paper-rubber-on-steel.toml"),
        "--yield-strength",
        "0.5MPa",
    ]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("no thickness passes"));
}

#[test]
fn output_file_csv_and_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.csv");
    let o = run(&[
        "check",
        &example("paper-rubber-on-steel.toml"),
        "--format",
        "csv",
        "--output",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(o.stdout.is_empty());
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.starts_with("scene,verdict,governing_check,"), "{text}");
    assert_eq!(text.lines().count(), 2, "{text}");
    assert!(
        text.lines()
            .nth(1)
            .unwrap()
            .contains(",pass,min-thickness,"),
        "{text}"
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "no temporaries left"
    );

    let o = run(&[
        "check",
        &example("paper-rubber-on-steel.toml"),
        "--sweep-thickness",
        "0.1um:1mm:9",
        "--format",
        "csv",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 10);
    assert!(lines[0].starts_with("thickness_m,area_fraction,"));
    let d: Vec<f64> = lines[1..]
        .iter()
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect();
    assert!((d[0] / 1e-7 - 1.0).abs() < 1e-12 && (d[8] / 1e-3 - 1.0).abs() < 1e-12);
    assert!((d[4] / 1e-5 - 1.0).abs() < 1e-12, "log-spaced: {d:?}");
}

#[test]
fn flags_override_the_scene_and_materials_dirs_override_the_library() {
    // The paper's film at 0.5 µm is below its d_min (about 0.92 µm): exit 1.
    let o = run(&[
        "check",
        &example("paper-rubber-on-steel.toml"),
        "--thickness",
        "0.5um",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    // A weaker "epoxy" from --materials makes the paper's 10 µm design fail bond-shear.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("weak-epoxy.toml"),
        "schema_version = 1\nname = \"epoxy\"\nkind = \"bond\"\nshear_strength = \"0.3 MPa\"\nsource = \"test\"\n",
    )
    .unwrap();
    let o = run(&[
        "check",
        &example("paper-rubber-on-steel.toml"),
        "--materials",
        dir.path().to_str().unwrap(),
        "--format",
        "json",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v = json_of(&o);
    let bond = &v["checks"][0];
    assert_eq!(bond["name"], "bond-shear");
    assert_eq!(bond["limit"], 3e5);
    assert_eq!(bond["pass"], false);
    assert_eq!(v["governing_check"], "bond-shear");
}

/// `check --profile` runs the `coatcheck psd` pipeline on heights: the same numbers as writing
/// the PSD with `coatcheck psd` and checking that file with `--psd`.
#[test]
fn profile_equals_psd_of_the_same_heights() {
    let dir = std::env::temp_dir().join(format!("coatcheck-profile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let map = root().join("examples/data/height-map.csv");
    let psd = dir.join("map-psd.csv");
    let o = run(&[
        "psd",
        map.to_str().unwrap(),
        "--output",
        psd.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let common = [
        "--film",
        "paper-rubber",
        "--substrate",
        "carbon-steel",
        "--bond",
        "epoxy",
        "--thickness",
        "20um",
        "--pressure",
        "0.1MPa",
        "--format",
        "json",
    ];
    let from_heights = run(&[&["check", "--profile", map.to_str().unwrap()][..], &common].concat());
    let from_psd = run(&[&["check", "--psd", psd.to_str().unwrap()][..], &common].concat());
    assert_eq!(
        from_heights.status.code(),
        Some(0),
        "{}",
        stderr(&from_heights)
    );
    assert_eq!(from_psd.status.code(), Some(0), "{}", stderr(&from_psd));
    let a: serde_json::Value = serde_json::from_slice(&from_heights.stdout).unwrap();
    let b: serde_json::Value = serde_json::from_slice(&from_psd.stdout).unwrap();
    for key in [
        "area_fraction",
        "tau_rms_interface_pa",
        "sigma_rms_interface_pa",
        "min_thickness_m",
    ] {
        let (x, y) = (a[key].as_f64().unwrap(), b[key].as_f64().unwrap());
        // The CSV round trip keeps 10+ significant digits.
        assert!(((x - y) / y).abs() < 1e-6, "{key}: {x} vs {y}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
