//! The exact path of `check --verify` on layer stacks (`coatcheck::exact::stack`,
//! `coatcheck::exact::stack_min_thickness`): for one layer, the film's exact minimum thickness
//! (`coatcheck::exact::min_thickness`, with the closed-form kernels of eq. 7 and App. B; the same
//! search and the same solves); for two, the exact verdict flips across the exact d_min.

use coatcheck::bem::{BemSettings, Surface};
use coatcheck::check::stack::{StackDesign, StackLayer};
use coatcheck::check::{CheckKind, Checks, Criteria, Design};
use coatcheck::exact::stack::on_stack_surface;
use coatcheck::exact::{min_thickness, stack_min_thickness};
use coatcheck::layer::{Bilayer, Elastic};
use coatcheck::topography::synth::{Amplitude, SynthSpec, self_affine_map};

fn el(e: f64, nu: f64) -> Elastic {
    Elastic::new(e, nu).unwrap()
}

/// A self-affine map like the bundled one (H = 0.8, h_rms 0.5 µm, 0.5 µm pixels), 64 × 64.
fn surface(seed: u64) -> Surface {
    let spec = SynthSpec {
        n: 64,
        dx: 0.5e-6,
        hurst: 0.8,
        q0: 2.0e5,
        q1: 3.0e6,
        amplitude: Amplitude::RmsHeight(0.5e-6),
        seed,
    };
    Surface::from_height_map(&self_affine_map(&spec).unwrap()).unwrap()
}

fn criteria(checks: Checks) -> Criteria {
    Criteria {
        shear_tail: None,
        epsilon: 1e-2,
        safety_factor: 1.0,
        checks,
    }
}

fn layer(name: &str, material: Elastic, d: f64, bond: f64) -> StackLayer {
    StackLayer {
        name: name.into(),
        material,
        thickness: d,
        bond_strength: bond,
    }
}

fn stack(layers: Vec<StackLayer>, thickness_of: usize, checks: Checks) -> StackDesign {
    StackDesign {
        layers,
        substrate: el(200e9, 0.3),
        pressure: 0.1e6,
        yield_strength: Some(1e12),
        friction: 0.0,
        criteria: criteria(checks),
        thickness_of,
    }
}

/// How far two exact d_min searches on kernels that agree to ~1e-13 may differ (relative): the
/// solver's tolerance (1e-6 of the gap) times the bracket's width ([`coatcheck::check::D_MIN_RTOL`],
/// 2e-3), with a factor 10 of slack.
const D_MIN_SOLVE_RTOL: f64 = 2e-8;

/// |a − b| ≤ tol·max(|a|, |b|).
fn close(a: f64, b: f64, tol: f64, what: &str) {
    assert!(
        a == b || (a - b).abs() <= tol * a.abs().max(b.abs()),
        "{what}: {a:e} vs {b:e} (tol {tol:e})"
    );
}

/// A one-layer stack's exact minimum thickness is the film's: the same search (the same
/// thicknesses solved, warm-started alike) and governing check, d_min to [`D_MIN_SOLVE_RTOL`]
/// and its bracket and grid errors to 1e-9 relative. The stack's kernels and the film's closed
/// forms agree to ~1e-13, but the solver's preconditioner rounds in single precision, so kernels
/// that differ by an ulp can take different iteration paths to the same tolerance: the solves
/// then agree to the solver's tolerance, not to the kernels' difference.
#[test]
fn one_layer_stack_min_thickness_is_the_films() {
    let s = surface(5);
    let settings = BemSettings::default();
    let rubber = el(2e6, 0.5);
    let film = Design {
        layers: Bilayer::new(rubber, el(200e9, 0.3)),
        pressure: 0.1e6,
        yield_strength: Some(1e12),
        bond_strength: 0.15e6,
        friction: 0.0,
        criteria: criteria(Checks::all()),
    };
    let want = min_thickness::min_thickness(&s, &film, &settings).unwrap();
    let one = stack(
        vec![layer("rubber", rubber, 5e-6, 0.15e6)],
        0,
        Checks::all(),
    );
    let got = stack_min_thickness::min_thickness(&s, &one, 0.0, &settings).unwrap();
    let (w, g) = (want.thickness().unwrap(), got.thickness().unwrap());
    assert!(!want.search.all_pass_to_floor, "{want:?}");
    close(g.value, w.value, D_MIN_SOLVE_RTOL, "d_min");
    close(g.err, w.err, 1e-9, "d_min error");
    close(got.grid_err, want.grid_err, 1e-9, "grid error");
    let (ws, gs) = (
        want.search.thickness.unwrap(),
        got.search.thickness.unwrap(),
    );
    close(gs.err, ws.err, 1e-9, "bracket error");
    assert_eq!(got.search.governing, want.search.governing);
    assert_eq!(got.search.evaluations, want.search.evaluations);
    assert_eq!(got.solves, want.solves);
    assert_eq!(
        (got.search.floor, got.search.bulk),
        (want.search.floor, want.search.bulk)
    );
}

/// The exact verdict of a two-layer stack flips between 0.9× and 1.1× the exact d_min of the
/// varied layer (the top rubber over an epoxy primer, then the primer under a fixed rubber): the
/// exact stress checks at every interface fail below and pass above (min-thickness off), and
/// with min-thickness on the design fails at 0.9 d_min and passes at 1.1 d_min, its exact d_min
/// the same at both.
#[test]
fn exact_stack_verdict_flips_across_the_exact_min_thickness() {
    let s = surface(5);
    let settings = BemSettings::default();
    let (rubber, epoxy) = (el(2e6, 0.5), el(3e9, 0.35));
    let mut stress = Checks::all();
    stress.min_thickness = false;
    for (of, bonds) in [(0, (0.15e6, 0.1e6)), (1, (1e9, 0.05e6))] {
        let layers = |d: f64| {
            let (d0, d1) = if of == 0 { (d, 1e-6) } else { (2e-6, d) };
            vec![
                layer("rubber", rubber, d0, bonds.0),
                layer("primer", epoxy, d1, bonds.1),
            ]
        };
        let at = |d: f64, checks| stack(layers(d), of, checks);
        let m = stack_min_thickness::min_thickness(&s, &at(5e-6, Checks::all()), 0.0, &settings)
            .unwrap();
        let d = m.thickness().expect("a thickness passes");
        assert!(!m.search.all_pass_to_floor, "layer {of}: {m:?}");
        assert_eq!(m.search.governing, Some(CheckKind::BondShear), "layer {of}");
        assert!(d.err.is_finite() && d.err < 0.1 * d.value, "{d:?}");
        for (factor, pass) in [(0.9, false), (1.1, true)] {
            let (v, _) =
                on_stack_surface(&s, &at(factor * d.value, stress), 0.0, &settings).unwrap();
            assert_eq!(
                v.pass, pass,
                "layer {of}: stress checks at {factor} d_min: {:?}",
                v.checks
            );
            let (v, em) =
                on_stack_surface(&s, &at(factor * d.value, Checks::all()), 0.0, &settings).unwrap();
            assert_eq!(v.pass, pass, "layer {of}: all checks at {factor} d_min");
            let c = v.checks.last().unwrap();
            assert_eq!(c.check.kind, CheckKind::MinThickness);
            assert_eq!(c.at, ["rubber", "primer"][of]);
            assert_eq!(em.unwrap().thickness(), Some(d));
        }
    }
}

/// A one-layer stack given by its spectrum alone gives the film's realisation output on the
/// same seeds: every mean exact number with its grid error and its spread, the mean exact d_min
/// with its spread, the checks and the verdict, the grid and its unresolved slope share (1e-12
/// relative for the numbers, 1e-9 for the errors and spreads, differences of nearby numbers).
/// The mean d_min (and the min-thickness check's limit) to [`D_MIN_SOLVE_RTOL`], its spread to
/// twice that of d_min (a difference of two of them): each search's probes interpolate solved
/// utilisations, each known to its solve's tolerance, and kernels that differ by ~1e-13 may stop
/// a solve one iteration apart.
#[test]
fn one_layer_stack_realisations_are_the_films() {
    use coatcheck::check::Checker;
    use coatcheck::exact::stack_realisations::on_stack_realisations;
    use coatcheck::exact::{ExactOptions, on_realisations};
    use coatcheck::prec::Settings;
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
    let rubber = el(2e6, 0.5);
    let d = 4e-6;
    let film = Design {
        layers: Bilayer::new(rubber, el(200e9, 0.3)),
        pressure: 0.1e6,
        yield_strength: Some(1e12),
        bond_strength: 0.15e6,
        friction: 0.0,
        criteria: criteria(Checks::all()),
    };
    let persson = Checker::new(&spectrum, film.clone(), Settings::default())
        .unwrap()
        .evaluate(d)
        .unwrap();
    let (wv, wm, wr) = on_realisations(&spectrum, &film, d, &persson, &opts).unwrap();
    let one = stack(vec![layer("rubber", rubber, d, 0.15e6)], 0, Checks::all());
    let (gv, gm, gr) = on_stack_realisations(&spectrum, &one, 0.0, &opts).unwrap();
    assert_eq!(
        (gr.count, gr.seeds.clone(), gr.grid),
        (wr.count, wr.seeds.clone(), wr.grid)
    );
    assert!(gr.grid.unresolved_slope_share > 0.0, "{:?}", gr.grid);
    let pairs = [
        (
            "area_fraction",
            gv.area_fraction,
            wv.area_fraction,
            gr.top_spread("area_fraction"),
        ),
        (
            "mean_contact_pressure_pa",
            gv.mean_contact_pressure,
            wv.mean_contact_pressure,
            gr.top_spread("mean_contact_pressure_pa"),
        ),
        (
            "sigma_rms_top_pa",
            gv.sigma_rms_top,
            wv.sigma_rms_top,
            gr.top_spread("sigma_rms_top_pa"),
        ),
        (
            "sigma_rms_interface_pa",
            gv.interfaces[0].sigma_rms,
            wv.sigma_rms_interface,
            gr.interface_spread(0, "sigma_rms_pa"),
        ),
        (
            "tau_rms_interface_pa",
            gv.interfaces[0].tau_rms,
            wv.tau_rms_interface,
            gr.interface_spread(0, "tau_rms_pa"),
        ),
        (
            "tau_peak_pa",
            gv.interfaces[0].tau_peak.value,
            wv.tau_peak.value,
            gr.interface_spread(0, "tau_peak_pa"),
        ),
        (
            "sigma_peak_interface_pa",
            gv.interfaces[0].sigma_peak.value,
            wv.sigma_peak_interface.value,
            gr.interface_spread(0, "sigma_peak_pa"),
        ),
        (
            "bond_exceedance",
            gv.interfaces[0].bond_exceedance,
            wv.bond_exceedance,
            gr.interface_spread(0, "bond_exceedance"),
        ),
    ];
    for (key, g, w, spread) in pairs {
        close(g.value, w.value, 1e-12, key);
        close(g.err, w.err, 1e-9, &format!("{key} err"));
        let (s, t) = (spread.unwrap(), wr.spread_of(key).unwrap());
        assert!(s > 0.0 || key == "bond_exceedance", "{key}: spread {s}");
        close(s, t, 1e-9, &format!("{key} spread"));
    }
    let (g, w) = (gm.unwrap(), wm.unwrap());
    let (gd, wd) = (g.thickness().unwrap(), w.thickness().unwrap());
    close(gd.value, wd.value, D_MIN_SOLVE_RTOL, "d_min");
    assert!((gd.value - wd.value).abs() <= wd.err, "{gd:?} vs {wd:?}");
    assert!(
        (gr.min_thickness_spread - wr.min_thickness_spread).abs()
            <= 2.0 * D_MIN_SOLVE_RTOL * wd.value,
        "d_min spread: {} vs {}",
        gr.min_thickness_spread,
        wr.min_thickness_spread
    );
    assert_eq!(gv.checks.len(), wv.checks.len());
    for (g, w) in gv.checks.iter().zip(&wv.checks) {
        assert_eq!((g.check.kind, g.check.pass), (w.kind, w.pass));
        close(g.check.value.value, w.value.value, 1e-12, "check value");
        let limit_rtol = if w.kind == CheckKind::MinThickness {
            D_MIN_SOLVE_RTOL
        } else {
            1e-12
        };
        close(g.check.limit, w.limit, limit_rtol, "check limit");
    }
    assert_eq!(gv.pass, wv.pass);
}

/// `check --verify` on a stack scene given by a model spectrum solves realisations of it: the
/// JSON (valid against `check.schema.json`) has the `exact` object with their number, the
/// spread of every interface's numbers and the exact d_min of the layer `thickness_of` beside
/// Persson's; the table has the spread column and both minimum thicknesses.
#[test]
fn check_verify_on_a_stack_spectrum_solves_realisations() {
    use crate::common::{json, run};
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("stack.toml");
    std::fs::write(
        &scene,
        "[roughness]\nmodel = \"self-affine\"\nhurst = 0.8\nq0 = \"1e5 1/m\"\nq1 = \"1.6e6 1/m\"\n\
         rms_height = \"0.5 um\"\n[[layer]]\nname = \"rubber\"\nyoungs_modulus = \"2 MPa\"\n\
         poisson_ratio = 0.5\nthickness = \"4 um\"\nbond = \"0.15 MPa\"\n[[layer]]\n\
         name = \"primer\"\nyoungs_modulus = \"3 GPa\"\npoisson_ratio = 0.35\n\
         thickness = \"1 um\"\nbond = \"10 MPa\"\n[substrate]\nyoungs_modulus = \"200 GPa\"\n\
         poisson_ratio = 0.3\n[load]\npressure = \"0.1 MPa\"\n[criteria]\nepsilon = 1e-2\n\
         checks = [\"bond-shear\", \"min-thickness\"]\n",
    )
    .unwrap();
    let scene = scene.to_str().unwrap();
    let args = [
        "check",
        scene,
        "--verify",
        "--realisations",
        "2",
        "--realisation-grid",
        "32",
    ];
    let mut with_json = args.to_vec();
    with_json.extend(["--format", "json"]);
    let o = run(&with_json);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{o:?}");
    let v = json(&o);
    let schema: serde_json::Value = serde_json::from_str(coatcheck::report::CHECK_SCHEMA).unwrap();
    let e = crate::schema::errors(&schema, &v);
    assert!(e.is_empty(), "{}", e.join("\n"));
    let x = &v["exact"];
    assert_eq!(x["surface"], "realisations");
    assert_eq!(
        (x["realisations"].clone(), x["nx"].clone()),
        (2.into(), 32.into())
    );
    assert_eq!(x["thickness_of"], "rubber");
    assert!(x["min_thickness_m"].as_f64().unwrap() > 0.0);
    assert!(x["min_thickness_m_ratio"].as_f64().unwrap() > 0.0);
    let inter = x["interfaces"].as_array().unwrap();
    assert_eq!(inter.len(), 2);
    for i in inter {
        assert!(i["tau_rms_pa_spread"].as_f64().unwrap() > 0.0, "{i}");
    }
    let c = x["checks"].as_array().unwrap();
    assert_eq!(c.last().unwrap()["name"], "min-thickness");
    assert_eq!(c.last().unwrap()["at"], "rubber");
    let table = String::from_utf8_lossy(&run(&args).stdout).into_owned();
    for needle in [
        "random-phase realisations",
        "spread",
        "minimum thickness of layer 'rubber'",
    ] {
        assert!(table.contains(needle), "{needle}: {table}");
    }
}
