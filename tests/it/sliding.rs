//! Sliding friction (notes.md, "Sliding friction"): the scene keys, Persson's theory under a
//! friction traction μσ along x (uncoupled approximation), the checks and d_min under sliding.

use crate::common::run;

const PAPER: &str = "examples/paper-rubber-on-steel.toml";

/// `--friction` outside 0..=10, an unknown `--shear-tail` and the half-normal rule with
/// friction are input errors (exit 2) naming the key.
#[test]
fn friction_and_shear_tail_reject_bad_values() {
    for (args, key) in [
        (vec!["--friction", "11"], "load.friction"),
        (vec!["--friction", "-0.1"], "load.friction"),
        (vec!["--shear-tail", "rayleigh"], "criteria.shear_tail"),
        (
            vec!["--friction", "0.5", "--shear-tail", "half-normal"],
            "criteria.shear_tail",
        ),
    ] {
        let mut all = vec!["check", PAPER];
        all.extend(args.iter());
        let o = run(&all);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(key), "{args:?}: {err}");
    }
}

use coatcheck::contact::{Engine, Request, SlidingShear};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::Settings;
use coatcheck::psd::Spectrum;
use std::f64::consts::PI;

fn paper_spectrum() -> Spectrum {
    Spectrum::self_affine(1.0, 1e5, 1e8, None)
        .unwrap()
        .scaled_to_rms_slope(1.0)
        .unwrap()
}

fn rubber_on_steel() -> Bilayer {
    Bilayer::new(
        Elastic::new(1e6, 0.5).unwrap(),
        Elastic::new(1e11, 0.5).unwrap(),
    )
}

/// The integrals 2∫P K dG of the module doc (src/contact/sliding.rs) for K = f², g², f_t²/2,
/// ((g_t + h)/2)² + (g_t − h)²/8 and (g_t − h)²/8, by an independent method: the ODE system
/// G' = (π/4)E0*² q⁴ C S⁻², I_K' = 2 P(G) K G' in u = ln q from q0 to q1, integrated by the
/// classical Runge–Kutta method on steps growing geometrically (factor `growth`) from 1e-14
/// away from q0 up to `h_max` (P leaves 1 within ln(q/q0) ~ 1e-7 for thin films), with the
/// exact kernels.
fn ode_reference(layers: &Bilayer, d: f64, p0: f64, growth: f64, h_max: f64) -> [f64; 5] {
    let s = paper_spectrum();
    let e0 = layers.film.e_star();
    let cg = 0.25 * PI * e0 * e0;
    let rhs = |u: f64, y: &[f64; 6]| -> [f64; 6] {
        let q = u.exp();
        let x = q * d;
        let r = layers.response(x);
        let t = layers.tangential(x);
        let gp = cg * q.powi(4) * s.c(q) / (r.s * r.s);
        let p = if y[0] > 0.0 {
            libm::erf(p0 / (2.0 * y[0].sqrt()))
        } else {
            1.0
        };
        let (half_sum, diff) = (0.5 * (t.g_t + t.h), t.g_t - t.h);
        let ky = diff * diff / 8.0;
        let k = [
            r.f * r.f,
            r.g * r.g,
            0.5 * t.f_t * t.f_t,
            half_sum * half_sum + ky,
            ky,
        ];
        let mut out = [gp, 0.0, 0.0, 0.0, 0.0, 0.0];
        for i in 0..5 {
            out[i + 1] = 2.0 * p * k[i] * gp;
        }
        out
    };
    let (u0, u1) = (1e5f64.ln(), 1e8f64.ln());
    let mut y = [0.0; 6];
    let (mut u, mut h) = (u0, 1e-14f64);
    let axpy = |y: &[f64; 6], k: &[f64; 6], a: f64| -> [f64; 6] {
        std::array::from_fn(|i| y[i] + a * k[i])
    };
    while u < u1 {
        let step = h.min(u1 - u);
        let k1 = rhs(u, &y);
        let k2 = rhs(u + 0.5 * step, &axpy(&y, &k1, 0.5 * step));
        let k3 = rhs(u + 0.5 * step, &axpy(&y, &k2, 0.5 * step));
        let k4 = rhs(u + step, &axpy(&y, &k3, step));
        for i in 0..6 {
            y[i] += step / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        u += step;
        h = (h * growth).min(h_max);
    }
    [y[1], y[2], y[3], y[4], y[5]]
}

fn sliding_at(d: f64, mu: f64) -> (coatcheck::contact::Contact, SlidingShear) {
    let engine = Engine::new(&paper_spectrum(), Settings::default());
    let stack = Stack {
        layers: rubber_on_steel(),
        thickness: d,
    };
    let (c, s) = engine
        .evaluate_sliding(&stack, 1e5, mu, Request::all())
        .unwrap();
    (c, s.unwrap())
}

/// The engine's sliding integrals against the ODE reference (two step sizes, which agree to
/// 1e-10 and so bound the reference's own error) on the paper's scene with μ = 0.7 at
/// q0·d = 0.1, 1 and 10: τ_x, τ_y, σ_rms(d) within their error estimates plus the reference's
/// error, and those estimates within the engine's rtol (1e-8).
#[test]
fn sliding_rms_match_an_independent_ode_solution() {
    let mu = 0.7;
    for d in [1e-6, 1e-5, 1e-4] {
        let layers = rubber_on_steel();
        let coarse = ode_reference(&layers, d, 1e5, 1.01, 2e-4);
        let fine = ode_reference(&layers, d, 1e5, 1.005, 1e-4);
        let values = |i: [f64; 5]| {
            [
                (i[0] + mu * mu * i[2]).sqrt(),
                (0.5 * i[1] + mu * mu * i[3]).sqrt(),
                (0.5 * i[1] + mu * mu * i[4]).sqrt(),
                i[1].sqrt(),
            ]
        };
        let (a, b) = (values(coarse), values(fine));
        let (c, s) = sliding_at(d, mu);
        let got = [
            c.sigma_rms_interface.unwrap(),
            s.tau_x_rms,
            s.tau_y_rms,
            c.tau_rms_interface.unwrap(),
        ];
        for k in 0..4 {
            let ref_err = (a[k] - b[k]).abs();
            assert!(ref_err <= 1e-10 * b[k], "d = {d}, {k}: {a:?} vs {b:?}");
            assert!(
                (got[k].value - b[k]).abs() <= got[k].err + 2.0 * ref_err + 1e-15 * b[k],
                "d = {d}, {k}: {:?} vs {}",
                got[k],
                b[k]
            );
            assert!(got[k].err <= 1e-8 * got[k].value, "{:?}", got[k]);
        }
        assert_eq!(s.mean.value, mu * 1e5);
    }
}

/// μ = 0 reduces to the static theory exactly: the same contact result to the last bit, and
/// the shear vector's components each τ_rms/√2 (so the vector rule is the Rayleigh tail).
#[test]
fn zero_friction_is_static_exactly() {
    let engine = Engine::new(&paper_spectrum(), Settings::default());
    for d in [1e-7, 1e-5, 1e-3] {
        let stack = Stack {
            layers: rubber_on_steel(),
            thickness: d,
        };
        let stat = engine.evaluate(&stack, 1e5, Request::all()).unwrap();
        let (c, s) = engine
            .evaluate_sliding(&stack, 1e5, 0.0, Request::all())
            .unwrap();
        let s = s.unwrap();
        assert_eq!(c, stat);
        let tau = stat.tau_rms_interface.unwrap().value;
        for comp in [s.tau_x_rms, s.tau_y_rms] {
            assert!((comp.value - tau / 2f64.sqrt()).abs() <= 4.0 * f64::EPSILON * tau);
        }
        assert_eq!(s.mean.value, 0.0);
    }
}

/// Every sliding integral is a weighted mean of its kernel against the top surface's pressure
/// variance: μ² I_K = τ_x² − τ²/2 (etc.) lies between μ² σ_top² times the least and the largest
/// K over the spectrum's q·d. A thin film (q1·d = 1e-3) passes the friction fluctuation almost
/// unchanged (K_x → 1, K_y → 0, f_t²/2 → 0: the bounds pinch to within 1e-3), a thick one
/// (q0·d = 100) screens it (every K below e^{−180}, about 4e^{−200} with the stiff substrate's mirror).
#[test]
fn friction_parts_are_bounded_by_the_kernels_thin_and_thick() {
    let spectrum = Spectrum::self_affine(1.0, 1e5, 1e6, None)
        .unwrap()
        .scaled_to_rms_slope(0.5)
        .unwrap();
    let engine = Engine::new(&spectrum, Settings::default());
    let layers = rubber_on_steel();
    let mu = 0.8;
    for d in [1e-9, 1e-7, 1e-5, 1e-3] {
        let stack = Stack {
            layers,
            thickness: d,
        };
        let (c, s) = engine
            .evaluate_sliding(&stack, 1e5, mu, Request::all())
            .unwrap();
        let s = s.unwrap();
        let stat = engine.evaluate(&stack, 1e5, Request::all()).unwrap();
        let top2 = stat.sigma_rms_top.unwrap().value.powi(2);
        let tau2 = stat.tau_rms_interface.unwrap().value.powi(2);
        let sig2 = stat.sigma_rms_interface.unwrap().value.powi(2);
        // The kernels' range over q·d in [q0 d, q1 d].
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [0.0f64; 3]);
        for i in 0..=2000 {
            let x = 1e5 * d * 10f64.powf(i as f64 / 2000.0);
            let t = layers.tangential(x);
            let ky = (t.g_t - t.h).powi(2) / 8.0;
            let k = [(0.5 * (t.g_t + t.h)).powi(2) + ky, ky, 0.5 * t.f_t * t.f_t];
            for j in 0..3 {
                lo[j] = lo[j].min(k[j]);
                hi[j] = hi[j].max(k[j]);
            }
        }
        let parts = [
            s.tau_x_rms.value.powi(2) - 0.5 * tau2,
            s.tau_y_rms.value.powi(2) - 0.5 * tau2,
            c.sigma_rms_interface.unwrap().value.powi(2) - sig2,
        ];
        for j in 0..3 {
            let (a, b) = (mu * mu * top2 * lo[j], mu * mu * top2 * hi[j]);
            let slack = 1e-7 * (tau2 + sig2 + mu * mu * top2);
            assert!(
                parts[j] >= a - slack && parts[j] <= b + slack,
                "d = {d}, {j}: {} not in [{a}, {b}]",
                parts[j]
            );
        }
        if d == 1e-9 {
            assert!(
                lo[0] > 1.0 - 1e-3 && hi[1] < 1e-3 && hi[2] < 1e-3,
                "{lo:?} {hi:?}"
            );
        }
        if d == 1e-3 {
            assert!(hi.iter().all(|&k| k < (-180.0f64).exp()), "{hi:?}");
        }
    }
}

/// The peak |τ| of the paper's scene at d = 10 µm, ε = 1e-6, μ = 0, 0.5, 1 against the
/// 30/45-digit reference (tests/data/sliding_tail_ref.py, a different integral from
/// src/tail.rs): from the reference's inputs to 1e-10 relative, and end to end (the check's
/// own rms, converged to 1e-8) to 1e-8.
#[test]
fn paper_scene_vector_peaks_match_the_high_precision_tail() {
    use coatcheck::check::{Checker, Checks};
    use coatcheck::tail::ShearVector;
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/sliding_tail_ref.csv"
    ))
    .unwrap();
    for line in text.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let (mu, m, sx, sy, eps, want) = (v[0], v[1], v[2], v[3], v[4], v[5]);
        let peak = ShearVector::new(m, sx, sy).unwrap().peak(eps).unwrap();
        assert!(
            ((peak.value - want) / want).abs() < 1e-10,
            "{line}: {peak:?}"
        );
        let mut design = crate::check::paper_design(
            Checks {
                bond_shear: true,
                substrate_yield: false,
                min_thickness: false,
            },
            10e6,
            250e6,
        );
        design.friction = mu;
        design.criteria.shear_tail = Some(coatcheck::check::ShearTail::Vector);
        let checker = Checker::new(&paper_spectrum(), design, Settings::default()).unwrap();
        let ev = checker.evaluate(1e-5).unwrap();
        let got = ev.tau_peak.unwrap();
        assert!(((got.value - want) / want).abs() < 1e-8, "{line}: {got:?}");
        assert!((got.value - want).abs() <= got.err, "{line}: {got:?}");
        let s = ev.sliding.unwrap();
        assert_eq!(s.mean.value, m);
    }
}

/// d_min under the vector rule without friction (`--shear-tail vector` at μ = 0, the Rayleigh
/// tail of the static shear) against the same dense scan: the search is the one of the
/// half-normal rule with another peak, and must be right for it too.
#[test]
fn d_min_under_the_vector_rule_without_friction_matches_a_dense_scan() {
    use crate::check::{assert_d_min_matches_brute_force, checker, paper_design};
    use coatcheck::check::Checks;
    for bond in [1e6, 2e6] {
        let mut design = paper_design(Checks::all(), bond, 2.5e8);
        design.criteria.shear_tail = Some(coatcheck::check::ShearTail::Vector);
        assert_d_min_matches_brute_force(&checker(design), 100.0);
    }
}

/// d_min under sliding (vector rule, bond shear and substrate yield) against a dense
/// brute-force scan of the full check (100 points per decade): in the scan's bracket, passing
/// just above and failing just below, and never thinner than the static d_min (friction only
/// adds shear). Friction μ = 0.02, 0.5 and 1, with bond strengths that put d_min inside the
/// range. (Under sliding the peak of this scene keeps rising towards the floor, μσ_top
/// growing as the film thins: no failing band with passing films below it.)
#[test]
fn d_min_under_sliding_matches_a_dense_scan() {
    use crate::check::{assert_d_min_matches_brute_force, checker, paper_design};
    use coatcheck::check::Checks;
    let all = Checks::all();
    for (mu, bond) in [(0.02, 1e6), (0.5, 2e6), (1.0, 3e6)] {
        let mut design = paper_design(all, bond, 2.5e8);
        design.friction = mu;
        let c = checker(design);
        let d_min = assert_d_min_matches_brute_force(&c, 100.0);
        // Friction only adds shear: d_min is at least the static one.
        let mut stat = paper_design(all, bond, 2.5e8);
        stat.criteria.shear_tail = Some(coatcheck::check::ShearTail::Vector);
        let s = checker(stat)
            .min_thickness()
            .unwrap()
            .thickness
            .map_or(0.0, |t| t.value);
        assert!(
            d_min >= s * (1.0 - coatcheck::check::D_MIN_RTOL),
            "{mu}: {d_min} < {s}"
        );
    }
}

/// A scene whose friction coupling exceeds the neglected-term threshold (the NBR gasket at
/// μ = 0.8: max μ|c|/S ≈ 4.5) warns with the number in table and JSON; the same scene without
/// friction (no sliding evaluation) does not.
#[test]
fn strong_coupling_is_warned() {
    let scene = "examples/nbr-gasket-fretting.toml";
    let json = |extra: &[&str]| -> serde_json::Value {
        let o = run(&[&["check", scene, "--format", "json"], extra].concat());
        assert!(o.status.code().is_some_and(|c| c < 2), "{o:?}");
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let coupled = |v: &serde_json::Value| {
        v["warnings"].as_array().unwrap().iter().any(|w| {
            w.as_str()
                .unwrap()
                .contains("coupling the sliding theory neglects")
        })
    };
    let v = json(&[]);
    let c = v["friction_coupling"].as_f64().unwrap();
    assert!(c > coatcheck::check::COUPLING_WARN, "{c}");
    assert!(coupled(&v), "{v}");
    let table = String::from_utf8(run(&["check", scene]).stdout).unwrap();
    assert!(table.contains(&format!("mu|c|/S = {c:.3}")), "{table}");
    let v = json(&["--friction", "0", "--shear-tail", "half-normal"]);
    assert!(!coupled(&v), "{v}");
}
