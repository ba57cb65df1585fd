//! The contact engine's interface integrals against an independent high-precision reference:
//! σ_rms at the top and at the interface, τ_rms at the interface (eqs. B8–B10 as in notes.md),
//! G(q1) (B12) and A/A0 (B11), from tests/data/interface_ref.py. That script evaluates
//! 2∫P F² dG with the kernels of the 6×6 boundary-value solve (kernels_ref.py, no closed form)
//! by two quadratures (in ln q graded towards q_L, and in G itself) at 30 and 40 digits, which
//! agree to 2e-26; it prints 25 digits.
//!
//! Scenes: the four of contact_ref.py on the paper's spectrum (self-affine H = 1, q0 = 1e5,
//! q1 = 1e8 1/m, rms slope 1; C0 given as the exact double in the CSV), and rubber on steel with
//! a 20-point tabulated spectrum (tests/data/interface_ref_psd.csv, H = 0.8 with a 3 % ripple) at
//! q_L d = 0.01, 1 and 10. The reference is posed on exactly the engine's f64 inputs, so its own
//! error here is the f64 rounding of the printed value, ≤ 2^-53 relative ([`REF_RTOL`]).

use coatcheck::contact::{Contact, Engine, Request};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::{Estimate, Settings, Termination};
use coatcheck::psd::{Spectrum, Tabulated};

/// The reference's own relative error as seen from f64: the rounding of its 25-digit value
/// (2^-53 ≈ 1.1e-16; the quadrature itself is good to ~1e-25), with a factor 2 to spare.
const REF_RTOL: f64 = 2.3e-16;

const NAMES: [&str; 5] = [
    "G1",
    "A/A0",
    "sigma_top",
    "sigma_interface",
    "tau_interface",
];

struct Scene {
    label: String,
    spectrum: Spectrum,
    stack: Stack,
    p0: f64,
    /// G1, A/A0, σ_top, σ_interface, τ_interface.
    reference: [f64; 5],
}

fn tabulated() -> Spectrum {
    let (mut q, mut c) = (vec![], vec![]);
    for line in include_str!("../data/interface_ref_psd.csv")
        .lines()
        .skip(1)
    {
        let v: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
        q.push(v[0]);
        c.push(v[1]);
    }
    assert_eq!(q.len(), 20);
    Spectrum::Tabulated(Tabulated::new(q, c).unwrap())
}

fn scenes() -> Vec<Scene> {
    let table = tabulated();
    include_str!("../data/interface_ref.csv")
        .lines()
        .skip(1)
        .map(|line| {
            let f: Vec<&str> = line.split(',').collect();
            let num = |i: usize| -> f64 { f[i].parse().unwrap() };
            let spectrum = match f[0] {
                "paper" => Spectrum::self_affine(1.0, 1e5, 1e8, None)
                    .unwrap()
                    .scaled(num(1)),
                "tabulated" => table.clone(),
                other => panic!("unknown spectrum {other}"),
            };
            let layers = Bilayer::new(
                Elastic::new(num(2), num(3)).unwrap(),
                Elastic::new(num(4), num(5)).unwrap(),
            );
            Scene {
                label: format!(
                    "{} E0={} nu0={} E1={} nu1={} d={}",
                    f[0], f[2], f[3], f[4], f[5], f[6]
                ),
                spectrum,
                stack: Stack::new(layers, num(6)).unwrap(),
                p0: num(7),
                reference: std::array::from_fn(|k| num(8 + k)),
            }
        })
        .collect()
}

fn estimates(c: &Contact) -> [Estimate; 5] {
    [
        c.g1,
        c.area_fraction,
        c.sigma_rms_top.unwrap(),
        c.sigma_rms_interface.unwrap(),
        c.tau_rms_interface.unwrap(),
    ]
}

/// Every scene and quantity at one rtol: converged, within rtol of the reference, and the
/// reported error bounds the true error (plus the reference's own).
fn check(rtol: f64) {
    let list = scenes();
    assert_eq!(list.len(), 7);
    let mut failures = vec![];
    for s in &list {
        let c = Engine::new(&s.spectrum, Settings { rtol })
            .evaluate(&s.stack, s.p0, Request::all())
            .unwrap();
        for ((got, want), name) in estimates(&c).iter().zip(s.reference).zip(NAMES) {
            let true_err = (got.value - want).abs();
            let line = format!(
                "rtol {rtol:e}, {}: {name} = {:.17e}, reference {want:.17e}, error {:.2e} \
                 (relative {:.2e}), estimate {:.2e}, {:?}",
                s.label,
                got.value,
                true_err,
                true_err / want,
                got.err,
                got.status
            );
            if got.status != Termination::Converged
                || true_err > rtol * want
                || true_err > got.err + REF_RTOL * want
            {
                failures.push(line);
            }
        }
    }
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

#[test]
fn interface_integrals_match_reference_at_default_rtol() {
    check(Settings::default().rtol);
}

#[test]
fn interface_integrals_match_reference_at_rtol_1e6() {
    check(1e-6);
}

/// The data the other tests rely on: the tabulated scenes span q_L d = 0.01, 1 and 10, and the
/// reference reproduces notes.md's three-digit Fig. 7 values (d = 10 µm on the paper spectrum).
#[test]
fn reference_table_is_what_it_claims() {
    let list = scenes();
    let qd: Vec<f64> = list
        .iter()
        .filter(|s| s.label.starts_with("tabulated"))
        .map(|s| s.spectrum.q_low() * s.stack.thickness)
        .collect();
    assert_eq!(qd.len(), 3);
    for (got, want) in qd.iter().zip([0.01, 1.0, 10.0]) {
        assert!((got / want - 1.0).abs() < 1e-12, "q_L d = {got}");
    }
    let fig7 = &list[0].reference;
    for (got, want) in fig7[1..].iter().zip([0.0927, 0.357e6, 0.222e6, 0.133e6]) {
        assert!((got / want - 1.0).abs() < 2.5e-3, "{got} vs {want}");
    }
}
