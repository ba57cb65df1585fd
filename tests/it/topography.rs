//! Heights → PSD (`topography::spectrum`), the synthetic generator, and the readers.

use coatcheck::psd::{Spectrum, Tabulated};
use coatcheck::topography::spectrum::{PsdOptions, map_psd, profile_c1d, profile_psd};
use coatcheck::topography::synth::{Amplitude, SynthSpec, self_affine_map};
use coatcheck::topography::{HeightMap, Profile};
use std::f64::consts::PI;

const N: usize = 256;
const DX: f64 = 1e-6;

fn q_fund() -> f64 {
    2.0 * PI / (N as f64 * DX)
}

/// H = 0.8, roll-off at 8 q_L, cut-off q1 at half the Nyquist wavenumber, rms height 1 µm.
fn spec(seed: u64) -> SynthSpec {
    SynthSpec {
        n: N,
        dx: DX,
        hurst: 0.8,
        q0: 8.0 * q_fund(),
        q1: 64.0 * q_fund(),
        amplitude: Amplitude::RmsHeight(1e-6),
        seed,
    }
}

fn all_modes() -> PsdOptions {
    PsdOptions {
        cutoff_pixels: 2.0,
        ..Default::default()
    }
}

/// 2π∫ q C dq of a tabulated 2D PSD.
fn h2_of(c2d: &Tabulated) -> f64 {
    Spectrum::Tabulated(c2d.clone()).h_rms_sq().value
}

/// ∫ C1D dq of a tabulated one-sided 1D PSD.
fn h2_of_1d(c1d: &Tabulated) -> f64 {
    Spectrum::Tabulated(c1d.clone()).moment(-1).value / (2.0 * PI)
}

#[test]
fn synth_map_has_the_requested_rms_and_is_reproducible() {
    let m = self_affine_map(&spec(7)).unwrap();
    assert!((m.rms() / 1e-6 - 1.0).abs() < 1e-12, "{}", m.rms());
    assert_eq!(m, self_affine_map(&spec(7)).unwrap());
    assert_ne!(m.z, self_affine_map(&spec(8)).unwrap().z);
    let slope = SynthSpec {
        amplitude: Amplitude::RmsSlope(0.5),
        ..spec(7)
    };
    let p = map_psd(&self_affine_map(&slope).unwrap(), &all_modes()).unwrap();
    assert!(
        (p.summary.rms_slope / 0.5 - 1.0).abs() < 1e-12,
        "{:?}",
        p.summary
    );
}

#[test]
fn parseval_map_without_window() {
    // Discrete Parseval is exact; the binned, interpolated PSD integrates to within 3 %.
    let m = self_affine_map(&spec(1)).unwrap();
    let p = map_psd(&m, &all_modes()).unwrap();
    let s = p.summary;
    assert!((s.h_rms / m.rms() - 1.0).abs() < 1e-12);
    assert!((s.h_rms_kept / s.h_rms - 1.0).abs() < 1e-12, "{s:?}");
    assert!(s.outside_fraction < 1e-12);
    let r = h2_of(&p.c2d) / s.h_rms.powi(2);
    eprintln!("map, no window: 2π∫qC dq / h_rms² = {r}");
    assert!((r - 1.0).abs() < 0.03, "{r}");
}

#[test]
fn parseval_map_with_hann_window() {
    // Surfaces treated as non-periodic: Hann window, power loss corrected by 1/<w²>. Parseval
    // then holds on average over realisations, not exactly for one map (the window weighs the
    // centre); with the roll-off at 32 q_L each map holds ~1000 independent patches. Tolerance:
    // 4 % per map, 2 % for the mean over four maps, mode sum and binned PSD alike.
    let (mut sum_modes, mut sum_psd) = (0.0, 0.0);
    for seed in 0..4 {
        let sp = SynthSpec {
            q0: 32.0 * q_fund(),
            q1: 128.0 * q_fund(),
            ..spec(seed)
        };
        let mut m = self_affine_map(&sp).unwrap();
        m.periodic = false;
        let p = map_psd(&m, &all_modes()).unwrap();
        assert!(p.steps.iter().any(|s| s.starts_with("window: hann")));
        let s = p.summary;
        let r_modes = (s.h_rms_kept / s.h_rms).powi(2);
        let r = h2_of(&p.c2d) / s.h_rms.powi(2);
        eprintln!("map, Hann, seed {seed}: mode sum / h_rms² = {r_modes}, 2π∫qC dq / h_rms² = {r}");
        assert!((r_modes - 1.0).abs() < 0.04, "{r_modes}");
        assert!((r - 1.0).abs() < 0.04, "{r}");
        sum_modes += r_modes / 4.0;
        sum_psd += r / 4.0;
    }
    assert!((sum_modes - 1.0).abs() < 0.02, "{sum_modes}");
    assert!((sum_psd - 1.0).abs() < 0.02, "{sum_psd}");
}

fn cos_map(waves: &[(f64, usize, usize)]) -> HeightMap {
    // Sum of a·cos(2π(mx x/L + my y/L) + phase): each on the grid's modes, periodic.
    let mut z = vec![0.0; N * N];
    for iy in 0..N {
        for ix in 0..N {
            z[iy * N + ix] = waves
                .iter()
                .map(|&(a, mx, my)| {
                    a * (2.0 * PI * (mx * ix + my * iy) as f64 / N as f64 + 0.3).cos()
                })
                .sum();
        }
    }
    HeightMap {
        nx: N,
        ny: N,
        dx: DX,
        dy: DX,
        z,
        periodic: true,
    }
}

#[test]
fn a_sinusoid_lands_at_its_q_with_its_height() {
    let a = 0.2e-6;
    let m = cos_map(&[(a, 12, 5)]);
    let p = map_psd(&m, &all_modes()).unwrap();
    let q_true = q_fund() * 13.0; // |(12, 5)| = 13
    let (q, c) = (p.c2d.q(), p.c2d.c_values());
    let peak = (0..q.len()).max_by(|&i, &j| c[i].total_cmp(&c[j])).unwrap();
    // The peak bin (mean q of its modes) is the one holding q_true: within half a bin.
    assert!(
        (q[peak] / q_true).log10().abs() <= 0.05,
        "{} vs {q_true}",
        q[peak]
    );
    assert!((p.summary.h_rms_kept / (a / 2f64.sqrt()) - 1.0).abs() < 1e-12);
    // Everything else is rounding.
    let rest: f64 = (0..q.len()).filter(|&i| i != peak).map(|i| c[i]).sum();
    assert!(rest < 1e-20 * c[peak], "{rest:e}");
}

#[test]
fn a_sum_of_sinusoids_puts_each_power_at_its_q() {
    // a at |q| = 10 q_L, b at |q| = 50 q_L; a cut-off between them (λ ≥ 8 px ⇔ q ≤ 32 q_L)
    // keeps a alone and reports b's share of h_rms² as outside.
    let (a, b) = (0.3e-6, 0.1e-6);
    let m = cos_map(&[(a, 6, 8), (b, 30, 40)]);
    let p = map_psd(
        &m,
        &PsdOptions {
            cutoff_pixels: 8.0,
            ..Default::default()
        },
    )
    .unwrap();
    let s = p.summary;
    assert!((s.h_rms / ((a * a + b * b) / 2.0).sqrt() - 1.0).abs() < 1e-12);
    assert!(
        (s.h_rms_kept / (a / 2f64.sqrt()) - 1.0).abs() < 1e-12,
        "{s:?}"
    );
    let frac = b * b / (a * a + b * b);
    assert!((s.outside_fraction - frac).abs() < 1e-12, "{s:?}");
    assert!((s.rms_slope / (a / 2f64.sqrt() * 10.0 * q_fund()) - 1.0).abs() < 1e-12);
    // Without the cut-off both peaks show, at their q.
    let p = map_psd(&m, &all_modes()).unwrap();
    let (q, c) = (p.c2d.q(), p.c2d.c_values());
    let mut idx: Vec<usize> = (0..q.len()).collect();
    idx.sort_by(|&i, &j| c[j].total_cmp(&c[i]));
    let mut top = [q[idx[0]] / q_fund(), q[idx[1]] / q_fund()];
    top.sort_by(f64::total_cmp);
    assert!(
        (top[0] / 10.0).log10().abs() <= 0.05 && (top[1] / 50.0).log10().abs() <= 0.05,
        "{top:?}"
    );
}

/// Log–log least-squares slope of C over q in [lo, hi].
fn slope(t: &Tabulated, lo: f64, hi: f64) -> f64 {
    let pts: Vec<(f64, f64)> = t
        .q()
        .iter()
        .zip(t.c_values())
        .filter(|(q, _)| **q >= lo && **q <= hi)
        .map(|(q, c)| (q.ln(), c.ln()))
        .collect();
    let n = pts.len() as f64;
    let (mx, my) = pts
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (sxy, sxx) = pts.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx))
    });
    sxy / sxx
}

#[test]
fn self_affine_map_gives_back_its_psd_and_hurst_exponent() {
    let sp = spec(3);
    for periodic in [true, false] {
        let mut m = self_affine_map(&sp).unwrap();
        m.periodic = periodic;
        // Periodic, no window: the periodogram is exact mode by mode (deterministic
        // amplitudes), so only the bins' convexity bias (C averaged over a bin vs C at its mean
        // q, ~s²σ²/2) is left: 20 points per decade keep it below 1 %; tolerance 2 %.
        // Hann window: it mixes neighbouring modes with random phases, a speckle-like scatter
        // of up to ±17 % per bin at 10 points per decade on one map; tolerance 25 %.
        let opts = PsdOptions {
            points_per_decade: if periodic { 20 } else { 10 },
            ..Default::default()
        };
        let p = map_psd(&m, &opts).unwrap();
        // Reliable range: above the roll-off (2 q0) and below the cut-off.
        let (lo, hi) = (2.0 * sp.q0, p.summary.q_max.min(sp.q1));
        let mut worst: f64 = 0.0;
        for (q, c) in p.c2d.q().iter().zip(p.c2d.c_values()) {
            if *q >= lo && *q <= hi {
                worst = worst.max((c / sp.c(*q) - 1.0).abs());
            }
        }
        let h = -slope(&p.c2d, lo, hi) / 2.0 - 1.0;
        eprintln!("periodic = {periodic}: max |C/C_true - 1| = {worst:.4}, H = {h:.4}");
        assert!(worst < if periodic { 0.02 } else { 0.25 }, "{worst}");
        assert!((h - sp.hurst).abs() < 0.05, "{h}");
    }
}

fn rows_as_scans(m: &HeightMap) -> Profile {
    Profile {
        dx: m.dx,
        scans: (0..m.ny).map(|iy| m.row(iy).to_vec()).collect(),
        periodic: m.periodic,
    }
}

#[test]
fn parseval_line_scans() {
    // Roughness up to the grid's corners (q1 beyond √2 × Nyquist), so that no 1D bin is empty;
    // the roll-off at 32 q_L keeps the power below the first point (q_L, where the tabulated
    // PSD starts; ~half a mode's worth) small. Tolerances: mode sum 1e-12 (periodic) or 5 %
    // (Hann), ∫C1D dq of the binned PSD 3 %.
    let sp = SynthSpec {
        q0: 32.0 * q_fund(),
        q1: 1000.0 * q_fund(),
        ..spec(4)
    };
    let m = self_affine_map(&sp).unwrap();
    for periodic in [true, false] {
        let mut pr = rows_as_scans(&m);
        pr.periodic = periodic;
        let p = profile_psd(&pr, &all_modes()).unwrap();
        let s = p.summary;
        let r_modes = (s.h_rms_kept / s.h_rms).powi(2);
        let r = h2_of_1d(p.c1d.as_ref().unwrap()) / s.h_rms.powi(2);
        eprintln!("lines, periodic = {periodic}: mode sum {r_modes}, ∫C1D dq / h² = {r}");
        if periodic {
            assert!((r_modes - 1.0).abs() < 1e-12, "{r_modes}");
        } else {
            assert!((r_modes - 1.0).abs() < 0.05, "{r_modes}");
        }
        assert!((r - 1.0).abs() < 0.03, "{r}");
    }
}

// ---------------------------------------------------------------------------------------
// Readers, writers and the command line.

use coatcheck::Error;
use coatcheck::topography::io::{
    HeightKind, MapOptions, ProfileOptions, parse_profile, read_height_map, read_profile, sniff,
    write_height_map, write_profile,
};
use std::path::{Path, PathBuf};

fn tmp(name: &str) -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("topo_{name}"))
}

fn write_tmp(name: &str, text: &str) -> PathBuf {
    let p = tmp(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn input_line(r: Result<impl std::fmt::Debug, Error>) -> (usize, String) {
    match r {
        Err(Error::Input { line, msg, .. }) => (line, msg),
        other => panic!("expected an input error, got {other:?}"),
    }
}

#[test]
fn height_map_round_trips_through_its_file() {
    let m = self_affine_map(&SynthSpec { n: 32, ..spec(5) }).unwrap();
    let p = tmp("map_rt.csv");
    coatcheck::report::write_with(&p, |w| write_height_map(w, &m, &["a note".into()])).unwrap();
    assert_eq!(sniff(&p).unwrap(), Some(HeightKind::Map));
    let back = read_height_map(&p, &MapOptions::default()).unwrap();
    assert_eq!(
        back, m,
        "shortest round-trip formatting must give back every bit"
    );
    // Options override the metadata; dy defaults to the given dx.
    let o = read_height_map(
        &p,
        &MapOptions {
            dx: Some(2e-6),
            z_unit: Some("um".into()),
            periodic: Some(false),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!((o.dx, o.dy, o.periodic), (2e-6, 2e-6, false));
    assert!((o.z[3] / (m.z[3] * 1e-6) - 1.0).abs() < 1e-15);
    // No temporary file of this output is left beside it (other tests write into the same
    // directory at the same time, so only this file's temporaries are looked for).
    let dir = p.parent().unwrap();
    assert!(std::fs::read_dir(dir).unwrap().all(|e| {
        let name = e.unwrap().file_name().to_string_lossy().into_owned();
        !(name.starts_with(".topo_map_rt.csv.") && name.ends_with(".tmp"))
    }));
}

#[test]
fn height_map_reader_rejects_bad_input_with_its_line() {
    let cases: &[(&str, &str, usize, &str)] = &[
        (
            "ragged",
            "# c\n1,2,3,4\n1,2,3,4\n1,2,3\n1,2,3,4\n",
            4,
            "expected 4 heights (as on line 2), found 3",
        ),
        (
            "nonnum",
            "1,2,3,4\n1,2,x,4\n1,2,3,4\n1,2,3,4\n",
            2,
            "column 3, found 'x'",
        ),
        (
            "nan",
            "1,2,3,4\n1,2,3,4\n1,NaN,3,4\n1,2,3,4\n",
            3,
            "expected a finite height",
        ),
        ("small", "1,2,3,4\n1,2,3,4\n", 2, "expected at least 4 x 4"),
        (
            "nopix",
            "1,2,3,4\n1,2,3,4\n1,2,3,4\n1,2,3,4\n",
            1,
            "needs its pixel size",
        ),
        (
            "badmeta",
            "# coatcheck height map: dx = 1 furlong\n1,2,3,4\n",
            1,
            "metadata dx",
        ),
    ];
    for &(name, text, line, needle) in cases {
        let p = write_tmp(&format!("bad_{name}.csv"), text);
        let opts = MapOptions {
            dx: (name != "nopix" && name != "badmeta").then_some(1e-6),
            ..Default::default()
        };
        let (l, msg) = input_line(read_height_map(&p, &opts));
        assert_eq!(l, line, "{name}: {msg}");
        assert!(msg.contains(needle), "{name}: '{msg}' lacks '{needle}'");
    }
}

#[test]
fn line_scans_with_x_column_units_and_round_trip() {
    let text = "x (um); z1 (nm); z2 (nm)\r\n0;1;2\r\n0,5;2;3\r\n1;3;4\r\n1,5;4;5\r\n2;5;6\r\n2,5;6;7\r\n3;7;8\r\n3,5;8;9\r\n";
    let p = parse_profile(text, Path::new("s.csv"), &ProfileOptions::default()).unwrap();
    assert!((p.dx / 0.5e-6 - 1.0).abs() < 1e-12);
    assert_eq!(p.scans.len(), 2);
    assert!((p.scans[1][7] / 9e-9 - 1.0).abs() < 1e-15);
    // Heights only, with dx given.
    let q = parse_profile(
        "1\n2\n3\n4\n5\n6\n7\n8\n",
        Path::new("s.csv"),
        &ProfileOptions {
            dx: Some(1e-6),
            z_unit: Some("um".into()),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(
        q.scans,
        vec![(1..=8).map(|v| v as f64 * 1e-6).collect::<Vec<_>>()]
    );
    // Written and read back.
    let m = self_affine_map(&SynthSpec { n: 16, ..spec(6) }).unwrap();
    let pr = Profile {
        dx: m.dx,
        scans: vec![m.row(0).to_vec(), m.row(8).to_vec()],
        periodic: true,
    };
    let path = tmp("scans_rt.csv");
    coatcheck::report::write_with(&path, |w| write_profile(w, &pr, &[])).unwrap();
    assert_eq!(sniff(&path).unwrap(), Some(HeightKind::Lines));
    let back = read_profile(&path, &ProfileOptions::default()).unwrap();
    assert_eq!(back.scans, pr.scans);
    assert!((back.dx / pr.dx - 1.0).abs() < 1e-12 && back.periodic);
}

#[test]
fn line_scan_reader_rejects_bad_input_with_its_line() {
    let rows = |extra: &str| {
        let mut s = String::from("x,z\n");
        for i in 0..8 {
            s += &format!("{i},{}\n", i * i);
        }
        s + extra
    };
    let cases: Vec<(String, ProfileOptions, usize, &str)> = vec![
        (
            rows("8\n"),
            ProfileOptions::default(),
            10,
            "expected 2 columns",
        ),
        (
            rows("8,abc\n"),
            ProfileOptions::default(),
            10,
            "found 'abc'",
        ),
        (
            rows("8,inf\n"),
            ProfileOptions::default(),
            10,
            "expected a finite value",
        ),
        (
            rows("9.5,1\n"),
            ProfileOptions::default(),
            10,
            "expected equally spaced x",
        ),
        (
            "x,z\n3,1\n2,1\n1,1\n0,1\n-1,1\n-2,1\n-3,1\n-4,1\n".into(),
            ProfileOptions::default(),
            3,
            "x must increase",
        ),
        (
            "x,z\n0,1\n1,2\n".into(),
            ProfileOptions::default(),
            1,
            "expected at least 8",
        ),
        (
            "1\n2\n3\n4\n5\n6\n7\n8\n".into(),
            ProfileOptions::default(),
            1,
            "at least one column of heights",
        ),
        (
            "z\n1\n2\n3\n4\n5\n6\n7\n8\n".into(),
            ProfileOptions::default(),
            1,
            "need the spacing dx",
        ),
        (
            rows(""),
            ProfileOptions {
                dx: Some(2.0),
                ..Default::default()
            },
            1,
            "was given but the x column has spacing",
        ),
        (
            "x (furlong),z\n".to_string() + &rows("")[4..],
            ProfileOptions::default(),
            1,
            "unknown unit",
        ),
    ];
    for (text, opts, line, needle) in cases {
        let (l, msg) = input_line(parse_profile(&text, Path::new("s.csv"), &opts));
        assert_eq!(l, line, "{text:?}: {msg}");
        assert!(msg.contains(needle), "{text:?}: '{msg}' lacks '{needle}'");
    }
}

fn coatcheck(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_coatcheck"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn cli_psd_on_the_bundled_examples() {
    let root = env!("CARGO_MANIFEST_DIR");
    let map = format!("{root}/examples/data/height-map.csv");
    let out = tmp("cli_map_psd.csv");
    let o = coatcheck(&["psd", &map, "--output", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let table = String::from_utf8_lossy(&o.stdout);
    assert!(
        table.contains("h_rms (all wavelengths)") && table.contains("0.5000 µm"),
        "{table}"
    );
    // The written PSD reads back as a spectrum, with the map's kept h_rms².
    let (t, w) = coatcheck::psd::read::read_spectrum(&out, &Default::default()).unwrap();
    assert!(w.is_empty(), "{w:?}");
    assert!(t.q().len() >= 10);
    let lines = format!("{root}/examples/data/line-scans.csv");
    let o = coatcheck(&["psd", &lines, "--format", "json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["kind"], "lines");
    assert!(v["c1d_m3"].as_array().unwrap().len() == v["q_per_m"].as_array().unwrap().len());
    assert!(
        v["steps"]
            .as_array()
            .unwrap()
            .iter()
            .any(|s| s.as_str().unwrap().contains("inverse Abel"))
    );
}

#[test]
fn cli_errors_exit_2_with_one_line_and_write_nothing() {
    let bad = write_tmp(
        "cli_bad.csv",
        "# coatcheck height map: dx = 1e-6 m\n1,2,3,4\n1,2,3\n",
    );
    let out = tmp("cli_bad_out.csv");
    let _ = std::fs::remove_file(&out);
    let o = coatcheck(&["psd", bad.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("coatcheck: ") && err.contains("cli_bad.csv:3:"),
        "{err}"
    );
    assert!(!out.exists());
    let o = coatcheck(&["psd", bad.to_str().unwrap(), "--dx", "3 furlong"]);
    assert_eq!(o.status.code(), Some(2));
    let o = coatcheck(&["psd", "/nonexistent/heights.csv", "--pixel-size", "1um"]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn cli_synth_writes_a_map_with_the_requested_rms() {
    let out = tmp("cli_synth.csv");
    let o = coatcheck(&[
        "synth",
        "--n",
        "64",
        "--pixel-size",
        "1um",
        "--hurst",
        "0.7",
        "--q0",
        "0.05 1/um",
        "--q1",
        "1 1/um",
        "--rms-height",
        "2um",
        "--seed",
        "3",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let m = read_height_map(&out, &MapOptions::default()).unwrap();
    assert_eq!((m.nx, m.ny, m.dx), (64, 64, 1e-6));
    assert!((m.rms() / 2e-6 - 1.0).abs() < 1e-12);
    let o = coatcheck(&[
        "synth",
        "--n",
        "64",
        "--pixel-size",
        "1um",
        "--q0",
        "2 1/um",
        "--q1",
        "1 1/um",
        "--rms-slope",
        "0.1",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn detrending_removes_exactly_its_polynomial() {
    // A plane plus a quadratic bowl on a non-periodic map: tilt removal leaves the bowl's
    // non-planar part, curvature removal leaves nothing (to rounding); a line scan likewise.
    let n = 64;
    let z: Vec<f64> = (0..n * n)
        .map(|i| {
            let (x, y) = ((i % n) as f64, (i / n) as f64);
            1e-6 * (3.0 + 0.2 * x - 0.1 * y) + 1e-9 * (x * x - 0.5 * x * y + 2.0 * y * y)
        })
        .collect();
    let m = HeightMap {
        nx: n,
        ny: n,
        dx: DX,
        dy: DX,
        z,
        periodic: false,
    };
    let with = |d| PsdOptions {
        detrend: Some(d),
        window: Some(coatcheck::topography::spectrum::Window::None),
        ..all_modes()
    };
    use coatcheck::topography::spectrum::Detrend;
    let tilt = map_psd(&m, &with(Detrend::Tilt)).unwrap().summary.h_rms;
    let curv = map_psd(&m, &with(Detrend::Curvature))
        .unwrap()
        .summary
        .h_rms;
    assert!(tilt > 1e-7, "{tilt:e}");
    assert!(curv < 1e-12 * m.rms(), "{curv:e} vs {:e}", m.rms());
    // Line scan: quadratic + a sine off the grid's modes. After curvature removal h_rms must
    // be the rms of the sine's residual from its own least-squares quadratic, computed here
    // independently by solving the 3 × 3 normal equations (Cramer's rule).
    let sine: Vec<f64> = (0..n)
        .map(|i| 1e-3 * (2.0 * PI * 5.3 * i as f64 / n as f64).sin())
        .collect();
    let scan: Vec<f64> = (0..n)
        .map(|i| 2.0 + 0.3 * i as f64 - 0.01 * (i * i) as f64 + sine[i])
        .collect();
    let mom = |k: i32| (0..n).map(|i| (i as f64).powi(k)).sum::<f64>();
    let rhs = |k: i32| (0..n).map(|i| (i as f64).powi(k) * sine[i]).sum::<f64>();
    let a = [
        [mom(0), mom(1), mom(2)],
        [mom(1), mom(2), mom(3)],
        [mom(2), mom(3), mom(4)],
    ];
    let b = [rhs(0), rhs(1), rhs(2)];
    let det3 = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det3(a);
    let coef: Vec<f64> = (0..3)
        .map(|c| {
            let mut mc = a;
            for r in 0..3 {
                mc[r][c] = b[r];
            }
            det3(mc) / d
        })
        .collect();
    let expect = ((0..n)
        .map(|i| {
            let x = i as f64;
            (sine[i] - coef[0] - coef[1] * x - coef[2] * x * x).powi(2)
        })
        .sum::<f64>()
        / n as f64)
        .sqrt();
    let pr = Profile {
        dx: DX,
        scans: vec![scan],
        periodic: false,
    };
    let got = profile_c1d(&pr, &with(Detrend::Curvature))
        .unwrap()
        .summary
        .h_rms;
    assert!((got / expect - 1.0).abs() < 1e-8, "{got:e} vs {expect:e}");
    let tilt = profile_c1d(&pr, &with(Detrend::Tilt))
        .unwrap()
        .summary
        .h_rms;
    assert!(tilt > 10.0 * expect, "{tilt:e}");
}

#[test]
fn hann_window_is_what_makes_a_non_periodic_crop_usable() {
    // A 256² crop of a 1024² periodic H = 1 surface is not periodic: its edges jump. Without
    // a window the jumps leak power ∝ q^−3 towards high q and flatten the spectrum up to the
    // Nyquist wavenumber (measured H ≈ 0.88); with the Hann window H comes back within ±0.05
    // (measured ≈ 0.97). Three surfaces.
    for seed in [21, 22, 23] {
        let big = SynthSpec {
            n: 1024,
            dx: DX,
            hurst: 1.0,
            q0: 8.0 * q_fund(),
            q1: 4.0 * 256.0 * q_fund(),
            amplitude: Amplitude::RmsHeight(1e-6),
            seed,
        };
        let m = self_affine_map(&big).unwrap();
        let z: Vec<f64> = (0..N).flat_map(|iy| m.row(iy)[..N].to_vec()).collect();
        let crop = HeightMap {
            nx: N,
            ny: N,
            dx: DX,
            dy: DX,
            z,
            periodic: false,
        };
        let fit = |w| {
            let p = map_psd(
                &crop,
                &PsdOptions {
                    window: Some(w),
                    ..all_modes()
                },
            )
            .unwrap();
            -slope(&p.c2d, 2.0 * big.q0, p.summary.q_max) / 2.0 - 1.0
        };
        use coatcheck::topography::spectrum::Window;
        let (h_hann, h_none) = (fit(Window::Hann), fit(Window::None));
        eprintln!("crop {seed}: H with Hann {h_hann:.3}, without window {h_none:.3}");
        assert!((h_hann - 1.0).abs() < 0.05, "{h_hann}");
        assert!(h_none < 0.93, "{h_none}");
    }
}

#[test]
fn odd_rectangular_grids_keep_parseval_and_put_a_sinusoid_at_its_q() {
    // 243 × 100 pixels (odd and non-power-of-two sizes), dx ≠ dy, white-noise heights from
    // SplitMix64: the mode sum over all modes is ⟨h²⟩ exactly (kept + outside), no window.
    use coatcheck::topography::synth::SplitMix64;
    let (nx, ny, dx, dy) = (243usize, 100usize, 1e-6, 2.5e-6);
    let mut rng = SplitMix64::new(9);
    let z: Vec<f64> = (0..nx * ny).map(|_| rng.next_f64() - 0.5).collect();
    let mean = z.iter().sum::<f64>() / z.len() as f64;
    let h2 = z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / z.len() as f64;
    let m = HeightMap {
        nx,
        ny,
        dx,
        dy,
        z,
        periodic: true,
    };
    let s = map_psd(&m, &all_modes()).unwrap().summary;
    assert!(s.outside_fraction > 0.1, "{s:?}"); // the corners and the long-x axis modes
    let total = s.h_rms_kept.powi(2) / (1.0 - s.outside_fraction);
    assert!((total / h2 - 1.0).abs() < 1e-12, "{total} vs {h2}");
    assert!((s.h_rms.powi(2) / h2 - 1.0).abs() < 1e-12);
    // A sinusoid along y on the same grid (mode 7 of 100 rows: q = 7·2π/(100 dy)).
    let a = 1e-7;
    let z: Vec<f64> = (0..nx * ny)
        .map(|i| a * (2.0 * PI * 7.0 * (i / nx) as f64 / ny as f64).cos())
        .collect();
    let m = HeightMap { z, ..m };
    let p = map_psd(&m, &all_modes()).unwrap();
    let q_true = 7.0 * 2.0 * PI / (ny as f64 * dy);
    let (q, c) = (p.c2d.q(), p.c2d.c_values());
    let peak = (0..q.len()).max_by(|&i, &j| c[i].total_cmp(&c[j])).unwrap();
    assert!(
        (q[peak] / q_true).log10().abs() <= 0.05,
        "{} vs {q_true}",
        q[peak]
    );
    assert!((p.summary.h_rms_kept / (a / 2f64.sqrt()) - 1.0).abs() < 1e-12);
    // Line scans of odd length: the one-sided mode sum is ⟨h²⟩ exactly.
    let scan: Vec<f64> = (0..243).map(|_| rng.next_f64() - 0.5).collect();
    let mean = scan.iter().sum::<f64>() / 243.0;
    let h2 = scan.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 243.0;
    let pr = Profile {
        dx,
        scans: vec![scan],
        periodic: true,
    };
    let s = profile_c1d(&pr, &all_modes()).unwrap().summary;
    assert!((s.h_rms_kept.powi(2) / h2 - 1.0).abs() < 1e-12 && s.outside_fraction < 1e-12);
}

#[test]
fn synth_works_on_odd_sizes() {
    // n = 75: Hermitian symmetry without a Nyquist row; the heights are real only if it holds,
    // and the rms (from the real part) is then the requested one.
    let sp = SynthSpec {
        n: 75,
        q0: 4.0 * 2.0 * PI / (75.0 * DX),
        q1: 30.0 * 2.0 * PI / (75.0 * DX),
        ..spec(13)
    };
    let m = self_affine_map(&sp).unwrap();
    assert!((m.rms() / 1e-6 - 1.0).abs() < 1e-12, "{}", m.rms());
}
