//! Error against run time of the contact engine (issue 5).
//!
//! For several scenes and each tolerance setting rtol = 1e-3 … 1e-10, prints the median run
//! time of `Engine::new` + `evaluate` (cold: the d-independent grid is built inside) and of
//! `evaluate` alone (warm: grid cached, as in a thickness sweep), and for each reported quantity
//! (A/A0, σ_rms top, σ_rms interface, τ_rms, τ_peak at ε = 1e-6) the true relative error
//! against a reference and the engine's estimated relative error (`Estimate.err / value`).
//!
//! Reference: the engine at rtol = 1e-12; its A/A0 is cross-checked against the 30-digit mpmath
//! quadrature in tests/data/contact_ref.csv where the scene matches. A row "bounds" when
//! |value − ref| ≤ est.err + ref.err (the reference's own estimate, ≤ 1e-12 relative, is the
//! only slack); any row where it does not is printed as BOUND VIOLATED.
//!
//! Run: `cargo run --release --example accuracy`

use coatcheck::contact::{Contact, Engine, Request, tau_peak};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::{DEFAULT_EPSILON, DEFAULT_RTOL, Estimate, Settings, Termination};
use coatcheck::psd::Spectrum;
use std::hint::black_box;
use std::time::Instant;

#[path = "../tests/it/fixtures.rs"]
mod fixtures;
use fixtures::measured_like;

const RTOLS: [f64; 8] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];
const REF_RTOL: f64 = 1e-12;
const QUANTITIES: [&str; 5] = ["A/A0", "σ_rms top", "σ_rms interface", "τ_rms", "τ_peak"];

struct Scene {
    name: &'static str,
    spectrum: Spectrum,
    stack: Stack,
    p0: f64,
    /// A/A0 from tests/data/contact_ref.csv (30-digit mpmath), when the scene is one of its rows.
    mpmath_area: Option<f64>,
}

fn stack(e0: f64, nu0: f64, e1: f64, nu1: f64, d: f64) -> Stack {
    Stack::new(
        Bilayer::new(
            Elastic::new(e0, nu0).expect("valid film"),
            Elastic::new(e1, nu1).expect("valid substrate"),
        ),
        d,
    )
    .expect("valid thickness")
}

fn paper_spectrum() -> Spectrum {
    Spectrum::self_affine(1.0, 1e5, 1e8, None)
        .and_then(|s| s.scaled_to_rms_slope(1.0))
        .expect("valid spectrum")
}

/// A/A0 column of tests/data/contact_ref.csv for the row matching (e0, nu0, e1, nu1, d, p0).
fn mpmath_area(key: [f64; 6]) -> Option<f64> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/contact_ref.csv");
    let text = std::fs::read_to_string(path).expect("tests/data/contact_ref.csv readable");
    text.lines().skip(1).find_map(|line| {
        let v: Vec<f64> = line
            .split(',')
            .map(|x| x.parse().expect("numeric reference"))
            .collect();
        (v[..6] == key).then_some(v[7])
    })
}

fn scenes() -> Vec<Scene> {
    vec![
        Scene {
            name: "paper: rubber 1 MPa on steel, H = 1, q0 = 1e5, q1 = 1e8 1/m, xi = 1, p0 = 0.1 MPa, d = 10 um",
            spectrum: paper_spectrum(),
            stack: stack(1e6, 0.5, 1e11, 0.5, 1e-5),
            p0: 1e5,
            mpmath_area: mpmath_area([1e6, 0.5, 1e11, 0.5, 1e-5, 1e5]),
        },
        Scene {
            name: "measured-like 1000-point PSD (1e4..1e8 1/m, xi = 0.5), rubber on steel (2e11, 0.3), p0 = 0.1 MPa, d = 20 um",
            spectrum: measured_like(1000),
            stack: stack(1e6, 0.5, 2e11, 0.3, 20e-6),
            p0: 1e5,
            mpmath_area: None,
        },
        Scene {
            name: "thin film: paper's case at q0 d = 1e-4 (d = 1 nm)",
            spectrum: paper_spectrum(),
            stack: stack(1e6, 0.5, 1e11, 0.5, 1e-9),
            p0: 1e5,
            mpmath_area: None,
        },
        Scene {
            name: "thin, slightly compressible film: nu = 0.49985 on steel (nu 0.3), q0 d = 0.3, p0 = 0.1 MPa",
            spectrum: paper_spectrum(),
            stack: stack(1e6, 0.49985, 1e11, 0.3, 3e-6),
            p0: 1e5,
            mpmath_area: mpmath_area([1e6, 0.49985, 1e11, 0.3, 3e-6, 1e5]),
        },
        Scene {
            name: "hard film on soft substrate: E 1 GPa (nu 0.3) on 1 MPa (nu 0.5), paper's PSD, p0 = 10 kPa, d = 10 um",
            spectrum: paper_spectrum(),
            stack: stack(1e9, 0.3, 1e6, 0.5, 1e-5),
            p0: 1e4,
            mpmath_area: mpmath_area([1e9, 0.3, 1e6, 0.5, 1e-5, 1e4]),
        },
    ]
}

fn request() -> Request {
    Request {
        sigma_top: true,
        sigma_interface: true,
        tau_interface: true,
        e_eff: false,
    }
}

fn evaluate(engine: &Engine, s: &Scene) -> Contact {
    engine
        .evaluate(&s.stack, s.p0, request())
        .expect("scene evaluates")
}

/// The five reported quantities as estimates; τ_peak = k τ_rms is linear in τ_rms.
fn quantities(c: &Contact) -> [Estimate; 5] {
    let tau = c.tau_rms_interface.expect("requested");
    let k = tau_peak(1.0, DEFAULT_EPSILON);
    [
        c.area_fraction,
        c.sigma_rms_top.expect("requested"),
        c.sigma_rms_interface.expect("requested"),
        tau,
        tau.map(|t| k * t, |_| k),
    ]
}

/// Median wall time in µs of `f`, repeated until ~0.2 s or 201 runs (at least 5).
fn median_us(mut f: impl FnMut()) -> f64 {
    f();
    let mut t = Vec::new();
    let start = Instant::now();
    while t.len() < 5 || (t.len() < 201 && start.elapsed().as_secs_f64() < 0.2) {
        let s = Instant::now();
        f();
        t.push(s.elapsed().as_secs_f64() * 1e6);
    }
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

struct Row {
    rtol: f64,
    cold_us: f64,
    warm_us: f64,
    /// Per quantity: (true relative error, estimated relative error, bound holds).
    errs: [(f64, f64, bool); 5],
    not_reached: bool,
}

fn main() {
    let mut all_rows: Vec<(usize, Row)> = Vec::new();
    let mut violations = Vec::new();
    for (si, s) in scenes().iter().enumerate() {
        let reference = Engine::new(&s.spectrum, Settings { rtol: REF_RTOL });
        let rc = evaluate(&reference, s);
        let mut refs = quantities(&rc);
        println!("\n### Scene {}: {}\n", si + 1, s.name);
        let status = if rc.area_fraction.status == Termination::ToleranceNotReached {
            "tolerance NOT reached"
        } else {
            "converged"
        };
        print!(
            "Reference (rtol {REF_RTOL:.0e}, {status}): A/A0 = {:.15e} ± {:.1e}",
            refs[0].value, refs[0].err
        );
        match s.mpmath_area {
            Some(mp) => {
                let diff = (refs[0].value - mp).abs();
                let ok = diff <= refs[0].err + 1e-15 * mp;
                println!(
                    "; mpmath (30 digits) {mp:.15e}, |diff| = {diff:.1e} ({})",
                    if ok {
                        "within the reference's estimate"
                    } else {
                        "REFERENCE BOUND VIOLATED"
                    }
                );
                if !ok {
                    violations.push(format!(
                        "scene {}: engine at rtol {REF_RTOL:.0e}, A/A0: true {:.1e} > est {:.1e}",
                        si + 1,
                        diff / mp,
                        refs[0].rel_err()
                    ));
                }
                // The 30-digit value is the reference for A/A0 (rounded to 20 digits in the file).
                refs[0] = Estimate::new(mp, 1e-17 * mp, Termination::Exact);
            }
            None => println!(" (no mpmath row for this scene)"),
        }
        println!(
            "σ_top = {:.6e} Pa, σ_if = {:.6e} Pa, τ_rms = {:.6e} Pa, τ_peak = {:.6e} Pa; lowest-octave share of G1 = {:.3}\n",
            refs[1].value, refs[2].value, refs[3].value, refs[4].value, rc.low_octave_share
        );
        println!(
            "| rtol | new+evaluate [µs] | evaluate [µs] | {} |",
            QUANTITIES
                .iter()
                .map(|q| format!("{q} true / est"))
                .collect::<Vec<_>>()
                .join(" | ")
        );
        println!("|---:|---:|---:|{}", "---:|".repeat(QUANTITIES.len()));
        for &rtol in &RTOLS {
            let settings = Settings { rtol };
            let cold_us = median_us(|| {
                black_box(evaluate(&Engine::new(black_box(&s.spectrum), settings), s));
            });
            let engine = Engine::new(&s.spectrum, settings);
            let c = evaluate(&engine, s);
            let warm_us = median_us(|| {
                black_box(evaluate(&engine, black_box(s)));
            });
            let qs = quantities(&c);
            let mut errs = [(0.0, 0.0, true); 5];
            for (k, (q, r)) in qs.iter().zip(refs.iter()).enumerate() {
                let diff = (q.value - r.value).abs();
                let holds = diff <= q.err + r.err;
                if !holds {
                    violations.push(format!(
                        "scene {}, rtol {rtol:.0e}, {}: true {:.2e} > est {:.2e} (+ ref {:.1e})",
                        si + 1,
                        QUANTITIES[k],
                        diff / r.value.abs(),
                        q.rel_err(),
                        r.rel_err()
                    ));
                }
                errs[k] = (diff / r.value.abs(), q.err / r.value.abs(), holds);
            }
            let not_reached = qs
                .iter()
                .any(|e| e.status == Termination::ToleranceNotReached);
            let cells: Vec<String> = errs
                .iter()
                .map(|&(t, e, ok)| {
                    format!(
                        "{t:.1e} / {e:.1e}{}",
                        if ok { "" } else { " BOUND VIOLATED" }
                    )
                })
                .collect();
            println!(
                "| {rtol:.0e}{} | {cold_us:.0} | {warm_us:.0} | {} |",
                if not_reached { " (not reached)" } else { "" },
                cells.join(" | ")
            );
            all_rows.push((
                si,
                Row {
                    rtol,
                    cold_us,
                    warm_us,
                    errs,
                    not_reached,
                },
            ));
        }
    }
    summary(&all_rows, &violations);
}

fn summary(rows: &[(usize, Row)], violations: &[String]) {
    println!("\n### Summary over all scenes and quantities\n");
    println!(
        "| rtol | worst new+evaluate [µs] | worst evaluate [µs] | worst true rel. error | worst est. rel. error | worst true/est |"
    );
    println!("|---:|---:|---:|---:|---:|---:|");
    let mut worst_ratio: (f64, String) = (0.0, String::new());
    for &rtol in &RTOLS {
        let sel: Vec<&Row> = rows
            .iter()
            .filter(|(_, r)| r.rtol == rtol)
            .map(|(_, r)| r)
            .collect();
        let max = |f: &dyn Fn(&Row) -> f64| sel.iter().map(|r| f(r)).fold(0.0, f64::max);
        let cold = max(&|r| r.cold_us);
        let warm = max(&|r| r.warm_us);
        let t = max(&|r| r.errs.iter().map(|e| e.0).fold(0.0, f64::max));
        let e = max(&|r| r.errs.iter().map(|e| e.1).fold(0.0, f64::max));
        let ratio = max(&|r| r.errs.iter().map(|e| e.0 / e.1).fold(0.0, f64::max));
        let nr = sel.iter().filter(|r| r.not_reached).count();
        println!(
            "| {rtol:.0e}{} | {cold:.0} | {warm:.0} | {t:.1e} | {e:.1e} | {ratio:.2} |",
            if nr > 0 {
                format!(" ({nr} scene(s) not reached)")
            } else {
                String::new()
            }
        );
        for (si, r) in rows.iter().filter(|(_, r)| r.rtol == rtol) {
            for (k, e) in r.errs.iter().enumerate() {
                if e.0 / e.1 > worst_ratio.0 {
                    worst_ratio = (
                        e.0 / e.1,
                        format!("scene {}, rtol {rtol:.0e}, {}", si + 1, QUANTITIES[k]),
                    );
                }
            }
        }
    }
    println!(
        "\nWorst true/estimated error ratio: {:.3} ({}).",
        worst_ratio.0, worst_ratio.1
    );
    if violations.is_empty() {
        println!("Every estimate bounds its true error.");
    } else {
        for v in violations {
            println!("BOUND VIOLATED: {v}");
        }
    }
    // Total warm evaluation time over the scenes and the worst true relative error.
    let at = |rtol: f64| {
        rows.iter()
            .filter(|(_, r)| r.rtol == rtol)
            .map(|(_, r)| (r.warm_us, r.errs.iter().map(|e| e.0).fold(0.0, f64::max)))
            .fold((0.0, 0.0), |a: (f64, f64), b| (a.0 + b.0, a.1.max(b.1)))
    };
    let (t_default, e_default) = at(DEFAULT_RTOL);
    let (t_loose, e_loose) = at(DEFAULT_RTOL * 100.0);
    let (t_tight, _) = at(DEFAULT_RTOL / 100.0);
    println!(
        "\nDefault: rtol = {DEFAULT_RTOL:.0e} (coatcheck::prec::DEFAULT_RTOL). Its worst true \
         relative error over all scenes and quantities is {e_default:.1e}, far below any input's \
         uncertainty yet tight enough that differences between thicknesses (d_min) are not \
         numerical noise, for {t_default:.0} µs of evaluation over the {} scenes. \
         rtol = {:.0e} saves little ({t_loose:.0} µs) for an error of {e_loose:.1e}; \
         rtol = {:.0e} costs {t_tight:.0} µs (grid refinement, and the estimates approach the \
         kernels' rounding floor) for digits no input carries.",
        rows.iter().filter(|(_, r)| r.rtol == DEFAULT_RTOL).count(),
        DEFAULT_RTOL * 100.0,
        DEFAULT_RTOL / 100.0
    );
}
