//! Where the theory is strained, the check says so (issue 5): the share of G(q1) from the lowest
//! octave (checked against G of the spectrum cut to that octave, a second computation), and the
//! warnings for few dominant waves, near-full contact and large slopes, each triggered only on
//! its side of the threshold.

use coatcheck::check::{Checker, Checks, Criteria, Design, LOW_OCTAVE_WARN};
use coatcheck::contact::{Engine, Request};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::Settings;
use coatcheck::psd::{Spectrum, Tabulated};

fn rubber_on_steel() -> Bilayer {
    Bilayer::new(
        Elastic::new(1e6, 0.5).unwrap(),
        Elastic::new(1e11, 0.5).unwrap(),
    )
}

/// The paper's self-affine spectrum (H = 1, q0 = 1e5, q1 = 1e8 1/m) as a 301-point table with
/// slope `xi`.
fn table(xi: f64) -> Tabulated {
    let s = Spectrum::self_affine(1.0, 1e5, 1e8, None)
        .unwrap()
        .scaled_to_rms_slope(xi)
        .unwrap();
    let q: Vec<f64> = (0..=300)
        .map(|i| 1e5 * 10f64.powf(i as f64 / 100.0))
        .collect();
    let c = q.iter().map(|&q| s.c(q)).collect();
    Tabulated::new(q, c).unwrap()
}

#[test]
fn low_octave_share_is_g_of_the_lowest_octave_over_g() {
    let full = table(1.0);
    let octave = full.restricted(None, Some(2e5)).unwrap();
    for d in [0.3e-6, 3e-6, 30e-6, 300e-6] {
        let stack = Stack::new(rubber_on_steel(), d).unwrap();
        let req = Request {
            sigma_top: false,
            sigma_interface: false,
            tau_interface: false,
            e_eff: false,
        };
        let c = Engine::new(&Spectrum::Tabulated(full.clone()), Settings::default())
            .evaluate(&stack, 1e5, req)
            .unwrap();
        let low = Engine::new(&Spectrum::Tabulated(octave.clone()), Settings::default())
            .evaluate(&stack, 1e5, req)
            .unwrap();
        let share = low.g1.value / c.g1.value;
        // Both are converged quadratures at rtol 1e-8; the share is their ratio.
        assert!(
            (c.low_octave_share - share).abs() <= 1e-6 * share,
            "d = {d}: {} vs {share}",
            c.low_octave_share
        );
    }
}

fn warnings(xi: f64, p0: f64, d: f64) -> Vec<String> {
    let design = Design {
        layers: rubber_on_steel(),
        pressure: p0,
        yield_strength: Some(250e6),
        bond_strength: 10e6,
        friction: 0.0,
        criteria: Criteria {
            shear_tail: None,
            epsilon: 1e-6,
            safety_factor: 1.0,
            checks: Checks {
                bond_shear: true,
                substrate_yield: false,
                min_thickness: false,
            },
        },
    };
    let checker =
        Checker::new(&Spectrum::Tabulated(table(xi)), design, Settings::default()).unwrap();
    let o = checker.run(d).unwrap();
    let share = o.evaluation.contact.low_octave_share;
    let a = o.evaluation.contact.area_fraction.value;
    // Each warning fires exactly when its quantity crosses its threshold.
    assert_eq!(
        o.warnings.iter().any(|w| w.contains("lowest octave")),
        share > LOW_OCTAVE_WARN,
        "{share}"
    );
    assert_eq!(
        o.warnings.iter().any(|w| w.contains("full contact")),
        a > 0.9
    );
    o.warnings
}

#[test]
fn thin_film_warning_names_the_share_and_calls_pressures_conservative() {
    // q_L d = 0.1: 98 % of G(q1) from the lowest octave.
    let w = warnings(1.0, 1e5, 1e-6);
    let low = w
        .iter()
        .find(|w| w.contains("lowest octave"))
        .expect("warned");
    assert!(
        low.starts_with("98 %") && low.contains("q_L d = 0.100"),
        "{low}"
    );
    assert!(
        low.contains("conservative") && low.contains("--verify"),
        "{low}"
    );
    // q_L d = 10: 10 % (no warning of the lowest octave; d is then longer than the longest
    // wavelength 2π/q_L = 63 µm, which has its own warning).
    let w = warnings(1.0, 1e5, 100e-6);
    assert!(!w.iter().any(|w| w.contains("lowest octave")), "{w:?}");
    assert!(
        w.iter()
            .any(|w| w.contains("longest wavelength") && w.contains("6.2832e-5 m")),
        "{w:?}"
    );
}

#[test]
fn near_full_contact_and_large_slope_are_flagged() {
    let w = warnings(1.0, 3e6, 100e-6);
    assert!(
        w.iter()
            .any(|w| w.starts_with("near full contact (A/A0 = ")),
        "{w:?}"
    );
    let w = warnings(1.5, 1e5, 100e-6);
    assert!(
        w.iter().any(|w| w.starts_with("rms slope 1.500 > 1")),
        "{w:?}"
    );
    // The paper's own slope (1) is not flagged.
    assert!(
        !warnings(1.0, 1e5, 100e-6)
            .iter()
            .any(|w| w.contains("rms slope"))
    );
}
