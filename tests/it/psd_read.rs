//! The spectrum reader (`psd::read`): layouts users have, and bad input named by file and line.

use coatcheck::Error;
use coatcheck::psd::abel::Conversion;
use coatcheck::psd::read::{Column, PsdKind, ReadOptions, parse_spectrum, read_spectrum};
use std::path::{Path, PathBuf};

fn write(name: &str, bytes: &[u8]) -> PathBuf {
    let p = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("psd_read_{name}"));
    std::fs::write(&p, bytes).unwrap();
    p
}

/// (q, C, warnings) of a parsed spectrum.
type Parsed = (Vec<f64>, Vec<f64>, Vec<String>);

fn parse(text: &str, opts: &ReadOptions) -> Result<Parsed, Error> {
    parse_spectrum(text, Path::new("spec.csv"), opts)
        .map(|(t, w)| (t.q().to_vec(), t.c_values().to_vec(), w))
}

fn close(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| (x - y).abs() <= 1e-14 * y.abs())
}

/// The (line, message) of an input error, or a panic naming what came instead.
fn input_err(r: Result<Parsed, Error>) -> (usize, String) {
    match r {
        Err(Error::Input { path, line, msg }) => {
            assert_eq!(path, Path::new("spec.csv"));
            (line, msg)
        }
        other => panic!("expected an input error, got {other:?}"),
    }
}

#[test]
fn header_units_are_applied() {
    let (q, c, w) = parse(
        "q (1/um),C (um^4)\n1,2e-3\n2,1e-4\n",
        &ReadOptions::default(),
    )
    .unwrap();
    assert!(close(&q, &[1e6, 2e6]));
    assert!(close(&c, &[2e-27, 1e-28]));
    assert!(w.is_empty(), "{w:?}");
}

#[test]
fn whitespace_header_with_spaced_units_and_brackets() {
    let (q, c, _) = parse(
        "# exported by some tool\nq [1/m]   C [nm^4]\n1e5   3\n2e5   1.5\n",
        &ReadOptions::default(),
    )
    .unwrap();
    assert!(close(&q, &[1e5, 2e5]));
    assert!(close(&c, &[3e-36, 1.5e-36]));
}

#[test]
fn bom_crlf_comments_tabs_and_decimal_commas() {
    let text =
        "\u{feff}% comment\r\nq\tC\r\n\r\n1,5e5\t2,0e-20\r\n// another comment\r\n3e5\t1e-21\r\n";
    let (q, c, _) = parse(text, &ReadOptions::default()).unwrap();
    assert!(close(&q, &[1.5e5, 3e5]));
    assert!(close(&c, &[2e-20, 1e-21]));
    let (q, c, _) = parse("q;C\n1,5e5;2e-20\n3e5;1e-21\n", &ReadOptions::default()).unwrap();
    assert!(close(&q, &[1.5e5, 3e5]));
    assert!(close(&c, &[2e-20, 1e-21]));
}

#[test]
fn bom_read_from_a_file() {
    let p = write("bom.csv", b"\xef\xbb\xbfq,C\r\n1e5,1e-20\r\n2e5,1e-21\r\n");
    let (t, _) = read_spectrum(&p, &ReadOptions::default()).unwrap();
    assert!(close(t.q(), &[1e5, 2e5]));
}

#[test]
fn columns_by_name_and_index_and_default() {
    let text = "x,q (1/m),C raw (m^4),C smooth (m^4)\n0,1e5,1e-20,2e-20\n0,2e5,1e-21,2e-21\n";
    let (q, c, _) = parse(text, &ReadOptions::default()).unwrap();
    assert!(close(&q, &[1e5, 2e5]));
    assert!(close(&c, &[1e-20, 1e-21]));
    let by_name = ReadOptions {
        c_col: Some("c smooth".parse().unwrap()),
        ..Default::default()
    };
    let (_, c, _) = parse(text, &by_name).unwrap();
    assert!(close(&c, &[2e-20, 2e-21]));
    let by_index = ReadOptions {
        q_col: Some(Column::Index(2)),
        c_col: Some("4".parse().unwrap()),
        ..Default::default()
    };
    let (_, c, _) = parse(text, &by_index).unwrap();
    assert!(close(&c, &[2e-20, 2e-21]));
    // No header: columns 1 and 2.
    let (q, _, _) = parse("1e5 1e-20 7\n2e5 1e-21 7\n", &ReadOptions::default()).unwrap();
    assert!(close(&q, &[1e5, 2e5]));
    assert!("0".parse::<Column>().is_err());
}

#[test]
fn unrecognised_header_names_fall_back_with_a_warning() {
    let (q, _, w) = parse("a,b\n1e5,1e-20\n2e5,1e-21\n", &ReadOptions::default()).unwrap();
    assert!(close(&q, &[1e5, 2e5]));
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(w[0].contains("column 1 ('a')"), "{w:?}");
}

#[test]
fn flag_units_override_the_header_with_a_warning() {
    let opts = ReadOptions {
        q_unit: Some("1/um".into()),
        c_unit: Some("um^4".into()),
        ..Default::default()
    };
    let (q, c, w) = parse("q (1/m),C (m^4)\n1,1\n2,0.5\n", &opts).unwrap();
    assert!(close(&q, &[1e6, 2e6]));
    assert!(close(&c, &[1e-24, 0.5e-24]));
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(w[0].contains("spec.csv:1:"), "{w:?}");
}

#[test]
fn unsorted_q_is_sorted_with_a_warning_naming_the_line() {
    let (q, c, w) = parse(
        "q,C\n3e5,1e-22\n1e5,1e-20\n2e5,1e-21\n",
        &ReadOptions::default(),
    )
    .unwrap();
    assert!(close(&q, &[1e5, 2e5, 3e5]));
    assert!(close(&c, &[1e-20, 1e-21, 1e-22]));
    assert_eq!(w.len(), 1);
    assert!(w[0].starts_with("spec.csv:3:"), "{w:?}");
}

#[test]
fn bad_rows_are_errors_with_their_line() {
    let cases: &[(&str, usize, &str)] = &[
        ("q,C\n1e5,1e-20\n2e5,1e-20\n1e5,3e-21\n", 4, "duplicate q"),
        (
            "q,C\n1e5,1e-20\n2e5,-1e-21\n",
            3,
            "expected a finite value > 0",
        ),
        ("q,C\n1e5,1e-20\n0,1e-21\n", 3, "q = 0"),
        ("q,C\n1e5,nan\n2e5,1e-21\n", 2, "C = nan"),
        (
            "q,C\n1e5,inf\n2e5,1e-21\n",
            2,
            "expected a finite value > 0",
        ),
        (
            "q,C\n# c\n1e5,1e-20\n2e5,abc\n",
            4,
            "expected a number for C in column 2, found 'abc'",
        ),
        ("q,C\n1e5,1e-20\n2e5\n", 3, "expected at least 2 columns"),
        ("q,C\n1e5,1e-20\n", 2, "expected at least 2 rows"),
        ("q,C\n", 1, "found 0 data row(s)"),
        ("", 1, "no data"),
        ("# only comments\n\n", 1, "no data"),
        ("q (furlong),C\n1,1\n2,1\n", 1, "unknown unit 'furlong'"),
        ("q,C (um^2)\n1,1\n2,1\n", 1, "neither a length^4"),
        ("f (1/um),C (um^4)\n1,1\n2,1\n", 1, "spatial frequency"),
        ("lambda (um),C (um^4)\n1,1\n2,1\n", 1, "wavelength"),
    ];
    for &(text, line, needle) in cases {
        let (l, msg) = input_err(parse(text, &ReadOptions::default()));
        assert_eq!(l, line, "{text:?}: {msg}");
        assert!(msg.contains(needle), "{text:?}: '{msg}' lacks '{needle}'");
    }
}

#[test]
fn bad_column_choices_are_errors() {
    let name_no_header = ReadOptions {
        c_col: Some(Column::Name("C".into())),
        ..Default::default()
    };
    let (l, msg) = input_err(parse("\n1e5,1e-20\n2e5,1e-21\n", &name_no_header));
    assert_eq!(l, 2);
    assert!(msg.contains("no header line"), "{msg}");
    let unknown = ReadOptions {
        c_col: Some(Column::Name("PSD".into())),
        ..Default::default()
    };
    let (l, msg) = input_err(parse("q,C\n1e5,1e-20\n2e5,1e-21\n", &unknown));
    assert_eq!(l, 1);
    assert!(
        msg.contains("no column named 'PSD'") && msg.contains("q, C"),
        "{msg}"
    );
    let too_far = ReadOptions {
        c_col: Some(Column::Index(5)),
        ..Default::default()
    };
    let (l, msg) = input_err(parse("q,C\n1e5,1e-20\n2e5,1e-21\n", &too_far));
    assert_eq!(l, 1);
    assert!(msg.contains("only 2 columns"), "{msg}");
    let same = ReadOptions {
        q_col: Some(Column::Index(2)),
        ..Default::default()
    };
    let (_, msg) = input_err(parse("q,C\n1e5,1e-20\n2e5,1e-21\n", &same));
    assert!(msg.contains("both read from column 2"), "{msg}");
}

#[test]
fn file_errors() {
    let missing = Path::new(env!("CARGO_TARGET_TMPDIR")).join("psd_read_missing.csv");
    assert!(matches!(
        read_spectrum(&missing, &ReadOptions::default()),
        Err(Error::Io { .. })
    ));
    let p = write("latin1.csv", b"q,C\n1e5,1e-20\n2e5,1e-21 \xb5m\n");
    match read_spectrum(&p, &ReadOptions::default()) {
        Err(Error::Input { line, msg, .. }) => {
            assert_eq!(line, 3);
            assert!(msg.contains("UTF-8"), "{msg}");
        }
        other => panic!("{other:?}"),
    }
}

/// A 2D PSD C(k) = (1 + k²/k0²)^−(1+H) and its one-sided 1D PSD in closed form,
/// C1D(q) = 2√π Γ(H+½)/Γ(H+1) · √(k0² + q²) · (1 + q²/k0²)^−(1+H).
fn lorentz_pair(h: f64, k0: f64) -> (impl Fn(f64) -> f64, impl Fn(f64) -> f64) {
    let g = statrs::function::gamma::gamma;
    let a = 2.0 * std::f64::consts::PI.sqrt() * g(h + 0.5) / g(h + 1.0);
    let c2 = move |k: f64| (1.0 + (k / k0).powi(2)).powf(-(1.0 + h));
    let c1 = move |q: f64| a * (k0 * k0 + q * q).sqrt() * (1.0 + (q / k0).powi(2)).powf(-(1.0 + h));
    (c2, c1)
}

#[test]
fn one_d_psd_is_converted_exactly() {
    // 20 points per decade of the closed-form C1D in nm^3 with q in 1/um; the exact inverse
    // Abel transform must give back C(k) (m^4) within 5e-4 (measured 2.8e-4, the cubic
    // interpolation error of the tabulated C1D).
    let (c2, c1) = lorentz_pair(0.8, 1e5);
    let q: Vec<f64> = (0..=100)
        .map(|i| 1e3 * 10f64.powf(i as f64 / 20.0))
        .collect();
    let mut text = String::from("q (1/um), PSD (nm^3)\n");
    for &x in &q {
        text += &format!("{:.17e}, {:.17e}\n", x * 1e-6, c1(x) * 1e27);
    }
    let (qs, cs, w) = parse(&text, &ReadOptions::default()).unwrap();
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].contains("inverse Abel"), "{w:?}");
    for (x, c) in qs.iter().zip(&cs) {
        let r = c / c2(*x) - 1.0;
        assert!(r.abs() < 5e-4, "q = {x:e}: relative error {r:e}");
    }
    // The same file with the kind stated but no unit: identical result.
    let plain = text.replace(" (1/um)", "").replace(" (nm^3)", "");
    let opts = ReadOptions {
        kind: Some(PsdKind::OneD),
        q_unit: Some("1/um".into()),
        c_unit: Some("nm^3".into()),
        ..Default::default()
    };
    let (_, cs2, _) = parse(&plain, &opts).unwrap();
    assert!(close(&cs2, &cs));
    // The shortcut is available by name and is what it says.
    let short = ReadOptions {
        conversion: Conversion::PiQShortcut,
        ..Default::default()
    };
    let (qs3, cs3, w3) = parse(&text, &short).unwrap();
    assert!(w3[0].contains("shortcut"), "{w3:?}");
    let expect: Vec<f64> = qs3
        .iter()
        .map(|&x| c1(x) / (std::f64::consts::PI * x))
        .collect();
    for (a, b) in cs3.iter().zip(&expect) {
        assert!((a / b - 1.0).abs() < 1e-13);
    }
}

#[test]
fn one_d_psd_errors() {
    // A 1D unit while a 2D PSD was requested.
    let opts = ReadOptions {
        kind: Some(PsdKind::TwoD),
        ..Default::default()
    };
    let (l, msg) = input_err(parse("q,C (m^3)\n1e5,1e-10\n2e5,1e-11\n", &opts));
    assert_eq!(l, 1);
    assert!(msg.contains("1D (m^3)"), "{msg}");
    // A noise floor at the high-q end cannot be continued.
    let (l, msg) = input_err(parse(
        "q,C (m^3)\n1e5,1e-10\n2e5,1e-11\n4e5,1e-12\n6e5,1e-12\n8e5,1e-12\n",
        &ReadOptions::default(),
    ));
    assert_eq!(l, 4, "{msg}");
    assert!(msg.contains("faster than 1/q"), "{msg}");
    // A C1D that rises steeply cannot come from an isotropic surface: C < 0 somewhere.
    let (l, msg) = input_err(parse(
        "q,C (m^3)\n1e5,1e-14\n1.1e5,1e-10\n2e5,1e-12\n4e5,1e-13\n8e5,1e-14\n",
        &ReadOptions::default(),
    ));
    assert_eq!(l, 2, "{msg}");
    assert!(msg.contains("expected C > 0"), "{msg}");
}
