//! The design checks at library level: the paper's reference numbers, d_min against an
//! independent dense brute-force scan (including a non-monotone failing band where a naive
//! bisection fails, and a band narrower than the scan step), the "no thickness passes" and
//! "everything passes" ends, and the sweep.

use coatcheck::check::{CheckKind, Checker, Checks, Criteria, D_MIN_RTOL, Design};
use coatcheck::layer::{Bilayer, Elastic};
use coatcheck::material::Library;
use coatcheck::prec::Settings;
use coatcheck::psd::Spectrum;
use coatcheck::scene::Scene;
use std::path::PathBuf;

pub(crate) fn paper_spectrum() -> Spectrum {
    Spectrum::self_affine(1.0, 1e5, 1e8, None)
        .unwrap()
        .scaled_to_rms_slope(1.0)
        .unwrap()
}

fn checks(bond_shear: bool, substrate_yield: bool) -> Checks {
    Checks {
        bond_shear,
        substrate_yield,
        min_thickness: true,
    }
}

pub(crate) fn paper_design(checks: Checks, bond: f64, yield_strength: f64) -> Design {
    Design {
        layers: Bilayer::new(
            Elastic::new(1e6, 0.5).unwrap(),
            Elastic::new(1e11, 0.5).unwrap(),
        ),
        pressure: 1e5,
        yield_strength: Some(yield_strength),
        bond_strength: bond,
        friction: 0.0,
        criteria: Criteria {
            shear_tail: None,
            epsilon: 1e-6,
            safety_factor: 1.0,
            checks,
        },
    }
}

pub(crate) fn checker(design: Design) -> Checker {
    Checker::new(&paper_spectrum(), design, Settings::default()).unwrap()
}

/// |x − reference| within half a unit of the reference's last stated digit.
fn within_digits(x: f64, reference: f64, digits: i32) {
    let unit = 10f64.powi(reference.abs().log10().floor() as i32 - digits + 1);
    assert!(
        (x - reference).abs() <= 0.5 * unit,
        "{x} vs {reference} ({digits} digits)"
    );
}

#[test]
fn paper_case_reference_numbers() {
    let c = checker(paper_design(Checks::all(), 1e7, 2.5e8));
    let ev = c.evaluate(10e-6).unwrap();
    let k = &ev.contact;
    // notes.md, "Reference values" (three digits).
    within_digits(k.area_fraction.value, 0.0927, 3);
    within_digits(k.sigma_rms_top.unwrap().value, 0.357e6, 3);
    within_digits(k.sigma_rms_interface.unwrap().value, 0.222e6, 3);
    within_digits(k.tau_rms_interface.unwrap().value, 0.133e6, 3);
    // τ_peak at ε = 1e-6 is √2 erfc⁻¹(1e-6) τ_rms (mpmath: 4.8916384756985903862).
    let ratio = ev.tau_peak.unwrap().value / k.tau_rms_interface.unwrap().value;
    assert!(
        (ratio / 4.891_638_475_698_59 - 1.0).abs() < 1e-10,
        "{ratio}"
    );
    // p0·A0/A.
    let p = ev.mean_contact_pressure.value * k.area_fraction.value;
    assert!((p / 1e5 - 1.0).abs() < 1e-14);
    // Every result carries a small, non-negative error estimate.
    for e in [
        k.area_fraction,
        ev.mean_contact_pressure,
        ev.tau_peak.unwrap(),
        ev.sigma_peak_interface.unwrap(),
    ] {
        assert!(e.err >= 0.0 && e.err <= 1e-6 * e.value.abs(), "{e:?}");
    }
}

/// (thickness, utilisation) pairs.
type Samples = Vec<(f64, f64)>;

/// Dense brute-force scan of the full check (`evaluate`, all quantities) over ln d:
/// (largest failing thickness, the next sampled thickness above it), or None if all pass.
fn brute_force(c: &Checker, per_decade: f64) -> (Option<(f64, f64)>, Samples) {
    let (lo, hi) = c.scan_range();
    let n = ((hi / lo).log10() * per_decade).ceil() as usize;
    let d: Vec<f64> = (0..=n)
        .map(|i| lo * (hi / lo).powf(i as f64 / n as f64))
        .collect();
    let rows = c.sweep(&d).unwrap();
    let util: Vec<(f64, f64)> = rows
        .iter()
        .map(|ev| {
            let u = ev
                .checks
                .iter()
                .map(|ch| ch.value.value / ch.limit.unwrap())
                .fold(0.0, f64::max);
            (ev.contact.thickness, u)
        })
        .collect();
    let last_fail = util.iter().rposition(|&(_, u)| u > 1.0);
    (
        last_fail.map(|i| (util[i].0, util.get(i + 1).map_or(f64::INFINITY, |x| x.0))),
        util,
    )
}

/// d_min must lie in the brute-force bracket, and the full check must pass just above it
/// and fail just below it.
pub(crate) fn assert_d_min_matches_brute_force(c: &Checker, per_decade: f64) -> f64 {
    let m = c.min_thickness().unwrap();
    let d_min = m.thickness.unwrap();
    let (bracket, _) = brute_force(c, per_decade);
    let (d_fail, d_pass) = bracket.expect("brute force finds a failing thickness");
    assert!(!m.all_pass_to_floor);
    assert!(
        d_min.value >= d_fail * (1.0 - D_MIN_RTOL) && d_min.value <= d_pass * (1.0 + D_MIN_RTOL),
        "d_min {} outside brute-force bracket [{d_fail}, {d_pass}]",
        d_min.value
    );
    assert!(
        d_min.err <= 0.5 * D_MIN_RTOL * d_min.value * 1.01,
        "{d_min:?}"
    );
    let pass = |d: f64| c.evaluate(d).unwrap().checks.iter().all(|ch| ch.pass);
    assert!(
        pass(d_min.value * (1.0 + D_MIN_RTOL)),
        "fails just above d_min"
    );
    assert!(
        !pass(d_min.value * (1.0 - D_MIN_RTOL)),
        "passes just below d_min"
    );
    d_min.value
}

#[test]
fn d_min_of_the_paper_case_matches_a_dense_scan() {
    let c = checker(paper_design(checks(true, true), 1e7, 2.5e8));
    let d_min = assert_d_min_matches_brute_force(&c, 100.0);
    let m = c.min_thickness().unwrap();
    assert!(m.governing.is_some());
    // The paper's 10 µm film is thicker than d_min here, and the verdict says so.
    let out = c.run(10e-6).unwrap();
    assert_eq!(out.pass, d_min <= 10e-6);
}

/// Bond-shear only, with a bond strength between τ_peak at the scan floor and the maximum of
/// τ_peak(d): the failing thicknesses form a band with passing thicknesses on both sides.
#[test]
fn non_monotone_band_is_found_where_naive_bisection_fails() {
    let probe = checker(paper_design(checks(true, false), 1e12, 2.5e8));
    let (_, util) = brute_force(&probe, 50.0);
    // With a 1e12 Pa limit, u·1e12 is τ_peak itself.
    let tau: Vec<(f64, f64)> = util.iter().map(|&(d, u)| (d, u * 1e12)).collect();
    let (i_max, &(d_peak, tau_max)) = tau
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.1.total_cmp(&b.1.1))
        .unwrap();
    let tau_floor = tau[0].1;
    assert!(
        i_max > 0 && i_max < tau.len() - 1,
        "τ_peak(d) has an interior maximum"
    );
    assert!(tau_floor < 0.8 * tau_max, "τ falls again as d → 0");
    let bond = 0.5 * (tau_floor + tau_max);
    let c = checker(paper_design(checks(true, false), bond, 2.5e8));
    let d_min = assert_d_min_matches_brute_force(&c, 100.0);
    assert!(d_min > d_peak);
    // Naive bisection for "the smallest passing thickness" on [floor, bulk] assumes
    // monotonicity; both ends pass here, so it cannot even bracket the answer.
    let (lo, hi) = c.scan_range();
    let pass = |d: f64| c.evaluate(d).unwrap().checks.iter().all(|ch| ch.pass);
    assert!(pass(lo) && pass(hi));
    assert_eq!(
        c.min_thickness().unwrap().governing,
        Some(CheckKind::BondShear)
    );
}

/// A failing band narrower than the scan step (bond strength just under the peak of τ_peak).
#[test]
fn narrow_failing_band_is_not_missed() {
    let probe = checker(paper_design(checks(true, false), 1e12, 2.5e8));
    let (_, util) = brute_force(&probe, 400.0);
    let tau_max = util.iter().map(|&(_, u)| u * 1e12).fold(0.0, f64::max);
    let c = checker(paper_design(checks(true, false), 0.997 * tau_max, 2.5e8));
    let (bracket, util) = brute_force(&c, 400.0);
    let (d_fail, _) = bracket.unwrap();
    let first_fail = util.iter().position(|&(_, u)| u > 1.0).unwrap();
    let band = d_fail / util[first_fail].0;
    assert!(
        band.log10() < 1.0 / coatcheck::check::POINTS_PER_DECADE,
        "the band ({band}) must be narrower than a scan step for this test to mean anything"
    );
    assert_d_min_matches_brute_force(&c, 400.0);
}

#[test]
fn no_thickness_passes_when_even_the_bulk_film_fails() {
    // Bulk rubber: A/A0 ≈ 0.154 at p0 = 0.1 MPa, so the mean contact pressure is ≈ 0.65 MPa.
    let c = checker(paper_design(checks(true, true), 1e7, 0.5e6));
    let m = c.min_thickness().unwrap();
    assert_eq!(m.thickness, None);
    assert_eq!(m.governing, Some(CheckKind::SubstrateYield));
    let out = c.run(1e-3).unwrap();
    assert!(!out.pass);
    let mt = out
        .checks
        .iter()
        .find(|ch| ch.kind == CheckKind::MinThickness)
        .unwrap();
    assert!(!mt.pass && mt.limit.is_none());
}

#[test]
fn everything_passes_down_to_the_floor() {
    let c = checker(paper_design(checks(true, false), 1e10, 2.5e8));
    let m = c.min_thickness().unwrap();
    assert!(m.all_pass_to_floor);
    assert_eq!(m.thickness.unwrap().value, c.scan_range().0);
    assert!(c.run(10e-6).unwrap().pass);
}

#[test]
fn sweep_equals_single_evaluations() {
    let c = checker(paper_design(Checks::all(), 1e7, 2.5e8));
    let d = [1e-7, 1e-6, 1e-5, 1e-4];
    let rows = c.sweep(&d).unwrap();
    for (row, &di) in rows.iter().zip(&d) {
        assert_eq!(row, &c.evaluate(di).unwrap());
    }
}

fn example(name: &str) -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name);
    Scene::load(Some(&path), &[], &Library::builtin().unwrap()).unwrap()
}

fn run_scene(scene: &Scene) -> coatcheck::check::Outcome {
    let (spectrum, _) = scene.roughness.spectrum().unwrap();
    Checker::new(&spectrum, scene.design(), scene.settings)
        .unwrap()
        .run(scene.thickness.unwrap())
        .unwrap()
}

#[test]
fn paper_example_scene_is_the_paper_case() {
    let scene = example("paper-rubber-on-steel.toml");
    let out = run_scene(&scene);
    let k = &out.evaluation.contact;
    within_digits(k.area_fraction.value, 0.0927, 3);
    within_digits(k.tau_rms_interface.unwrap().value, 0.133e6, 3);
    assert!(out.pass, "{:?}", out.checks);
}

/// The measured-looking PSD is the self-affine model with roll-off times mild log-normal
/// noise (mean factor e^{σ²/2} = 1.011): its results must be close to the noise-free model's.
#[test]
fn measured_example_agrees_with_its_noise_free_model() {
    let scene = example("measured-rolloff.toml");
    let out = run_scene(&scene);
    let model = Spectrum::self_affine(0.8, 2e3, 2e8, Some(1e5))
        .unwrap()
        .scaled(1e-12 / (std::f64::consts::PI * 1e10 * (1.0 + 1.0 / 0.8)) * 1.011);
    let clean = Checker::new(&model, scene.design(), scene.settings)
        .unwrap()
        .evaluate(scene.thickness.unwrap())
        .unwrap();
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    let k = &out.evaluation.contact;
    assert!(rel(k.area_fraction.value, clean.contact.area_fraction.value) < 0.03);
    assert!(
        rel(
            k.sigma_rms_top.unwrap().value,
            clean.contact.sigma_rms_top.unwrap().value
        ) < 0.03
    );
    assert!(out.pass, "{:?}", out.checks);
}

/// The waviness example: a narrow band at q0·d ≈ 0.03. With (almost) all roughness at q0,
/// G(q1) ≈ (π/4)E0*² q0³C… reduces to the homogeneous result with E* → E0*/S(q0 d), so
/// A/A0 ≈ erf(√2 p0 S(q0 d)/(E0* ξ)) (eq. B11 with B12 for a single band).
#[test]
fn waviness_example_fails_and_matches_the_single_band_limit() {
    let scene = example("waviness-thin-film.toml");
    let out = run_scene(&scene);
    assert!(!out.pass);
    let (spectrum, _) = scene.roughness.spectrum().unwrap();
    let xi = spectrum.slope_sq().value.sqrt();
    let layers = scene.design().layers;
    let s = layers.s(6283.0 * scene.thickness.unwrap());
    let e0 = layers.film.e_star();
    let approx = libm::erf(2f64.sqrt() * scene.pressure * s / (e0 * xi));
    let a = out.evaluation.contact.area_fraction.value;
    assert!((a / approx - 1.0).abs() < 0.1, "{a} vs {approx}");
}

/// The peaks the checks use, against mpmath at 50 digits: √2·erfinv(1 − ε) for the shear and
/// the root of P(σ > L) = ε for Persson's interface normal-stress distribution (notes.md).
/// The tolerance (1e-9) is set by statrs' erf/erfc (about 1e-10 relative).
#[test]
#[allow(clippy::excessive_precision)]
fn peak_definitions_match_mpmath() {
    use coatcheck::contact::{NormalStress, tau_exceedance, tau_peak};
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    for (eps, want) in [
        (1e-6, 4.8916384756985903862),
        (1e-3, 3.2905267314918947932),
        (1e-12, 7.130506848171324458),
    ] {
        assert!(rel(tau_peak(1.0, eps), want) < 1e-9, "{eps}");
        assert!(rel(tau_exceedance(1.0, want), eps) < 1e-9, "{eps}");
    }
    for (p0, s, level, want) in [
        (1e5, 2.22e5, 1e6, 0.000071363725175927777202),
        (1e5, 1e11, 3e11, 0.011108996538258969991),
        (1e5, 1e3, 1.05e5, 2.8665157187919391167e-7),
    ] {
        let got = NormalStress { p0, sigma_rms: s }.exceedance(level);
        assert!(rel(got, want) < 1e-9, "{p0} {s} {level}: {got}");
    }
    for (p0, s, eps, want) in [
        (1e5, 2.22e5, 1e-6, 1201435.4789189519625),
        (1e5, 1e11, 1e-6, 525652176975.78080742),
        (1e5, 1e3, 1e-6, 104753.42430882289896),
        (1e5, 1e2, 0.3, 100052.44005127080408),
        (1e5, 1e5, 0.9, 54437.864440880885955),
    ] {
        let got = NormalStress { p0, sigma_rms: s }.peak(eps).value;
        assert!(rel(got, want) < 1e-9, "{p0} {s} {eps}: {got}");
    }
}

/// A spectrum whose lowest octave carries most of G(q1) gets a warning that the result depends
/// on where the data start; the paper's self-affine spectrum (H = 1: equal G per octave) not.
#[test]
fn low_octave_dominance_is_warned() {
    use coatcheck::psd::Tabulated;
    let q: Vec<f64> = vec![1e5, 1.5e5, 2e5, 1e6, 1e7];
    let c: Vec<f64> = q
        .iter()
        .map(|&q| {
            if q <= 2e5 {
                1e-20
            } else {
                1e-20 * (q / 2e5).powi(-8)
            }
        })
        .collect();
    let steep = Spectrum::Tabulated(Tabulated::new(q, c).unwrap())
        .scaled_to_rms_slope(0.5)
        .unwrap();
    let design = paper_design(checks(true, false), 1e7, 2.5e8);
    let out = Checker::new(&steep, design.clone(), Settings::default())
        .unwrap()
        .run(10e-6)
        .unwrap();
    assert!(out.evaluation.contact.low_octave_share > 0.5);
    assert!(
        out.warnings.iter().any(|w| w.contains("lowest octave")),
        "{:?}",
        out.warnings
    );
    let paper = checker(design).run(10e-6).unwrap();
    assert!(!paper.warnings.iter().any(|w| w.contains("lowest octave")));
}
