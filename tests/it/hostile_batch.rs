//! A batch of degenerate scenes: each one is its own error row (naming its file, and the line
//! where there is one), while the batch still judges every other scene and writes its table,
//! totals and JUnit report, with exit code 2.

use super::common::run;
use std::path::Path;

/// (scene file, what its error message must contain).
const BROKEN: [(&str, &str); 10] = [
    (
        "narrow-psd.toml",
        "narrow-psd.toml: invalid spectrum's wavenumber range",
    ),
    (
        "q-range.toml",
        "q-range.toml: invalid spectrum's wavenumber range",
    ),
    ("nan-psd.toml", "nan.csv:3: C = NaN in column 2"),
    (
        "huge-pressure.toml",
        "huge-pressure.toml:20: load.pressure: 1e300 (SI) is outside the accepted range",
    ),
    (
        "tiny-pressure.toml",
        "tiny-pressure.toml:20: load.pressure: 1e-300 (SI) is outside the accepted range",
    ),
    (
        "zero-thickness.toml",
        "zero-thickness.toml:11: film.thickness: 0e0 (expected a value > 0)",
    ),
    ("dangling.toml", "dangling.toml: No such file or directory"),
    ("missing-psd.toml", "nowhere.csv"),
    ("garbage.toml", "garbage.toml"),
    (
        "wrong-type.toml",
        "wrong-type.toml:11: film.thickness: got true",
    ),
];

/// The measured-rolloff example with `from` replaced by `to`, next to a copy of its PSD.
fn scene(dir: &Path, name: &str, from: &str, to: &str) {
    let base = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/measured-rolloff.toml"
    ))
    .unwrap();
    assert!(base.contains(from), "{from}");
    std::fs::write(dir.join(name), base.replacen(from, to, 1)).unwrap();
}

#[test]
fn a_batch_of_degenerate_scenes_reports_every_other_scene() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    std::fs::copy(
        concat!(env!("CARGO_MANIFEST_DIR"), "/examples/measured-rolloff.csv"),
        dir.join("measured-rolloff.csv"),
    )
    .unwrap();
    std::fs::write(
        dir.join("narrow.csv"),
        "q (1/m),C (m^4)\n1e5,1e-20\n1.000000000001e5,1e-20\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("nan.csv"),
        "q (1/m),C (m^4)\n1e5,1e-20\n2e5,NaN\n4e5,1e-22\n",
    )
    .unwrap();
    let psd = "psd = \"measured-rolloff.csv\"";
    scene(dir, "good.toml", "[film]", "[film]");
    scene(dir, "narrow-psd.toml", psd, "psd = \"narrow.csv\"");
    scene(
        dir,
        "q-range.toml",
        psd,
        "psd = \"measured-rolloff.csv\"\nq_min = \"1e5 1/m\"\nq_max = \"1.0000000000001e5 1/m\"",
    );
    scene(dir, "nan-psd.toml", psd, "psd = \"nan.csv\"");
    scene(dir, "missing-psd.toml", psd, "psd = \"nowhere.csv\"");
    let pressure = "pressure = \"0.5 MPa\"";
    scene(
        dir,
        "huge-pressure.toml",
        pressure,
        "pressure = \"1e300 Pa\"",
    );
    scene(
        dir,
        "tiny-pressure.toml",
        pressure,
        "pressure = \"1e-300 Pa\"",
    );
    let thickness = "thickness = \"200 um\"";
    scene(
        dir,
        "zero-thickness.toml",
        thickness,
        "thickness = \"0 um\"",
    );
    scene(dir, "wrong-type.toml", thickness, "thickness = true");
    std::fs::write(dir.join("garbage.toml"), b"\xff\xfe\x00[[[\x00binary").unwrap();
    std::os::unix::fs::symlink(dir.join("gone.toml"), dir.join("dangling.toml")).unwrap();
    // Unreadable: an error row, unless the tests run as root (who reads it: a passing row).
    scene(dir, "unreadable.toml", "[film]", "[film]");
    let unreadable = dir.join("unreadable.toml");
    std::fs::set_permissions(
        &unreadable,
        std::os::unix::fs::PermissionsExt::from_mode(0o000),
    )
    .unwrap();
    let root = std::fs::read(&unreadable).is_ok();

    let junit = dir.join("junit.xml");
    let o = run(&[
        "check",
        dir.to_str().unwrap(),
        "--format",
        "csv",
        "--junit",
        junit.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(2), "{err}");
    let rows: Vec<&str> = out.lines().skip(1).collect();
    assert_eq!(rows.len(), BROKEN.len() + 2, "{out}");
    let row = |name: &str| {
        let r: Vec<&&str> = rows
            .iter()
            .filter(|r| r.contains(&format!("/{name},")))
            .collect();
        assert_eq!(r.len(), 1, "{name}: {out}");
        *r[0]
    };
    for (name, message) in BROKEN {
        let r = row(name);
        assert!(r.contains(",error,"), "{r}");
        assert!(r.contains(message), "{name}: {r}");
        assert!(err.contains(message), "{name}: {err}");
    }
    assert!(row("good.toml").contains(",pass,"), "{out}");
    let unreadable_row = row("unreadable.toml");
    if root {
        assert!(unreadable_row.contains(",pass,"), "{unreadable_row}");
    } else {
        assert!(
            unreadable_row.contains(",error,") && unreadable_row.contains("ermission denied"),
            "{unreadable_row}"
        );
    }
    let errors = BROKEN.len() + usize::from(!root);
    let xml = std::fs::read_to_string(&junit).unwrap();
    assert!(xml.contains(&format!("errors=\"{errors}\"")), "{xml}");
    for (name, _) in BROKEN {
        assert!(xml.contains(name), "{name} not in the JUnit report");
    }
    // The table's totals line.
    let t = run(&["check", dir.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&t.stdout);
    let passed = 2 - usize::from(!root);
    assert!(
        text.contains(&format!(
            "{} scenes: {passed} passed, 0 failed, {errors} could not be evaluated",
            BROKEN.len() + 2
        )),
        "{text}"
    );
}
