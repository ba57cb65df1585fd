//! The exact contact on a layer stack under sliding friction (`coatcheck::verify_stack::sliding`,
//! `verify --layer --friction`, `check --verify` on a `[[layer]]` scene with `load.friction`)
//! against independent references: the film's sliding solver (`coatcheck::verify::sliding`,
//! with the film's closed-form tangential kernels) for one layer; a single oblique mode in full
//! contact, whose every interface stress is a closed form in the stack's kernels; the static
//! output at μ = 0; one layer of the summed thickness for two identical adjacent layers.

use crate::common::{json, run};
use crate::golden::mask_timings;
use crate::verify_stack::{
    close, close_est, design, el, layer, map, same_interface, surface, tight,
};
use coatcheck::bem::{BemSettings, FieldStats, InterfaceFields, Surface};
use coatcheck::check::{Checks, Criteria, Design};
use coatcheck::layer::Bilayer;
use coatcheck::prec::{Estimate, Settings};
use coatcheck::verify::sliding::{ExactSliding, SlidingVerification, with_friction_kernels};
use coatcheck::verify_stack::sliding::{compare_sliding, interface_kernels, with_friction};
use coatcheck::verify_stack::{InterfaceExact, design_stack, verify};
use serde_json::Value;
use std::f64::consts::PI;

/// Per pixel, |a − b| ≤ tol·max|b| for the three stress fields.
fn same_fields(a: &InterfaceFields, b: &InterfaceFields, tol: f64, what: &str) {
    for (x, y, name) in [
        (&a.normal, &b.normal, "sigma_n"),
        (&a.shear_x, &b.shear_x, "tau_x"),
        (&a.shear_y, &b.shear_y, "tau_y"),
    ] {
        let scale = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (i, (u, v)) in x.iter().zip(y).enumerate() {
            assert!(
                (u - v).abs() <= tol * scale,
                "{what} {name} pixel {i}: {u:e} vs {v:e} (scale {scale:e})"
            );
        }
    }
}

fn same_summary(a: &ExactSliding, b: &ExactSliding, tol: f64) {
    assert_eq!(a.friction, b.friction);
    close(a.mean[0], b.mean[0], tol, "mean tau_x");
    // The mean τ_y is 0 up to FFT rounding: absolute, against the mean τ_x.
    assert!((a.mean[1] - b.mean[1]).abs() <= 1e-13 * b.mean[0].abs());
    close(a.tau_x_rms, b.tau_x_rms, tol, "tau_x rms");
    close(a.tau_y_rms, b.tau_y_rms, tol, "tau_y rms");
    close(
        a.sigma_rms_interface,
        b.sigma_rms_interface,
        tol,
        "sigma_rms",
    );
    close(a.static_tau_rms, b.static_tau_rms, tol, "static tau_rms");
}

fn same_sliding(a: &SlidingVerification, b: &SlidingVerification, tol: f64) {
    assert_eq!(a.friction, b.friction);
    // The means are μ p0 (and 0) up to FFT rounding, and their error estimates differences of
    // such: absolute, against μ p0.
    let scale = b.mean_x.value.abs();
    close(a.mean_x.value, b.mean_x.value, tol, "mean tau_x");
    for (x, y) in [
        (a.mean_x.err, b.mean_x.err),
        (a.mean_y.value, b.mean_y.value),
        (a.mean_y.err, b.mean_y.err),
    ] {
        assert!((x - y).abs() <= 1e-13 * scale, "{a:?} vs {b:?}");
    }
    let pairs = [
        (a.tau_x_rms, b.tau_x_rms, "tau_x rms"),
        (a.tau_y_rms, b.tau_y_rms, "tau_y rms"),
        (a.quantiles[0], b.quantiles[0], "|tau| q0.5"),
        (a.quantiles[1], b.quantiles[1], "|tau| q0.99"),
        (a.quantiles[2], b.quantiles[2], "|tau| q0.999"),
        (a.max, b.max, "|tau| max"),
    ];
    for (x, y, what) in pairs {
        close_est(&x, &y, tol, what);
    }
}

/// Every reported number of two interfaces under sliding, the shear vector included.
fn same_sliding_interface(a: &InterfaceExact, b: &InterfaceExact, tol: f64) {
    same_interface(a, b, tol);
    same_sliding(
        a.sliding.as_ref().unwrap(),
        b.sliding.as_ref().unwrap(),
        tol,
    );
}

/// A one-layer stack under friction is the film under friction (the film's solver with its own
/// closed-form kernels): on a map in partial contact, every pixel of the total interface fields
/// to 1e-12 of the field's largest value, the shear vector's summary and every exact comparison
/// row to 1e-12 relative, Persson's rows to 1e-7 (two evaluations of the same integrals to
/// rtol 1e-8); and `check --verify`'s numbers (levels, bond exceedance, the shear vector, each
/// with its error estimate) to 1e-12.
#[test]
fn one_layer_stack_under_friction_is_the_film() {
    let (rubber, steel) = (el(2e6, 0.5), el(2e11, 0.3));
    let (d, p0, mu, bond) = (3e-6, 2e5, 0.6, 3e4);
    let film = coatcheck::layer::Stack::new(Bilayer::new(rubber, steel), d).unwrap();
    let one = design(vec![layer("rubber", 2e6, 0.5, d, bond)], p0, 1e-3);
    let stack = design_stack(&one).unwrap();
    let m = map();
    let settings = Settings::default();
    let want = coatcheck::verify::sliding::compare_sliding(
        &m,
        &film,
        (p0, mu),
        &tight(),
        settings,
        Some(bond),
    )
    .unwrap();
    let got = compare_sliding(&m, &stack, (p0, mu), &tight(), settings, Some(bond)).unwrap();
    assert!(want.comparison.solution.area_fraction.value < 0.9);
    same_fields(
        &got.comparison.fields[0],
        &want.comparison.fields,
        1e-12,
        "total",
    );
    same_summary(&got.exact[0], &want.exact, 1e-12);
    let rows = got
        .comparison
        .rows
        .iter()
        .chain(&got.comparison.interfaces[0].rows);
    let mut matched = 0;
    for r in rows {
        let Some(w) = want.comparison.rows.iter().find(|w| w.name == r.name) else {
            continue;
        };
        matched += 1;
        if r.name.contains("mean tau_y") {
            assert!((r.exact - w.exact).abs() <= 1e-13 * mu * p0, "{}", r.name);
        } else {
            close(r.exact, w.exact, 1e-12, &r.name);
        }
        match (r.persson, w.persson) {
            (Some(a), Some(b)) => close(a.value, b.value, 1e-7, &format!("Persson {}", r.name)),
            (a, b) => assert_eq!(a.is_none(), b.is_none(), "{}", r.name),
        }
    }
    assert_eq!(
        matched,
        want.comparison.rows.len(),
        "every film row has its stack row"
    );
    // `check --verify`: the film's exact check with friction against the stack's.
    let film_design = Design {
        layers: Bilayer::new(rubber, steel),
        pressure: p0,
        yield_strength: Some(2.5e8),
        bond_strength: bond,
        friction: mu,
        criteria: crate::verify_stack::criteria(1e-3),
    };
    let w = coatcheck::verify::verify(&surface(), &film_design, d, &tight()).unwrap();
    let g = verify(&surface(), &one, mu, &tight()).unwrap();
    let i = &g.interfaces[0];
    let tol = 1e-12;
    close_est(&i.sigma_rms, &w.sigma_rms_interface, tol, "sigma_rms");
    close_est(&i.tau_rms, &w.tau_rms_interface, tol, "tau_rms (static)");
    close_est(&i.tau_peak.value, &w.tau_peak.value, tol, "tau_peak");
    close_est(
        &i.sigma_peak.value,
        &w.sigma_peak_interface.value,
        tol,
        "sigma_peak",
    );
    close_est(&i.bond_exceedance, &w.bond_exceedance, tol, "bond");
    same_sliding(
        i.sliding.as_ref().unwrap(),
        w.sliding.as_ref().unwrap(),
        tol,
    );
    for (a, b) in g.checks.iter().zip(&w.checks) {
        assert_eq!(a.check.kind, b.kind);
        close_est(&a.check.value, &b.value, tol, "check value");
        assert_eq!(a.check.pass, b.pass);
    }
    // Friction raises the bond level over the static one.
    let s = verify(&surface(), &one, 0.0, &tight()).unwrap();
    assert!(i.tau_peak.value.value > s.interfaces[0].tau_peak.value.value);
    assert!(s.interfaces[0].sliding.is_none());
}

/// A single oblique mode a cos ψ, ψ = k·r ((kx, ky) = (2, 1) periods over a 64 × 64 map), on
/// rubber 2 µm / epoxy 1 µm / rubber 3 µm on steel, in full contact at p0 = 2p* with
/// p* = a q E1*/(2 S): at interface k (c, s = cos φ, sin φ; f_k, g_k, g_t,k, f_t,k, h_k at q)
/// τ_x = μp0 + p*[μ(g_t c² + h s²) cos ψ − g c sin ψ], τ_y = p*[μ(g_t − h) c s cos ψ −
/// g s sin ψ], σ_n = p0 + p*[f cos ψ − μ f_t c sin ψ], every pixel to 1e-8 of p0 (the solver's
/// 1e-10 on the gap); the rms are p*/√2 times the quadrature sums of the cos ψ and sin ψ
/// amplitudes; `verify` (the road of `check --verify`) reports the same, with the grid maximum
/// of |τ| as the level at ε = 1e-6.
#[test]
fn single_mode_in_full_contact_gives_the_closed_form_fields_at_every_interface() {
    let (n, l, a, mu) = (64usize, 100e-6, 0.2e-6, 0.7);
    let (kx, ky) = (2.0, 1.0);
    let mut dsg = design(
        vec![
            layer("rubber", 1e6, 0.5, 2e-6, 1e12),
            layer("epoxy", 3e9, 0.35, 1e-6, 1e12),
            layer("base", 5e6, 0.45, 3e-6, 1e12),
        ],
        0.0,
        1e-6,
    );
    dsg.yield_strength = Some(1e12);
    let stack = design_stack(&dsg).unwrap();
    let q = 2.0 * PI / l * f64::hypot(kx, ky);
    let (c, s) = (kx / kx.hypot(ky), ky / kx.hypot(ky));
    let psi = |i: usize| 2.0 * PI * (kx * (i % n) as f64 + ky * (i / n) as f64) / n as f64;
    let heights = (0..n * n).map(|i| a * psi(i).cos()).collect();
    let surf = Surface::new(heights, n, n, l / n as f64, l / n as f64).unwrap();
    let r = stack.response(q);
    let t = stack.tangential(q);
    let p_star = a * q * stack.layers()[0].material.e_star() / (2.0 * r.s);
    let p0 = 2.0 * p_star;
    dsg.pressure = p0;
    let (sol, fields) = coatcheck::verify_stack::solve(&surf, &stack, p0, &tight()).unwrap();
    assert_eq!(sol.area_fraction.value, 1.0);
    let total = with_friction(&sol, &stack, fields, mu).unwrap();
    let v = verify(&surf, &dsg, mu, &tight()).unwrap();
    let tol = 1e-8 * p0;
    let close_abs = |x: f64, want: f64, what: &str| {
        assert!((x - want).abs() <= tol, "{what}: {x:e} vs {want:e}");
    };
    let rms = |u: f64, v: f64| p_star * u.hypot(v) / 2f64.sqrt();
    for (k, ((f, summary), t)) in total.iter().zip(&t).enumerate() {
        let summary = summary.as_ref().unwrap();
        let (fk, gk) = r.interfaces[k];
        // Amplitudes of cos ψ and sin ψ per unit p*.
        let (xc, xs) = (mu * (t.g_t * c * c + t.h * s * s), -gk * c);
        let (yc, ys) = (mu * (t.g_t - t.h) * c * s, -gk * s);
        let (zc, zs) = (fk, -mu * t.f_t * c);
        let mut max = 0.0f64;
        for i in 0..n * n {
            let (co, si) = (psi(i).cos(), psi(i).sin());
            let want = [
                mu * p0 + p_star * (xc * co + xs * si),
                p_star * (yc * co + ys * si),
                p0 + p_star * (zc * co + zs * si),
            ];
            let got = [f.shear_x[i], f.shear_y[i], f.normal[i]];
            for (g, w) in got.iter().zip(want) {
                assert!(
                    (g - w).abs() <= tol,
                    "interface {k} pixel {i}: {got:?} vs {want:?}"
                );
            }
            max = max.max(want[0].hypot(want[1]));
        }
        close_abs(summary.mean[0], mu * p0, "mean tau_x");
        close_abs(summary.mean[1], 0.0, "mean tau_y");
        close_abs(summary.tau_x_rms, rms(xc, xs), "tau_x rms");
        close_abs(summary.tau_y_rms, rms(yc, ys), "tau_y rms");
        close_abs(summary.sigma_rms_interface, rms(zc, zs), "sigma_rms");
        close_abs(summary.static_tau_rms, rms(gk, 0.0), "static tau_rms");
        let e = &v.interfaces[k];
        let sl = e.sliding.as_ref().unwrap();
        close_abs(e.tau_peak.value.value, max, "tau_peak");
        assert!(!e.tau_peak.resolved);
        close_abs(sl.max.value, max, "max");
        close_abs(sl.tau_x_rms.value, rms(xc, xs), "verify tau_x rms");
        close_abs(sl.tau_y_rms.value, rms(yc, ys), "verify tau_y rms");
        close_abs(e.sigma_rms.value, rms(zc, zs), "verify sigma_rms");
        close_abs(e.tau_rms.value, rms(gk, 0.0), "verify tau_rms");
        // The half-resolution map holds the same mode: the error estimates are ~0.
        assert!(sl.tau_x_rms.err <= tol, "{sl:?}");
    }
    // The interfaces differ: the mode's shear is not a uniform pass-through.
    assert!((total[0].0.shear_stats.max - total[2].0.shear_stats.max).abs() > 1e-3 * p0);
}

/// μ = 0 is the static output exactly: the friction fields of every interface at μ = 0 add
/// nothing (the total fields equal the static ones bit for bit), and `verify --layer` and
/// `check --verify` on a stack scene print the same bytes with `--friction 0` as without (but
/// the solve times).
#[test]
fn zero_friction_is_the_static_stack_output() {
    let dsg = design(
        vec![
            layer("rubber", 2e6, 0.5, 2e-6, 3e4),
            layer("primer", 3e9, 0.35, 1e-6, 1e7),
        ],
        2e5,
        1e-3,
    );
    let stack = design_stack(&dsg).unwrap();
    let (sol, fields) =
        coatcheck::verify_stack::solve(&surface(), &stack, 2e5, &BemSettings::default()).unwrap();
    for (k, f) in fields.iter().enumerate() {
        let (total, summary) =
            with_friction_kernels(&sol, f, 0.0, interface_kernels(&stack, k)).unwrap();
        assert_eq!(&total, f, "interface {k}");
        assert_eq!(summary.tau_x_rms, FieldStats::of(&f.shear_x).rms_dev);
        assert_eq!(summary.static_tau_rms, f.shear_stats.rms);
    }
    let text = |o: std::process::Output| {
        assert!(o.status.code().is_some_and(|c| c < 2), "{o:?}");
        mask_timings(&String::from_utf8(o.stdout).unwrap())
    };
    for format in ["table", "json", "csv"] {
        let base = [
            "verify",
            "examples/data/height-map.csv",
            "--layer",
            "2MPa,0.5,2um",
            "--layer",
            "3GPa,0.35,1um",
            "--substrate",
            "200GPa,0.3",
            "--pressure",
            "0.1MPa",
            "--format",
            format,
        ];
        let a = text(run(&base));
        let b = text(run(&[&base[..], &["--friction", "0"]].concat()));
        assert_eq!(a, b, "verify --layer {format}");
    }
    for format in ["table", "json"] {
        let base = [
            "check",
            "examples/height-map-stack.toml",
            "--verify",
            "--checks",
            "bond-shear,substrate-yield",
            "--format",
            format,
        ];
        let a = text(run(&base));
        let b = text(run(&[&base[..], &["--friction", "0"]].concat()));
        assert_eq!(a, b, "check --verify {format}");
    }
}

/// Two identical adjacent layers are one layer of the summed thickness under friction too:
/// rubber 1 + 2 µm on an epoxy primer on steel gives rubber 3 µm's total fields at the two
/// matching interfaces (every pixel to 1e-12 of the field's largest value), the shear vector's
/// summary, and `check --verify`'s numbers with their error estimates, to 1e-12 relative.
#[test]
fn two_identical_layers_under_friction_are_one_of_the_summed_thickness() {
    let (p0, mu) = (2e5, 0.5);
    let primer = layer("primer", 3e9, 0.35, 2e-6, 2e7);
    let one = design(
        vec![layer("rubber", 2e6, 0.5, 3e-6, 3e4), primer.clone()],
        p0,
        1e-3,
    );
    let two = design(
        vec![
            layer("rubber a", 2e6, 0.5, 1e-6, 1e7),
            layer("rubber", 2e6, 0.5, 2e-6, 3e4),
            primer,
        ],
        p0,
        1e-3,
    );
    let (sa, sb) = (design_stack(&one).unwrap(), design_stack(&two).unwrap());
    let settings = Settings::default();
    let a = compare_sliding(&map(), &sa, (p0, mu), &tight(), settings, None).unwrap();
    let b = compare_sliding(&map(), &sb, (p0, mu), &tight(), settings, None).unwrap();
    for (kb, ka) in [(1, 0), (2, 1)] {
        same_fields(
            &b.comparison.fields[kb],
            &a.comparison.fields[ka],
            1e-12,
            &format!("interface {kb}"),
        );
        same_summary(&b.exact[kb], &a.exact[ka], 1e-12);
        close(
            b.persson[kb].tau_x_rms.value,
            a.persson[ka].tau_x_rms.value,
            1e-7,
            "Persson tau_x",
        );
        close(
            b.persson[kb].tau_y_rms.value,
            a.persson[ka].tau_y_rms.value,
            1e-7,
            "Persson tau_y",
        );
    }
    let va = verify(&surface(), &one, mu, &tight()).unwrap();
    let vb = verify(&surface(), &two, mu, &tight()).unwrap();
    same_sliding_interface(&vb.interfaces[1], &va.interfaces[0], 1e-12);
    same_sliding_interface(&vb.interfaces[2], &va.interfaces[1], 1e-12);
}

/// `verify --layer --friction` in JSON follows `verify.schema.json`: every interface carries
/// its `sliding` object (mean (μ p0, 0), Persson's mean μ p0) and the top-level one is the
/// bottom interface's; the CSV carries every interface's shear vector rows; `check --verify` on
/// a stack scene under friction follows `check.schema.json`, with the shear vector at every
/// interface in `verify` and in `exact`.
#[test]
fn stack_sliding_outputs_follow_their_schemas() {
    let base = [
        "verify",
        "examples/data/height-map.csv",
        "--layer",
        "2MPa,0.5,2um",
        "--layer",
        "3GPa,0.35,1um",
        "--substrate",
        "200GPa,0.3",
        "--pressure",
        "0.1MPa",
        "--bond-strength",
        "0.3MPa",
        "--friction",
        "0.5",
    ];
    let o = run(&[&base[..], &["--format", "json"]].concat());
    assert!(o.status.code().is_some_and(|c| c < 2), "{o:?}");
    let v = json(&o);
    let schema: Value = serde_json::from_str(coatcheck::report::VERIFY_SCHEMA).unwrap();
    let e = crate::schema::errors(&schema, &v);
    assert!(e.is_empty(), "{}", e.join("\n"));
    let interfaces = v["interfaces"].as_array().unwrap();
    assert_eq!(interfaces.len(), 2);
    for i in interfaces {
        let s = &i["sliding"];
        assert_eq!(s["friction"], 0.5);
        assert_eq!(s["persson_mean_interface_shear_pa"], 0.5 * 1e5);
        close(
            s["mean_interface_shear_pa"][0].as_f64().unwrap(),
            0.5e5,
            1e-12,
            "mean",
        );
        assert!(s["friction_coupling"].is_null());
    }
    assert_eq!(v["sliding"], interfaces[1]["sliding"]);
    let csv = String::from_utf8(run(&[&base[..], &["--format", "csv"]].concat()).stdout).unwrap();
    for at in ["layer 1", "layer 2"] {
        for q in [
            "tau_x rms interface",
            "tau_y rms interface",
            "interface |tau| q0.99",
        ] {
            assert!(
                csv.lines()
                    .any(|l| l.starts_with(&format!("{at},")) && l.contains(q)),
                "{at} {q}:\n{csv}"
            );
        }
    }
    let table = String::from_utf8(run(&base).stdout).unwrap();
    assert!(table.contains("sliding friction mu = 0.5"), "{table}");
    let o = run(&[
        "check",
        "examples/height-map-stack.toml",
        "--verify",
        "--friction",
        "0.5",
        "--format",
        "json",
    ]);
    assert!(o.status.code().is_some_and(|c| c < 2), "{o:?}");
    let j = json(&o);
    let schema: Value = serde_json::from_str(coatcheck::report::CHECK_SCHEMA).unwrap();
    let e = crate::schema::errors(&schema, &j);
    assert!(e.is_empty(), "{}", e.join("\n"));
    for section in ["verify", "exact"] {
        let items = j[section]["interfaces"].as_array().unwrap();
        assert_eq!(items.len(), 2, "{section}");
        for i in items {
            let s = &i["sliding"];
            assert_eq!(s["friction"], 0.5, "{section}");
            close(
                s["mean_interface_shear_pa"].as_f64().unwrap(),
                0.5e5,
                1e-12,
                section,
            );
            let (q99, max) = (
                s["tau_abs_q99_pa"].as_f64().unwrap(),
                s["tau_abs_max_pa"].as_f64().unwrap(),
            );
            assert!(q99 > 0.0 && q99 <= max, "{section}: {s}");
        }
    }
}

/// A one-layer stack given by its spectrum alone under friction gives the film's realisation
/// output on the same seeds: the mean shear vector's numbers with their grid errors (1e-12
/// relative, 1e-9 for the errors), their spreads over the realisations (1e-9; the means' spreads
/// rounding-level, 1e-13 of μ p0 absolute) and the mean levels they set.
#[test]
fn one_layer_stack_realisations_under_friction_are_the_films() {
    use coatcheck::check::Checker;
    use coatcheck::exact::stack_realisations::{SLIDING_KEYS, on_stack_realisations};
    use coatcheck::exact::{ExactOptions, on_realisations};
    use coatcheck::psd::Spectrum;
    let spectrum = Spectrum::self_affine(0.8, 1e5, 3.2e6, None)
        .unwrap()
        .scaled_to_rms_height(0.5e-6)
        .unwrap();
    let opts = ExactOptions {
        realisations: 3,
        max_side: 32,
        ..ExactOptions::default()
    };
    let (rubber, mu, d) = (el(2e6, 0.5), 0.5, 4e-6);
    let mut checks = Checks::all();
    checks.min_thickness = false;
    let criteria = Criteria {
        shear_tail: None,
        epsilon: 1e-2,
        safety_factor: 1.0,
        checks,
    };
    let film = Design {
        layers: Bilayer::new(rubber, el(200e9, 0.3)),
        pressure: 0.1e6,
        yield_strength: Some(1e12),
        bond_strength: 0.15e6,
        friction: mu,
        criteria,
    };
    let persson = Checker::new(&spectrum, film.clone(), Settings::default())
        .unwrap()
        .evaluate(d)
        .unwrap();
    let (wv, _, wr) = on_realisations(&spectrum, &film, d, &persson, &opts).unwrap();
    let mut one = design(vec![layer("rubber", 2e6, 0.5, d, 0.15e6)], 0.1e6, 1e-2);
    one.substrate = el(200e9, 0.3);
    one.yield_strength = Some(1e12);
    one.criteria = criteria;
    let (gv, gm, gr) = on_stack_realisations(&spectrum, &one, mu, &opts).unwrap();
    assert!(gm.is_none());
    let (g, w) = (&gv.interfaces[0], &wv);
    let (gs, ws) = (g.sliding.as_ref().unwrap(), w.sliding.as_ref().unwrap());
    let pairs: [(Estimate, Estimate, &str); 6] = [
        (gs.tau_x_rms, ws.tau_x_rms, "tau_x rms"),
        (gs.tau_y_rms, ws.tau_y_rms, "tau_y rms"),
        (gs.quantiles[1], ws.quantiles[1], "|tau| q0.99"),
        (gs.max, ws.max, "|tau| max"),
        (g.tau_peak.value, w.tau_peak.value, "tau_peak"),
        (g.sigma_rms, w.sigma_rms_interface, "sigma_rms"),
    ];
    for (a, b, what) in pairs {
        close(a.value, b.value, 1e-12, what);
        close(a.err, b.err, 1e-9, &format!("{what} err"));
    }
    // The spreads of the shear vector's numbers over the realisations, by report key.
    for (key, _) in SLIDING_KEYS {
        let (s, t) = (
            gr.interface_spread(0, key).unwrap(),
            wr.spread_of(key).unwrap(),
        );
        if key == "mean_interface_shear_y_pa" || key == "mean_interface_shear_pa" {
            assert!((s - t).abs() <= 1e-13 * mu * 0.1e6, "{key}: {s:e} vs {t:e}");
        } else {
            assert!(s > 0.0, "{key}");
            close(s, t, 1e-9, &format!("{key} spread"));
        }
    }
    assert_eq!(gv.pass, wv.pass);
}

/// The exact minimum thickness of a one-layer stack under friction is the film's under the same
/// friction (the same search over the same solves, each judged on the total fields): d_min, its
/// bracket and grid errors to 1e-12 and 1e-9 relative, the same governing check and number of
/// solves; and friction raises it over the static one (the mean shear μ p0 passes the film).
#[test]
fn one_layer_stack_min_thickness_under_friction_is_the_films() {
    use coatcheck::exact::{min_thickness, stack_min_thickness};
    let s = surface();
    let settings = BemSettings::default();
    let (rubber, p0, mu, bond) = (el(2e6, 0.5), 1e5, 0.5, 0.15e6);
    let criteria = Criteria {
        shear_tail: None,
        epsilon: 1e-2,
        safety_factor: 1.0,
        checks: Checks::all(),
    };
    let film = Design {
        layers: Bilayer::new(rubber, el(2e11, 0.3)),
        pressure: p0,
        yield_strength: Some(1e12),
        bond_strength: bond,
        friction: mu,
        criteria,
    };
    let want = min_thickness::min_thickness(&s, &film, &settings).unwrap();
    let mut one = design(vec![layer("rubber", 2e6, 0.5, 5e-6, bond)], p0, 1e-2);
    one.yield_strength = Some(1e12);
    one.criteria = criteria;
    let got = stack_min_thickness::min_thickness(&s, &one, mu, &settings).unwrap();
    let (w, g) = (want.thickness().unwrap(), got.thickness().unwrap());
    assert!(!want.search.all_pass_to_floor, "{want:?}");
    // The two compliances agree to rounding, but the solves' single-precision start can round
    // them to different f32 values, so the paths agree to the solves' gap tolerance (1e-6 h_rms),
    // not to rounding: d_min to 1e-8 (its stated error is 4e-3 of it), the error estimates to
    // 1e-5 of themselves.
    close(g.value, w.value, 1e-8, "d_min");
    close(g.err, w.err, 1e-5, "d_min error");
    close(got.grid_err, want.grid_err, 1e-5, "grid error");
    assert_eq!(got.search.governing, want.search.governing);
    assert_eq!(got.solves, want.solves);
    let static_d = stack_min_thickness::min_thickness(&s, &one, 0.0, &settings).unwrap();
    let d0 = static_d.thickness().unwrap().value;
    assert!(!static_d.search.all_pass_to_floor, "{static_d:?}");
    assert!(g.value > d0, "sliding {g:?}, static {d0:e}");
}
