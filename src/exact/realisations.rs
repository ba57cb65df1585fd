//! Random-phase realisations of a spectrum, for the exact check of a scene given by its power
//! spectrum alone (no height map): K surfaces with the spectrum's amplitudes and independent
//! random phases (paper eq. A1; [`crate::topography::synth::random_phase_map`], seeds 1..=K),
//! each solved exactly; every exact number is then the mean over the K surfaces with its
//! spread.
//!
//! # Grid
//! One period L = 2π/q_L holds the spectrum's lowest wavenumber q_L as its fundamental; the
//! pixel dx = L/n with n the smallest power of two (at least 32, so that the half-resolution
//! error estimate runs) whose Nyquist wavenumber π/dx reaches the spectrum's upper end q_hi,
//! capped at `max_side` (memory and time: a solve holds about 15 n² doubles, 120 MB at
//! n = 1024). The grid holds the modes with |q| ≤ π/dx; the share of the slope variance above
//! it, 2π∫_{π/dx}^{q_hi} q³C dq / 2π∫_{q_L}^{q_hi} q³C dq, is reported as what the grid could
//! not hold (rough small-scale contact the solve does not see).
//!
//! # Spread
//! The spread of a number is the standard error of its mean over the K realisations, the
//! sample standard deviation (K − 1 in the denominator) over √K: it shrinks as 1/√K because
//! the realisations are independent (independent phases). Its grid error is the mean of the
//! realisations' grid errors ([`crate::verify`]). Under sliding friction the shear vector's
//! numbers ([`crate::verify::sliding`]) are averaged and spread in the same way.

use crate::bem::Surface;
use crate::check::{Design, MinThickness};
use crate::error::Error;
use crate::prec::{Estimate, Termination};
use crate::psd::Spectrum;
use crate::topography::synth::random_phase_map;
use crate::verify::sliding::SlidingVerification;
use crate::verify::{Level, Verification, exact_checks};
use std::f64::consts::PI;

use super::min_thickness::ExactMinThickness;

/// Realisations solved when `--realisations` is not given.
pub const DEFAULT_REALISATIONS: usize = 4;
/// The most realisations accepted.
pub const MAX_REALISATIONS: usize = 256;
/// The largest grid side used when `--realisation-grid` is not given.
pub const DEFAULT_MAX_SIDE: usize = 256;
/// The largest grid side accepted (a 4096² solve holds about 2 GB).
pub const MAX_SIDE: usize = 4096;
/// The smallest grid side (the half-resolution error needs 32).
pub const MIN_SIDE: usize = 32;

/// The grid the realisations are synthesised and solved on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// Pixels per side.
    pub n: usize,
    /// Pixel size (m).
    pub dx: f64,
    /// The spectrum's support [q_L, q_hi] (1/m).
    pub q_low: f64,
    pub q_high: f64,
    /// π/dx (1/m): the grid holds the modes with |q| up to it.
    pub q_nyquist: f64,
    /// The share of the spectrum's slope variance above `q_nyquist` (0 when the grid holds the
    /// whole spectrum).
    pub unresolved_slope_share: f64,
}

/// The mean-square slope 2π∫_a^b q³C dq, in ln q by 10-point Gauss–Legendre on panels no wider
/// than 0.25 between the spectrum's knots.
pub fn slope_between(spectrum: &Spectrum, a: f64, b: f64) -> f64 {
    let mut knots = vec![a];
    knots.extend(spectrum.knots().into_iter().filter(|&q| q > a && q < b));
    knots.push(b);
    let (x10, w10) = crate::quad::gl10();
    let mut sum = 0.0;
    for pair in knots.windows(2) {
        let (ua, ub) = (pair[0].ln(), pair[1].ln());
        let panels = (((ub - ua) / 0.25).ceil() as usize).max(1);
        let h = (ub - ua) / panels as f64;
        for p in 0..panels {
            let mid = ua + (p as f64 + 0.5) * h;
            for (x, w) in x10.iter().zip(w10) {
                let q = (mid + 0.5 * h * x).exp();
                sum += w * 0.5 * h * q.powi(4) * spectrum.c(q);
            }
        }
    }
    2.0 * PI * sum
}

/// The grid for `spectrum` with at most `max_side` pixels a side (module docs).
pub fn grid(spectrum: &Spectrum, max_side: usize) -> Grid {
    let (q_low, q_high) = spectrum.support();
    let length = 2.0 * PI / q_low;
    // π n / L ≥ q_hi  ⇔  n ≥ 2 q_hi / q_L.
    let want = (2.0 * q_high / q_low).ceil().min(MAX_SIDE as f64) as usize;
    let n = want
        .max(MIN_SIDE)
        .next_power_of_two()
        .min(max_side.max(MIN_SIDE));
    let dx = length / n as f64;
    let q_nyquist = PI / dx;
    let unresolved_slope_share = if q_nyquist >= q_high {
        0.0
    } else {
        slope_between(spectrum, q_nyquist, q_high) / slope_between(spectrum, q_low, q_high)
    };
    Grid {
        n,
        dx,
        q_low,
        q_high,
        q_nyquist,
        unresolved_slope_share,
    }
}

/// Realisation `seed` of `spectrum` on `grid`: the modes with |q| ≤ π/dx at the spectrum's
/// amplitude, random phases.
pub fn realisation(spectrum: &Spectrum, grid: &Grid, seed: u64) -> Result<Surface, Error> {
    let q_max = grid.q_nyquist;
    let c = |q: f64| if q <= q_max { spectrum.c(q) } else { 0.0 };
    Surface::from_height_map(&random_phase_map(grid.n, grid.dx, c, seed))
}

/// The standard error of the mean of `values`: sample standard deviation / √K (NaN for K < 2).
pub fn spread(values: &[f64]) -> f64 {
    let k = values.len() as f64;
    if values.len() < 2 {
        return f64::NAN;
    }
    let mean = values.iter().sum::<f64>() / k;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (k - 1.0);
    (var / k).sqrt()
}

/// The mean of `values`.
pub(crate) fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    s / n as f64
}

/// The mean of an estimate over the realisations: mean value, mean (grid) error, the worst
/// status.
fn mean_estimate<T>(vs: &[T], f: impl Fn(&T) -> Estimate) -> Estimate {
    Estimate {
        value: mean(vs.iter().map(|v| f(v).value)),
        err: mean(vs.iter().map(|v| f(v).err)),
        status: vs
            .iter()
            .map(|v| f(v).status)
            .fold(Termination::Converged, Estimate::worst),
    }
}

/// The realisations' exact numbers averaged (errors: the mean grid error), with the stress
/// checks judged on the mean levels; the solver's record is the realisation that needed the
/// most iterations, the time the total.
pub fn mean_verification(vs: &[Verification], design: &Design) -> Verification {
    let level = |f: fn(&Verification) -> Level| Level {
        value: mean_estimate(vs, |v| f(v).value),
        resolved: vs.iter().all(|v| f(v).resolved),
    };
    let tau_peak = level(|v| v.tau_peak);
    let sigma_peak_interface = level(|v| v.sigma_peak_interface);
    let mean_contact_pressure = mean_estimate(vs, |v| v.mean_contact_pressure);
    let checks = exact_checks(
        design,
        tau_peak,
        sigma_peak_interface,
        mean_contact_pressure,
    );
    let pass = checks.iter().all(|c| c.pass);
    let first = &vs[0];
    Verification {
        nx: first.nx,
        ny: first.ny,
        q_low_d: first.q_low_d,
        area_fraction: mean_estimate(vs, |v| v.area_fraction),
        mean_contact_pressure,
        sigma_rms_top: mean_estimate(vs, |v| v.sigma_rms_top),
        sigma_rms_interface: mean_estimate(vs, |v| v.sigma_rms_interface),
        tau_rms_interface: mean_estimate(vs, |v| v.tau_rms_interface),
        tau_peak,
        sigma_peak_interface,
        bond_exceedance: mean_estimate(vs, |v| v.bond_exceedance),
        checks,
        pass,
        sliding: mean_sliding(vs),
        convergence: vs
            .iter()
            .map(|v| v.convergence)
            .max_by_key(|c| c.iterations)
            .unwrap_or(first.convergence),
        seconds: vs.iter().map(|v| v.seconds).sum(),
    }
}

/// The realisations' exact sliding numbers averaged as [`mean_verification`] averages the
/// static ones (none without friction).
fn mean_sliding(vs: &[Verification]) -> Option<SlidingVerification> {
    let ss: Vec<&SlidingVerification> = vs
        .iter()
        .map(|v| v.sliding.as_ref())
        .collect::<Option<_>>()?;
    let m = |f: fn(&SlidingVerification) -> Estimate| mean_estimate(&ss, |s| f(s));
    Some(SlidingVerification {
        friction: ss[0].friction,
        mean_x: m(|s| s.mean_x),
        mean_y: m(|s| s.mean_y),
        tau_x_rms: m(|s| s.tau_x_rms),
        tau_y_rms: m(|s| s.tau_y_rms),
        quantiles: [0, 1, 2].map(|i| mean_estimate(&ss, |s| s.quantiles[i])),
        max: m(|s| s.max),
    })
}

/// The realisations' minimum thicknesses averaged: the mean d_min with the mean bracket error
/// and the mean grid error (none when some realisation has no passing thickness), the check
/// that sets most of them, and the spread of d_min.
pub fn mean_min_thickness(ms: &[ExactMinThickness]) -> (ExactMinThickness, f64) {
    let all: Option<Vec<Estimate>> = ms.iter().map(|m| m.search.thickness).collect();
    let thickness = all.as_ref().map(|ds| Estimate {
        value: mean(ds.iter().map(|d| d.value)),
        err: mean(ds.iter().map(|d| d.err)),
        status: Termination::Converged,
    });
    let spread = all.map_or(f64::NAN, |ds| {
        spread(&ds.iter().map(|d| d.value).collect::<Vec<_>>())
    });
    let governing = ms
        .iter()
        .map(|m| m.search.governing)
        .max_by_key(|g| ms.iter().filter(|m| m.search.governing == *g).count())
        .flatten();
    let first = &ms[0].search;
    let combined = ExactMinThickness {
        search: MinThickness {
            thickness,
            governing,
            floor: first.floor,
            bulk: first.bulk,
            all_pass_to_floor: ms.iter().all(|m| m.search.all_pass_to_floor),
            evaluations: ms.iter().map(|m| m.search.evaluations).sum(),
        },
        grid_err: mean(ms.iter().map(|m| m.grid_err)),
        solves: ms.iter().map(|m| m.solves).sum(),
        iterations: ms.iter().map(|m| m.iterations).sum(),
    };
    (combined, spread)
}
