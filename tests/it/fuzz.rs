//! Hardened inputs (issue 7): property-based fuzzing of the PSD/CSV reader, the unit parser, the
//! scene reader and the instrument readers (truncated and corrupted sample files). Every input
//! either reads into valid SI data or is rejected with an `Error::Input` naming the file and a
//! line of it (or, for a key missing from a scene, the file and the key; for an instrument file,
//! the file); nothing panics, nothing hangs, and no NaN or infinity reaches a verdict.
//!
//! Inputs are generated from the grammar the readers accept (numbers of every shape, units,
//! separators, headers, comments, BOM, CRLF) mixed with arbitrary text, so that most cases get
//! past the first line. The case counts are bounded for CI (about a second in all); a long run
//! multiplies them: `COATCHECK_FUZZ_SCALE=1000 cargo test --test it fuzz`. CI runs them over
//! the seeds 1 to 8 (`PROPTEST_RNG_SEED`), so a failure there reproduces with its seed.
//! Failures found are kept below as plain regression tests.

use coatcheck::Error;
use coatcheck::material::Library;
use coatcheck::pipeline::judge;
use coatcheck::psd::read::{ReadOptions, parse_spectrum};
use coatcheck::scene::Scene;
use coatcheck::units::{Dim, parse_quantity};
use proptest::prelude::*;
use std::path::Path;
use std::sync::OnceLock;

/// Cases per property: `default` times `COATCHECK_FUZZ_SCALE` (1 in CI).
fn config(default: u32) -> ProptestConfig {
    let scale: u32 = std::env::var("COATCHECK_FUZZ_SCALE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    ProptestConfig {
        cases: default.saturating_mul(scale),
        // Shrinking a failure can take long; the first counterexample is kept as it is.
        max_shrink_iters: 256,
        ..ProptestConfig::default()
    }
}

fn library() -> &'static Library {
    static LIB: OnceLock<Library> = OnceLock::new();
    LIB.get_or_init(|| Library::builtin().unwrap())
}

// ---------------------------------------------------------------- the PSD/CSV reader

/// A number as files have them, well-formed or not.
fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        6 => (-30i32..30, 1u32..999_999).prop_map(|(e, m)| format!("{}e{e}", m as f64 / 1e5)),
        2 => (1u32..1000).prop_map(|m| format!("{}", m as f64 / 7.0)),
        1 => Just("0".to_string()),
        1 => Just("-1e-20".to_string()),
        1 => prop::sample::select(vec![
            "nan", "NaN", "inf", "-inf", "infinity", "1e308", "1e-308", "4.9e-324", "1e400",
            "-0", "0x10", "1,5e-20", "1.5.3", "", "  ", "\"1e5\"", "1e5 ", "e5", "1e", "+3",
        ])
        .prop_map(String::from),
        1 => "[ -~]{0,12}",
    ]
}

fn header_field() -> impl Strategy<Value = String> {
    prop::sample::select(vec![
        "q (1/m)",
        "C (m^4)",
        "q [1/um]",
        "C [um^4]",
        "PSD (nm^3)",
        "k",
        "wavenumber (1/nm)",
        "freq (1/m)",
        "wavelength",
        "x",
        "C (furlong^4)",
        "q (1/Pa)",
        "q ()",
        "C (m^4",
        "power",
        "q (1/pm)",
    ])
    .prop_map(String::from)
}

fn sep() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![",", ";", "\t", " ", "   ", ", "])
}

/// A spectrum file: optional BOM, comments, an optional header, rows of fields with one
/// separator per file; most rows look like data, so that cases get past the first lines.
fn psd_text() -> impl Strategy<Value = String> {
    let good = (0.5f64..9.5, -300i32..300);
    let row = prop_oneof![
        6 => (good.clone(), good).prop_map(|((a, ea), (b, eb))| vec![format!("{a}e{ea}"), format!("{b}e{eb}")]),
        2 => prop::collection::vec(number(), 2..3),
        1 => prop::collection::vec(number(), 0..5),
    ];
    (
        any::<bool>(),
        sep(),
        prop::option::of(prop_oneof![
            3 => (
                prop::sample::select(vec!["q (1/m)", "q [1/um]", "wavenumber (1/nm)", "k", "q (1/mm)"]),
                prop::sample::select(vec!["C (m^4)", "C [um^4]", "PSD (nm^4)", "power", "C (nm^3)"]),
            )
                .prop_map(|(q, c)| vec![q.to_string(), c.to_string()]),
            2 => prop::collection::vec(header_field(), 1..4),
        ]),
        prop::collection::vec(
            prop_oneof![
                12 => row.prop_map(Some),
                1 => prop::sample::select(vec!["# comment", "% c", "// c", "", "  "])
                    .prop_map(|c| Some(vec![c.to_string()])),
                1 => "\\PC{0,30}".prop_map(|t| Some(vec![t])),
                1 => Just(None),
            ],
            0..16,
        ),
        any::<bool>(),
    )
        .prop_map(|(bom, sep, header, rows, crlf)| {
            let mut lines = Vec::new();
            if let Some(h) = header {
                lines.push(h.join(sep));
            }
            let mut last: Option<String> = None;
            for r in rows {
                match r {
                    Some(fields) => {
                        let l = fields.join(sep);
                        last = Some(l.clone());
                        lines.push(l);
                    }
                    // A repeated row (duplicate q).
                    None => lines.extend(last.clone()),
                }
            }
            let end = if crlf { "\r\n" } else { "\n" };
            format!("{}{}", if bom { "\u{feff}" } else { "" }, lines.join(end))
        })
}

/// A well-formed spectrum with a random unit, row order and extreme magnitudes.
fn valid_psd_text() -> impl Strategy<Value = String> {
    (
        prop::sample::select(vec!["1/m", "1/um", "1/nm", "1/mm"]),
        prop::sample::select(vec!["m^4", "um^4", "nm^4"]),
        -200i32..200,
        prop::collection::vec((1.0f64..10.0, -3.0f64..3.0), 2..20),
        any::<bool>(),
    )
        .prop_map(|(qu, cu, shift, pts, reverse)| {
            let mut rows: Vec<String> = pts
                .iter()
                .enumerate()
                .map(|(i, (m, lc))| {
                    let q = format!("{m}e{}", i as i32 + shift / 4);
                    let c = format!("{}e{}", 10f64.powf(*lc), -20 + shift);
                    format!("{q},{c}")
                })
                .collect();
            if reverse {
                rows.reverse();
            }
            format!("q ({qu}),C ({cu})\n{}\n", rows.join("\n"))
        })
}

/// The reader's contract on any text.
fn check_reader(text: &str) -> Result<(), TestCaseError> {
    let path = Path::new("fuzz/scan.csv");
    let n_lines = text.split('\n').count();
    match parse_spectrum(text, path, &ReadOptions::default()) {
        Ok((t, _)) => {
            let (q, c) = (t.q(), t.c_values());
            prop_assert!(q.len() >= 2 && q.len() == c.len());
            prop_assert!(q.iter().all(|x| x.is_finite() && *x > 0.0), "{q:?}");
            prop_assert!(c.iter().all(|x| x.is_finite() && *x > 0.0), "{c:?}");
            prop_assert!(q.windows(2).all(|w| w[0] < w[1]), "{q:?}");
        }
        Err(Error::Input { path: p, line, msg }) => {
            prop_assert_eq!(p.as_path(), path);
            prop_assert!(
                line >= 1 && line <= n_lines,
                "line {line} of {n_lines}: {msg}"
            );
            prop_assert!(!msg.contains('\n'), "{msg}");
        }
        Err(e) => prop_assert!(false, "not an Input error naming the file and line: {e}"),
    }
    Ok(())
}

/// A bad row among good ones: the error names exactly its line. The units make some rows
/// overflow or underflow only in SI (1e300 1/nm is infinite in 1/m, 1e-300 nm^4 is 0 in m^4).
fn bad_row_file() -> impl Strategy<Value = (String, usize)> {
    (
        prop::collection::vec((1.0f64..9.0, 1e-3f64..1.0), 2..12),
        0usize..12,
        prop::sample::select(vec![
            "abc,1e-10",
            "1e300,1e-10",
            "5,1e-300",
            "0,1e-10",
            "-2,1e-10",
            "3,0",
            "3,-1e-10",
            "nan,1e-10",
            "3,inf",
            "7",
            "DUP",
        ]),
    )
        .prop_map(|(pts, at, bad)| {
            // Increasing q in 1/nm, C in nm^4; all finite in SI.
            let mut rows: Vec<String> = pts
                .iter()
                .enumerate()
                .map(|(i, (m, c))| format!("{}e{},{c}e-10", m, i as i32 - 3))
                .collect();
            let at = at % rows.len() + 1;
            let bad = if bad == "DUP" {
                rows[at - 1].clone()
            } else {
                bad.to_string()
            };
            rows.insert(at, bad);
            // Line 1 is the header; row k (0-based) is on line k + 2.
            (format!("q (1/nm),C (nm^4)\n{}\n", rows.join("\n")), at + 2)
        })
}

proptest! {
    #![proptest_config(config(512))]

    #[test]
    fn psd_errors_name_the_offending_row((text, line) in bad_row_file()) {
        match parse_spectrum(&text, Path::new("f.csv"), &ReadOptions::default()) {
            Err(Error::Input { line: got, msg, .. }) => prop_assert_eq!(got, line, "{}", msg),
            other => prop_assert!(false, "{other:?}"),
        }
    }

    #[test]
    fn psd_reader_reads_or_names_file_and_line(text in psd_text()) {
        check_reader(&text)?;
    }

    #[test]
    fn psd_reader_on_arbitrary_text(text in "\\PC{0,200}") {
        check_reader(&text)?;
    }

    #[test]
    fn psd_reader_on_valid_files_in_any_unit(text in valid_psd_text()) {
        check_reader(&text)?;
    }
}

// ---------------------------------------------------------------- the unit parser

fn dim() -> impl Strategy<Value = Dim> {
    prop::sample::select(vec![
        Dim::Length(1),
        Dim::Length(-1),
        Dim::Length(3),
        Dim::Length(4),
        Dim::Pressure,
        Dim::Dimensionless,
    ])
}

proptest! {
    #![proptest_config(config(2048))]

    /// No panic; a NaN only from a literal "nan".
    #[test]
    fn units_never_panic(text in prop_oneof![
        "\\PC{0,40}",
        (number(), "[ ]{0,2}", prop::sample::select(vec![
            "um", "µm", "mm", "m", "nm", "1/m", "1/um", "/m", "m^-1", "um^4", "m4", "nm^3",
            "Pa", "kPa", "MPa", "GPa", "psi", "bar", "MPa^2", "1/Pa", "furlong", "m^", "m^x",
            "m^99999999999", "1/", "^4", "Tm", "cm", "",
        ])).prop_map(|(n, s, u)| format!("{n}{s}{u}")),
    ], d in dim()) {
        if let Ok(v) = parse_quantity(&text, d) {
            prop_assert!(!v.is_nan() || text.to_lowercase().contains("nan"), "{text} -> {v}");
        }
    }

    /// Against an independent reference: a prefix is an exact power of ten, so "x um" is the
    /// decimal "xe-6" to within one rounding (the reference rounds once, the parser at most
    /// twice: the mantissa, then the scaling).
    #[test]
    fn prefixes_are_exact_powers_of_ten(
        m in 1u64..10_000_000,
        e in -20i32..20,
        (unit, shift, d) in prop::sample::select(vec![
            ("nm", -9, Dim::Length(1)), ("um", -6, Dim::Length(1)), ("mm", -3, Dim::Length(1)),
            ("cm", -2, Dim::Length(1)), ("1/um", 6, Dim::Length(-1)),
            ("um^4", -24, Dim::Length(4)), ("nm^3", -27, Dim::Length(3)),
            ("kPa", 3, Dim::Pressure), ("MPa", 6, Dim::Pressure), ("GPa", 9, Dim::Pressure),
        ]),
    ) {
        let text = format!("{m}e{e} {unit}");
        let got = parse_quantity(&text, d).unwrap();
        let want: f64 = format!("{m}e{}", e + shift).parse().unwrap();
        prop_assert!(((got - want) / want).abs() <= 2.3e-16, "{text}: {got:e} vs {want:e}");
    }
}

// ---------------------------------------------------------------- the scene reader

const SCENE: &str = "\
schema_version = 1
[roughness]
model = \"self-affine\"
hurst = 0.8
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
[criteria]
epsilon = 1e-6
safety_factor = 1
checks = [\"bond-shear\", \"substrate-yield\"]
";

/// A TOML value, well-formed or not.
fn toml_value() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => (number(), prop::sample::select(vec![
            "", " um", " 1/m", " MPa", " Pa", "um", " GPa", " furlong", " 1/um", " bar",
        ])).prop_map(|(n, u)| format!("\"{n}{u}\"")),
        2 => (-40i32..40, 1u32..99).prop_map(|(e, m)| format!("{m}e{e}")),
        1 => prop::sample::select(vec![
            "0", "-1", "1e400", "nan", "inf", "-inf", "true", "[]", "[\"a\"]", "{ a = 1 }",
            "\"\"", "\"paper-rubber\"", "\"natural-rubber\"", "\"epoxy\"", "\"gaussian\"",
            "\"self-affine\"", "1979-05-27", "\"bond-shear, min-thickness\"", "[1, 2]", "\"1.2.3\"",
            "\"0.1.0\"", "'lit'", "\"\"\"x\"\"\"", "0x1F", "1_000",
        ]).prop_map(String::from),
        1 => "[ -~]{0,10}",
    ]
}

/// A mutation of one line of the scene.
#[derive(Debug, Clone)]
enum Edit {
    Value(usize, String),
    Drop(usize),
    Rename(usize, String),
    Insert(usize, String),
}

fn edit() -> impl Strategy<Value = Edit> {
    let line = 0usize..21;
    prop_oneof![
        5 => (line.clone(), toml_value()).prop_map(|(l, v)| Edit::Value(l, v)),
        1 => line.clone().prop_map(Edit::Drop),
        1 => (line.clone(), "[a-z_]{1,12}").prop_map(|(l, k)| Edit::Rename(l, k)),
        1 => (line, prop_oneof![
            "[a-z_]{1,10} = [0-9]{1,3}".boxed(),
            Just("[numerics]\nrtol = 1e-6".to_string()).boxed(),
            Just("coatcheck_version = \"9.9.9\"".to_string()).boxed(),
            Just("psd = \"missing.csv\"".to_string()).boxed(),
            Just("width = \"1e4 1/m\"".to_string()).boxed(),
            Just("roll_off = \"2e5 1/m\"".to_string()).boxed(),
            Just("yield_strength = \"-5 MPa\"".to_string()).boxed(),
            "\\PC{0,20}".boxed(),
        ]).prop_map(|(l, t)| Edit::Insert(l, t)),
    ]
}

fn apply(edits: &[Edit]) -> String {
    let mut lines: Vec<String> = SCENE.lines().map(String::from).collect();
    for e in edits {
        let n = lines.len().max(1);
        match e {
            Edit::Value(l, v) => {
                let l = l % n;
                if let Some(i) = lines.get(l).and_then(|s| s.find(" = ")) {
                    lines[l] = format!("{} = {v}", &lines[l][..i]);
                }
            }
            Edit::Drop(l) => {
                if !lines.is_empty() {
                    lines.remove(l % n);
                }
            }
            Edit::Rename(l, k) => {
                let l = l % n;
                if let Some(i) = lines.get(l).and_then(|s| s.find(" = ")) {
                    lines[l] = format!("{k}{}", &lines[l][i..]);
                }
            }
            Edit::Insert(l, t) => lines.insert(l % (n + 1), t.clone()),
        }
    }
    lines.join("\n") + "\n"
}

/// The scene reader's contract, and for a scene that loads, the verdict's.
fn check_scene(text: &str) -> Result<(), TestCaseError> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fuzz.toml");
    std::fs::write(&path, text).unwrap();
    let n_lines = text.split('\n').count();
    let scene = match Scene::load(Some(&path), &[], library()) {
        Ok(s) => s,
        Err(Error::Input { path: p, line, msg }) => {
            prop_assert_eq!(&p, &path);
            prop_assert!(
                line >= 1 && line <= n_lines,
                "line {line} of {n_lines}: {msg}"
            );
            prop_assert!(!msg.contains('\n'), "{msg}");
            return Ok(());
        }
        Err(Error::Value { origin, msg }) => {
            // A key missing from the scene has no line: the file and the key are named.
            prop_assert_eq!(origin, path.display().to_string());
            prop_assert!(msg.contains("is missing"), "{msg}");
            return Ok(());
        }
        Err(e) => {
            return Err(TestCaseError::fail(format!(
                "not an error naming the scene file: {e}"
            )));
        }
    };
    for x in [
        scene.pressure,
        scene.film.elastic.youngs,
        scene.substrate.elastic.youngs,
    ] {
        prop_assert!(x.is_finite() && x > 0.0, "{x}");
    }
    if let Some(d) = scene.thickness {
        prop_assert!(d.is_finite() && d > 0.0);
    }
    match judge(&scene, None) {
        Ok(j) => {
            let o = j.outcome.film().expect("the fuzzed scenes are films");
            prop_assert!(o.evaluation.contact.area_fraction.value.is_finite());
            for c in &o.checks {
                prop_assert!(c.value.value.is_finite(), "{c:?}");
                prop_assert!(c.margin.is_none_or(f64::is_finite), "{c:?}");
                // Pass is a non-negative margin (up to the rounding of value/limit near 1).
                if let Some(m) = c.margin.filter(|m| m.abs() > 1e-15) {
                    prop_assert_eq!(c.pass, m >= 0.0, "{:?}", c);
                }
            }
            prop_assert_eq!(o.pass, o.checks.iter().all(|c| c.pass));
        }
        // Anything the scene reader let through is judged, or refused naming the scene file
        // (a missing thickness), or is a numerical failure that says what failed.
        Err(Error::Numerical { .. }) => {}
        Err(Error::Value { origin, .. }) => prop_assert_eq!(origin, path.display().to_string()),
        Err(e) => prop_assert!(false, "the verdict failed without naming the scene: {e}"),
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn scene_reader_loads_or_names_file_and_line(edits in prop::collection::vec(edit(), 1..4)) {
        check_scene(&apply(&edits))?;
    }
}

// ---------------------------------------------------------------- the CLI: exit code 2

proptest! {
    #![proptest_config(config(64))]

    /// Through the binary: exit 0, 1 or 2; a rejection is one line on stderr naming the file.
    #[test]
    fn cli_rejects_with_exit_2_and_one_line(edits in prop::collection::vec(edit(), 1..3)) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("fuzz.toml");
        std::fs::write(&path, apply(&edits)).unwrap();
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_coatcheck"))
            .args(["check", path.to_str().unwrap(), "--format", "json"])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        prop_assert!(!err.contains("panicked"), "{err}");
        match o.status.code() {
            Some(0 | 1) => {
                let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
                prop_assert!(v["verdict"] == "pass" || v["verdict"] == "fail");
            }
            Some(2) => {
                let last = err.lines().last().unwrap_or_default();
                // Input errors name the scene file; a numerical failure says what failed.
                prop_assert!(
                    last.starts_with("coatcheck: ")
                        && (last.contains("fuzz.toml") || last.contains("numerical failure")),
                    "{err}"
                );
                prop_assert!(o.stdout.is_empty());
            }
            other => prop_assert!(false, "exit {other:?}: {err}"),
        }
    }
}

// ---------------------------------------------------------------- regressions found by fuzzing

/// Found by `psd_errors_name_the_offending_row`: a value finite in the file's unit but not in
/// SI (1e300 1/nm, 1e-300 nm^4) was caught only by the spectrum's validation, which named the
/// first data line instead of the row.
#[test]
fn si_overflow_and_underflow_name_their_row() {
    for (text, line) in [
        ("q (1/nm),C (m^4)\n1e-4,1e-20\n1e-3,1e-23\n1e300,1e-30\n", 4),
        ("q (1/m),C (nm^4)\n1e5,1e-20\n1e6,1e-23\n1e7,1e-300\n", 4),
    ] {
        let Err(Error::Input { line: got, msg, .. }) =
            parse_spectrum(text, Path::new("s.csv"), &ReadOptions::default())
        else {
            panic!("accepted: {text}");
        };
        assert_eq!(got, line, "{msg}");
        assert!(msg.contains("outside the floating-point range"), "{msg}");
    }
}

/// Found by `psd_reader_reads_or_names_file_and_line` (2 of 60 seeds): a 1D PSD whose points
/// lie more than 308 decades apart made the inverse Abel transform's substitution variable
/// acosh(e^t) infinite and its panel count usize::MAX; the reader never returned (this test hung
/// before the fix). Now it reads the file or names its file and line.
#[test]
fn one_d_psd_spanning_beyond_f64_range_returns() {
    let text = "\u{feff}q (1/m);C (nm^3)\n\
                2.619265000922726e157;3.339036897997493e250\n\
                6.752991253610662e-298;9.098456516005827e219\n\
                8.335795680492916e-286;0.8153936278483861e-227\n\
                3.3212954118117803e265;4.456059503974242e-160\n";
    check_reader(text).unwrap();
}

/// Found by `scene_reader_loads_or_names_file_and_line`: model parameters outside the model's
/// domain (H > 1, q1 below q0, a roll-off outside [q0, q1), a Gaussian band reaching q = 0)
/// passed the scene reader and failed later without the scene file or line.
#[test]
fn model_domain_errors_name_the_key_and_line() {
    let cases = [
        (
            "hurst = 0.8",
            "hurst = 7.6e19",
            "fuzz.toml:4: roughness.hurst",
        ),
        (
            "q1 = \"1e8 1/m\"",
            "q1 = \"1e4 1/m\"",
            "fuzz.toml:6: roughness.q1",
        ),
        (
            "rms_slope = 1",
            "rms_slope = 1\nroll_off = \"1e9 1/m\"",
            "fuzz.toml:8: roughness.roll_off",
        ),
    ];
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fuzz.toml");
    for (from, to, needle) in cases {
        std::fs::write(&path, SCENE.replace(from, to)).unwrap();
        let e = Scene::load(Some(&path), &[], library())
            .unwrap_err()
            .to_string();
        assert!(e.contains(needle), "{e}");
    }
    let gaussian = SCENE
        .replace("\"self-affine\"", "\"gaussian\"")
        .replace("hurst = 0.8\n", "")
        .replace("q1 = \"1e8 1/m\"", "width = \"1e5 1/m\"");
    std::fs::write(&path, gaussian).unwrap();
    let e = Scene::load(Some(&path), &[], library())
        .unwrap_err()
        .to_string();
    assert!(e.contains("fuzz.toml:5: roughness.width"), "{e}");
}

/// Found by `scene_reader_loads_or_names_file_and_line` (long run): absurd magnitudes (a
/// wavenumber of 1e308 1/m, an rms slope of 1e308) passed the scene reader and overflowed in
/// the contact integrals (a debug assertion in the quadrature, a bare numerical failure in
/// release). They are now rejected at their line; so is a measured spectrum whose rms slope is
/// absurd (C in a wrong unit), naming its file.
#[test]
fn absurd_magnitudes_are_rejected_at_their_line() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fuzz.toml");
    for (from, to, needle) in [
        (
            "q1 = \"1e8 1/m\"",
            "q1 = \"1e308\"",
            "fuzz.toml:6: roughness.q1",
        ),
        (
            "rms_slope = 1",
            "rms_slope = \"1e308\"",
            "fuzz.toml:7: roughness.rms_slope",
        ),
        (
            "thickness = \"10 um\"",
            "thickness = 1e-300",
            "fuzz.toml:10: film.thickness",
        ),
        (
            "pressure = \"0.1 MPa\"",
            "pressure = 1e300",
            "fuzz.toml:16: load.pressure",
        ),
    ] {
        std::fs::write(&path, SCENE.replace(from, to)).unwrap();
        let e = Scene::load(Some(&path), &[], library())
            .unwrap_err()
            .to_string();
        assert!(e.contains(needle) && e.contains("outside"), "{e}");
    }
    std::fs::write(
        dir.path().join("s.csv"),
        // Units stated: the file is taken as SI, and the scene's rms-slope range rejects it.
        "q (1/m),C (m^4)\n1e5,1e290\n1e6,1e280\n1e7,1e270\n",
    )
    .unwrap();
    let measured = SCENE
        .replace("model = \"self-affine\"", "psd = \"s.csv\"")
        .replace("hurst = 0.8\n", "")
        .replace("q0 = \"1e5 1/m\"\n", "")
        .replace("q1 = \"1e8 1/m\"\n", "")
        .replace("rms_slope = 1\n", "");
    std::fs::write(&path, measured).unwrap();
    let scene = Scene::load(Some(&path), &[], library()).unwrap();
    let e = judge(&scene, None).unwrap_err().to_string();
    assert!(
        e.contains("fuzz.toml:3: ") && e.contains("rms slope") && e.contains("s.csv"),
        "{e}"
    );
}

// ---------------------------------------------------------------- the instrument readers

/// The instrument sample files of tests/data/instrument/, with their bytes.
fn instrument_files() -> &'static [(String, Vec<u8>)] {
    static FILES: OnceLock<Vec<(String, Vec<u8>)>> = OnceLock::new();
    FILES.get_or_init(|| {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/instrument");
        let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| !p.extension().is_some_and(|x| x == "md" || x == "py"))
            .map(|p| {
                let name = p.file_name().unwrap().to_string_lossy().into_owned();
                (name, std::fs::read(&p).unwrap())
            })
            .collect();
        files.sort();
        files
    })
}

/// A damaged copy of an instrument file: cut short at a fraction of its length, or with
/// bytes overwritten at fractions of it (headers and sizes sit near the start, so half the
/// positions fall in the first 4 KiB).
#[derive(Debug, Clone)]
enum Damage {
    Truncate(f64),
    Flip(Vec<(bool, f64, u8)>),
}

fn damage() -> impl Strategy<Value = Damage> {
    prop_oneof![
        (0.0..1.0f64).prop_map(Damage::Truncate),
        prop::collection::vec((any::<bool>(), 0.0..1.0f64, any::<u8>()), 1..8)
            .prop_map(Damage::Flip),
    ]
}

fn damaged(bytes: &[u8], d: &Damage) -> Vec<u8> {
    match d {
        Damage::Truncate(f) => bytes[..(bytes.len() as f64 * f) as usize].to_vec(),
        Damage::Flip(flips) => {
            let mut b = bytes.to_vec();
            for &(head, f, v) in flips {
                let span = if head { b.len().min(4096) } else { b.len() };
                let i = ((span as f64 * f) as usize).min(b.len() - 1);
                b[i] = v;
            }
            b
        }
    }
}

proptest! {
    #![proptest_config(config(64))]

    /// A truncated or corrupted instrument file reads or is refused naming the file; never a
    /// panic.
    #[test]
    fn instrument_readers_read_or_name_the_file(
        i in 0..instrument_files().len(),
        d in damage(),
    ) {
        let (name, bytes) = &instrument_files()[i];
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(name);
        std::fs::write(&path, damaged(bytes, &d)).unwrap();
        if let Err(e) = coatcheck::instrument::read(&path) {
            let msg = e.to_string();
            prop_assert!(msg.contains(name.as_str()), "{name}: {msg}");
        }
    }
}

proptest! {
    #![proptest_config(config(32))]

    /// A truncated or corrupted height map (the bundled example's CSV) reads or is refused
    /// naming the file; never a panic.
    #[test]
    fn height_map_reader_reads_or_names_the_file(d in damage()) {
        static MAP: OnceLock<Vec<u8>> = OnceLock::new();
        let bytes = MAP.get_or_init(|| {
            std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/data/height-map.csv"))
                .unwrap()
        });
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("map.csv");
        std::fs::write(&path, damaged(bytes, &d)).unwrap();
        let opts = coatcheck::topography::io::MapOptions::default();
        match coatcheck::topography::io::read_height_map(&path, &opts) {
            Ok(map) => prop_assert!(map.z.iter().all(|z| z.is_finite())),
            Err(e) => {
                let msg = e.to_string();
                prop_assert!(msg.contains("map.csv"), "{msg}");
            }
        }
    }
}
