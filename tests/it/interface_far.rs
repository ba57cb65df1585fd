//! Interface stresses of thick films, where f² and g² leave f64's range (q·d ≳ 355) and the
//! stresses themselves its normal range (q0·d ≳ 708): `check` on the paper's scene with
//! `--thickness` from q0·d = 100 to 800 against tests/data/interface_far_ref.py (mpmath, 40
//! digits: f and g from the 6×6 boundary-value solve of kernels_ref.py, G in closed form,
//! tanh-sinh and graded Gauss–Legendre quadratures agreeing to 1e-22; printed to 20 digits,
//! held here as the nearest f64), and
//! `response` at q·d = 600, 700, 800 against the same 6×6 solve at 100 digits
//! (`kernels_ref.kernels(1e6/1e11, 0.5, 0.5, x)`).

use super::common::{json, run};
use coatcheck::contact::{Engine, Request};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::{INTERFACE_ATOL, Settings, Termination};
use coatcheck::psd::Spectrum;

const SCENE: &str = "examples/paper-rubber-on-steel.toml";

/// d (m, as given on the command line), σ_rms and τ_rms at the interface (Pa), from
/// interface_far_ref.py. At d = 8 mm both are 3.7e-341 Pa: below the smallest subnormal.
const REFERENCE: [(&str, f64, f64); 6] = [
    ("0.001", 1.3508464080800283e-37, 1.3375374817671868e-37),
    ("0.003", 3.2119678132262574e-124, 3.20131452012922e-124),
    ("0.005", 5.729000555178636e-211, 5.717576825244596e-211),
    ("0.006", 2.3336778661077334e-254, 2.3297981024044555e-254),
    ("0.007", 9.374264371022258e-298, 9.360901200139185e-298),
    // 3.7272477398075058926e-341 and 3.722597399519648728e-341: 0 in f64.
    ("0.008", 0.0, 0.0),
];

/// Every interface stress of `check` within its error estimate of the reference, the estimate
/// within the default rtol (1e-8) of the value or [`INTERFACE_ATOL`] where the value rounds into
/// the subnormals (d = 8 mm: 0 ± 5e-324), and no warning (nothing marked as missing its
/// tolerance).
#[test]
fn thick_film_interface_stresses_match_the_reference() {
    let rtol = Settings::default().rtol;
    for (d, sigma, tau) in REFERENCE {
        let o = run(&["check", SCENE, "--thickness", d, "--format", "json"]);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
        let v = json(&o);
        // The only warning is about the data (the paper's spectrum ends at 2π/q0 = 63 µm < d),
        // never about the numerics.
        for w in v["warnings"].as_array().unwrap() {
            let w = w.as_str().unwrap();
            assert!(
                w.starts_with("the longest wavelength of the spectrum"),
                "d = {d}: {w}"
            );
        }
        for (key, want) in [
            ("sigma_rms_interface_pa", sigma),
            ("tau_rms_interface_pa", tau),
        ] {
            let got = v[key].as_f64().unwrap();
            let err = v[format!("{key}_err")].as_f64().unwrap();
            assert!(
                (got - want).abs() <= err,
                "d = {d}, {key}: {got:e} vs {want:e}, estimate {err:e}"
            );
            assert!(
                err <= rtol * got + INTERFACE_ATOL,
                "d = {d}, {key}: {got:e} ± {err:e}"
            );
            if want > 1e-300 {
                assert!(err < 1e-8 * want, "d = {d}, {key}: {got:e} ± {err:e}");
            }
        }
    }
}

/// The engine at every rtol from 1e-3 to 1e-10 at those thicknesses: converged, and the error
/// estimate bounds the true error against the reference (the flushed value at d = 8 mm
/// included: 0 within its estimate of the true 3.7e-341).
#[test]
fn thick_film_error_estimates_bound_the_true_error_at_every_rtol() {
    let spectrum = Spectrum::self_affine(1.0, 1e5, 1e8, None)
        .unwrap()
        .scaled_to_rms_slope(1.0)
        .unwrap();
    let layers = Bilayer::new(
        Elastic::new(1e6, 0.5).unwrap(),
        Elastic::new(1e11, 0.5).unwrap(),
    );
    for k in 3..=10 {
        let rtol = 10f64.powi(-k);
        let engine = Engine::new(&spectrum, Settings { rtol });
        for (d, sigma, tau) in REFERENCE {
            let stack = Stack::new(layers, d.parse().unwrap()).unwrap();
            let c = engine.evaluate(&stack, 1e5, Request::all()).unwrap();
            for (e, want) in [
                (c.sigma_rms_interface.unwrap(), sigma),
                (c.tau_rms_interface.unwrap(), tau),
            ] {
                assert_eq!(
                    e.status,
                    Termination::Converged,
                    "rtol {rtol}, d = {d}: {e:?}"
                );
                assert!(
                    (e.value - want).abs() <= e.err,
                    "rtol {rtol}, d = {d}: {e:?} vs {want:e}"
                );
                assert!(
                    e.err <= rtol * want + INTERFACE_ATOL,
                    "rtol {rtol}, d = {d}: {e:?}"
                );
            }
        }
    }
}

/// The table shows a stress whose MPa would leave f64's normal range in Pa, with its error:
/// 1.871e-319 Pa at d = 7.5 mm, and 0 ± 4.941e-324 Pa (not 0 ± 0 MPa) at 8 mm.
#[test]
fn the_table_shows_subnormal_stresses_and_errors_in_pa() {
    for (d, sigma, tau) in [
        ("7.5mm", "1.871e-319 Pa", "1.869e-319 Pa"),
        ("8mm", "0 Pa", "0 Pa"),
    ] {
        let o = run(&["check", SCENE, "--thickness", d]);
        assert_eq!(o.status.code(), Some(0));
        let text = String::from_utf8(o.stdout).unwrap();
        for (name, value) in [("sigma_rms interface", sigma), ("tau_rms interface", tau)] {
            let row = text.lines().find(|l| l.contains(name)).unwrap();
            let cells: Vec<&str> = row.split('┆').map(|c| c.trim_matches(['│', ' '])).collect();
            assert_eq!(cells[1..], [value, "4.941e-324 Pa"], "d = {d}: {row}");
        }
    }
}

/// `response` at q·d = 600 and 700 (normal numbers, to 2e-13) and 800 (5.9e-345: 0 with an
/// error estimate of the smallest subnormal, not 0 ± 0).
#[test]
fn response_reports_f_and_g_and_their_flush() {
    let o = run(&[
        "response",
        "--film",
        "1e6,0.5",
        "--substrate",
        "1e11,0.5",
        "--qd",
        "600,700,800",
        "--format",
        "csv",
    ]);
    assert_eq!(o.status.code(), Some(0));
    let text = String::from_utf8(o.stdout).unwrap();
    let want = [
        (3.185744799263189e-258, 3.1804440591645813e-258),
        (1.3823128283068368e-301, 1.3803409127172408e-301),
        // 5.8758763250894040219e-345 and 5.8685406492778067635e-345: 0 in f64.
        (0.0, 0.0),
    ];
    for (line, (f, g)) in text.lines().skip(1).zip(want) {
        let v: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
        for (got, err, want) in [(v[3], v[4], f), (v[5], v[6], g)] {
            assert!((got - want).abs() <= err, "{line}: {want:e}");
            assert!(err <= 2e-13 * want + 5e-324, "{line}");
        }
    }
}
