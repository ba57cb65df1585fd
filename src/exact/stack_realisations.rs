//! The exact check of a layer stack given by its spectrum alone: K random-phase realisations of
//! the spectrum on the grid of [`super::realisations`] (seeds 1..=K), each solved with the
//! stack's kernels and judged at every interface ([`super::stack::on_stack_surface`]); every
//! exact number, at the top and at each interface, is then the mean over the K surfaces with its
//! spread (the standard error of that mean, [`super::realisations::spread`]) and its grid error
//! (the mean of the realisations' half-resolution differences), as for a film.
//!
//! The field statistics of an interface (σ_n and |τ|: mean, rms, quantiles, maximum) are the
//! means of the realisations' statistics, and so are its sliding numbers under friction. The stress checks are judged on the mean levels, the
//! minimum thickness is the mean of the realisations' d_min
//! ([`super::realisations::mean_min_thickness`]).

use super::ExactOptions;
use super::min_thickness::ExactMinThickness;
use super::realisations::{self, Grid, mean, mean_min_thickness, realisation, spread};
use super::stack::{add_min_thickness, on_stack_surface};
use crate::bem::{FieldStats, Quantile};
use crate::check::stack::StackDesign;
use crate::error::Error;
use crate::prec::{Estimate, Termination};
use crate::psd::Spectrum;
use crate::verify::Level;
use crate::verify::sliding::SlidingVerification;
use crate::verify_stack::{InterfaceExact, StackVerification, judge};

/// The realisations behind the exact check of a stack's spectrum.
#[derive(Debug, Clone, PartialEq)]
pub struct StackRealisations {
    /// Their number K.
    pub count: usize,
    pub grid: Grid,
    /// Seeds of the random phases, one per realisation.
    pub seeds: Vec<u64>,
    /// The spread of the top surface's numbers, by report key (`area_fraction`,
    /// `mean_contact_pressure_pa`, `sigma_rms_top_pa`).
    pub top: Vec<(&'static str, f64)>,
    /// The spread of every interface's numbers (top first), by report key (`sigma_rms_pa`,
    /// `tau_rms_pa`, `tau_peak_pa`, `sigma_peak_pa`, `bond_exceedance`; under sliding friction
    /// also those of [`SLIDING_KEYS`]).
    pub interfaces: Vec<Vec<(&'static str, f64)>>,
    /// The spread of the exact d_min (NaN when it was not searched or some realisation has no
    /// passing thickness).
    pub min_thickness_spread: f64,
}

impl StackRealisations {
    /// The spread of the top surface's number with report key `key`.
    pub fn top_spread(&self, key: &str) -> Option<f64> {
        self.top.iter().find(|(k, _)| *k == key).map(|(_, s)| *s)
    }

    /// The spread of interface `k`'s number with report key `key`.
    pub fn interface_spread(&self, k: usize, key: &str) -> Option<f64> {
        self.interfaces
            .get(k)?
            .iter()
            .find(|(x, _)| *x == key)
            .map(|(_, s)| *s)
    }
}

/// A report key and how to read its number.
pub type Keyed<T> = (&'static str, fn(&T) -> Estimate);

/// The top surface's numbers by report key.
pub const TOP_KEYS: [Keyed<StackVerification>; 3] = [
    ("area_fraction", |v| v.area_fraction),
    ("mean_contact_pressure_pa", |v| v.mean_contact_pressure),
    ("sigma_rms_top_pa", |v| v.sigma_rms_top),
];

/// An interface's numbers by report key.
pub const INTERFACE_KEYS: [Keyed<InterfaceExact>; 5] = [
    ("sigma_rms_pa", |i| i.sigma_rms),
    ("tau_rms_pa", |i| i.tau_rms),
    ("tau_peak_pa", |i| i.tau_peak.value),
    ("sigma_peak_pa", |i| i.sigma_peak.value),
    ("bond_exceedance", |i| i.bond_exceedance),
];

/// An interface's shear-vector numbers under sliding friction by report key.
pub const SLIDING_KEYS: [Keyed<SlidingVerification>; 8] = [
    ("mean_interface_shear_pa", |s| s.mean_x),
    ("mean_interface_shear_y_pa", |s| s.mean_y),
    ("tau_x_rms_interface_pa", |s| s.tau_x_rms),
    ("tau_y_rms_interface_pa", |s| s.tau_y_rms),
    ("tau_abs_q50_pa", |s| s.quantiles[0]),
    ("tau_abs_q99_pa", |s| s.quantiles[1]),
    ("tau_abs_q999_pa", |s| s.quantiles[2]),
    ("tau_abs_max_pa", |s| s.max),
];

/// The mean of estimates: mean value, mean (grid) error, the worst status.
fn mean_of(es: impl Iterator<Item = Estimate> + Clone) -> Estimate {
    Estimate {
        value: mean(es.clone().map(|e| e.value)),
        err: mean(es.clone().map(|e| e.err)),
        status: es
            .map(|e| e.status)
            .fold(Termination::Converged, Estimate::worst),
    }
}

/// The mean of the realisations' field statistics, component by component.
fn mean_stats(all: &[&FieldStats]) -> FieldStats {
    let m = |f: &dyn Fn(&FieldStats) -> f64| mean(all.iter().map(|s| f(s)));
    FieldStats {
        samples: all[0].samples,
        mean: m(&|s| s.mean),
        rms: m(&|s| s.rms),
        rms_dev: m(&|s| s.rms_dev),
        quantiles: all[0]
            .quantiles
            .iter()
            .enumerate()
            .map(|(i, q)| Quantile {
                prob: q.prob,
                value: m(&|s| s.quantiles[i].value),
            })
            .collect(),
        max: m(&|s| s.max),
    }
}

/// Interface `k` averaged over the realisations.
fn mean_interface(vs: &[StackVerification], k: usize) -> InterfaceExact {
    let all: Vec<&InterfaceExact> = vs.iter().map(|v| &v.interfaces[k]).collect();
    let est = |f: fn(&InterfaceExact) -> Estimate| mean_of(all.iter().map(|i| f(i)));
    let level = |f: fn(&InterfaceExact) -> Level| Level {
        value: mean_of(all.iter().map(|i| f(i).value)),
        resolved: all.iter().all(|i| f(i).resolved),
    };
    let first = all[0];
    InterfaceExact {
        name: first.name.clone(),
        depth: first.depth,
        sigma_rms: est(|i| i.sigma_rms),
        tau_rms: est(|i| i.tau_rms),
        tau_peak: level(|i| i.tau_peak),
        sigma_peak: level(|i| i.sigma_peak),
        bond_strength: first.bond_strength,
        bond_exceedance: est(|i| i.bond_exceedance),
        normal: mean_stats(&all.iter().map(|i| &i.normal).collect::<Vec<_>>()),
        shear: mean_stats(&all.iter().map(|i| &i.shear).collect::<Vec<_>>()),
        sliding: first.sliding.as_ref().map(|s| {
            let slid: Vec<&SlidingVerification> =
                all.iter().filter_map(|i| i.sliding.as_ref()).collect();
            mean_sliding(s.friction, &slid)
        }),
    }
}

/// The realisations' sliding numbers of one interface averaged as the others are.
fn mean_sliding(friction: f64, all: &[&SlidingVerification]) -> SlidingVerification {
    let est = |f: fn(&SlidingVerification) -> Estimate| mean_of(all.iter().map(|s| f(s)));
    SlidingVerification {
        friction,
        mean_x: est(|s| s.mean_x),
        mean_y: est(|s| s.mean_y),
        tau_x_rms: est(|s| s.tau_x_rms),
        tau_y_rms: est(|s| s.tau_y_rms),
        quantiles: [
            est(|s| s.quantiles[0]),
            est(|s| s.quantiles[1]),
            est(|s| s.quantiles[2]),
        ],
        max: est(|s| s.max),
    }
}

/// The realisations' exact numbers averaged (errors: the mean grid error), with the stress
/// checks judged on the mean levels; the solver's record is the realisation that needed the
/// most iterations, the time the total.
pub fn mean_stack_verification(
    vs: &[StackVerification],
    design: &StackDesign,
) -> StackVerification {
    let first = &vs[0];
    let interfaces: Vec<InterfaceExact> = (0..first.interfaces.len())
        .map(|k| mean_interface(vs, k))
        .collect();
    let top = |f: fn(&StackVerification) -> Estimate| mean_of(vs.iter().map(f));
    let mean_contact_pressure = top(|v| v.mean_contact_pressure);
    let checks = judge(design, &interfaces, mean_contact_pressure);
    StackVerification {
        nx: first.nx,
        ny: first.ny,
        q_low_z: first.q_low_z,
        area_fraction: top(|v| v.area_fraction),
        mean_contact_pressure,
        sigma_rms_top: top(|v| v.sigma_rms_top),
        interfaces,
        pass: checks.iter().all(|c| c.check.pass),
        checks,
        convergence: vs
            .iter()
            .map(|v| v.convergence)
            .max_by_key(|c| c.iterations)
            .unwrap_or(first.convergence),
        seconds: vs.iter().map(|v| v.seconds).sum(),
    }
}

/// The exact check of a stack design on `opts.realisations` random-phase realisations of
/// `spectrum` under the sliding friction `mu` (0: static contact; module docs).
pub fn on_stack_realisations(
    spectrum: &Spectrum,
    design: &StackDesign,
    mu: f64,
    opts: &ExactOptions,
) -> Result<
    (
        StackVerification,
        Option<ExactMinThickness>,
        StackRealisations,
    ),
    Error,
> {
    let grid = realisations::grid(spectrum, opts.max_side);
    let seeds: Vec<u64> = (1..=opts.realisations as u64).collect();
    let mut vs = Vec::new();
    let mut ms = Vec::new();
    for &seed in &seeds {
        let surface = realisation(spectrum, &grid, seed)?;
        let (v, m) = on_stack_surface(&surface, design, mu, &opts.bem)?;
        vs.push(v);
        ms.extend(m);
    }
    let mut mean = mean_stack_verification(&vs, design);
    let spread_of =
        |f: &dyn Fn(&StackVerification) -> f64| spread(&vs.iter().map(f).collect::<Vec<_>>());
    let top = TOP_KEYS
        .iter()
        .map(|&(key, f)| (key, spread_of(&|v| f(v).value)))
        .collect();
    let interfaces = (0..mean.interfaces.len())
        .map(|k| {
            let mut keyed: Vec<(&'static str, f64)> = INTERFACE_KEYS
                .iter()
                .map(|&(key, f)| (key, spread_of(&|v| f(&v.interfaces[k]).value)))
                .collect();
            if mean.interfaces[k].sliding.is_some() {
                keyed.extend(SLIDING_KEYS.iter().map(|&(key, f)| {
                    let of = |v: &StackVerification| {
                        v.interfaces[k]
                            .sliding
                            .as_ref()
                            .map_or(f64::NAN, |s| f(s).value)
                    };
                    (key, spread_of(&of))
                }));
            }
            keyed
        })
        .collect();
    let (m, min_thickness_spread) = if ms.is_empty() {
        (None, f64::NAN)
    } else {
        let (m, s) = mean_min_thickness(&ms);
        add_min_thickness(&mut mean, design, &m);
        (Some(m), s)
    };
    Ok((
        mean,
        m,
        StackRealisations {
            count: seeds.len(),
            grid,
            seeds,
            top,
            interfaces,
            min_thickness_spread,
        },
    ))
}
