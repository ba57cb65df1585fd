//! `check --q-col/--c-col/--q-unit/--c-unit/--psd-kind` (scene keys roughness.q_col, c_col,
//! q_unit, c_unit, psd_kind): the same spectrum written in other units, column orders and as a
//! 1D PSD gives the same contact numbers as the SI file; bad values are exit 2 naming the key.

use crate::common::{json, run};

/// A self-affine PSD (H = 0.8) at 9 points per decade, in SI.
fn points() -> Vec<(f64, f64)> {
    (0..=27)
        .map(|i| {
            let q = 1e5 * 10f64.powf(i as f64 / 9.0);
            (q, 1e-21 * (q / 1e5).powf(-3.6))
        })
        .collect()
}

fn check(psd: &std::path::Path, extra: &[&str]) -> serde_json::Value {
    let mut args = vec![
        "check",
        "examples/paper-rubber-on-steel.toml",
        "--psd",
        psd.to_str().unwrap(),
        "--rms-slope",
        "0.5",
        "--checks",
        "bond-shear",
        "--format",
        "json",
    ];
    args.extend(extra);
    let o = run(&args);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    json(&o)
}

#[test]
fn columns_and_units_from_flags_give_the_si_result() {
    let dir = tempfile::tempdir().unwrap();
    let si = dir.path().join("si.csv");
    let text: String = points()
        .iter()
        .map(|(q, c)| format!("{q:e},{c:e}\n"))
        .collect();
    std::fs::write(&si, format!("q,C\n{text}")).unwrap();
    let want = check(&si, &[]);
    // Columns the header cannot identify, in another order, q in 1/um and C in um^4.
    let other = dir.path().join("other.csv");
    let text: String = points()
        .iter()
        .map(|(q, c)| format!("7;{:e};{:e}\n", c * 1e24, q * 1e-6))
        .collect();
    std::fs::write(&other, format!("id;power;wavenumber\n{text}")).unwrap();
    let got = check(
        &other,
        &[
            "--q-col",
            "wavenumber",
            "--c-col",
            "2",
            "--q-unit",
            "1/um",
            "--c-unit",
            "um^4",
        ],
    );
    for key in ["area_fraction", "tau_rms_interface_pa", "tau_peak_pa"] {
        let (a, b) = (want[key].as_f64().unwrap(), got[key].as_f64().unwrap());
        assert!((a - b).abs() <= 1e-12 * a, "{key}: {a} vs {b}");
    }
}

/// `coatcheck psd` on line scans writes C (2D, from the exact inverse Abel transform) and C1D;
/// reading the C1D column as a 1D PSD runs the same conversion and gives the same result.
#[test]
fn a_1d_psd_column_is_converted_like_the_psd_command() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("lines.csv");
    let o = run(&[
        "psd",
        "examples/data/line-scans.csv",
        "--output",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0));
    let two_d = check(&out, &[]);
    let one_d = check(&out, &["--c-col", "3", "--psd-kind", "1d"]);
    for key in ["area_fraction", "tau_rms_interface_pa"] {
        let (a, b) = (two_d[key].as_f64().unwrap(), one_d[key].as_f64().unwrap());
        assert!((a - b).abs() <= 1e-9 * a, "{key}: {a} vs {b}");
    }
}

#[test]
fn bad_format_values_name_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("lines.csv");
    run(&[
        "psd",
        "examples/data/line-scans.csv",
        "--output",
        out.to_str().unwrap(),
    ]);
    for (flag, value, want) in [
        ("--psd-kind", "3d", "roughness.psd_kind"),
        ("--q-col", "0", "roughness.q_col"),
        ("--c-unit", "m^2", "unit of C"),
    ] {
        let o = run(&[
            "check",
            "examples/paper-rubber-on-steel.toml",
            "--psd",
            out.to_str().unwrap(),
            flag,
            value,
        ]);
        assert_eq!(o.status.code(), Some(2), "{flag} {value}");
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(e.contains(want) && e.lines().count() == 1, "{e}");
    }
}
