//! Absurd values on the command line: every command takes the scene's accepted ranges (the key
//! table of `coatcheck::scene`) or bounds of its own, and says which flag and range on exit 2
//! rather than printing NaN, inf or a meaningless number with exit 0.

use super::common::run;
use std::process::Output;

const MAP: &str = "examples/data/height-map.csv";
const SCENE: &str = "examples/paper-rubber-on-steel.toml";

/// Exit code 2 with every one of `parts` in the message, and nothing on standard output.
fn refused(o: &Output, parts: &[&str]) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    for p in parts {
        assert!(err.contains(p), "{p:?} not in {err:?}");
    }
    assert!(
        o.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
}

fn verify(extra: &[&str]) -> Output {
    let mut args = vec![
        "verify",
        MAP,
        "--film",
        "2MPa,0.5",
        "--substrate",
        "200GPa,0.3",
        "--thickness",
        "3um",
    ];
    args.extend_from_slice(extra);
    run(&args)
}

#[test]
fn verify_takes_the_scene_ranges() {
    let range = "outside the accepted range";
    for p in ["1e-300", "1e300", "1e-3Pa", "2TPa"] {
        refused(
            &verify(&["--pressure", p]),
            &["--pressure", "load.pressure", range],
        );
    }
    refused(
        &verify(&["--pressure", "1MPa", "--bond-strength=-1MPa"]),
        &[
            "--bond-strength",
            "bond.shear_strength",
            "expected a value > 0",
        ],
    );
    refused(
        &verify(&["--pressure", "1MPa", "--bond-strength", "1e20"]),
        &["--bond-strength", "bond.shear_strength", range],
    );
    refused(
        &run(&[
            "verify",
            MAP,
            "--film",
            "1e20,0.5",
            "--substrate",
            "200GPa,0.3",
            "--thickness",
            "3um",
            "--pressure",
            "1MPa",
        ]),
        &["--film", "film.youngs_modulus", range],
    );
    refused(
        &run(&[
            "verify",
            MAP,
            "--film",
            "2MPa,0.5",
            "--substrate",
            "0.5Pa,0.3",
            "--thickness",
            "3um",
            "--pressure",
            "1MPa",
        ]),
        &["--substrate", "substrate.youngs_modulus", range],
    );
    refused(
        &run(&[
            "verify",
            MAP,
            "--film",
            "2MPa,0.5",
            "--substrate",
            "200GPa,0.3",
            "--thickness",
            "1e-300",
            "--pressure",
            "1MPa",
        ]),
        &["--thickness", "film.thickness", range],
    );
    refused(
        &verify(&["--pressure", "1MPa", "--rtol", "0.5"]),
        &["--rtol", "numerics.rtol", "1e-13 <= rtol <= 1e-2"],
    );
}

#[test]
fn verify_solver_settings_are_bounded() {
    for tol in ["1e10", "0.011", "0", "-1e-6", "NaN"] {
        refused(
            &verify(&["--pressure", "1MPa", "--gap-tol", tol]),
            &["--gap-tol", "0 < gap-tol <= 1e-2"],
        );
    }
    for n in ["0", "1000001"] {
        refused(
            &verify(&["--pressure", "1MPa", "--max-iter", n]),
            &["--max-iter", "1 <= max-iter <= 1000000"],
        );
    }
}

fn synth(extra: &[&str]) -> Output {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("map.csv");
    let mut args = vec!["synth", "--pixel-size", "1um", "--q0", "1e5", "--q1", "1e6"];
    args.extend_from_slice(extra);
    args.extend_from_slice(&["--output", out.to_str().unwrap()]);
    let o = run(&args);
    if o.status.code() == Some(2) {
        assert!(!out.exists(), "a refused map is not written");
    }
    o
}

#[test]
fn synth_takes_the_scene_ranges_and_bounds_n() {
    let range = "outside the accepted range";
    for h in ["1e200", "1e-300", "2m"] {
        refused(
            &synth(&["--n", "16", "--rms-height", h]),
            &["--rms-height", "roughness.rms_height", range],
        );
    }
    for x in ["1e300", "1e-13"] {
        refused(
            &synth(&["--n", "16", "--rms-slope", x]),
            &["--rms-slope", "roughness.rms_slope", range],
        );
    }
    refused(
        &synth(&["--n", "16", "--rms-slope", "-0.1"]),
        &["--rms-slope", "expected a value > 0"],
    );
    refused(
        &run(&[
            "synth",
            "--pixel-size",
            "1um",
            "--q0",
            "1e-9",
            "--q1",
            "1e6",
            "--rms-height",
            "1um",
            "--output",
            "never.csv",
        ]),
        &["--q0", "roughness.q0", "wavenumbers this tool models"],
    );
    refused(
        &synth(&["--n", "8193", "--rms-height", "1um"]),
        &["map size n", "4 <= n <= 8192"],
    );
}

#[test]
fn sweep_ends_take_the_thickness_range() {
    for sweep in ["1e-300:1e300:7", "1um:1e300:7", "1e-11:1um:3"] {
        refused(
            &run(&["check", SCENE, "--sweep-thickness", sweep]),
            &[
                "--sweep-thickness",
                "film.thickness",
                "outside the accepted range",
            ],
        );
    }
}

#[test]
fn response_grid_is_bounded() {
    let r = |qd: &str| {
        run(&[
            "response",
            "--film",
            "1MPa,0.5",
            "--substrate",
            "200GPa,0.3",
            "--qd",
            qd,
        ])
    };
    refused(&r("1e-3:1e3:100000000"), &["--qd", "2 <= n <= 1000000"]);
    for qd in ["1e7", "0.1,1e300", "1:2e6:3"] {
        refused(&r(qd), &["--qd", "from 0 to 1e6"]);
    }
}

#[test]
fn a_dangling_scene_link_in_a_batch_is_its_error_row() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(SCENE, dir.path().join("a.toml")).unwrap();
    std::os::unix::fs::symlink(dir.path().join("gone.toml"), dir.path().join("b.toml")).unwrap();
    let o = run(&["check", dir.path().to_str().unwrap(), "--format", "csv"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("b.toml") && err.contains("No such file"),
        "{err}"
    );
    let out = String::from_utf8_lossy(&o.stdout);
    let rows: Vec<&str> = out.lines().skip(1).collect();
    assert_eq!(rows.len(), 2, "{out}");
    assert!(
        rows.iter()
            .any(|r| r.contains("b.toml") && r.contains("error")),
        "{out}"
    );
    assert!(
        rows.iter()
            .any(|r| r.contains("a.toml") && r.contains("pass")),
        "{out}"
    );
}

/// A key given twice in a scene table: the message names the key and its second line.
#[test]
fn a_duplicate_scene_key_is_named() {
    let d = tempfile::tempdir().unwrap();
    let scene = d.path().join("dup.toml");
    std::fs::write(
        &scene,
        "[film]\nmaterial = \"natural-rubber\"\nmaterial = \"nbr\"\n",
    )
    .unwrap();
    let o = run(&["check", scene.to_str().unwrap()]);
    refused(&o, &["dup.toml:3:", "duplicate key `material`"]);
}

/// A value of the wrong TOML type (a boolean, a table, a list of numbers, where a number, a
/// quantity string or a list of names belongs): the message names the file, the line, the
/// dotted key and what was expected, not serde's "did not match any variant of untagged enum".
#[test]
fn a_value_of_the_wrong_type_names_its_key_and_what_was_expected() {
    let base = std::fs::read_to_string(SCENE).unwrap();
    let d = tempfile::tempdir().unwrap();
    let cases = [
        (
            "thickness = \"10 um\"",
            "thickness = true",
            "film.thickness: got true (expected a length",
        ),
        (
            "thickness = \"10 um\"",
            "thickness = { value = 10 }",
            "film.thickness: invalid type: a table, expected a number",
        ),
        (
            "pressure = \"0.1 MPa\"",
            "pressure = 2024-01-01",
            "load.pressure: invalid type: a date-time, expected a number",
        ),
        (
            "checks = [",
            "checks = [1, ",
            "criteria.checks: unknown check '1' (expected bond-shear",
        ),
    ];
    for (i, (from, to, want)) in cases.into_iter().enumerate() {
        assert!(base.contains(from));
        let line = 1 + base[..base.find(from).unwrap()].matches('\n').count();
        let scene = d.path().join(format!("t{i}.toml"));
        std::fs::write(&scene, base.replacen(from, to, 1)).unwrap();
        let o = run(&["check", scene.to_str().unwrap()]);
        refused(&o, &[&format!("t{i}.toml:{line}: "), want]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!err.contains("untagged"), "{err}");
    }
}
