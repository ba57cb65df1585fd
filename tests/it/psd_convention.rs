//! PSD normalisations (`--psd-convention`) and contact.engineering downloads
//! (tests/data/ce/: CSV and TXT written by `make_ce.py` in contact.engineering's layout from an
//! exact self-affine spectrum with h_rms = 1 µm over q0 = 1e4 … q1 = 1e7 1/m, H = 0.8).

use coatcheck::psd::Spectrum;
use coatcheck::psd::convention::Convention;
use coatcheck::psd::read::{ReadOptions, read_spectrum};
use std::path::Path;

const CSV: &str = "tests/data/ce/ce-power-spectrum.csv";
const TXT: &str = "tests/data/ce/ce-power-spectrum.txt";

fn read(path: &str, opts: &ReadOptions) -> (Spectrum, Vec<String>) {
    let (t, w) = read_spectrum(Path::new(path), opts).unwrap_or_else(|e| panic!("{e}"));
    (Spectrum::Tabulated(t), w)
}

fn series(name: &str) -> ReadOptions {
    ReadOptions {
        series: Some(name.into()),
        ..ReadOptions::default()
    }
}

/// h_rms² of the generating spectrum over [q0, q_last]: h² (1 − (q0/q)^{2H}) / (1 − (q0/q1)^{2H}).
fn exact_h2(q_last: f64) -> f64 {
    let (h, q0, q1) = (0.8, 1e4, 1e7);
    1e-12 * (1.0 - (q0 / q_last).powf(2.0 * h)) / (1.0 - (q0 / q1).powf(2.0 * h))
}

#[test]
fn ce_csv_and_txt_give_the_2d_series_with_its_exact_h_rms() {
    let (csv, w) = read(CSV, &ReadOptions::default());
    assert!(
        w[0].contains("q/π × 2D PSD") && w[0].contains("surfacetopography"),
        "{w:?}"
    );
    let (txt, _) = read(TXT, &ReadOptions::default());
    assert_eq!(csv, txt, "the CSV and the TXT hold the same numbers");
    let Spectrum::Tabulated(t) = &csv else {
        unreachable!()
    };
    let q_last = *t.q().last().unwrap();
    // A power law between points is integrated exactly: only rounding remains.
    let h2 = csv.h_rms_sq().value;
    assert!((h2 / exact_h2(q_last) - 1.0).abs() < 1e-9, "{h2:e}");
}

#[test]
fn ce_series_are_chosen_by_name_and_1d_series_converted() {
    let (x, _) = read(TXT, &series("1D PSD along x"));
    let (y, _) = read(
        CSV,
        &series("synthetic self-affine H = 0.8: 1D PSD along y"),
    );
    // The y series is 1.1 times the x series; the 1D → 2D conversion is linear.
    let (hx, hy) = (x.h_rms_sq().value, y.h_rms_sq().value);
    assert!((hy / hx - 1.1).abs() < 1e-9, "{hx:e} {hy:e}");
    // From the 1D series, through π C1D_ST → C1D and the inverse Abel transform, the 2D
    // spectrum's h_rms² is the generating one within the conversion's accuracy at the ends
    // (the last octave depends on the tail's continuation): 3 %.
    let Spectrum::Tabulated(t) = &x else {
        unreachable!()
    };
    let rel = hx / exact_h2(*t.q().last().unwrap()) - 1.0;
    assert!(rel.abs() < 0.03, "{rel}");
}

#[test]
fn ce_errors_list_the_series_and_refuse_another_convention() {
    let e = read_spectrum(Path::new(TXT), &series("PSD"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains(TXT) && e.contains("'synthetic self-affine H = 0.8: 1D PSD along x'"),
        "{e}"
    );
    let opts = ReadOptions {
        convention: Some(Convention::Persson),
        ..ReadOptions::default()
    };
    let e = read_spectrum(Path::new(CSV), &opts)
        .unwrap_err()
        .to_string();
    assert!(e.contains("surfacetopography"), "{e}");
    // A series in a plain two-column file is an error, not ignored.
    let e = read_spectrum(Path::new("examples/measured-rolloff.csv"), &series("x"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("not a contact.engineering download"), "{e}");
}

/// A plain file of `q, c` with a header giving the units.
fn plain(dir: &Path, name: &str, unit: &str, rows: &[(f64, f64)]) -> String {
    let path = dir.join(name);
    let mut text = format!("q (1/m),C ({unit})\n");
    for (q, c) in rows {
        text += &format!("{q:e},{c:e}\n");
    }
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

#[test]
fn conventions_scale_plain_files_by_their_factors() {
    let dir = tempfile::tempdir().unwrap();
    let qs: Vec<f64> = (0..40).map(|i| 1e4 * 10f64.powf(i as f64 / 10.0)).collect();
    let c2: Vec<(f64, f64)> = qs
        .iter()
        .map(|&q| (q, 1e-20 * (q / 1e4).powf(-3.6)))
        .collect();
    let c1: Vec<(f64, f64)> = qs
        .iter()
        .map(|&q| (q, 1e-16 * (q / 1e4).powf(-2.6)))
        .collect();
    let scaled =
        |rows: &[(f64, f64)], f: f64| rows.iter().map(|&(q, c)| (q, c * f)).collect::<Vec<_>>();
    let four_pi2 = 4.0 * std::f64::consts::PI.powi(2);
    let cases = [
        // (rows in this tool's convention, unit, the file's rows, convention)
        (
            &c2,
            "m^4",
            scaled(&c2, four_pi2),
            Convention::SurfaceTopography,
        ),
        (&c2, "m^4", c2.clone(), Convention::Persson),
        (
            &c1,
            "m^3",
            scaled(&c1, std::f64::consts::PI),
            Convention::SurfaceTopography,
        ),
        (&c1, "m^3", scaled(&c1, 0.5), Convention::Persson),
    ];
    for (i, (own, unit, theirs, convention)) in cases.into_iter().enumerate() {
        let a = plain(dir.path(), &format!("own{i}.csv"), unit, own);
        let b = plain(dir.path(), &format!("theirs{i}.csv"), unit, &theirs);
        let (sa, _) = read(&a, &ReadOptions::default());
        let opts = ReadOptions {
            convention: Some(convention),
            ..ReadOptions::default()
        };
        let (sb, w) = read(&b, &opts);
        let (ha, hb) = (sa.h_rms_sq().value, sb.h_rms_sq().value);
        assert!((hb / ha - 1.0).abs() < 1e-12, "case {i}: {ha:e} vs {hb:e}");
        assert!(w.iter().any(|w| w.contains(convention.name())), "{w:?}");
    }
}
