//! Persson's theory on layer stacks (`Engine::evaluate_stack`) and stack scenes: the limits of
//! notes.md ("Layer stacks": two identical adjacent layers are one layer of the summed
//! thickness; one layer is the film), extreme contrasts, up to ten layers, and an independent
//! high-precision evaluation of the integrals.

use coatcheck::contact::{Contact, Engine, Request, StackContact};
use coatcheck::layer::stack::{Layer, Stack as LayerStack};
use coatcheck::layer::{Bilayer, Elastic, Stack};
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

fn layers(spec: &[(f64, f64, f64)], substrate: Elastic) -> LayerStack {
    LayerStack::new(
        spec.iter()
            .map(|&(e, nu, d)| Layer {
                material: el(e, nu),
                thickness: d,
            })
            .collect(),
        substrate,
    )
    .unwrap()
}

/// |a − b| within the sum of both error estimates (and a 1e-12 relative floor for two exact
/// computations of one number by different kernels).
fn agree(what: &str, a: &Estimate, b: &Estimate) {
    let tol = a.err + b.err + 1e-12 * b.value.abs();
    assert!(
        (a.value - b.value).abs() <= tol,
        "{what}: {} ± {} vs {} ± {}",
        a.value,
        a.err,
        b.value,
        b.err
    );
}

fn film(e0: Elastic, sub: Elastic, d: f64, engine: &Engine) -> Contact {
    let s = Stack::new(Bilayer::new(e0, sub), d).unwrap();
    engine.evaluate(&s, 1e5, Request::all()).unwrap()
}

/// Two identical adjacent layers equal one layer of the summed thickness: A/A0, G1, σ_rms at
/// the top, E_eff and the bottom interface's σ_rms, τ_rms against the Bilayer's (closed-form
/// kernels, another code path); and a one-layer stack equals the film.
#[test]
fn split_layer_equals_one_layer() {
    let engine = Engine::new(&paper_spectrum(), Settings::default());
    let (rubber, steel) = (el(1e6, 0.5), el(2e11, 0.3));
    let one = film(rubber, steel, 10e-6, &engine);
    let check = |c: &StackContact| {
        agree("G1", &c.top.g1, &one.g1);
        agree("A/A0", &c.top.area_fraction, &one.area_fraction);
        agree(
            "sigma top",
            c.top.sigma_rms_top.as_ref().unwrap(),
            one.sigma_rms_top.as_ref().unwrap(),
        );
        agree(
            "E_eff",
            c.top.e_eff_over_e_film.as_ref().unwrap(),
            one.e_eff_over_e_film.as_ref().unwrap(),
        );
        let bottom = c.interfaces.last().unwrap();
        agree(
            "sigma bottom",
            bottom.sigma_rms.as_ref().unwrap(),
            one.sigma_rms_interface.as_ref().unwrap(),
        );
        agree(
            "tau bottom",
            bottom.tau_rms.as_ref().unwrap(),
            one.tau_rms_interface.as_ref().unwrap(),
        );
    };
    for split in [[4e-6, 6e-6], [9.99e-6, 1e-8]] {
        let s = layers(&[(1e6, 0.5, split[0]), (1e6, 0.5, split[1])], steel);
        check(&engine.evaluate_stack(&s, 1e5, Request::all()).unwrap());
    }
    let s = layers(&[(1e6, 0.5, 10e-6)], steel);
    check(&engine.evaluate_stack(&s, 1e5, Request::all()).unwrap());
}
