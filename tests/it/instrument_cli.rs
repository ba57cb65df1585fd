//! The binary on instrument files (tests/data/instrument/): `psd` reports what it read,
//! `check --profile` reaches a verdict, too small a map is an error naming the file.

use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_coatcheck");
const DIR: &str = "tests/data/instrument";

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .expect("run coatcheck")
}

fn psd_json(file: &str, extra: &[&str]) -> serde_json::Value {
    let path = format!("{DIR}/{file}");
    let mut args = vec!["psd", path.as_str(), "--format", "json"];
    args.extend_from_slice(extra);
    let o = run(&args);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("json")
}

#[test]
fn x3p_map_reports_grid_size_and_format() {
    let v = psd_json("x3p-2.x3p", &[]);
    assert_eq!(v["grid"], serde_json::json!([650, 650]));
    assert_eq!(v["format"], "x3p");
    assert_eq!(v["missing_fraction"], 0.0);
    let size = v["size_m"].as_array().unwrap();
    // grid × pixel size, the pixel size as the x3p's record 1 states it.
    let px = v["pixel_size_m"].as_array().unwrap();
    for (s, p) in size.iter().zip(px) {
        let (s, p) = (s.as_f64().unwrap(), p.as_f64().unwrap());
        assert!((s - 650.0 * p).abs() <= 1e-12 * s);
    }
    // The physical size SurfaceTopography reads from the same file (its `physical_sizes`,
    // printed by tests/data/instrument/st_ref.py; also in tests/it/instrument.rs).
    for (got, reference) in size
        .iter()
        .zip([8.29767313942749e-05, 0.0002044783737930349])
    {
        let got = got.as_f64().unwrap();
        assert!(
            (got / reference - 1.0).abs() < 1e-12,
            "{got:e} vs {reference:e}"
        );
    }
}

#[test]
fn channel_by_name_and_number() {
    let by_number = psd_json("di-1.di", &["--channel", "3"]);
    assert_eq!(by_number["channel"], "Phase");
    let by_name = psd_json("di-1.di", &["--channel", "Phase"]);
    assert_eq!(by_name["summary"], by_number["summary"]);
    assert_eq!(psd_json("di-1.di", &[])["channel"], "Height");
}

#[test]
fn missing_points_are_reported() {
    let v = psd_json("opd-1.opd", &[]);
    assert!(v["missing_fraction"].as_f64().unwrap() > 0.0);
    assert!(v["used_fraction"].as_f64().unwrap() < 1.0);
    // sur-2.sur: 117 points not measured (SurfaceTopography's mask); the dropouts among them
    // are filled, so the rectangle keeps 84 % of the map (57 % without filling).
    let v = psd_json("sur-2.sur", &[]);
    let (used, filled) = (
        v["used_fraction"].as_f64().unwrap(),
        v["filled_fraction"].as_f64().unwrap(),
    );
    assert!(
        used > 0.8 && filled > 0.0 && filled <= 117.0 / (563.0 * 484.0),
        "{v}"
    );
}

#[test]
fn check_profile_on_x3p_reaches_a_verdict() {
    let o = run(&[
        "check",
        "examples/paper-rubber-on-steel.toml",
        "--profile",
        "tests/data/instrument/x3p-2.x3p",
    ]);
    assert!(
        matches!(o.status.code(), Some(0 | 1)),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn tiny_map_is_an_error_naming_the_file() {
    let f = "tests/data/instrument/gwyddion-export-english.txt";
    let o = run(&[
        "check",
        "examples/paper-rubber-on-steel.toml",
        "--profile",
        f,
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains(f) && err.contains("too few points"), "{err}");
}
