//! Plausibility of measured data in every output format: the h_rms and rms slope used, the
//! warnings (film thinner than h_rms, longest wavelength shorter than the film, rms slope
//! above 1, a non-periodic map used as periodic) in the table, JSON and CSV; files without
//! units accepted only with magnitudes plausible in SI.

use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_coatcheck");
const MATERIALS: [&str; 8] = [
    "--film",
    "paper-rubber",
    "--substrate",
    "paper-steel",
    "--bond",
    "epoxy",
    "--pressure",
    "0.1MPa",
];

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .expect("run coatcheck")
}

/// `check` with `args` in each format: (table, JSON, CSV) standard outputs.
fn each_format(args: &[&str]) -> (String, serde_json::Value, String) {
    let out = |format: &str| {
        let mut all = vec!["check"];
        all.extend_from_slice(args);
        all.extend_from_slice(&MATERIALS);
        all.extend_from_slice(&["--format", format]);
        let o = run(&all);
        assert!(
            matches!(o.status.code(), Some(0 | 1)),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        String::from_utf8(o.stdout).unwrap()
    };
    (
        out("table"),
        serde_json::from_str(&out("json")).expect("json"),
        out("csv"),
    )
}

/// The warning containing every needle, present in all three formats.
fn warned_everywhere(args: &[&str], needles: &[&str]) {
    let (table, json, csv) = each_format(args);
    let has = |text: &str| needles.iter().all(|n| text.contains(n));
    // Table prose wraps at 100 columns with a two-space indent: join it back.
    let flat = table.replace("\n  ", " ");
    assert!(
        flat.lines().any(|l| l.starts_with("warning: ") && has(l)),
        "table: {table}"
    );
    assert!(
        json["warnings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|w| has(w.as_str().unwrap())),
        "json: {}",
        json["warnings"]
    );
    assert!(has(&csv_cell(&csv, "warnings")), "csv: {csv}");
}

/// The cell under `column` in a one-scene `check --format csv` (header and one row).
fn csv_cell(csv: &str, column: &str) -> String {
    let mut r = csv::Reader::from_reader(csv.as_bytes());
    let at = r
        .headers()
        .unwrap()
        .iter()
        .position(|h| h == column)
        .unwrap_or_else(|| panic!("no column {column}: {csv}"));
    let row = r.records().next().expect("one row").unwrap();
    row[at].to_string()
}

const MODEL: [&str; 8] = [
    "--model",
    "self-affine",
    "--hurst",
    "0.8",
    "--q0",
    "1e5",
    "--q1",
    "1e8",
];

fn model(extra: &[&str]) -> Vec<&'static str> {
    let mut v: Vec<&'static str> = MODEL.to_vec();
    v.extend(
        extra
            .iter()
            .map(|s| -> &'static str { Box::leak(s.to_string().into_boxed_str()) }),
    );
    v
}

#[test]
fn h_rms_and_rms_slope_used_are_printed_in_every_format() {
    let args = model(&["--rms-height", "2um", "--thickness", "50um"]);
    let (table, json, csv) = each_format(&args);
    let h = json["h_rms_m"].as_f64().unwrap();
    assert!((h / 2e-6 - 1.0).abs() < 1e-6, "{h}");
    let xi = json["rms_slope"].as_f64().unwrap();
    assert!(xi > 0.0);
    assert!(
        table.contains("h_rms of the spectrum used") && table.contains("2.000 µm"),
        "{table}"
    );
    assert!(table.contains("rms slope of the spectrum used"), "{table}");
    let row = |name: &str| -> f64 { csv_cell(&csv, name).parse().unwrap() };
    // (serde_json parses floats to within an ulp or two.)
    assert!((row("h_rms_m") / h - 1.0).abs() < 1e-14);
    assert!((row("rms_slope") / xi - 1.0).abs() < 1e-14);
    // A given rms slope is the one used.
    let (_, json, _) = each_format(&model(&["--rms-slope", "0.5", "--thickness", "50um"]));
    assert!((json["rms_slope"].as_f64().unwrap() - 0.5).abs() < 1e-9);
}

#[test]
fn film_thinner_than_h_rms_is_warned_with_numbers() {
    warned_everywhere(
        &model(&["--rms-height", "5um", "--thickness", "2um"]),
        &["film thickness d = 2.0000e-6 m", "h_rms = 5.0000e-6 m"],
    );
}

#[test]
fn longest_wavelength_shorter_than_film_is_warned_with_numbers() {
    // q0 = 1e5 1/m: the longest wavelength is 2π/q0 = 62.8 µm < d = 100 µm.
    warned_everywhere(
        &model(&["--rms-slope", "0.5", "--thickness", "100um"]),
        &["2π/q_low = 6.2832e-5 m", "d = 1.0000e-4 m"],
    );
}

#[test]
fn rms_slope_above_one_is_warned_with_numbers() {
    warned_everywhere(
        &model(&["--rms-slope", "2", "--thickness", "50um"]),
        &["rms slope 2.000 > 1"],
    );
}

#[test]
fn non_periodic_map_used_as_periodic_is_warned() {
    // A measured map (x3p) is not periodic: its edges do not join.
    warned_everywhere(
        &[
            "--profile",
            "tests/data/instrument/x3p-2.x3p",
            "--periodic",
            "true",
            "--thickness",
            "1um",
        ],
        &["x3p-2.x3p", "edges do not join", "times the rms step"],
    );
    // The synthetic example map is one period: no such warning.
    let (table, _, _) = each_format(&[
        "--profile",
        "examples/data/height-map.csv",
        "--periodic",
        "true",
        "--thickness",
        "1um",
    ]);
    assert!(!table.contains("edges do not join"), "{table}");
    // `psd --periodic` says so too, in each of its formats.
    for format in ["table", "json", "csv"] {
        let o = run(&[
            "psd",
            "tests/data/instrument/x3p-2.x3p",
            "--periodic",
            "--format",
            format,
        ]);
        let out = String::from_utf8_lossy(&o.stdout);
        assert!(out.contains("edges do not join"), "{format}: {out}");
    }
    // and in the PSD file it writes.
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("c.csv");
    let o = run(&[
        "psd",
        "tests/data/instrument/x3p-2.x3p",
        "--periodic",
        "--output",
        file.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0));
    let written = std::fs::read_to_string(&file).unwrap();
    assert!(written.contains("# warning: ") && written.contains("edges do not join"));
}

#[test]
fn files_without_units_must_be_plausible_in_si() {
    let dir = tempfile::tempdir().unwrap();
    // A PSD in 1/um and um^4 without units: q 0.1 … 100, C up to 1e2.
    let psd = dir.path().join("um.csv");
    let rows: String = (0..31)
        .map(|i| {
            let q = 0.1 * 10f64.powf(i as f64 / 10.0);
            format!("{q:e},{:e}\n", 1e-2 * q.powf(-3.6))
        })
        .collect();
    std::fs::write(&psd, rows).unwrap();
    let o = run(&[
        "check",
        "--psd",
        psd.to_str().unwrap(),
        "--thickness",
        "10um",
        "--film",
        "paper-rubber",
        "--substrate",
        "paper-steel",
        "--bond",
        "epoxy",
        "--pressure",
        "0.1MPa",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        e.contains("um.csv") && e.contains("--q-unit") && e.contains("h_rms"),
        "{e}"
    );
    // The same file with its units given is read.
    let o = run(&[
        "check",
        "--psd",
        psd.to_str().unwrap(),
        "--q-unit",
        "1/um",
        "--c-unit",
        "um^4",
        "--thickness",
        "10um",
        "--film",
        "paper-rubber",
        "--substrate",
        "paper-steel",
        "--bond",
        "epoxy",
        "--pressure",
        "0.1MPa",
    ]);
    assert!(
        matches!(o.status.code(), Some(0 | 1)),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // Heights in nm without units: h_rms of hundreds of "metres".
    let map = dir.path().join("nm.csv");
    let text: String = (0..32)
        .map(|iy| {
            (0..32)
                .map(|ix| format!("{}", 300.0 * ((ix * 7 + iy * 3) % 11) as f64))
                .collect::<Vec<_>>()
                .join(",")
                + "\n"
        })
        .collect();
    std::fs::write(&map, text).unwrap();
    let o = run(&["psd", map.to_str().unwrap(), "--pixel-size", "1um"]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("nm.csv") && e.contains("--z-unit"), "{e}");
    let o = run(&[
        "psd",
        map.to_str().unwrap(),
        "--pixel-size",
        "1um",
        "--z-unit",
        "nm",
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn psd_summary_h_rms_is_the_rms_after_the_named_detrend() {
    // z = plane + A cos(θx i) cos(θy j) on a 32 × 32 grid: the pattern is orthogonal to 1, i and
    // j (Σ_j cos(θy j) = 0), so removing the least-squares plane leaves it alone, rms A/2;
    // removing the mean leaves plane + pattern, whose rms is computed here directly.
    let (n, a) = (32usize, 1e-6);
    let (tx, ty) = (
        2.0 * std::f64::consts::PI * 3.0 / n as f64,
        2.0 * std::f64::consts::PI * 5.0 / n as f64,
    );
    let z = |i: usize, j: usize| {
        2e-8 * i as f64 - 3e-8 * j as f64 + 5e-7 + a * (tx * i as f64).cos() * (ty * j as f64).cos()
    };
    let all: Vec<f64> = (0..n * n).map(|k| z(k % n, k / n)).collect();
    let mean = all.iter().sum::<f64>() / all.len() as f64;
    let rms_mean = (all.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / all.len() as f64).sqrt();
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("plane.csv");
    let text: String = (0..n)
        .map(|j| {
            (0..n)
                .map(|i| format!("{:e}", z(i, j)))
                .collect::<Vec<_>>()
                .join(",")
                + "\n"
        })
        .collect();
    std::fs::write(&map, text).unwrap();
    for (detrend, want) in [("tilt", a / 2.0), ("mean", rms_mean)] {
        let o = run(&[
            "psd",
            map.to_str().unwrap(),
            "--pixel-size",
            "1um",
            "--z-unit",
            "m",
            "--detrend",
            detrend,
            "--format",
            "json",
        ]);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let h = v["summary"]["h_rms_m"].as_f64().unwrap();
        assert!(
            (h / want - 1.0).abs() < 1e-9,
            "{detrend}: {h:e} vs {want:e}"
        );
    }
    assert!(rms_mean > 1.2 * a / 2.0, "the plane matters: {rms_mean:e}");
}

/// A key that says how to read a measured file, given with a model roughness (which reads no
/// file), is an error naming the key, exit 2: in the scene file (each reading key is written
/// into the paper scene's `[roughness]`) and as a flag without an alternative (`--conversion`;
/// a heights or PSD-file flag instead replaces the file's model, so the scene then lacks its
/// file); with a measured file the same key is taken.
#[test]
fn reading_keys_with_a_model_are_an_error() {
    let base = std::fs::read_to_string("examples/paper-rubber-on-steel.toml").unwrap();
    let dir = tempfile::tempdir().unwrap();
    for line in [
        "window = \"hann\"",
        "q_unit = \"1/um\"",
        "conversion = \"pi-q-shortcut\"",
    ] {
        let key = line.split(' ').next().unwrap();
        let text = base.replacen("[roughness]\n", &format!("[roughness]\n{line}\n"), 1);
        assert_ne!(text, base);
        let scene = dir.path().join(format!("{key}.toml"));
        std::fs::write(&scene, text).unwrap();
        let o = run(&["check", scene.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{key}: {err}");
        // Keys that belong to a measured source are a contradiction with the model; the others
        // (conversion) are refused as reading a file.
        assert!(
            err.contains(&format!("roughness.{key}"))
                && (err.contains("is a model")
                    || err.contains("contradicts roughness.model")
                    || err.contains("roughness.model: contradicts")),
            "{key}: {err}"
        );
    }
    let o = run(&[
        "check",
        "examples/paper-rubber-on-steel.toml",
        "--conversion",
        "pi-q-shortcut",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--conversion") && err.contains("is a model"),
        "{err}"
    );
    let o = run(&[
        "check",
        "examples/paper-rubber-on-steel.toml",
        "--profile",
        "examples/data/height-map.csv",
        "--window",
        "hann",
    ]);
    assert!(o.status.code().is_some_and(|c| c < 2), "{o:?}");
}
