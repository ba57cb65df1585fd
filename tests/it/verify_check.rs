//! `coatcheck check --verify` and `coatcheck::verify`: the check criteria judged on the exact
//! (boundary-element) fields. Closed form: a sinusoid in full contact, whose surface pressure is
//! p0 + p*·cos(qx) with p* = a·q·E0*/(2 S(qd)), so that at z = d the normal stress is
//! p0 + f·p*·cos(qx) and |τ| = |g|·p*·|sin(qx)| (paper eqs. 7, B7; `bem` module docs).

use crate::common::{json, run};
use coatcheck::bem::{BemSettings, Surface};
use coatcheck::check::{CheckKind, Checks, Criteria, Design};
use coatcheck::layer::{Bilayer, Elastic};
use coatcheck::verify::verify;
use std::f64::consts::PI;

/// `coatcheck verify` on the bundled map with the scene of [`FLAGS`] at d = 3 µm, JSON output.
const VERIFY: [&str; 12] = [
    "verify",
    "examples/data/height-map.csv",
    "--film",
    "2MPa,0.5",
    "--substrate",
    "200GPa,0.3",
    "--thickness",
    "3um",
    "--pressure",
    "0.1MPa",
    "--format",
    "json",
];

/// A sinusoid along x (64 pixels per period, 64 rows), amplitude `a`, period `l`.
fn sinusoid(a: f64, l: f64) -> Surface {
    let n = 64;
    let heights = (0..n * n)
        .map(|i| a * (2.0 * PI * (i % n) as f64 / n as f64).cos())
        .collect();
    Surface::new(heights, n, n, l / n as f64, l / n as f64).unwrap()
}

fn design(layers: Bilayer, p0: f64, bond: f64, yield_strength: f64) -> Design {
    Design {
        layers,
        pressure: p0,
        yield_strength: Some(yield_strength),
        bond_strength: bond,
        friction: 0.0,
        criteria: Criteria {
            shear_tail: None,
            epsilon: 1e-6,
            safety_factor: 1.0,
            checks: Checks::all(),
        },
    }
}

fn tight() -> BemSettings {
    BemSettings {
        gap_tol: 1e-10,
        max_iter: 2000,
        ..BemSettings::default()
    }
}

#[test]
fn full_contact_sinusoid_gives_the_closed_form_levels_and_verdicts() {
    let layers = Bilayer::new(
        Elastic::new(1e6, 0.5).unwrap(),
        Elastic::new(2e11, 0.3).unwrap(),
    );
    let (a, l, d) = (0.2e-6, 100e-6, 10e-6);
    let q = 2.0 * PI / l;
    let r = layers.response(q * d);
    let p_star = a * q * layers.film.e_star() / (2.0 * r.s);
    let p0 = 2.0 * p_star;
    let tau_max = r.g.abs() * p_star;
    let sigma_max = p0 + r.f.abs() * p_star;
    let surface = sinusoid(a, l);
    // Bond strength 1 % above and below the peak shear; yield far away, then just below.
    for (bond, yield_strength, bond_pass, yield_pass) in [
        (1.01 * tau_max, 1e9, true, true),
        (0.99 * tau_max, 1e9, false, true),
        (1e9, 0.99 * sigma_max, true, false),
    ] {
        let v = verify(
            &surface,
            &design(layers, p0, bond, yield_strength),
            d,
            &tight(),
        )
        .unwrap();
        let close = |x: f64, want: f64| (x - want).abs() <= 1e-8 * want;
        assert_eq!(v.area_fraction.value, 1.0);
        assert!(close(v.mean_contact_pressure.value, p0));
        assert!(close(v.tau_peak.value.value, tau_max), "{v:?}");
        assert!(
            close(v.sigma_peak_interface.value.value, sigma_max),
            "{v:?}"
        );
        assert!(close(v.tau_rms_interface.value, tau_max / 2f64.sqrt()));
        assert!(close(
            v.sigma_rms_interface.value,
            r.f.abs() * p_star / 2f64.sqrt()
        ));
        // 4096 pixels cannot resolve ε = 1e-6: the level is the maximum, flagged as such.
        assert!(!v.tau_peak.resolved);
        // The half-resolution map holds the same sinusoid exactly: the estimate is ~0.
        assert!(v.tau_peak.value.err <= 1e-8 * tau_max, "{v:?}");
        let verdict = |k| v.checks.iter().find(|c| c.kind == k).unwrap().pass;
        assert_eq!(verdict(CheckKind::BondShear), bond_pass);
        assert_eq!(verdict(CheckKind::SubstrateYield), yield_pass);
        assert_eq!(v.pass, bond_pass && yield_pass);
    }
}

const FLAGS: [&str; 16] = [
    "--profile",
    "examples/data/height-map.csv",
    "--film-youngs-modulus",
    "2MPa",
    "--film-poisson-ratio",
    "0.5",
    "--substrate-youngs-modulus",
    "200GPa",
    "--substrate-poisson-ratio",
    "0.3",
    "--yield-strength",
    "250MPa",
    "--shear-strength",
    "10MPa",
    "--pressure",
    "0.1MPa",
];

/// `check --verify` passes the scene's map, materials, thickness and load to the solver: its
/// exact numbers are those of `coatcheck verify` run with the same inputs.
#[test]
fn check_verify_matches_the_verify_command() {
    let mut args = vec!["check"];
    args.extend(FLAGS);
    args.extend(["--thickness", "3um", "--verify", "--format", "json"]);
    let o = run(&args);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let c = json(&o);
    let o = run(&VERIFY);
    assert_eq!(o.status.code(), Some(0));
    let v = json(&o);
    let cv = &c["verify"];
    assert_eq!(cv["area_fraction"], v["area_fraction"]);
    assert_eq!(
        cv["tau_rms_interface_pa"],
        v["interface_shear_abs_pa"]["rms"]
    );
    assert_eq!(cv["persson_area_fraction"], c["area_fraction"]);
    assert!(cv["area_fraction_err"].as_f64().unwrap() > 0.0);
    assert_eq!(cv["verdict"], "pass");
    assert_eq!(c["verdict_with_verify"], "pass");
    let checks = cv["checks"].as_array().unwrap();
    assert_eq!(checks.len(), 3);
    assert_eq!(checks[2]["name"], "min-thickness");
    assert_eq!(checks[2]["limit"], c["exact"]["min_thickness_m"]);
}

/// A bond weaker than the exact peak shear fails the exact check and, with it, the verdict
/// (exit code 1), in every format.
#[test]
fn exact_failure_fails_the_verdict() {
    for format in ["table", "json", "csv"] {
        let mut args = vec!["check"];
        args.extend(FLAGS);
        args[14] = "0.2MPa";
        args.extend([
            "--thickness",
            "3um",
            "--verify",
            "--checks",
            "bond-shear",
            "--format",
            format,
        ]);
        let o = run(&args);
        assert_eq!(o.status.code(), Some(1), "{format}");
        let out = String::from_utf8_lossy(&o.stdout);
        match format {
            "json" => assert_eq!(json(&o)["verify"]["verdict"], "fail"),
            "csv" => {
                let mut r = ::csv::Reader::from_reader(out.as_bytes());
                let head = r.headers().unwrap().clone();
                let row = r.records().next().unwrap().unwrap();
                let at = |k: &str| &row[head.iter().position(|h| h == k).unwrap()];
                assert_eq!(
                    (at("verify_verdict"), at("verdict")),
                    ("fail", "fail"),
                    "{out}"
                );
            }
            _ => assert!(out.contains("exact verdict: FAIL"), "{out}"),
        }
    }
}

/// Measured heights for `--verify` must be a map: line scans are refused (a spectrum or a model
/// is solved on realisations instead, `tests/it/exact.rs`).
#[test]
fn verify_needs_a_map_not_line_scans() {
    let mut args = vec!["check"];
    args.extend(FLAGS);
    args[2] = "examples/data/line-scans.csv";
    args.extend(["--thickness", "3um", "--verify"]);
    let o = run(&args);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        e.contains("line-scans.csv") && e.contains("line scans"),
        "{e}"
    );
    assert!(o.stdout.is_empty());
}

/// The bundled thin-film scene (q_L d ≈ 0.2): it passes both ways, and the exact contact area is
/// several times Persson's, as the boundary-element studies cited in issue 6 report for
/// q_L d ≲ 0.3 (2× at 0.3, 10× at 0.1).
#[test]
fn bundled_height_map_scene() {
    let o = run(&[
        "check",
        "examples/height-map-film.toml",
        "--verify",
        "--format",
        "json",
    ]);
    assert_eq!(o.status.code(), Some(0));
    let j = json(&o);
    let v = &j["verify"];
    let q_low_d = v["q_low_d"].as_f64().unwrap();
    assert!(
        (q_low_d - 2.0 * PI / 64e-6 * 2e-6).abs() < 1e-12,
        "{q_low_d}"
    );
    let ratio = v["area_fraction"].as_f64().unwrap() / j["area_fraction"].as_f64().unwrap();
    assert!(ratio > 2.0, "exact/Persson A/A0 = {ratio}");
    assert_eq!(v["peaks_resolved"], true);
    assert_eq!(j["verdict_with_verify"], "pass");
}

/// `verify --rtol` sets the tolerance of Persson's integrals; their error estimates are in the
/// JSON and within the requested tolerance; a tolerance outside (0, 1) is bad input.
#[test]
fn verify_rtol_and_persson_errors() {
    let mut base = VERIFY.to_vec();
    base.push("--rtol");
    for rtol in [1e-4, 1e-10] {
        let mut args = base.clone();
        let r = format!("{rtol}");
        args.push(&r);
        let o = run(&args);
        assert_eq!(o.status.code(), Some(0));
        let j = json(&o);
        let (a, e) = (
            j["persson_area_fraction"].as_f64().unwrap(),
            j["persson_area_fraction_err"].as_f64().unwrap(),
        );
        assert!(e > 0.0 && e <= rtol * a, "rtol {rtol}: {a} ± {e}");
        for row in j["comparison"].as_array().unwrap() {
            assert_eq!(row["persson"].is_null(), row["persson_err"].is_null());
        }
    }
    let mut args = base.clone();
    args.push("0");
    let o = run(&args);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--rtol"));
}
