//! The exact path of `check --verify`: the stress checks judged on solved fields
//! ([`crate::verify`]), the minimum thickness searched with the exact solver
//! ([`min_thickness`]), on the scene's height map or, for a scene given by a spectrum alone, on
//! K random-phase realisations of that spectrum ([`realisations`]), each number then the mean
//! over them with its spread; on a layer stack, at every interface, with the minimum thickness
//! of one layer ([`stack`], [`stack_min_thickness`]).
//!
//! The exact verdict: every enabled exact stress check passes at the design thickness and the
//! thickness is at least the exact d_min (when min-thickness is enabled).

pub mod levels;
pub mod min_thickness;
pub mod realisations;
pub mod stack;
pub mod stack_min_thickness;
pub mod stack_realisations;

use crate::bem::{BemSettings, Surface};
use crate::check::{Design, Evaluation};
use crate::error::Error;
use crate::psd::Spectrum;
use crate::verify::boundary::BoundaryChoice;
use crate::verify::{Verification, check_rows, verify};
use min_thickness::ExactMinThickness;
use realisations::Grid;

/// How the exact check runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactOptions {
    pub bem: BemSettings,
    /// Realisations of a spectrum (scenes without a height map).
    pub realisations: usize,
    /// The largest side of a realisation's grid (pixels, a power of two).
    pub max_side: usize,
    /// The boundary of the solves (`bem.boundary` is set from it).
    pub boundary: BoundaryChoice,
}

impl Default for ExactOptions {
    fn default() -> Self {
        Self {
            bem: BemSettings::default(),
            realisations: realisations::DEFAULT_REALISATIONS,
            max_side: realisations::DEFAULT_MAX_SIDE,
            boundary: BoundaryChoice::Auto,
        }
    }
}

/// The realisations behind an exact check of a spectrum.
#[derive(Debug, Clone, PartialEq)]
pub struct Realisations {
    /// Their number K.
    pub count: usize,
    pub grid: Grid,
    /// Seeds of the random phases, one per realisation.
    pub seeds: Vec<u64>,
    /// The spread (standard error of the mean) of each exact number, by report key
    /// ([`crate::verify::CheckRow::key`]).
    pub spread: Vec<(&'static str, f64)>,
    /// The spread of the exact d_min (NaN when it was not searched or some realisation has no
    /// passing thickness).
    pub min_thickness_spread: f64,
}

impl Realisations {
    /// The spread of the number with report key `key`.
    pub fn spread_of(&self, key: &str) -> Option<f64> {
        self.spread.iter().find(|(k, _)| *k == key).map(|(_, s)| *s)
    }
}

/// The exact check on one surface: the stress checks at `thickness` and, when min-thickness
/// is enabled, the exact d_min and its check (added to the verification's checks and verdict).
pub fn on_surface(
    surface: &Surface,
    design: &Design,
    thickness: f64,
    settings: &BemSettings,
) -> Result<(Verification, Option<ExactMinThickness>), Error> {
    let mut v = verify(surface, design, thickness, settings)?;
    let m = design
        .criteria
        .checks
        .min_thickness
        .then(|| min_thickness::min_thickness(surface, design, settings))
        .transpose()?;
    if let Some(m) = &m {
        add_min_thickness(&mut v, m, thickness);
    }
    Ok((v, m))
}

fn add_min_thickness(v: &mut Verification, m: &ExactMinThickness, thickness: f64) {
    let check = m.check(thickness);
    v.pass &= check.pass;
    v.checks.push(check);
}

/// The exact check on `opts.realisations` random-phase realisations of `spectrum` (module
/// docs of [`realisations`]); `persson` is the theory's evaluation at the design thickness,
/// whose rows name the reported numbers.
pub fn on_realisations(
    spectrum: &Spectrum,
    design: &Design,
    thickness: f64,
    persson: &Evaluation,
    opts: &ExactOptions,
) -> Result<(Verification, Option<ExactMinThickness>, Realisations), Error> {
    let grid = realisations::grid(spectrum, opts.max_side);
    let seeds: Vec<u64> = (1..=opts.realisations as u64).collect();
    let mut vs = Vec::new();
    let mut ms = Vec::new();
    for &seed in &seeds {
        let surface = realisations::realisation(spectrum, &grid, seed)?;
        let (v, m) = on_surface(&surface, design, thickness, &opts.bem)?;
        vs.push(v);
        ms.extend(m);
    }
    let mut mean = realisations::mean_verification(&vs, design);
    let rows: Vec<Vec<_>> = vs.iter().map(|v| check_rows(persson, v)).collect();
    let spread = rows[0]
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let values: Vec<f64> = rows.iter().map(|rs| rs[i].exact.value).collect();
            (r.key, realisations::spread(&values))
        })
        .collect();
    let (m, min_thickness_spread) = if ms.is_empty() {
        (None, f64::NAN)
    } else {
        let (m, s) = realisations::mean_min_thickness(&ms);
        add_min_thickness(&mut mean, &m, thickness);
        (Some(m), s)
    };
    Ok((
        mean,
        m,
        Realisations {
            count: seeds.len(),
            grid,
            seeds,
            spread,
            min_thickness_spread,
        },
    ))
}
