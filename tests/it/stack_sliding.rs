//! Persson's theory under sliding on layer stacks (`Engine::evaluate_stack_sliding`): one layer
//! is the film under sliding (`Engine::evaluate_sliding`, whose kernels come from another code
//! path: closed forms and their tables), two identical adjacent layers are one.

use coatcheck::contact::{Engine, Request};
use coatcheck::layer::stack::{Layer, Stack as LayerStack};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::{Estimate, Settings};
use coatcheck::psd::Spectrum;

fn engine() -> Engine {
    let spectrum = Spectrum::self_affine(1.0, 1e5, 1e8, None)
        .unwrap()
        .scaled_to_rms_slope(1.0)
        .unwrap();
    Engine::new(&spectrum, Settings::default())
}

fn el(e: f64, nu: f64) -> Elastic {
    Elastic::new(e, nu).unwrap()
}

fn stack(spec: &[(f64, f64, f64)], substrate: Elastic) -> LayerStack {
    let layers = spec
        .iter()
        .map(|&(e, nu, d)| Layer {
            material: el(e, nu),
            thickness: d,
        })
        .collect();
    LayerStack::new(layers, substrate).unwrap()
}

/// |a − b| within 1e-12 relative (measured: 1.3e-15 for one layer against the film, 2.6e-16
/// for the split layer); returns |a − b|/|b|.
fn agree(what: &str, a: &Estimate, b: &Estimate) -> f64 {
    let tol = 1e-12 * b.value.abs();
    assert!(
        (a.value - b.value).abs() <= tol,
        "{what}: {} ± {} vs {} ± {}",
        a.value,
        a.err,
        b.value,
        b.err
    );
    (a.value - b.value).abs() / b.value.abs()
}

/// One layer (rubber on steel at 0.1, 1, 10 µm, μ = 0, 0.5, 1) equals the film under sliding:
/// the mean shear, τ_x, τ_y and σ_rms at the interface, and A/A0.
#[test]
fn one_layer_stack_under_sliding_is_the_film() {
    let engine = engine();
    let (rubber, steel) = (el(1e6, 0.5), el(2e11, 0.3));
    let mut worst = 0.0f64;
    for d in [1e-7, 1e-6, 1e-5] {
        let film = Stack::new(Bilayer::new(rubber, steel), d).unwrap();
        let one = stack(&[(1e6, 0.5, d)], steel);
        for mu in [0.0, 0.5, 1.0] {
            let (fc, fs) = engine
                .evaluate_sliding(&film, 1e5, mu, Request::all())
                .unwrap();
            let (sc, ss) = engine
                .evaluate_stack_sliding(&one, 1e5, mu, Request::all())
                .unwrap();
            let (fs, ss) = (fs.unwrap(), &ss.unwrap()[0]);
            let what = format!("d {d}, mu {mu}");
            assert_eq!(ss.mean.value, fs.mean.value, "{what}");
            for (name, a, b) in [
                ("tau_x", ss.tau_x_rms, fs.tau_x_rms),
                ("tau_y", ss.tau_y_rms, fs.tau_y_rms),
                (
                    "sigma",
                    sc.interfaces[0].sigma_rms.unwrap(),
                    fc.sigma_rms_interface.unwrap(),
                ),
                ("A/A0", sc.top.area_fraction, fc.area_fraction),
            ] {
                worst = worst.max(agree(&format!("{what}: {name}"), &a, &b));
            }
        }
    }
    eprintln!(
        "one-layer stack against the film under sliding: worst relative difference {worst:e}"
    );
}

/// A layer split in two identical halves: the same τ_x, τ_y, σ_rms under sliding (μ = 0.7) at
/// the shared interfaces.
#[test]
fn two_identical_layers_under_sliding_equal_one() {
    let engine = engine();
    let steel = el(2e11, 0.3);
    let split = stack(
        &[(1e6, 0.5, 4e-6), (3e9, 0.35, 3e-6), (3e9, 0.35, 5e-6)],
        steel,
    );
    let whole = stack(&[(1e6, 0.5, 4e-6), (3e9, 0.35, 8e-6)], steel);
    let (sc, ss) = engine
        .evaluate_stack_sliding(&split, 1e5, 0.7, Request::all())
        .unwrap();
    let (wc, ws) = engine
        .evaluate_stack_sliding(&whole, 1e5, 0.7, Request::all())
        .unwrap();
    let (ss, ws) = (ss.unwrap(), ws.unwrap());
    let mut worst = 0.0f64;
    for (i, j) in [(0, 0), (2, 1)] {
        for (name, a, b) in [
            ("tau_x", ss[i].tau_x_rms, ws[j].tau_x_rms),
            ("tau_y", ss[i].tau_y_rms, ws[j].tau_y_rms),
            (
                "sigma",
                sc.interfaces[i].sigma_rms.unwrap(),
                wc.interfaces[j].sigma_rms.unwrap(),
            ),
        ] {
            worst = worst.max(agree(&format!("interface {j}: {name}"), &a, &b));
        }
    }
    eprintln!("split layer under sliding: worst relative difference {worst:e}");
}
