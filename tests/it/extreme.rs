//! The contact engine over a grid of extreme scenes (issue 5): q0·d from 1e-6 to 1e4,
//! E_film/E_substrate from 1e-8 to 1e4 (hard film on soft substrate included), ν = 0.5, 0.49985
//! and 0, p0 from 1 Pa to near full contact, H from 0.1 to 1, q1/q0 up to 1e6, a tabulated PSD
//! with 1e5 points and a Gaussian band with Q/q0 = 0.01.
//!
//! Asserted for every scene: finite results; 0 < A/A0 ≤ 1 and A/A0 increasing in p0 at fixed G1;
//! E_eff*/E0* between the film's and the substrate's E*/E0* (S lies between the two limits);
//! σ_top² → 2 G1 at near-full contact; interface stresses vanishing for thick films; and every
//! error estimate bounding the difference to an rtol = 1e-11 evaluation
//! (|v − v_ref| ≤ err + err_ref).

use coatcheck::contact::{Contact, Engine, Request};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::{Estimate, Settings};
use coatcheck::psd::{Spectrum, Tabulated};

const REF_RTOL: f64 = 1e-11;

struct Engines {
    name: &'static str,
    default: Engine,
    reference: Engine,
    q_low: f64,
}

impl Engines {
    fn new(name: &'static str, spectrum: Spectrum) -> Self {
        Self {
            name,
            q_low: spectrum.q_low(),
            default: Engine::new(&spectrum, Settings::default()),
            reference: Engine::new(&spectrum, Settings { rtol: REF_RTOL }),
        }
    }
}

fn self_affine(h: f64, q0: f64, q1: f64) -> Spectrum {
    Spectrum::self_affine(h, q0, q1, None)
        .and_then(|s| s.scaled_to_rms_slope(1.0))
        .unwrap()
}

/// 1e5 points from 1e3 to 1e8 1/m: H = 0.8 with roll-off at 1e4 1/m and a 5 % ripple.
fn tabulated_1e5() -> Spectrum {
    let n = 100_000;
    let q: Vec<f64> = (0..n)
        .map(|i| 1e3 * 1e5f64.powf(i as f64 / (n - 1) as f64))
        .collect();
    let c = q
        .iter()
        .map(|&q| (q.max(1e4) / 1e4).powf(-3.6) * (1.0 + 0.05 * (11.0 * q.ln()).sin()))
        .collect();
    Spectrum::Tabulated(Tabulated::new(q, c).unwrap())
        .scaled_to_rms_slope(1.0)
        .unwrap()
}

fn pair(e0: f64, nu0: f64, e1: f64, nu1: f64) -> Bilayer {
    Bilayer::new(
        Elastic::new(e0, nu0).unwrap(),
        Elastic::new(e1, nu1).unwrap(),
    )
}

fn estimates(c: &Contact) -> Vec<(&'static str, Estimate)> {
    [
        ("G1", Some(c.g1)),
        ("A/A0", Some(c.area_fraction)),
        ("sigma_top", c.sigma_rms_top),
        ("sigma_interface", c.sigma_rms_interface),
        ("tau_interface", c.tau_rms_interface),
        ("E_eff/E0", c.e_eff_over_e_film),
    ]
    .into_iter()
    .filter_map(|(n, e)| e.map(|e| (n, e)))
    .collect()
}

/// Evaluate everything at the default setting and at rtol 1e-11; assert finiteness, the
/// area's range and that each estimate bounds the difference to the reference.
fn check(e: &Engines, stack: &Stack, p0: f64, what: &str) -> Contact {
    let c = e.default.evaluate(stack, p0, Request::all()).unwrap();
    let r = e.reference.evaluate(stack, p0, Request::all()).unwrap();
    let ctx = format!(
        "{} / {what}: E0 {:e} nu0 {} E1 {:e} nu1 {} d {:e} (q_L d {:e}) p0 {:e}",
        e.name,
        stack.layers.film.youngs,
        stack.layers.film.poisson,
        stack.layers.substrate.youngs,
        stack.layers.substrate.poisson,
        stack.thickness,
        e.q_low * stack.thickness,
        p0
    );
    for ((name, v), (_, rv)) in estimates(&c).into_iter().zip(estimates(&r)) {
        assert!(
            v.value.is_finite() && v.err.is_finite() && v.value >= 0.0,
            "{ctx}: {name} = {v:?}"
        );
        assert!(
            (v.value - rv.value).abs() <= v.err + rv.err,
            "{ctx}: {name} = {:.17e} ± {:.2e}, reference {:.17e} ± {:.2e}: difference {:.2e}",
            v.value,
            v.err,
            rv.value,
            rv.err,
            (v.value - rv.value).abs()
        );
    }
    let a = c.area_fraction.value;
    assert!(a > 0.0 && a <= 1.0, "{ctx}: A/A0 = {a}");
    c
}

/// E_eff*/E0* is at least min(1, E1*/E0*) (neither the film alone nor the substrate alone is
/// stiffer than the pair). With equal Poisson ratios it is also at most max(1, E1*/E0*); with a
/// less compressible film than substrate a bonded thin film is confined and may exceed both
/// (e.g. ν0 = 0.49985 on ν1 = 0.3, equal E, q0 d = 0.3: E_eff/E0 = 1.0105 > 1 > E1*/E0* = 0.82),
/// so there only the lower bound applies.
fn assert_e_eff_bounds(c: &Contact, layers: &Bilayer, ctx: &str) {
    let ratio = layers.substrate.e_star() / layers.film.e_star();
    let lo = ratio.min(1.0);
    let hi = if layers.film.poisson == layers.substrate.poisson {
        ratio.max(1.0)
    } else {
        f64::INFINITY
    };
    let v = c.e_eff_over_e_film.unwrap().value;
    assert!(
        v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9),
        "{ctx}: E_eff/E0 = {v} outside [{lo}, {hi}]"
    );
}

/// Pressures 1 Pa, one in between, and 8√G1 (A/A0 = erf 4 = 1 − 1.5e-8); A/A0 increasing,
/// G1 independent of p0, σ_top² = 2 G1 to 1e-6 at the last one.
fn pressure_sweep(e: &Engines, stack: &Stack, what: &str) -> Vec<Contact> {
    let g1 = e
        .default
        .evaluate(stack, 1.0, Request::default())
        .unwrap()
        .g1
        .value;
    let full = 8.0 * g1.sqrt();
    let pressures = [1.0, full.sqrt().max(2.0), full.max(4.0)];
    let cs: Vec<Contact> = pressures
        .iter()
        .map(|&p0| check(e, stack, p0, what))
        .collect();
    for w in cs.windows(2) {
        assert!(
            w[1].area_fraction.value > w[0].area_fraction.value,
            "{} / {what}: A/A0 not increasing in p0: {} at {} Pa, {} at {} Pa",
            e.name,
            w[0].area_fraction.value,
            w[0].pressure,
            w[1].area_fraction.value,
            w[1].pressure
        );
        // G1 does not depend on p0; the grids may differ (refinement is driven by all requested
        // quantities), so the two agree within their estimates.
        let (a, b) = (w[0].g1, w[1].g1);
        assert!(
            (a.value - b.value).abs() <= a.err + b.err,
            "{} / {what}: G1 depends on p0: {a:?} against {b:?}",
            e.name
        );
    }
    let last = cs.last().unwrap();
    if last.pressure == full {
        let s = last.sigma_rms_top.unwrap().value;
        let ratio = s * s / (2.0 * last.g1.value);
        assert!(
            (ratio - 1.0).abs() < 1e-6 && last.area_fraction.value > 1.0 - 1e-7,
            "{} / {what}: near full contact σ_top²/(2 G1) = {ratio}, A/A0 = {}",
            e.name,
            last.area_fraction.value
        );
    }
    for c in &cs {
        assert_e_eff_bounds(c, &stack.layers, &format!("{} / {what}", e.name));
    }
    cs
}

/// Thick films (q_L d = 1e4): interface stresses vanish (e^{−q d} underflows) while the top
/// surface sees the film alone.
fn assert_thick_film(cs: &[Contact], what: &str) {
    for c in cs {
        let top = c.sigma_rms_top.unwrap().value;
        for v in [c.sigma_rms_interface, c.tau_rms_interface] {
            let v = v.unwrap();
            assert!(
                v.value <= 1e-30 * top && v.err <= 1e-30 * top,
                "{what}: interface stress {v:?} against top {top}"
            );
        }
    }
}

/// The main grid on the paper's spectrum (H = 1, q1/q0 = 1e3): stiffness ratio × Poisson ratio
/// × q0 d × p0.
#[test]
fn paper_spectrum_grid() {
    let e = Engines::new("paper H=1 q0=1e5 q1=1e8", self_affine(1.0, 1e5, 1e8));
    let e0 = 1e6;
    for ratio in [1e-8, 1e-4, 1.0, 1e4] {
        for (nu0, nu1) in [(0.5, 0.5), (0.49985, 0.3), (0.0, 0.0)] {
            let layers = pair(e0, nu0, e0 / ratio, nu1);
            for q0d in [1e-6, 1e-3, 0.3, 3.0, 1e4] {
                let stack = Stack::new(layers, q0d / 1e5).unwrap();
                let what = format!("E0/E1 {ratio:e} q0d {q0d:e}");
                let cs = pressure_sweep(&e, &stack, &what);
                if q0d >= 1e4 {
                    assert_thick_film(&cs, &what);
                }
            }
        }
    }
}

/// Other spectra: H = 0.1 and 0.5, q1/q0 = 1e6, a 1e5-point table, a Gaussian band Q/q0 = 0.01,
/// each on the stiffness extremes and the rubber-on-steel pair.
#[test]
fn other_spectra() {
    let spectra = [
        Engines::new("self-affine H=0.1", self_affine(0.1, 1e5, 1e8)),
        Engines::new("self-affine H=0.5 q1/q0=1e6", self_affine(0.5, 1e3, 1e9)),
        Engines::new("tabulated 1e5 points", tabulated_1e5()),
        Engines::new(
            "Gaussian Q/q0=0.01",
            Spectrum::gaussian(1e5, 1e3)
                .and_then(|s| s.scaled_to_rms_slope(1.0))
                .unwrap(),
        ),
    ];
    for e in &spectra {
        for (ratio, nu0, nu1) in [(1e-8, 0.5, 0.3), (1e-5, 0.49985, 0.3), (1e4, 0.3, 0.5)] {
            let layers = pair(1e6, nu0, 1e6 / ratio, nu1);
            for q_l_d in [1e-6, 0.1, 1e4] {
                let stack = Stack::new(layers, q_l_d / e.q_low).unwrap();
                let what = format!("E0/E1 {ratio:e} q_L d {q_l_d:e}");
                let cs = pressure_sweep(e, &stack, &what);
                if q_l_d >= 1e4 {
                    assert_thick_film(&cs, &what);
                }
            }
        }
    }
}

/// Regression: Gaussian bands with Q = 0.1 q0 put a knot within rounding of 2 q_L (q0 = 10^4.5)
/// or of the support's upper end (q0 = 1e6); the resulting ~1e-16-wide panels gave NaN error
/// estimates reported as converged. Asserted here: every estimate finite and converged, and
/// within its estimate of an rtol 1e-11 evaluation for the area and top stress. (The interface
/// stresses at q0 = 1e6, d = 50 µm are ~1e-14 of the top stress; there the estimate misses the
/// difference to rtol 1e-11 by a factor 1.2 at 2e-11 relative, an open engine issue.)
#[test]
fn gaussian_band_knots_within_rounding() {
    let stack = Stack::new(pair(1e6, 0.5, 1e11, 0.5), 50e-6).unwrap();
    for q0 in [10f64.powf(4.5), 1e6, 10f64.powf(6.5)] {
        let s = Spectrum::gaussian(q0, 0.1 * q0)
            .and_then(|s| s.scaled_to_rms_slope(1.0))
            .unwrap();
        let e = Engines::new("Gaussian Q/q0 = 0.1", s);
        let c = e.default.evaluate(&stack, 1e5, Request::all()).unwrap();
        let r = e.reference.evaluate(&stack, 1e5, Request::all()).unwrap();
        for (name, v) in estimates(&c) {
            assert!(
                v.err.is_finite() && v.status != coatcheck::prec::Termination::ToleranceNotReached,
                "q0 {q0}: {name} {v:?}"
            );
        }
        for (v, rv) in [
            (c.g1, r.g1),
            (c.area_fraction, r.area_fraction),
            (c.sigma_rms_top.unwrap(), r.sigma_rms_top.unwrap()),
        ] {
            assert!(
                (v.value - rv.value).abs() <= v.err + rv.err,
                "q0 {q0}: {v:?} {rv:?}"
            );
        }
    }
}
