//! The layer-stack checker under sliding friction (`StackChecker` with `friction` > 0 or the
//! vector shear rule), against independent references: one layer is the film's checker under
//! sliding (`Checker`, whose kernels come from closed forms and their tables), two identical
//! adjacent layers are one layer of the summed thickness, μ = 0 is the static stack, the vector
//! peak at μ = 0 is the Rayleigh tail of the static shear, and d_min agrees with a dense scan.

use coatcheck::check::stack::{StackChecker, StackDesign, StackLayer};
use coatcheck::check::{Checker, Checks, Criteria, D_MIN_RTOL, Design, ShearTail};
use coatcheck::layer::{Bilayer, Elastic};
use coatcheck::prec::{Estimate, Settings};
use coatcheck::psd::Spectrum;

fn paper_spectrum() -> Spectrum {
    Spectrum::self_affine(1.0, 1e5, 1e8, None)
        .unwrap()
        .scaled_to_rms_slope(1.0)
        .unwrap()
}

fn el(e: f64, nu: f64) -> Elastic {
    Elastic::new(e, nu).unwrap()
}

fn layer(name: &str, material: Elastic, thickness: f64, bond: f64) -> StackLayer {
    StackLayer {
        name: name.into(),
        material,
        thickness,
        bond_strength: bond,
    }
}

fn criteria(checks: Checks, shear_tail: Option<ShearTail>) -> Criteria {
    Criteria {
        epsilon: 1e-6,
        safety_factor: 1.0,
        checks,
        shear_tail,
    }
}

fn stack_design(layers: Vec<StackLayer>, friction: f64, criteria: Criteria) -> StackDesign {
    StackDesign {
        layers,
        substrate: el(2e11, 0.3),
        pressure: 1e5,
        yield_strength: Some(2.5e8),
        friction,
        criteria,
        thickness_of: 0,
    }
}

fn stack_checker(design: StackDesign) -> StackChecker {
    StackChecker::new(&paper_spectrum(), design, Settings::default()).unwrap()
}

/// |a − b| ≤ 1e-12 |b| (two computations of one number by different code paths, each to
/// rounding); returns the relative difference.
fn same(what: &str, a: f64, b: f64) -> f64 {
    assert!(
        (a - b).abs() <= 1e-12 * b.abs(),
        "{what}: {a:e} vs {b:e} (relative {:e})",
        (a - b).abs() / b.abs()
    );
    if b == 0.0 {
        0.0
    } else {
        (a - b).abs() / b.abs()
    }
}

/// A one-layer stack under sliding is the film under sliding: every number the film's report
/// gives under sliding (A/A0, p0·A0/A, σ_rms and its ε-peak at the interface with the
/// friction-driven part, the mean shear, τ_x, τ_y, the vector peak, P(|τ| > bond), the paper's
/// static peak, every check's value) to 1e-12 relative, and d_min to its own error estimate
/// (each search's samples agree to 1e-12; the two brackets differ only by that).
#[test]
fn one_layer_stack_under_sliding_is_the_film() {
    let (rubber, steel) = (el(1e6, 0.5), el(2e11, 0.3));
    let mut worst = 0.0f64;
    for (mu, d, bond) in [(0.3, 1e-6, 2e6), (1.0, 1e-5, 3e6), (0.5, 1e-7, 1e6)] {
        let crit = criteria(Checks::all(), None);
        let film = Checker::new(
            &paper_spectrum(),
            Design {
                layers: Bilayer::new(rubber, steel),
                pressure: 1e5,
                yield_strength: Some(2.5e8),
                bond_strength: bond,
                friction: mu,
                criteria: crit,
            },
            Settings::default(),
        )
        .unwrap();
        let stack = stack_checker(stack_design(
            vec![layer("rubber", rubber, d, bond)],
            mu,
            crit,
        ));
        let f = film.run(d).unwrap();
        let s = stack.run().unwrap();
        assert_eq!(f.evaluation.shear_tail, ShearTail::Vector);
        assert_eq!(s.shear_tail, ShearTail::Vector);
        let (fe, i) = (&f.evaluation, &s.interfaces[0]);
        let (fs, ss) = (fe.sliding.unwrap(), i.sliding.unwrap());
        let at = |n: &str| format!("mu {mu}, d {d}: {n}");
        assert_eq!(ss.mean.value, fs.mean.value, "{}", at("mean"));
        for (name, a, b) in [
            (
                "A/A0",
                s.contact.top.area_fraction,
                fe.contact.area_fraction,
            ),
            ("p0 A0/A", s.mean_contact_pressure, fe.mean_contact_pressure),
            (
                "sigma_rms",
                i.sigma_rms,
                fe.contact.sigma_rms_interface.unwrap(),
            ),
            ("sigma_peak", i.sigma_peak, fe.sigma_peak_interface.unwrap()),
            ("tau_rms", i.tau_rms, fe.contact.tau_rms_interface.unwrap()),
            ("tau_x", ss.tau_x_rms, fs.tau_x_rms),
            ("tau_y", ss.tau_y_rms, fs.tau_y_rms),
            ("tau_peak", i.tau_peak, fe.tau_peak.unwrap()),
            (
                "tau_peak_static",
                i.tau_peak_static.unwrap(),
                fe.tau_peak_static.unwrap(),
            ),
        ] {
            worst = worst.max(same(&at(name), a.value, b.value));
        }
        worst = worst.max(same(
            &at("P(|tau| > bond)"),
            i.bond_exceedance,
            fe.bond_exceedance.unwrap(),
        ));
        // Every check but min-thickness (whose d_min is compared below).
        for (c, fc) in s.checks.iter().zip(&f.checks) {
            assert_eq!(c.result.kind, fc.kind, "{}", at("checks"));
            assert_eq!(c.result.pass, fc.pass, "{}", at(fc.kind.name()));
            if fc.kind != coatcheck::check::CheckKind::MinThickness {
                worst = worst.max(same(
                    &at(fc.kind.name()),
                    c.result.value.value,
                    fc.value.value,
                ));
            }
        }
        let (a, b) = (
            s.min_thickness.unwrap().thickness.unwrap(),
            f.min_thickness.unwrap().thickness.unwrap(),
        );
        assert!(
            (a.value - b.value).abs() <= a.err.max(b.err),
            "{}: {a:?} vs {b:?}",
            at("d_min")
        );
    }
    eprintln!("one-layer stack checker against the film under sliding: worst {worst:e}");
}

/// Two identical adjacent layers are one layer of the summed thickness under sliding (μ = 0.5):
/// a PTFE skin on 40 µm of rubber split as 15 + 25 µm against the whole, both on steel. The top
/// surface, the skin's interface and the bottom interface (σ_rms, σ_peak, τ_rms, the shear
/// vector, its peak, P(|τ| > bond), the static peak) agree to 1e-12 relative.
#[test]
fn two_identical_layers_under_sliding_equal_one() {
    let (ptfe, rubber) = (el(5e8, 0.46), el(2e6, 0.5));
    let crit = criteria(Checks::all(), None);
    let split = stack_checker(stack_design(
        vec![
            layer("skin", ptfe, 5e-6, 2e6),
            layer("upper", rubber, 15e-6, 1e12),
            layer("lining", rubber, 25e-6, 3e6),
        ],
        0.5,
        crit,
    ));
    let whole = stack_checker(stack_design(
        vec![
            layer("skin", ptfe, 5e-6, 2e6),
            layer("lining", rubber, 40e-6, 3e6),
        ],
        0.5,
        crit,
    ));
    let (s, w) = (split.evaluate(5e-6).unwrap(), whole.evaluate(5e-6).unwrap());
    let mut worst = same(
        "A/A0",
        s.contact.top.area_fraction.value,
        w.contact.top.area_fraction.value,
    );
    for (i, j) in [(0, 0), (2, 1)] {
        let (a, b) = (&s.interfaces[i], &w.interfaces[j]);
        let (sa, sb) = (a.sliding.unwrap(), b.sliding.unwrap());
        let pairs: [(&str, Estimate, Estimate); 8] = [
            ("sigma_rms", a.sigma_rms, b.sigma_rms),
            ("sigma_peak", a.sigma_peak, b.sigma_peak),
            ("tau_rms", a.tau_rms, b.tau_rms),
            ("mean", sa.mean, sb.mean),
            ("tau_x", sa.tau_x_rms, sb.tau_x_rms),
            ("tau_y", sa.tau_y_rms, sb.tau_y_rms),
            ("tau_peak", a.tau_peak, b.tau_peak),
            (
                "tau_peak_static",
                a.tau_peak_static.unwrap(),
                b.tau_peak_static.unwrap(),
            ),
        ];
        for (name, x, y) in pairs {
            worst = worst.max(same(&format!("{}: {name}", b.name), x.value, y.value));
        }
        worst = worst.max(same(
            &format!("{}: P(|tau| > bond)", b.name),
            a.bond_exceedance,
            b.bond_exceedance,
        ));
    }
    eprintln!("split layer checker under sliding: worst {worst:e}");
}

/// μ = 0 is the static stack: without a rule asked for, the outcome is the static one to the
/// last bit (the static road); with the vector rule asked for, every static quantity is the
/// same to the last bit, τ_x = τ_y = τ_rms/√2, the mean is 0, and the vector peak is the
/// Rayleigh tail τ_rms·√(ln(1/ε)) (notes.md, "Sliding friction") to the tail's 1e-10.
#[test]
fn zero_friction_is_the_static_stack() {
    let (rubber, epoxy) = (el(1e6, 0.5), el(3e9, 0.35));
    let layers = vec![
        layer("rubber", rubber, 10e-6, 1e6),
        layer("primer", epoxy, 10e-6, 5e6),
    ];
    let run = |friction: f64, tail: Option<ShearTail>| {
        stack_checker(stack_design(
            layers.clone(),
            friction,
            criteria(Checks::all(), tail),
        ))
        .run()
        .unwrap()
    };
    let stat = run(0.0, None);
    assert_eq!(stat.shear_tail, ShearTail::HalfNormal);
    assert!(stat.interfaces.iter().all(|i| i.sliding.is_none()));
    let vector = run(0.0, Some(ShearTail::Vector));
    assert_eq!(vector.shear_tail, ShearTail::Vector);
    assert_eq!(vector.contact, stat.contact);
    assert_eq!(vector.mean_contact_pressure, stat.mean_contact_pressure);
    let eps: f64 = 1e-6;
    for (v, s) in vector.interfaces.iter().zip(&stat.interfaces) {
        assert_eq!(
            (v.sigma_rms, v.tau_rms, v.sigma_peak),
            (s.sigma_rms, s.tau_rms, s.sigma_peak)
        );
        let sh = v.sliding.unwrap();
        assert_eq!(sh.mean.value, 0.0);
        let half = s.tau_rms.value / 2f64.sqrt();
        same("tau_x", sh.tau_x_rms.value, half);
        same("tau_y", sh.tau_y_rms.value, half);
        let rayleigh = s.tau_rms.value * (1.0 / eps).ln().sqrt();
        assert!(
            (v.tau_peak.value - rayleigh).abs() <= 1e-10 * rayleigh,
            "{}: {} vs {rayleigh}",
            v.name,
            v.tau_peak.value
        );
        // P(|τ| > bond) of the Rayleigh law, exp(−bond²/τ_rms²).
        let p = (-(v.bond_strength / s.tau_rms.value).powi(2)).exp();
        assert!(
            (v.bond_exceedance - p).abs() <= 1e-10 * p.max(f64::MIN_POSITIVE),
            "{}: {} vs {p}",
            v.name,
            v.bond_exceedance
        );
        assert_eq!(v.tau_peak_static, Some(s.tau_peak));
    }
}

/// The utilisation of every check at every thickness of a dense log scan of the varied layer
/// (`per_decade` points a decade over the search's range), and the last failing thickness with
/// the next one above it.
fn dense_scan(c: &StackChecker, per_decade: f64) -> Option<(f64, f64)> {
    let (lo, hi) = c.scan_range();
    let n = ((hi / lo).log10() * per_decade).ceil() as usize;
    let d: Vec<f64> = (0..=n)
        .map(|i| lo * (hi / lo).powf(i as f64 / n as f64))
        .collect();
    let pass: Vec<bool> = c
        .sweep(&d)
        .unwrap()
        .iter()
        .map(|r| r.checks.iter().all(|ch| ch.result.pass))
        .collect();
    let last = pass.iter().rposition(|p| !p)?;
    Some((d[last], d.get(last + 1).copied().unwrap_or(f64::INFINITY)))
}

/// d_min of the varied layer under sliding against a dense scan (60 points a decade): no
/// scanned thickness above d_min fails, the last failing one is just below it, the full check
/// passes at d_min (1 + rtol) and fails at d_min (1 − rtol). A rubber lining under a PTFE skin
/// (the lining varied; bond-shear, the lining's bond below the shear its thin states reach) at
/// μ = 0.3 and 1, and rubber on an epoxy primer (the rubber varied, every check) at μ = 0.5.
#[test]
fn d_min_under_sliding_matches_a_dense_scan() {
    let (ptfe, rubber, epoxy) = (el(5e8, 0.46), el(2e6, 0.5), el(3e9, 0.35));
    let bond_only = Checks {
        bond_shear: true,
        substrate_yield: false,
        min_thickness: true,
    };
    let skin = |mu: f64, bond: f64| {
        stack_design(
            vec![
                layer("skin", ptfe, 5e-6, 1.5e7),
                layer("lining", rubber, 100e-6, bond),
            ],
            mu,
            criteria(bond_only, None),
        )
    };
    let primer = stack_design(
        vec![
            layer("rubber", el(1e6, 0.5), 10e-6, 5e6),
            layer("primer", epoxy, 10e-6, 1e7),
        ],
        0.5,
        criteria(Checks::all(), None),
    );
    let cases = [(skin(0.3, 2e5), 1), (skin(1.0, 1e6), 1), (primer, 0)];
    for (mut design, varied) in cases {
        design.thickness_of = varied;
        let name = design.layers[varied].name.clone();
        let c = stack_checker(design);
        let m = c.min_thickness().unwrap();
        let d_min = m.thickness.unwrap().value;
        assert!(!m.all_pass_to_floor, "{name}");
        let (d_fail, d_pass) = dense_scan(&c, 60.0).expect("a failing thickness");
        assert!(
            d_fail <= d_min * (1.0 + D_MIN_RTOL) && d_min <= d_pass * (1.0 + D_MIN_RTOL),
            "{name}: d_min {d_min:e} outside the scan's bracket [{d_fail:e}, {d_pass:e}]"
        );
        let pass = |d: f64| {
            c.evaluate(d)
                .unwrap()
                .checks
                .iter()
                .all(|ch| ch.result.pass)
        };
        assert!(
            pass(d_min * (1.0 + D_MIN_RTOL)),
            "{name}: fails above d_min"
        );
        assert!(
            !pass(d_min * (1.0 - D_MIN_RTOL)),
            "{name}: passes below d_min"
        );
        eprintln!(
            "{name}: d_min {d_min:e} in [{d_fail:e}, {d_pass:e}], {} evaluations",
            m.evaluations
        );
    }
}

/// The smallest ratio, over every window of at most `n` grid steps, of the larger value at its
/// ends to the largest inside it, for a kernel given by its ln on a grid: how far the kernel can
/// rise between the ends of a scan step of that length.
fn worst_end_ratio(ln_k: &[f64], n: usize) -> f64 {
    let mut worst = f64::INFINITY;
    for i in 0..ln_k.len() {
        let mut inside = f64::NEG_INFINITY;
        for j in i + 1..(i + n + 1).min(ln_k.len()) {
            worst = worst.min(ln_k[i].max(ln_k[j]) - inside);
            inside = inside.max(ln_k[j]);
        }
    }
    worst.exp()
}

/// The premise of the widened scan steps under sliding (`check::min_thickness`, "Under
/// sliding"), made for one film's kernels in q·d, on the stacks of the dense-scan test as
/// functions of the varied layer's thickness: for every mode q (1e5 … 1e8 1/m, 10 a decade) and
/// every interface, |g_k|, the x-shear kernel √(((g_t,k + h_k)/2)² + (g_t,k − h_k)²/8) and
/// |f_t,k| seen at 100 thicknesses a decade over the search's range: a step no longer than a
/// widened step sees at one end at least the step's level of the largest value inside.
#[test]
fn stack_kernels_rise_between_step_ends_no_more_than_a_widened_step_allows() {
    use coatcheck::check::WIDE_STEPS;
    use coatcheck::layer::stack::{Layer, Stack};
    let (ptfe, rubber, epoxy, steel) = (el(5e8, 0.46), el(2e6, 0.5), el(3e9, 0.35), el(2e11, 0.3));
    // Each stack's layers, top first, with `None` for the varied layer's thickness.
    let stacks = [
        (
            "PTFE skin on a rubber lining of thickness d",
            [(ptfe, Some(5e-6)), (rubber, None)],
        ),
        (
            "rubber of thickness d on an epoxy primer",
            [(el(1e6, 0.5), None), (epoxy, Some(10e-6))],
        ),
    ];
    let per_decade = 100.0;
    let (lo, hi) = (1e-9f64, 5e-4f64);
    let n = ((hi / lo).log10() * per_decade).ceil() as usize;
    let ds: Vec<f64> = (0..=n)
        .map(|i| lo * (hi / lo).powf(i as f64 / n as f64))
        .collect();
    let mut worst = [[f64::INFINITY; 2]; 3];
    for (name, spec) in &stacks {
        let at: Vec<Stack> = ds
            .iter()
            .map(|&d| {
                let layers = spec
                    .iter()
                    .map(|&(material, t)| Layer {
                        material,
                        thickness: t.unwrap_or(d),
                    })
                    .collect();
                Stack::new(layers, steel).unwrap()
            })
            .collect();
        for iq in 0..=30 {
            let q = 1e5 * 10f64.powf(iq as f64 / 10.0);
            // Per interface: ln |g|, ln x-shear, ln |f_t| over the thicknesses.
            let mut ln = vec![[Vec::new(), Vec::new(), Vec::new()]; 2];
            for s in &at {
                let r = s.response(q);
                for (k, t) in s.tangential(q).iter().enumerate() {
                    let half_sum = 0.5 * (t.g_t + t.h);
                    let diff = t.g_t - t.h;
                    let kx = (half_sum * half_sum + diff * diff / 8.0).sqrt();
                    ln[k][0].push(r.interfaces[k].1.abs().ln());
                    ln[k][1].push(kx.ln());
                    ln[k][2].push(t.f_t.abs().ln());
                }
            }
            for kernels in &ln {
                for (j, k) in kernels.iter().enumerate() {
                    for (i, w) in WIDE_STEPS.iter().enumerate() {
                        let steps = (w.decades * per_decade).round() as usize;
                        let r = worst_end_ratio(k, steps);
                        assert!(
                            r >= w.level,
                            "{name}, q {q:e}, kernel {j}, {} decades: {r} < {}",
                            w.decades,
                            w.level
                        );
                        worst[j][i] = worst[j][i].min(r);
                    }
                }
            }
        }
    }
    eprintln!("stack kernels' worst end ratios (|g|, x-shear, |f_t|) per widened step: {worst:?}");
}
