//! `coatcheck check` on several scenes (issue 7): exit codes 0/1/2 of a batch, failures first,
//! JUnit content (parsed back), json/csv records, several PSD files per scene (the worst is
//! named and equals a run on that file alone), the version pin warning, unknown keys naming key
//! and file, atomic outputs, and the bundled examples/specs directory.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_coatcheck");

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .expect("run coatcheck")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A fast scene (model roughness, no d_min search) with a given bond strength: 10 MPa passes,
/// 0.01 MPa fails bond-shear.
fn scene(bond: &str) -> String {
    format!(
        "\
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
shear_strength = \"{bond}\"
[load]
pressure = \"0.1 MPa\"
[criteria]
checks = [\"bond-shear\", \"substrate-yield\"]
"
    )
}

const PASS: &str = "10 MPa";
const FAIL: &str = "0.01 MPa";

/// A directory with the given (name, contents) files.
fn dir_with(files: &[(&str, String)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    dir
}

fn p(dir: &Path, name: &str) -> String {
    dir.join(name).to_string_lossy().into_owned()
}

fn json(o: &Output) -> serde_json::Value {
    serde_json::from_slice(&o.stdout).unwrap_or_else(|e| panic!("{e}: {}{}", stdout(o), stderr(o)))
}

#[test]
fn exit_codes_of_a_batch() {
    let broken = scene(PASS).replace("thickness", "thicknes");
    let d = dir_with(&[
        ("a.toml", scene(PASS)),
        ("b.toml", scene(PASS)),
        ("c.toml", scene(FAIL)),
        ("d.toml", broken),
    ]);
    let dp = d.path();
    let o = run(&["check", &p(dp, "a.toml"), &p(dp, "b.toml")]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    assert!(stdout(&o).contains("2 scenes: 2 passed, 0 failed, 0 could not be evaluated"));
    let o = run(&["check", &p(dp, "a.toml"), &p(dp, "c.toml")]);
    assert_eq!(o.status.code(), Some(1), "{}{}", stdout(&o), stderr(&o));
    // A directory: all four; the broken one is reported and the others still run.
    let o = run(&["check", dp.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}{}", stdout(&o), stderr(&o));
    let text = stdout(&o);
    assert!(
        text.contains("4 scenes: 2 passed, 1 failed, 1 could not be evaluated"),
        "{text}"
    );
    // The error names the file, the line and the unknown key.
    assert!(
        text.contains("d.toml:9: unknown field `thicknes`"),
        "{text}"
    );
    // One scene given as a directory is a batch too; an empty directory is bad input.
    let empty = tempfile::tempdir().unwrap();
    let o = run(&["check", empty.path().to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("no scene files"), "{}", stderr(&o));
    // A missing scene among others is an error row, not an abort.
    let o = run(&["check", &p(dp, "a.toml"), &p(dp, "nope.toml")]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stdout(&o).contains("1 passed, 0 failed, 1 could not be evaluated"));
}

#[test]
fn failures_come_first_then_errors_then_passes() {
    let d = dir_with(&[
        ("1-pass.toml", scene(PASS)),
        ("2-fail.toml", scene(FAIL)),
        ("3-broken.toml", scene(PASS).replace("[load]", "[lod]")),
        ("4-fail-worse.toml", scene("0.005 MPa")),
        ("5-pass-closer.toml", scene("1.5 MPa")),
    ]);
    let o = run(&["check", d.path().to_str().unwrap(), "--format", "json"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let v = json(&o);
    let order: Vec<String> = v["scenes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            let s = r["scene"].as_str().unwrap();
            Path::new(s).file_name().unwrap().to_string_lossy().into()
        })
        .collect();
    // Failures by margin (most negative first), the broken one, passes by margin.
    assert_eq!(
        order,
        [
            "4-fail-worse.toml",
            "2-fail.toml",
            "3-broken.toml",
            "5-pass-closer.toml",
            "1-pass.toml"
        ]
    );
    let margins: Vec<f64> = v["scenes"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|r| r["margin"].as_f64())
        .collect();
    assert!(margins[0] < margins[1] && margins[1] < 0.0, "{margins:?}");
    assert!(0.0 <= margins[2] && margins[2] < margins[3], "{margins:?}");
    assert_eq!(v["totals"]["fail"], 2);
    assert_eq!(v["totals"]["error"], 1);
    // The table has the same order.
    let o = run(&["check", d.path().to_str().unwrap()]);
    let text = stdout(&o);
    let pos = |name: &str| text.find(name).unwrap_or_else(|| panic!("{name}: {text}"));
    assert!(pos("4-fail-worse") < pos("2-fail") && pos("2-fail") < pos("3-broken"));
    assert!(pos("3-broken") < pos("5-pass-closer") && pos("5-pass-closer") < pos("1-pass"));
    for head in [
        "scene",
        "verdict",
        "governing",
        "utilisation",
        "margin",
        "d_min",
    ] {
        assert!(text.contains(head), "{head}");
    }
    // The broken scene names its file and the line of the unknown table.
    assert!(text.contains("3-broken.toml:14:"), "{text}");
}

#[test]
fn junit_has_a_case_per_scene_and_check_with_the_numbers() {
    let d = dir_with(&[
        ("pass.toml", scene(PASS)),
        ("fail.toml", scene(FAIL)),
        (
            "broken.toml",
            scene(PASS).replace("\"0.1 MPa\"", "\"0.1 furlong\""),
        ),
    ]);
    let out = tempfile::tempdir().unwrap();
    let junit = out.path().join("junit.xml");
    let o = run(&[
        "check",
        d.path().to_str().unwrap(),
        "--junit",
        junit.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let xml = std::fs::read_to_string(&junit).unwrap();
    let report = quick_junit::Report::deserialize_from_str(&xml).expect("valid JUnit XML");
    // 2 scenes × 2 checks + 1 error case.
    assert_eq!(report.tests, 5, "{xml}");
    assert_eq!(report.failures, 1, "{xml}");
    assert_eq!(report.errors, 1, "{xml}");
    assert_eq!(report.test_suites.len(), 3);
    let suite = |name: &str| {
        report
            .test_suites
            .iter()
            .find(|s| s.name.as_str().ends_with(name))
            .unwrap_or_else(|| panic!("{name}"))
    };
    let fail = suite("fail.toml");
    let names: Vec<&str> = fail.test_cases.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["bond-shear", "substrate-yield"]);
    let quick_junit::TestCaseStatus::NonSuccess { kind, message, .. } = &fail.test_cases[0].status
    else {
        panic!("bond-shear should fail: {xml}");
    };
    assert_eq!(*kind, quick_junit::NonSuccessKind::Failure);
    let msg = message.as_ref().unwrap().as_str();
    // The numbers: value in MPa, the limit 0.01 MPa, the margin in %.
    assert!(
        msg.starts_with("bond-shear: ") && msg.contains("exceeds the limit 0.01000 MPa"),
        "{msg}"
    );
    assert!(msg.contains("margin -"), "{msg}");
    assert!(matches!(
        fail.test_cases[1].status,
        quick_junit::TestCaseStatus::Success { .. }
    ));
    let broken = suite("broken.toml");
    let quick_junit::TestCaseStatus::NonSuccess { kind, message, .. } =
        &broken.test_cases[0].status
    else {
        panic!("{xml}");
    };
    assert_eq!(*kind, quick_junit::NonSuccessKind::Error);
    let msg = message.as_ref().unwrap().as_str();
    assert!(
        msg.contains("broken.toml:15:") && msg.contains("furlong"),
        "{msg}"
    );
    // Atomic: only the report in its directory.
    assert_eq!(std::fs::read_dir(out.path()).unwrap().count(), 1);
}

#[test]
fn json_and_csv_have_one_record_per_scene() {
    let d = dir_with(&[("a.toml", scene(PASS)), ("b.toml", scene(FAIL))]);
    let out = tempfile::tempdir().unwrap();
    let file = out.path().join("batch.json");
    let o = run(&[
        "check",
        d.path().to_str().unwrap(),
        "--format",
        "json",
        "--output",
        file.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(o.stdout.is_empty());
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    let scenes = v["scenes"].as_array().unwrap();
    assert_eq!(scenes.len(), 2);
    let b = &scenes[0];
    assert_eq!(b["verdict"], "fail");
    assert_eq!(b["governing_check"], "bond-shear");
    assert!((b["checks"][0]["limit"].as_f64().unwrap() / 1e4 - 1.0).abs() < 1e-15);
    assert_eq!(b["thickness_m"], 1e-5);
    // The record's numbers are the single-scene report's.
    let single = json(&run(&["check", &p(d.path(), "b.toml"), "--format", "json"]));
    for key in ["area_fraction", "tau_peak_pa", "sigma_peak_interface_pa"] {
        assert_eq!(b[key], single[key], "{key}");
    }
    assert_eq!(b["margin"], single["checks"][0]["margin"]);
    assert_eq!(std::fs::read_dir(out.path()).unwrap().count(), 1);

    let o = run(&["check", d.path().to_str().unwrap(), "--format", "csv"]);
    assert_eq!(o.status.code(), Some(1));
    let text = stdout(&o);
    let mut rows = csv::Reader::from_reader(text.as_bytes());
    let head = rows.headers().unwrap().clone();
    for col in [
        "scene",
        "verdict",
        "governing_check",
        "margin",
        "min_thickness_m",
        "worst_file",
        "warnings",
        "error",
    ] {
        assert!(head.iter().any(|h| h == col), "{col}");
    }
    let records: Vec<csv::StringRecord> = rows.records().map(Result::unwrap).collect();
    assert_eq!(records.len(), 2);
    let verdict = head.iter().position(|h| h == "verdict").unwrap();
    assert_eq!(&records[0][verdict], "fail");
    assert_eq!(&records[1][verdict], "pass");
    let margin = head.iter().position(|h| h == "margin").unwrap();
    let m: f64 = records[0][margin].parse().unwrap();
    // The CSV's shortest round-trip form read exactly; serde_json's parser may be an ulp off.
    let want = single["checks"][0]["margin"].as_f64().unwrap();
    assert!((m - want).abs() <= 4e-16 * want.abs(), "{m} {want}");
}

const PSD_A: &str = "q (1/m),C (m^4)\n1e5,1e-20\n1e6,1e-23\n1e7,1e-26\n1e8,1e-29\n";

/// A scene that lists several PSD files.
fn psd_scene(list: &str) -> String {
    scene(PASS)
        .replace(
            "model = \"self-affine\"\nhurst = 1\nq0 = \"1e5 1/m\"\nq1 = \"1e8 1/m\"\nrms_slope = 1\n",
            &format!("psd = {list}\n"),
        )
        .replace("\"bond-shear\", \"substrate-yield\"", "\"bond-shear\"")
}

#[test]
fn several_psd_files_report_the_worst_by_name() {
    // b.csv is a rougher scan (4x the power): larger interface shear, smaller margin.
    let psd_b = PSD_A.replace("1e-", "4e-");
    let d = dir_with(&[
        ("a.csv", PSD_A.to_string()),
        ("b.csv", psd_b),
        ("c.csv", PSD_A.replace("1e-", "2e-")),
        ("part.toml", psd_scene("[\"a.csv\", \"b.csv\", \"c.csv\"]")),
    ]);
    let scene_path = p(d.path(), "part.toml");
    let o = run(&["check", &scene_path, "--format", "json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = json(&o);
    let worst = v["worst_file"].as_str().unwrap();
    assert!(worst.ends_with("b.csv"), "{worst}");
    assert_eq!(v["files"].as_array().unwrap().len(), 3);
    // The reported numbers are those of b.csv checked alone.
    let alone = json(&run(&[
        "check",
        &scene_path,
        "--psd",
        &p(d.path(), "b.csv"),
        "--format",
        "json",
    ]));
    assert_eq!(v["tau_rms_interface_pa"], alone["tau_rms_interface_pa"]);
    assert_eq!(v["checks"], alone["checks"]);
    let margins: Vec<f64> = v["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["margin"].as_f64().unwrap())
        .collect();
    assert!(
        margins[1] < margins[2] && margins[2] < margins[0],
        "{margins:?}"
    );
    // The table names the worst file.
    let o = run(&["check", &scene_path]);
    let text = stdout(&o);
    assert!(
        text.contains("worst file: ") && text.contains("b.csv"),
        "{text}"
    );
    // In a batch the scene's row names the worst file too.
    let o = run(&["check", &scene_path, &scene_path, "--format", "csv"]);
    assert!(stdout(&o).contains("b.csv"), "{}", stdout(&o));
    // A missing file in the list: the scene line that named it, and the file.
    let d2 = dir_with(&[
        ("a.csv", PSD_A.to_string()),
        ("part.toml", psd_scene("[\"a.csv\", \"gone.csv\"]")),
    ]);
    let o = run(&["check", &p(d2.path(), "part.toml")]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(
        err.contains("part.toml:2: roughness.psd") && err.contains("gone.csv"),
        "{err}"
    );
    // An empty list and a repeated file are rejected with the line.
    for (list, needle) in [("[]", "empty list"), ("[\"a.csv\", \"a.csv\"]", "twice")] {
        let d3 = dir_with(&[("a.csv", PSD_A.to_string()), ("part.toml", psd_scene(list))]);
        let o = run(&["check", &p(d3.path(), "part.toml")]);
        assert_eq!(o.status.code(), Some(2));
        let err = stderr(&o);
        assert!(
            err.contains("part.toml:2:") && err.contains(needle),
            "{err}"
        );
    }
}

#[test]
fn a_version_pin_warns_when_the_running_version_differs() {
    let running = env!("CARGO_PKG_VERSION");
    let pinned = |v: &str| format!("coatcheck_version = \"{v}\"\n{}", scene(PASS));
    let d = dir_with(&[
        ("same.toml", pinned(running)),
        ("old.toml", pinned("0.0.1")),
        ("bad.toml", pinned("latest")),
    ]);
    let o = run(&["check", &p(d.path(), "same.toml")]);
    assert_eq!(o.status.code(), Some(0));
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
    let o = run(&["check", &p(d.path(), "old.toml")]);
    assert_eq!(o.status.code(), Some(0), "a pin warns, it does not fail");
    let err = stderr(&o);
    assert!(
        err.contains("warning") && err.contains("0.0.1") && err.contains(running),
        "{err}"
    );
    let o = run(&["check", &p(d.path(), "bad.toml")]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(
        err.contains("bad.toml:1: coatcheck_version") && err.contains("latest"),
        "{err}"
    );
    // In a batch the warning is counted in the scene's row and listed by file.
    let o = run(&["check", &p(d.path(), "same.toml"), &p(d.path(), "old.toml")]);
    let text = stdout(&o);
    assert!(
        text.contains("warning: ") && text.contains("old.toml: the scene pins"),
        "{text}"
    );
}

#[test]
fn unknown_keys_name_the_key_and_the_file() {
    let top = format!("coatcheck_verison = \"0.1.0\"\n{}", scene(PASS));
    let nested = scene(PASS).replace("rms_slope", "rms_slop");
    let d = dir_with(&[("top.toml", top), ("nested.toml", nested)]);
    for (name, key, line) in [
        ("top.toml", "coatcheck_verison", 1),
        ("nested.toml", "rms_slop", 6),
    ] {
        let o = run(&["check", &p(d.path(), name)]);
        assert_eq!(o.status.code(), Some(2));
        let err = stderr(&o);
        assert!(
            err.contains(&format!("{name}:{line}: unknown field `{key}`")),
            "{err}"
        );
        assert_eq!(err.lines().count(), 1, "{err}");
    }
    // Batch: both rows are errors with the same messages.
    let o = run(&["check", d.path().to_str().unwrap(), "--format", "json"]);
    assert_eq!(o.status.code(), Some(2));
    let v = json(&o);
    for r in v["scenes"].as_array().unwrap() {
        assert_eq!(r["verdict"], "error");
        let e = r["error"].as_str().unwrap();
        assert!(e.contains("unknown field"), "{e}");
    }
    assert_eq!(stderr(&o).lines().count(), 2, "{}", stderr(&o));
}

#[test]
fn progress_is_hidden_when_stderr_is_not_a_terminal() {
    let files: Vec<(String, String)> = (0..5)
        .map(|i| (format!("s{i}.toml"), scene(PASS)))
        .collect();
    let files: Vec<(&str, String)> = files.iter().map(|(n, t)| (n.as_str(), t.clone())).collect();
    let d = dir_with(&files);
    let o = run(&["check", d.path().to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0));
    assert!(o.stderr.is_empty(), "{}", stderr(&o));
}

/// Without the `parquet` feature, --parquet is refused before anything runs.
#[cfg(not(feature = "parquet"))]
#[test]
fn parquet_needs_the_feature() {
    let d = dir_with(&[("a.toml", scene(PASS))]);
    let out = d.path().join("r.parquet");
    let o = run(&[
        "check",
        &p(d.path(), "a.toml"),
        "--parquet",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--features parquet"), "{}", stderr(&o));
    assert!(o.stdout.is_empty() && !out.exists());
}

/// The bundled examples/specs directory: two pass, two fail, two are broken (exit 2); the
/// table lists failures first, the broken ones name file and line.
#[test]
fn the_example_specs_directory() {
    let specs: PathBuf = [env!("CARGO_MANIFEST_DIR"), "examples", "specs"]
        .iter()
        .collect();
    let o = run(&["check", specs.to_str().unwrap(), "--format", "json"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let v = json(&o);
    let verdict = |name: &str| {
        v["scenes"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["scene"].as_str().unwrap().ends_with(name))
            .map(|r| r["verdict"].as_str().unwrap().to_string())
            .unwrap()
    };
    assert_eq!(verdict("paper-rubber-on-steel.toml"), "pass");
    assert_eq!(verdict("lining-two-scans.toml"), "pass");
    assert_eq!(verdict("waviness-thin-film.toml"), "fail");
    assert_eq!(verdict("paper-film-too-thin.toml"), "fail");
    assert_eq!(verdict("broken-typo-key.toml"), "error");
    assert_eq!(verdict("broken-missing-psd.toml"), "error");
    let err = stderr(&o);
    assert!(
        err.contains("broken-typo-key.toml:14: unknown field `thicknes`"),
        "{err}"
    );
    assert!(
        err.contains("broken-missing-psd.toml:6: roughness.psd") && err.contains("scan-c.csv"),
        "{err}"
    );
}

/// With the `parquet` feature: the batch and a sweep written as Parquet read back with polars
/// itself, one row per scene (per thickness), the same numbers as the JSON records.
#[cfg(feature = "parquet")]
#[test]
fn parquet_reads_back_with_polars() {
    use polars::prelude::{ParquetReader, SerReader};
    let read = |path: &Path| {
        ParquetReader::new(std::fs::File::open(path).unwrap())
            .finish()
            .unwrap()
    };
    let d = dir_with(&[
        ("a.toml", scene(PASS)),
        ("b.toml", scene(FAIL)),
        ("c.toml", scene(PASS).replace("[load]", "[lod]")),
    ]);
    let out = tempfile::tempdir().unwrap();
    let pq = out.path().join("batch.parquet");
    let o = run(&[
        "check",
        d.path().to_str().unwrap(),
        "--format",
        "json",
        "--parquet",
        pq.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let v = json(&o);
    let df = read(&pq);
    assert_eq!(df.height(), 3);
    let verdict = df.column("verdict").unwrap().str().unwrap();
    let verdicts: Vec<&str> = (0..verdict.len())
        .map(|i| verdict.get(i).unwrap())
        .collect();
    assert_eq!(verdicts, ["fail", "error", "pass"]);
    let margin = df.column("margin").unwrap().f64().unwrap();
    let margins: Vec<Option<f64>> = (0..margin.len()).map(|i| margin.get(i)).collect();
    // serde_json's default float parser may be off by an ulp; Parquet keeps the f64 exactly.
    for (i, m) in margins.iter().enumerate() {
        match (m, v["scenes"][i]["margin"].as_f64()) {
            (Some(a), Some(b)) => assert!((a - b).abs() <= 4e-16 * b.abs(), "row {i}: {a} {b}"),
            (a, b) => assert_eq!(*a, b, "row {i}"),
        }
    }
    assert_eq!(margins[1], None, "the broken scene has no margin");
    let errors = df.column("error").unwrap().str().unwrap();
    assert!(errors.get(1).unwrap().contains("c.toml:14:"));
    assert_eq!(df.column("files").unwrap().u64().unwrap().get(0), Some(1));
    // Atomic: only the file itself.
    assert_eq!(std::fs::read_dir(out.path()).unwrap().count(), 1);

    // A sweep: one row per thickness, log-spaced.
    let sweep = out.path().join("sweep.parquet");
    let o = run(&[
        "check",
        &p(d.path(), "a.toml"),
        "--sweep-thickness",
        "1um:100um:3",
        "--parquet",
        sweep.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let df = read(&sweep);
    assert_eq!(df.height(), 3);
    let thickness = df.column("thickness_m").unwrap().f64().unwrap();
    let d: Vec<f64> = (0..thickness.len())
        .map(|i| thickness.get(i).unwrap())
        .collect();
    assert!((d[1] / 1e-5 - 1.0).abs() < 1e-12, "{d:?}");
    let tau = df.column("tau_rms_interface_pa").unwrap().f64().unwrap();
    assert!((0..tau.len()).all(|i| tau.get(i).is_some_and(|t| t > 0.0)));
    let pass = df.column("bond_shear_pass").unwrap().bool().unwrap();
    assert_eq!(pass.len(), 3);
}

/// With the `parquet` feature: a batch of layer stacks and a film as Parquet, one row per
/// stack interface (top first, `interface` from 1) and one per film (interface columns null),
/// each row carrying its scene's columns; every number equal to the batch JSON's (its
/// interfaces and their bond-shear checks). A single stack scene writes the same rows; a
/// stack's thickness sweep is refused (exit 2, nothing written).
#[cfg(feature = "parquet")]
#[test]
fn parquet_has_a_row_per_stack_interface() {
    use polars::prelude::{DataFrame, ParquetReader, SerReader};
    let read = |path: &Path| {
        ParquetReader::new(std::fs::File::open(path).unwrap())
            .finish()
            .unwrap()
    };
    let example = |name: &str| {
        std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("examples")
                .join(name),
        )
        .unwrap()
    };
    let d = dir_with(&[
        ("film.toml", scene(PASS)),
        ("primer.toml", example("rubber-epoxy-primer-steel.toml")),
        ("ptfe.toml", example("ptfe-rubber-steel.toml")),
    ]);
    let out = tempfile::tempdir().unwrap();
    let pq = out.path().join("batch.parquet");
    let o = run(&[
        "check",
        d.path().to_str().unwrap(),
        "--format",
        "json",
        "--parquet",
        pq.to_str().unwrap(),
    ]);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    let v = json(&o);
    let df = read(&pq);
    let text = |df: &DataFrame, c: &str, i: usize| {
        df.column(c)
            .unwrap()
            .str()
            .unwrap()
            .get(i)
            .map(String::from)
    };
    let number = |df: &DataFrame, c: &str, i: usize| df.column(c).unwrap().f64().unwrap().get(i);
    let index = |df: &DataFrame, i: usize| df.column("interface").unwrap().u64().unwrap().get(i);
    // serde_json's default float parser may be off by an ulp; Parquet keeps the f64 exactly.
    let close = |a: Option<f64>, b: Option<f64>, what: &str| match (a, b) {
        (Some(a), Some(b)) => assert!((a - b).abs() <= 4e-16 * b.abs(), "{what}: {a} {b}"),
        (a, b) => assert_eq!(a, b, "{what}"),
    };
    let mut row = 0;
    let mut stacks = 0;
    for s in v["scenes"].as_array().unwrap() {
        let scene = s["scene"].as_str().unwrap();
        match s["interfaces"].as_array() {
            None => {
                assert_eq!(text(&df, "scene", row).as_deref(), Some(scene));
                assert_eq!(index(&df, row), None);
                assert_eq!(text(&df, "interface_name", row), None);
                assert_eq!(number(&df, "interface_tau_rms_pa", row), None);
                assert_eq!(text(&df, "thickness_of", row), None);
                close(
                    number(&df, "tau_rms_interface_pa", row),
                    s["tau_rms_interface_pa"].as_f64(),
                    scene,
                );
                row += 1;
            }
            Some(interfaces) => {
                stacks += 1;
                assert!(interfaces.len() >= 2, "{scene}");
                for (k, i) in interfaces.iter().enumerate() {
                    let name = i["name"].as_str().unwrap();
                    let what = format!("{scene} {name}");
                    assert_eq!(text(&df, "scene", row).as_deref(), Some(scene));
                    assert_eq!(text(&df, "verdict", row).as_deref(), s["verdict"].as_str());
                    assert_eq!(
                        text(&df, "thickness_of", row).as_deref(),
                        s["thickness_of"].as_str()
                    );
                    close(number(&df, "margin", row), s["margin"].as_f64(), &what);
                    assert_eq!(index(&df, row), Some(k as u64 + 1));
                    assert_eq!(text(&df, "interface_name", row).as_deref(), Some(name));
                    for key in [
                        "depth_m",
                        "sigma_rms_pa",
                        "sigma_rms_pa_err",
                        "tau_rms_pa",
                        "tau_rms_pa_err",
                        "tau_peak_pa",
                        "tau_peak_pa_err",
                        "sigma_peak_pa",
                        "sigma_peak_pa_err",
                        "bond_strength_pa",
                        "bond_exceedance",
                    ] {
                        close(
                            number(&df, &format!("interface_{key}"), row),
                            i[key].as_f64(),
                            &format!("{what} {key}"),
                        );
                    }
                    let bond = s["checks"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .find(|c| c["name"] == "bond-shear" && c["at"] == name)
                        .unwrap();
                    for (col, key) in [
                        ("interface_bond_shear_limit_pa", "limit"),
                        ("interface_bond_shear_utilisation", "utilisation"),
                        ("interface_bond_shear_margin", "margin"),
                    ] {
                        close(number(&df, col, row), bond[key].as_f64(), &what);
                    }
                    assert_eq!(
                        text(&df, "interface_bond_shear_pass", row),
                        Some(bond["pass"].to_string())
                    );
                    row += 1;
                }
            }
        }
    }
    assert_eq!(stacks, 2);
    assert_eq!(df.height(), row);

    // One stack scene: its rows as in the batch.
    let one = out.path().join("one.parquet");
    let o = run(&[
        "check",
        &p(d.path(), "primer.toml"),
        "--parquet",
        one.to_str().unwrap(),
    ]);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    let df1 = read(&one);
    assert_eq!(df1.height(), 2);
    let names: Vec<Option<String>> = (0..2).map(|i| text(&df1, "interface_name", i)).collect();
    assert_eq!(names, [Some("rubber".into()), Some("primer".into())]);
    assert_eq!(df1.width(), df.width(), "one schema for every batch");

    // A stack's sweep has no Parquet form.
    let sweep = out.path().join("sweep.parquet");
    let o = run(&[
        "check",
        &p(d.path(), "primer.toml"),
        "--sweep-thickness",
        "1um:100um:3",
        "--parquet",
        sweep.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--parquet with --sweep-thickness"),
        "{}",
        stderr(&o)
    );
    assert!(!sweep.exists());
}
