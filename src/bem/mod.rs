//! Exact contact on a height map: a periodic FFT boundary-element solver for a rigid flat pressed
//! onto a rough film bonded to an elastic substrate, and the interface stresses it implies.
//!
//! # Problem
//! The film's top surface has heights h(x) (m, positive towards the flat) on a periodic
//! `ny × nx` grid with pixel sizes dx, dy. A rigid flat presses on it with nominal pressure p0
//! (load control); the contact is frictionless and non-adhesive. Unknown: the contact pressure
//! p(x) ≥ 0 with mean p0, the surface displacement u = K ∗ p (into the solid) and the gap
//! g(x) = u − h − ḡ ≥ 0 (ḡ: the rigid approach), with p·g = 0.
//!
//! # Kernel
//! The surface Green's function of the layered solid (paper eqs. 6–7, notes.md):
//! u_z(q) = K(q) p(q) with K(q) = 2 S(q d)/(q E0*) (E0* the film's plane-strain modulus); S = 1
//! is the homogeneous half-space. The kernel is sampled at the grid wavevectors (a spectral
//! discretisation: the pressure and displacement are trigonometric polynomials on the grid).
//! The q = 0 mode is handled explicitly: load control fixes the mean pressure to p0, and the
//! mean displacement (infinite for a substrate half-space) is a rigid-body shift absorbed in ḡ,
//! so K(0) is never evaluated and no factor 1/(1 − 2ν) appears (ν = 0.5 is fine).
//!
//! # Algorithm
//! Constrained conjugate gradients of Polonsky & Keer (Wear 231, 1999, 206–219), load-control
//! form: conjugate directions on the current contact set, projection to p ≥ 0, re-admission of
//! penetrating points and rescaling to the mean pressure p0. One deviation: PK restart the
//! conjugacy whenever points are re-admitted; here the directions are reset to the
//! preconditioned gradient only when the last projection moved more than a share of the
//! contact set (`RESTART_SHARE`: clamped or re-admitted points) or when they stop being descent
//! directions (Σ g·t ≤ 0 on the contact set). On self-affine surfaces this needs fewer
//! iterations for the same converged answer: the stopping test below is independent of the
//! path. A re-admitted pixel starts at the pressure that would close its own gap, times the
//! step. While the gap is large the convolutions run in single precision (`convolve`).
//! The conjugate directions are preconditioned with the inverse of the influence operator on the
//! full grid, a Fourier multiplier 1/K(q) (`precond`), which slows the growth of the iterations
//! with the size of the contact patches in pixels.
//! Convergence is judged in physical units: the rms gap on the contact set and the largest
//! penetration outside it must both be at most `gap_tol · h_rms`; the load balance is exact by
//! construction (reported). The result always carries iterations, residuals and the
//! [`Termination`].
//! A cold start on a grid of 512² pixels or more begins from the solution on the map at half
//! the resolution (`multilevel`), so the full-grid iteration starts near its contact set.
//!
//! # Interface stresses
//! For one Fourier mode of the surface pressure, the normal stress at z = d is f(qd) times it and
//! the shear traction at z = d is along q̂ with amplitude g(qd) (paper eq. B7; notes.md). With
//! stresses in the usual tension-positive convention, σ_zz(x, 0) = −p(x), and the notes' sign
//! convention σ_xz(x, d) = g·s0·sin(qx) for σ_zz(x, 0) = s0·cos(qx) gives, in Fourier space,
//! τ(q) = (σ_xz, σ_yz)(q) = i g(qd) q̂ p(q), i.e. p = a·cos(qx) gives τ_x = −g·a·sin(qx).
//! The interface normal stress is reported compression-positive, σ_n(q) = f(qd) p(q) (mean p0).
//! |τ| is what is compared with the bond strength.
//!
//! Layer stacks (`stack`): the same solve with the stack's compliance and the fields at every
//! interface ([`solve_stack`], [`stack_interface_fields`]).

mod convolve;
mod fft;
pub mod free;
mod multilevel;
mod passes;
mod pool;
mod precond;
pub mod sliding;
mod stack;
pub use free::Boundary;
pub use stack::{solve_stack, solve_stack_from, stack_interface_fields};

use crate::error::Error;
use crate::layer::Stack;
use crate::prec::{EPS, Estimate, Termination};
use crate::topography::HeightMap;
use fft::Fft2;
use rayon::prelude::*;
use rustfft::num_complex::Complex64;
use serde::Serialize;
use std::f64::consts::PI;

/// Probabilities at which field quantiles are reported (increasing).
pub const QUANTILES: [f64; 4] = [0.5, 0.9, 0.99, 0.999];

/// Incremental displacement updates between two FFT recomputations, at most.
const REFRESH_EVERY: usize = 32;

/// Points clamped or re-admitted in one step up to which the displacement is updated by adding
/// their columns of the real-space influence matrix instead of a new FFT convolution (each
/// column costs one pass over the grid; a convolution costs about as much as a few dozen).
const SPARSE_MAX: usize = 16;

/// Share of the contact set that, clamped or re-admitted in one projection, restarts the
/// conjugate directions (Polonsky & Keer restart on any re-admission; a few points settling at
/// the edges of the patches leave the directions useful, a swing of the set does not).
const RESTART_SHARE: f64 = 0.02;

/// A periodic height map: `heights[iy * nx + ix]` (m), pixel sizes `dx`, `dy` (m).
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    pub heights: Vec<f64>,
    pub nx: usize,
    pub ny: usize,
    pub dx: f64,
    pub dy: f64,
}

impl Surface {
    /// Validate and wrap a height map.
    pub fn new(heights: Vec<f64>, nx: usize, ny: usize, dx: f64, dy: f64) -> Result<Self, Error> {
        if nx == 0 || ny == 0 || heights.len() != nx * ny {
            return Err(Error::invalid(
                "height map size",
                format!("{} values for {nx} x {ny}", heights.len()),
                "nx * ny > 0 values",
            ));
        }
        for (what, v) in [("pixel size dx", dx), ("pixel size dy", dy)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid(what, v, "a finite length > 0"));
            }
        }
        if let Some(i) = heights.iter().position(|h| !h.is_finite()) {
            return Err(Error::invalid(
                "height",
                format!("{} at x index {}, y index {}", heights[i], i % nx, i / nx),
                "finite heights",
            ));
        }
        Ok(Self {
            heights,
            nx,
            ny,
            dx,
            dy,
        })
    }

    /// The heights of a map read or synthesised by [`crate::topography`] (treated as one
    /// period of a periodic surface, as the solver requires).
    pub fn from_height_map(map: &HeightMap) -> Result<Self, Error> {
        Self::new(map.z.clone(), map.nx, map.ny, map.dx, map.dy)
    }

    /// Number of grid points.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Always false for a validated surface (kept for the `len` convention).
    pub fn is_empty(&self) -> bool {
        self.heights.is_empty()
    }

    /// Periodic lengths (Lx, Ly) in m.
    pub fn lengths(&self) -> (f64, f64) {
        (self.nx as f64 * self.dx, self.ny as f64 * self.dy)
    }

    /// Smallest non-zero wavenumber of the map, 2π / max(Lx, Ly) (1/m): the q_L of the issue.
    pub fn q_low(&self) -> f64 {
        let (lx, ly) = self.lengths();
        2.0 * PI / lx.max(ly)
    }

    /// Mean height (m).
    pub fn mean(&self) -> f64 {
        self.heights.iter().sum::<f64>() / self.len() as f64
    }

    /// Rms height about the mean (m).
    pub fn h_rms(&self) -> f64 {
        let m = self.mean();
        (self.heights.iter().map(|h| (h - m) * (h - m)).sum::<f64>() / self.len() as f64).sqrt()
    }

    /// Rms slope ξ = ⟨|∇h|²⟩^(1/2), spectral definition (Σ q² |h_q|², consistent with the
    /// spectral kernel; for a band-limited map this is the exact slope of its trigonometric
    /// interpolant). Nyquist modes count with their |q|.
    pub fn rms_slope(&self) -> f64 {
        let (nx, ny) = (self.nx, self.ny);
        let (qx, qy) = wavenumbers(nx, ny, self.dx, self.dy);
        let n = self.len() as f64;
        let s = Fft2::<f64>::new(nx, ny).spectrum_sum(&self.heights, |kx, col| {
            half_spectrum_weight(kx, nx)
                * col
                    .iter()
                    .zip(&qy)
                    .map(|(c, q)| (qx[kx] * qx[kx] + q * q) * c.norm_sqr())
                    .sum::<f64>()
        });
        (s / (n * n)).sqrt()
    }
}

/// Settings of the solver.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BemSettings {
    /// Gap tolerance relative to h_rms: converged when the rms gap on the contact set and the
    /// largest penetration outside it are both ≤ `gap_tol · h_rms`.
    pub gap_tol: f64,
    /// Iteration limit; reaching it gives [`Termination::ToleranceNotReached`].
    pub max_iter: usize,
    /// Periodic map, or a window with free boundaries ([`free`]).
    pub boundary: Boundary,
}

impl Default for BemSettings {
    fn default() -> Self {
        Self {
            gap_tol: 1e-6,
            max_iter: 20_000,
            boundary: Boundary::Periodic,
        }
    }
}

/// How the solver ended, in physical units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Convergence {
    /// Conjugate-gradient iterations on the full grid (each costs four or six real FFTs); the
    /// iterations of a coarse-to-fine start's solve on the coarse map are not counted.
    pub iterations: usize,
    /// Restarts of the conjugate directions (a direction that was not a descent direction on
    /// the updated contact set was replaced by the gradient).
    pub restarts: usize,
    /// Rms gap on the contact set (m): should be 0.
    pub gap_rms_in_contact: f64,
    /// Largest penetration outside the contact set (m): should be 0.
    pub max_penetration: f64,
    /// The tolerance both were held to (m), `gap_tol · h_rms`.
    pub tolerance: f64,
    /// |mean(p) − p0| / p0 of the returned pressure.
    pub load_error: f64,
    pub status: Termination,
}

impl Convergence {
    /// How an iteration ended: converged if the gap rms in contact and the penetration are both
    /// within `tolerance` (m); the load error is set when the solution is formed.
    fn of_iteration(
        iterations: usize,
        restarts: usize,
        gap_rms: f64,
        penetration: f64,
        tolerance: f64,
    ) -> Self {
        let status = if gap_rms <= tolerance && penetration <= tolerance {
            Termination::Converged
        } else {
            Termination::ToleranceNotReached
        };
        Self {
            iterations,
            restarts,
            gap_rms_in_contact: gap_rms,
            max_penetration: penetration,
            tolerance,
            load_error: 0.0,
            status,
        }
    }
}

/// Quantile of a field at probability `prob` (nearest rank: the smallest sample value with at
/// least a fraction `prob` of the samples at or below it).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Quantile {
    pub prob: f64,
    pub value: f64,
}

/// Summary statistics of a sampled field.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FieldStats {
    /// Number of samples (pixels) summarised.
    pub samples: usize,
    pub mean: f64,
    /// Root mean square (about 0).
    pub rms: f64,
    /// Root mean square deviation about the mean.
    pub rms_dev: f64,
    /// At the probabilities [`QUANTILES`].
    pub quantiles: Vec<Quantile>,
    pub max: f64,
}

impl FieldStats {
    /// Statistics of `values` (not modified). Empty input gives zero samples and NaN values.
    pub fn of(values: &[f64]) -> Self {
        let n = values.len();
        if n == 0 {
            return Self {
                samples: 0,
                mean: f64::NAN,
                rms: f64::NAN,
                rms_dev: f64::NAN,
                quantiles: QUANTILES
                    .iter()
                    .map(|&prob| Quantile {
                        prob,
                        value: f64::NAN,
                    })
                    .collect(),
                max: f64::NAN,
            };
        }
        let nf = n as f64;
        let sums = chunked_ref(values, |_, c| {
            [c.iter().sum(), c.iter().map(|v| v * v).sum()]
        });
        let mean = sum(&sums, 0) / nf;
        let ms = sum(&sums, 1) / nf;
        let var = sum(
            &chunked_ref(values, |_, c| {
                [c.iter().map(|v| (v - mean) * (v - mean)).sum()]
            }),
            0,
        ) / nf;
        let mut work = pool::F64.take(n, 0.0);
        work.copy_from_slice(values);
        // Nearest-rank order statistics by selection, in increasing rank: after selecting rank
        // r, `work[..r]` holds the r smallest values, so the next rank is selected in the rest.
        let mut done = 0;
        let mut quantiles = Vec::with_capacity(QUANTILES.len());
        for &prob in &QUANTILES {
            let idx = ((prob * nf).ceil() as usize).clamp(1, n) - 1;
            if idx >= done {
                work[done..].select_nth_unstable_by(idx - done, f64::total_cmp);
                done = idx + 1;
            }
            quantiles.push(Quantile {
                prob,
                value: work[idx],
            });
        }
        let max = work[done.min(n - 1)..]
            .iter()
            .copied()
            .max_by(f64::total_cmp)
            .expect("n > 0");
        Self {
            samples: n,
            mean,
            rms: ms.sqrt(),
            rms_dev: var.sqrt(),
            quantiles,
            max,
        }
    }

    /// The quantile at `prob` if it is one of [`QUANTILES`].
    pub fn quantile(&self, prob: f64) -> Option<f64> {
        self.quantiles
            .iter()
            .find(|q| q.prob == prob)
            .map(|q| q.value)
    }
}

/// The solved contact.
#[derive(Debug, Clone, PartialEq)]
pub struct BemSolution {
    pub nx: usize,
    pub ny: usize,
    pub dx: f64,
    pub dy: f64,
    /// Nominal pressure (Pa).
    pub p0: f64,
    /// Rms height of the map (m).
    pub h_rms: f64,
    /// Contact pressure (Pa), `pressure[iy * nx + ix]`; exactly 0 off contact.
    pub pressure: Vec<f64>,
    /// Gap to the flat (m); 0 to the tolerance in contact.
    pub gap: Vec<f64>,
    /// A/A0: the fraction of pixels in contact. `err` is the part due to the solver tolerance
    /// (pixels off contact whose gap is within the tolerance); the discretisation error is not
    /// included and shows under grid refinement.
    pub area_fraction: Estimate,
    /// Contact pressure over the contact area (mean = p0 / (A/A0)).
    pub contact_pressure: FieldStats,
    /// Rms of p − p0 over the whole nominal area (Persson's σ_rms at z = 0).
    pub sigma_rms_top: f64,
    pub convergence: Convergence,
    /// The boundary the contact was solved with.
    pub boundary: Boundary,
}

/// Interface (z = d) stress fields and their statistics.
#[derive(Debug, Clone, PartialEq)]
pub struct InterfaceFields {
    /// Normal stress at z = d, compression positive (Pa); mean p0.
    pub normal: Vec<f64>,
    /// Shear traction components σ_xz, σ_yz at z = d (Pa).
    pub shear_x: Vec<f64>,
    pub shear_y: Vec<f64>,
    /// Statistics of the normal stress over the whole interface (rms_dev = σ_rms(d)).
    pub normal_stats: FieldStats,
    /// Statistics of |τ| over the whole interface (rms = τ_rms of eq. B9).
    pub shear_stats: FieldStats,
}

impl InterfaceFields {
    /// |τ| at pixel `i`.
    pub fn shear_magnitude(&self, i: usize) -> f64 {
        self.shear_x[i].hypot(self.shear_y[i])
    }

    /// Fraction of the interface where |τ| exceeds `level` (e.g. the bond strength).
    pub fn shear_fraction_above(&self, level: f64) -> f64 {
        let n = self.shear_x.len();
        let count = (0..n)
            .into_par_iter()
            .filter(|&i| self.shear_magnitude(i) > level)
            .count();
        count as f64 / n as f64
    }

    /// Fraction of the interface where the normal stress exceeds `level`.
    pub fn normal_fraction_above(&self, level: f64) -> f64 {
        let count = self.normal.par_iter().filter(|&&s| s > level).count();
        count as f64 / self.normal.len() as f64
    }
}

/// Grid wavenumbers: qx for kx in 0..=nx/2, qy for ky in 0..ny (wrap-around order), in 1/m.
fn wavenumbers(nx: usize, ny: usize, dx: f64, dy: f64) -> (Vec<f64>, Vec<f64>) {
    let qx = (0..nx / 2 + 1)
        .map(|k| 2.0 * PI * k as f64 / (nx as f64 * dx))
        .collect();
    let qy = (0..ny)
        .map(|k| {
            let s = if k <= ny / 2 {
                k as f64
            } else {
                k as f64 - ny as f64
            };
            2.0 * PI * s / (ny as f64 * dy)
        })
        .collect();
    (qx, qy)
}

/// Weight of half-spectrum column kx in a sum over the full spectrum of a real field.
fn half_spectrum_weight(kx: usize, nx: usize) -> f64 {
    if kx == 0 || (nx.is_multiple_of(2) && kx == nx / 2) {
        1.0
    } else {
        2.0
    }
}

fn check_pressure(p0: f64) -> Result<(), Error> {
    if p0.is_finite() && p0 > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            "nominal pressure",
            p0,
            "a finite p0 > 0 in Pa",
        ))
    }
}

/// The nominal pressure and the settings' gap tolerance, checked before a solve.
fn check_inputs(p0: f64, settings: &BemSettings) -> Result<(), Error> {
    check_pressure(p0)?;
    if settings.gap_tol > 0.0 && settings.gap_tol.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(
            "gap tolerance",
            settings.gap_tol,
            "a finite value > 0 (relative to h_rms)",
        ))
    }
}

fn check_stack(stack: &Stack) -> Result<(), Error> {
    let d = stack.thickness;
    if d.is_finite() && d > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid("film thickness", d, "a finite d > 0 in m"))
    }
}

/// Solve the contact of a rigid flat with the layered solid `stack` whose top has the heights
/// of `surface`, at nominal pressure `p0`.
pub fn solve(
    surface: &Surface,
    stack: &Stack,
    p0: f64,
    settings: &BemSettings,
) -> Result<BemSolution, Error> {
    check_stack(stack)?;
    let e0 = stack.layers.film.e_star();
    let d = stack.thickness;
    let layers = stack.layers;
    if settings.boundary == Boundary::Free {
        return free::solve_free(
            surface,
            &film_solid(stack, &|q| layers.s(q * d)),
            p0,
            settings,
            None,
        );
    }
    solve_with_compliance(surface, |q| 2.0 * layers.s(q * d) / (q * e0), p0, settings)
}

/// The film on its substrate as the free-boundary kernel sees it (`s`: S at q).
fn film_solid<'a>(stack: &Stack, s: &'a (dyn Fn(f64) -> f64 + Sync)) -> free::Solid<'a> {
    free::Solid::Layered {
        e_star: stack.layers.film.e_star(),
        s,
        thinnest: stack.thickness,
        total: stack.thickness,
    }
}

/// [`solve`] warm-started from the pressure field `start` (Pa, `start[iy * nx + ix]`, e.g. the
/// solution of a neighbouring thickness): the iteration begins on its contact set, rescaled to
/// the mean p0, instead of the full contact of a cold start. The converged answer is the same
/// (the contact problem has one solution and the stopping test does not depend on the path);
/// only the iterations differ.
pub fn solve_from(
    surface: &Surface,
    stack: &Stack,
    p0: f64,
    settings: &BemSettings,
    start: &[f64],
) -> Result<BemSolution, Error> {
    check_stack(stack)?;
    let e0 = stack.layers.film.e_star();
    let d = stack.thickness;
    let layers = stack.layers;
    if settings.boundary == Boundary::Free {
        let s = |q: f64| layers.s(q * d);
        return free::solve_free(surface, &film_solid(stack, &s), p0, settings, Some(start));
    }
    let compliance = |q: f64| 2.0 * layers.s(q * d) / (q * e0);
    solve_compliance_from(surface, compliance, p0, settings, Some(start))
}

/// Solve with an arbitrary isotropic surface compliance `compliance(q)` = u_z(q)/p(q) (m/Pa,
/// finite and > 0 for q > 0); e.g. `|q| 2.0 / (q * e_star)` for a homogeneous half-space.
pub fn solve_with_compliance<K>(
    surface: &Surface,
    compliance: K,
    p0: f64,
    settings: &BemSettings,
) -> Result<BemSolution, Error>
where
    K: Fn(f64) -> f64 + Sync,
{
    solve_compliance_from(surface, compliance, p0, settings, None)
}

/// The initial pressure of a warm start: `start` rescaled to the mean `p0`; it must have one
/// value per pixel, all finite and ≥ 0, not all 0.
fn warm_pressure(start: &[f64], n: usize, p0: f64) -> Result<Vec<f64>, Error> {
    let total: f64 = start.iter().sum();
    if start.len() != n || start.iter().any(|v| !(v.is_finite() && *v >= 0.0)) || total <= 0.0 {
        return Err(Error::invalid(
            "warm-start pressure",
            format!("{} values summing to {total:e} Pa", start.len()),
            "one finite pressure >= 0 per pixel, not all 0",
        ));
    }
    let scale = p0 * n as f64 / total;
    Ok(start.iter().map(|v| v * scale).collect())
}

/// [`solve_with_compliance`], from the full contact (`start` = None) or a warm start.
fn solve_compliance_from<K>(
    surface: &Surface,
    compliance: K,
    p0: f64,
    settings: &BemSettings,
    start: Option<&[f64]>,
) -> Result<BemSolution, Error>
where
    K: Fn(f64) -> f64 + Sync,
{
    solve_from_dyn(surface, &compliance, p0, settings, start)
}

/// [`solve_compliance_from`] with the compliance behind a reference (the coarse-to-fine start
/// calls it again on the coarse map). A cold start on a large grid begins from the prolonged
/// solution on the coarse map ([`multilevel`]).
fn solve_from_dyn(
    surface: &Surface,
    compliance: &(dyn Fn(f64) -> f64 + Sync),
    p0: f64,
    settings: &BemSettings,
    start: Option<&[f64]>,
) -> Result<BemSolution, Error> {
    check_inputs(p0, settings)?;
    let coarse_start = match start {
        Some(_) => None,
        None => multilevel::coarse_start(surface, compliance, p0, settings),
    };
    let start = coarse_start.as_deref().or(start);
    let (nx, ny) = (surface.nx, surface.ny);
    let n = nx * ny;
    // Work fields from the pool (see `pool`), filled as fresh ones would be.
    let take = |fill| pool::F64.take(n, fill);
    let kernel = kernel_grid(surface, &compliance)?;
    let mut conv = convolve::Convolutions::new(&kernel, nx, ny);
    let (mut graw, mut t, mut r) = (vec![0.0; n], take(0.0), take(0.0));
    // The periodic real-space influence matrix's first column (its mean is zero, as the
    // kernel's q = 0 entry); r is free until the iteration starts.
    let mut green = take(0.0);
    conv.first_column(&mut r, &mut green);
    let field = Field {
        nx,
        ny,
        green: &green,
    };
    let mean_h = surface.mean();
    let mut h = take(0.0);
    for (hi, v) in h.iter_mut().zip(&surface.heights) {
        *hi = v - mean_h;
    }
    let h_rms = surface.h_rms();
    let tol = settings.gap_tol * h_rms;

    // p: admissible pressure (p ≥ 0, mean p0) is ps·p, the rescaling to the mean p0 of each step
    // being applied when p is next read; contact: p > 0; graw = u − h with u = K ps·p, the gap
    // being graw − ḡ (`passes`); t: conjugate direction; r = K t.
    let mut ps = 1.0;
    let mut p = match start {
        Some(start) => warm_pressure(start, n, p0)?,
        None => vec![p0; n],
    };
    drop(coarse_start);
    let mut contact = pool::BOOL.take(n, false);
    for (c, &v) in contact.iter_mut().zip(&p) {
        *c = v > 0.0;
    }
    let mut z = take(0.0);
    let mut precond = precond::Preconditioner::new(&kernel, nx, ny);
    let (mut g_old, mut restarts, mut iterations) = (1.0, 0usize, 0);
    // u is recomputed by FFT unless the last update changed few points beyond the linear one:
    // then u ← s(u − step·r + Σ δ_j G_j) is exact (δ_j: the change at a clamped or re-admitted
    // point j beyond p − step·t, G_j: column j of the influence matrix); drift is bounded by a
    // periodic refresh, and every verdict (converged or not) is taken on a freshly computed u.
    let (mut need_fresh, mut since_fresh, mut gap) = (true, 0usize, None);
    let (mut gap_rms, mut penetration);
    // Points clamped or re-admitted by the last projection.
    let mut moved = 0usize;
    loop {
        let sums = match gap {
            Some(sums) if !need_fresh => sums,
            _ => {
                need_fresh = false;
                since_fresh = 0;
                conv.fresh((&p, ps), &mut graw, (&h, &contact, &t))
            }
        };
        gap = Some(sums);
        gap_rms = (sums.g2 / sums.n_c).sqrt();
        penetration = sums.pen;
        let (within, capped) = (
            gap_rms <= tol && penetration <= tol,
            iterations >= settings.max_iter,
        );
        if conv.end_single_at(within || capped, (gap_rms, penetration, h_rms), iterations) {
            // The rest of the iteration, and every verdict, in double precision.
            need_fresh = true;
            continue;
        }
        // A converged answer is the result of a double-precision step (or of none), unless it
        // is exact (no gap on the contact set, no penetration: nothing a step could improve).
        let exact = gap_rms == 0.0 && penetration == 0.0;
        if (within && (conv.last_step_double(iterations) || exact)) || capped {
            if since_fresh > 0 {
                need_fresh = true;
                continue;
            }
            break;
        }
        iterations += 1;
        // r is free until K t is formed: it holds the masked gap the preconditioner filters.
        let (gz, zbar) = precond.apply((&graw, &contact, &sums), &mut r, &mut z);
        let set_moved = moved as f64 > RESTART_SHARE * sums.n_c;
        let (beta, num, restarted) = coefficient(gz, g_old, sums.gt, iterations > 1 && !set_moved);
        restarts += usize::from(restarted && iterations > 1);
        g_old = gz;
        let den = conv.conjugate((&mut t, &mut r), (&z, zbar, &contact), sums.n_c, beta);
        let den = match positive_denominator("boundary-element contact", den, iterations) {
            Ok(den) => den,
            Err(_) if conv.single() => {
                // K is positive, so this is single precision's rounding (Σ r·t cancelling):
                // the step is taken again in double precision, from the preconditioned gradient.
                conv.end_single(iterations);
                (need_fresh, g_old) = (true, 0.0);
                continue;
            }
            Err(e) => return Err(e),
        };
        let step = num / den;
        // A re-admitted pixel gets the pressure that would close its own gap (1/G(0) per unit
        // gap, G(0) the influence matrix's diagonal), times the step like the rest.
        let readmit = step / green[0];
        let (total, moved_now, changes) = passes::project(
            &mut p,
            Some(&mut contact[..]),
            (ps, step, readmit),
            &t,
            &graw,
            sums.gbar,
        );
        let scale = p0 * n as f64 / total;
        ps = scale;
        moved = moved_now;
        match changes {
            Some(ch) if since_fresh < REFRESH_EVERY => {
                let fields = (&h[..], &r[..], &t[..]);
                let rows = passes::update(&field, &mut graw, fields, &contact, (step, scale), &ch);
                gap = Some(passes::GapSums::of(&rows));
                since_fresh += 1;
            }
            _ => need_fresh = true,
        }
    }
    // The work fields go back to the pool before the solution's statistics take theirs.
    drop(conv);
    drop((t, r, green, z, h, contact, precond, kernel));
    // The gap g = graw − ḡ and the pressure ps·p.
    let gbar = gap.map_or(0.0, |sums| sums.gbar);
    let mut g = graw;
    g.par_iter_mut().for_each(|gi| *gi -= gbar);
    p.par_iter_mut().for_each(|pi| *pi *= ps);
    let convergence = Convergence::of_iteration(iterations, restarts, gap_rms, penetration, tol);
    Ok(solution(surface, p0, p, g, convergence))
}

/// The conjugate-gradient coefficient β = gz / g_old (Fletcher–Reeves, preconditioned) and the
/// step's numerator Σ_c g·t = gz + β·gt of the new direction t = (z − z̄) + β t, and whether the
/// directions restart from the preconditioned gradient (β = 0): when `conjugate` is false (the
/// first step, or a large move of the contact set, which leaves the old direction conjugate to
/// nothing) or when the new direction would not descend on the new contact set.
fn coefficient(gz: f64, g_old: f64, gt: f64, conjugate: bool) -> (f64, f64, bool) {
    let beta = if conjugate && g_old > 0.0 {
        gz / g_old
    } else {
        0.0
    };
    let num = gz + beta * gt;
    if beta != 0.0 && num <= 0.0 {
        (0.0, gz, true)
    } else {
        (beta, num, !conjugate)
    }
}

/// The conjugate-gradient step's denominator Σ_c (r − r̄) t = Σ_c r (t − t̄) over the contact
/// set (p > 0), in which the rigid-shift part of r = K t drops out; an error if it is not > 0.
fn step_denominator(
    what: &'static str,
    r: &[f64],
    t: &[f64],
    p: &[f64],
    tbar: f64,
    iterations: usize,
) -> Result<f64, Error> {
    let den = sum(
        &chunked_ref(r, |o, rc| {
            let mut den = 0.0;
            for (ri, (ti, pi)) in rc.iter().zip(t[o..].iter().zip(&p[o..])) {
                if *pi > 0.0 {
                    den += ri * (ti - tbar);
                }
            }
            [den]
        }),
        0,
    );
    positive_denominator(what, den, iterations)
}

/// `den` if the conjugate-gradient step's denominator is > 0, else the error naming `what`.
fn positive_denominator(what: &'static str, den: f64, iterations: usize) -> Result<f64, Error> {
    if den.is_nan() || den <= 0.0 {
        return Err(Error::Numerical {
            what,
            detail: format!(
                "conjugate-gradient step lost positivity at iteration {iterations} \
                 (is the compliance positive?)"
            ),
        });
    }
    Ok(den)
}

/// g ← u − h − ḡ with ḡ the mean of u − h on the contact set (p > 0); returns Σ_c g², the
/// largest penetration −g outside the contact set and the number of contact points (≥ 1).
fn measure_gap(g: &mut [f64], u: &[f64], h: &[f64], p: &[f64]) -> (f64, f64, f64) {
    let parts = chunked(g, |o, gc| {
        let (mut s, mut k) = (0.0, 0.0);
        for ((gi, ui), (hi, pi)) in gc.iter_mut().zip(&u[o..]).zip(h[o..].iter().zip(&p[o..])) {
            *gi = ui - hi;
            if *pi > 0.0 {
                s += *gi;
                k += 1.0;
            }
        }
        [s, k]
    });
    let (sum_c, n_c) = (sum(&parts, 0), sum(&parts, 1));
    let n_c = n_c.max(1.0);
    let gbar = sum_c / n_c;
    let parts = chunked(g, |o, gc| {
        let (mut g2, mut pen) = (0.0, 0.0f64);
        for (gi, pi) in gc.iter_mut().zip(&p[o..]) {
            *gi -= gbar;
            if *pi > 0.0 {
                g2 += *gi * *gi;
            } else {
                pen = pen.max(-*gi);
            }
        }
        [g2, pen]
    });
    let (g2, pen) = (sum(&parts, 0), max(&parts, 1));
    (g2, pen, n_c)
}

/// t ← g + β t on the contact set (0 elsewhere); returns Σ_c g·t and Σ_c t.
fn direction(t: &mut [f64], g: &[f64], p: &[f64], beta: f64) -> (f64, f64) {
    let parts = chunked(t, |o, tc| {
        let (mut num, mut sum_t) = (0.0, 0.0);
        for (ti, (gi, pi)) in tc.iter_mut().zip(g[o..].iter().zip(&p[o..])) {
            if *pi > 0.0 {
                *ti = gi + beta * *ti;
                num += gi * *ti;
                sum_t += *ti;
            } else {
                *ti = 0.0;
            }
        }
        [num, sum_t]
    });
    (sum(&parts, 0), sum(&parts, 1))
}

/// Changed points (index, change) of one projection step.
type Changes = Vec<(usize, f64)>;

/// p ← ps·p − step·t on the contact set, projected to p ≥ 0, with penetrating points (g < 0)
/// re-admitted at −readmit·g; returns Σ p and, if there are at most [`SPARSE_MAX`], the points
/// clamped or re-admitted with their change beyond the linear update ps·p − step·t (t is 0 off
/// the contact set), in index order.
fn project(
    p: &mut [f64],
    ps: f64,
    t: &[f64],
    g: &[f64],
    step: f64,
    readmit: f64,
) -> (f64, Option<Changes>) {
    let (total, _, changes) = passes::project(p, None, (ps, step, readmit), t, g, 0.0);
    (total, changes)
}

/// A periodic grid's influence matrix, given by its first column `green` (the response at every
/// pixel to a unit pressure at pixel 0; column j is that field shifted to pixel j).
struct Field<'a> {
    nx: usize,
    ny: usize,
    green: &'a [f64],
}

impl Field<'_> {
    /// Row y of u ← u + Σ_j δ_j G_j for the point changes (j, δ_j).
    fn add_columns(&self, y: usize, urow: &mut [f64], changes: &[(usize, f64)]) {
        let (nx, ny, green) = (self.nx, self.ny, self.green);
        for &(j, delta) in changes {
            let (xj, yj) = (j % nx, j / nx);
            let grow = &green[((y + ny - yj) % ny) * nx..][..nx];
            // u(x) += δ G(x − xj): x ≥ xj reads G from 0, x < xj wraps to nx − xj.
            let (head, tail) = urow.split_at_mut(xj);
            for (ui, gi) in tail.iter_mut().zip(&grow[..nx - xj]) {
                *ui += delta * gi;
            }
            for (ui, gi) in head.iter_mut().zip(&grow[nx - xj..]) {
                *ui += delta * gi;
            }
        }
    }
}

/// The solution's statistics from the converged pressure and gap.
fn solution(
    surface: &Surface,
    p0: f64,
    p: Vec<f64>,
    g: Vec<f64>,
    convergence: Convergence,
) -> BemSolution {
    let (nx, ny) = (surface.nx, surface.ny);
    let n = nx * ny;
    let (tol, status) = (convergence.tolerance, convergence.status);
    let in_contact: Vec<f64> = p.iter().copied().filter(|&v| v > 0.0).collect();
    let n_c = in_contact.len();
    let near = g
        .iter()
        .zip(&p)
        .filter(|&(&gi, &pi)| pi == 0.0 && gi < tol)
        .count();
    let nf = n as f64;
    let area_fraction = Estimate::new(n_c as f64 / nf, (near as f64 / nf).max(EPS), status);
    let mean_p = p.iter().sum::<f64>() / nf;
    let sigma_rms_top = (p.iter().map(|v| (v - p0) * (v - p0)).sum::<f64>() / nf).sqrt();
    BemSolution {
        nx,
        ny,
        dx: surface.dx,
        dy: surface.dy,
        p0,
        h_rms: surface.h_rms(),
        contact_pressure: FieldStats::of(&in_contact),
        pressure: p,
        gap: g,
        area_fraction,
        sigma_rms_top,
        convergence: Convergence {
            load_error: (mean_p - p0).abs() / p0,
            ..convergence
        },
        boundary: Boundary::Periodic,
    }
}

/// Elements per parallel task of the pointwise passes.
const PAR_CHUNK: usize = 1 << 14;

/// Apply `f(offset, chunk)` to consecutive chunks of `data` in parallel; returns the per-chunk
/// results in chunk order (combined with [`sum`] or [`max`], so the totals do not depend on
/// the thread count or scheduling).
fn chunked<const K: usize>(
    data: &mut [f64],
    f: impl Fn(usize, &mut [f64]) -> [f64; K] + Sync,
) -> Vec<[f64; K]> {
    data.par_chunks_mut(PAR_CHUNK)
        .enumerate()
        .map(|(c, chunk)| f(c * PAR_CHUNK, chunk))
        .collect()
}

/// Read-only version of [`chunked`].
fn chunked_ref<const K: usize>(
    data: &[f64],
    f: impl Fn(usize, &[f64]) -> [f64; K] + Sync,
) -> Vec<[f64; K]> {
    data.par_chunks(PAR_CHUNK)
        .enumerate()
        .map(|(c, chunk)| f(c * PAR_CHUNK, chunk))
        .collect()
}

/// Sum of entry `i` of the per-chunk results.
fn sum<const K: usize>(parts: &[[f64; K]], i: usize) -> f64 {
    parts.iter().map(|p| p[i]).sum()
}

/// Maximum of entry `i` of the per-chunk results.
fn max<const K: usize>(parts: &[[f64; K]], i: usize) -> f64 {
    parts.iter().map(|p| p[i]).fold(f64::NEG_INFINITY, f64::max)
}

/// The compliance on the (transposed half-) spectrum grid, including the 1/N of the inverse
/// FFT; the q = 0 entry is 0 (the mean is fixed by the load, see the module docs).
fn kernel_grid<K>(surface: &Surface, compliance: &K) -> Result<pool::Buf<f64>, Error>
where
    K: Fn(f64) -> f64 + Sync,
{
    let (nx, ny) = (surface.nx, surface.ny);
    let (qx, qy) = wavenumbers(nx, ny, surface.dx, surface.dy);
    let inv_n = 1.0 / (nx * ny) as f64;
    let mut kernel = pool::F64.take((nx / 2 + 1) * ny, 0.0);
    kernel
        .par_chunks_mut(ny)
        .enumerate()
        .try_for_each(|(kx, col)| {
            // qy at ky and ny − ky are opposite (exactly: the same magnitude is rounded), so
            // |q| and the compliance are the same: evaluated once, for ky ≤ ny/2.
            let (low, high) = col.split_at_mut(ny / 2 + 1);
            for (ky, k) in low.iter_mut().enumerate() {
                if kx == 0 && ky == 0 {
                    continue;
                }
                let q = qx[kx].hypot(qy[ky]);
                let c = compliance(q);
                if !(c.is_finite() && c > 0.0) {
                    return Err(Error::Numerical {
                        what: "surface compliance",
                        detail: format!("{c} at q = {q:e} 1/m (expected finite and > 0)"),
                    });
                }
                *k = c * inv_n;
            }
            for (i, k) in high.iter_mut().enumerate() {
                *k = low[ny - (ny / 2 + 1 + i)];
            }
            Ok(())
        })?;
    Ok(kernel)
}

/// Interface fields of a solved contact on the layered solid `stack`.
pub fn interface_fields(solution: &BemSolution, stack: &Stack) -> Result<InterfaceFields, Error> {
    check_stack(stack)?;
    let d = stack.thickness;
    let layers = stack.layers;
    interface_fields_with(solution, |q| {
        let r = layers.response(q * d);
        (r.f, r.g)
    })
}

/// Interface fields with arbitrary transfer functions `transfer(q) = (f, g)`: normal stress and
/// shear amplitude at z = d per unit surface pressure of a mode of wavenumber q > 0 (the q = 0
/// mode passes unchanged to the normal stress, f(0) = 1, and carries no shear).
pub fn interface_fields_with<T>(
    solution: &BemSolution,
    transfer: T,
) -> Result<InterfaceFields, Error>
where
    T: Fn(f64) -> (f64, f64) + Sync,
{
    if solution.boundary == Boundary::Free {
        return free::interface_fields_with(solution, transfer);
    }
    let (nx, ny) = (solution.nx, solution.ny);
    let n = nx * ny;
    let nxc = nx / 2 + 1;
    let (qx, qy) = wavenumbers(nx, ny, solution.dx, solution.dy);
    // (f, g, |q|) at every half-spectrum wavevector; as in `kernel_grid`, ky and ny − ky have the
    // same |q|, so the transfer functions are evaluated for ky ≤ ny/2 and copied.
    let mut fg = vec![(0.0, 0.0, 0.0); nxc * ny];
    fg.par_chunks_mut(ny)
        .enumerate()
        .try_for_each(|(kx, col)| {
            let (low, high) = col.split_at_mut(ny / 2 + 1);
            for (ky, v) in low.iter_mut().enumerate() {
                if kx == 0 && ky == 0 {
                    *v = (1.0, 0.0, 0.0);
                    continue;
                }
                let q = qx[kx].hypot(qy[ky]);
                let (f, g) = transfer(q);
                if !(f.is_finite() && g.is_finite()) {
                    return Err(Error::Numerical {
                        what: "interface transfer functions",
                        detail: format!("f = {f}, g = {g} at q = {q:e} 1/m"),
                    });
                }
                *v = (f, g, q);
            }
            for (i, v) in high.iter_mut().enumerate() {
                *v = low[ny - (ny / 2 + 1 + i)];
            }
            Ok(())
        })?;
    let mut plan = Fft2::new(nx, ny);
    let inv_n = 1.0 / n as f64;
    // Odd (derivative-like) operators cannot be represented on a Nyquist mode of a real field:
    // the shear's component along an axis is set to zero on that axis's Nyquist wavenumber.
    let nyq_x = nx.is_multiple_of(2).then_some(nx / 2);
    let nyq_y = ny.is_multiple_of(2).then_some(ny / 2);
    let p = &solution.pressure;
    let mut normal = vec![0.0; n];
    plan.filter(p, &mut normal, |kx, col| {
        for (c, (f, _, _)) in col.iter_mut().zip(&fg[kx * ny..(kx + 1) * ny]) {
            *c *= f * inv_n;
        }
    });
    let mut shear_x = vec![0.0; n];
    plan.filter(p, &mut shear_x, |kx, col| {
        for (c, (_, g, q)) in col.iter_mut().zip(&fg[kx * ny..(kx + 1) * ny]) {
            *c *= if *q == 0.0 || Some(kx) == nyq_x {
                Complex64::new(0.0, 0.0)
            } else {
                Complex64::new(0.0, g * qx[kx] / q * inv_n)
            };
        }
    });
    let mut shear_y = vec![0.0; n];
    plan.filter(p, &mut shear_y, |kx, col| {
        for (ky, (c, (_, g, q))) in col.iter_mut().zip(&fg[kx * ny..(kx + 1) * ny]).enumerate() {
            *c *= if *q == 0.0 || Some(ky) == nyq_y {
                Complex64::new(0.0, 0.0)
            } else {
                Complex64::new(0.0, g * qy[ky] / q * inv_n)
            };
        }
    });
    let mut magnitude = pool::F64.take(n, 0.0);
    magnitude
        .par_iter_mut()
        .zip(shear_x.par_iter().zip(shear_y.par_iter()))
        .for_each(|(m, (a, b))| *m = a.hypot(*b));
    Ok(InterfaceFields {
        normal_stats: FieldStats::of(&normal),
        shear_stats: FieldStats::of(&magnitude),
        normal,
        shear_x,
        shear_y,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn field_stats_nearest_rank_quantiles() {
        // 1..=1000: the nearest-rank quantile at P is the ⌈P·n⌉-th value.
        let v: Vec<f64> = (1..=1000).rev().map(f64::from).collect();
        let s = FieldStats::of(&v);
        assert_eq!(s.samples, 1000);
        assert_eq!(s.quantile(0.5), Some(500.0));
        assert_eq!(s.quantile(0.9), Some(900.0));
        assert_eq!(s.quantile(0.99), Some(990.0));
        assert_eq!(s.quantile(0.999), Some(999.0));
        assert_eq!(s.max, 1000.0);
        assert!((s.mean - 500.5).abs() < 1e-12);
        // Variance of 1..n is (n² − 1)/12.
        assert!((s.rms_dev - ((1e6 - 1.0) / 12.0f64).sqrt()).abs() < 1e-9);
        assert!(FieldStats::of(&[]).mean.is_nan());
    }

    #[test]
    fn field_stats_quantiles_are_the_sorted_samples() {
        // Ties, signed zeros and ranks that coincide (n = 7: 0.99 and 0.999 both give rank 7)
        // against the nearest-rank values of a full sort.
        for n in [1, 2, 7, 1000, 4099] {
            let v: Vec<f64> = (0..n)
                .map(|i| match (i * 7919) % 13 {
                    0 => 0.0,
                    1 => -0.0,
                    k => ((i * 104_729) % 97) as f64 - 40.0 + k as f64,
                })
                .collect();
            let mut sorted = v.clone();
            sorted.sort_by(f64::total_cmp);
            let s = FieldStats::of(&v);
            for q in &s.quantiles {
                let rank = ((q.prob * n as f64).ceil() as usize).clamp(1, n);
                assert_eq!(q.value.to_bits(), sorted[rank - 1].to_bits(), "n = {n}");
            }
            assert_eq!(s.max.to_bits(), sorted[n - 1].to_bits(), "n = {n}");
        }
    }

    #[test]
    fn surface_rejects_bad_input_and_measures_a_sinusoid() {
        assert!(Surface::new(vec![0.0; 5], 2, 2, 1.0, 1.0).is_err());
        assert!(Surface::new(vec![0.0; 4], 2, 2, 0.0, 1.0).is_err());
        assert!(Surface::new(vec![0.0, f64::NAN, 0.0, 0.0], 2, 2, 1.0, 1.0).is_err());
        // h = a cos(2π·3x/L) sin(2π·2y/L): h_rms = a/2, slope² = a²(q1² + q2²)/4.
        let (n, l, a) = (24, 2.0, 0.1);
        let h = (0..n * n)
            .map(|i| {
                let (x, y) = ((i % n) as f64 / n as f64, (i / n) as f64 / n as f64);
                a * (2.0 * PI * 3.0 * x).cos() * (2.0 * PI * 2.0 * y).sin()
            })
            .collect();
        let s = Surface::new(h, n, n, l / n as f64, l / n as f64).unwrap();
        assert!((s.h_rms() - a / 2.0).abs() < 1e-15);
        let (q1, q2) = (2.0 * PI * 3.0 / l, 2.0 * PI * 2.0 / l);
        let want = a * ((q1 * q1 + q2 * q2) / 4.0).sqrt();
        assert!((s.rms_slope() - want).abs() < 1e-13 * want);
    }

    #[test]
    fn sparse_update_matches_the_convolution() {
        // K(scale·(p − step·t + δ)) by FFT against the update of K p with K t and the columns
        // of the changed points (corners and wrap-around included).
        let (nx, ny) = (12, 10);
        let n = nx * ny;
        let s = Surface::new(vec![0.0; n], nx, ny, 1e-6, 2e-6).unwrap();
        let kernel = kernel_grid(&s, &|q: f64| 2.0 / q).unwrap();
        let mut plan = Fft2::new(nx, ny);
        let conv = |plan: &mut Fft2, x: &[f64], out: &mut [f64]| {
            plan.filter(x, out, |kx, col| {
                for (c, k) in col.iter_mut().zip(&kernel[kx * ny..(kx + 1) * ny]) {
                    *c *= *k;
                }
            })
        };
        let field = |i: usize| ((i * 7919) % 101) as f64 / 50.0;
        let p: Vec<f64> = (0..n).map(field).collect();
        let t: Vec<f64> = (0..n).map(|i| field(i + 13) - 1.0).collect();
        let mut unit = vec![0.0; n];
        unit[0] = 1.0;
        let (mut green, mut u, mut r) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        conv(&mut plan, &unit, &mut green);
        conv(&mut plan, &p, &mut u);
        conv(&mut plan, &t, &mut r);
        let (step, scale) = (0.3, 1.7);
        let changes = [(0, 0.4), (5 * nx + 7, 2.0), (n - 1, -1.1)];
        let green_field = Field {
            nx,
            ny,
            green: &green,
        };
        // The update works on graw = u − h; its gap statistics are those of the result.
        let h: Vec<f64> = (0..n).map(|i| field(i + 29) * 1e-3).collect();
        let contact: Vec<bool> = p.iter().map(|&v| v > 0.5).collect();
        let mut graw: Vec<f64> = u.iter().zip(&h).map(|(a, b)| a - b).collect();
        let rows = passes::update(
            &green_field,
            &mut graw,
            (&h, &r, &t),
            &contact,
            (step, scale),
            &changes,
        );
        for (y, row) in rows.iter().enumerate() {
            let o = y * nx;
            let want = passes::gap_row(&graw[o..o + nx], &contact[o..o + nx], &t[o..o + nx]);
            assert_eq!(row, &want);
        }
        let u: Vec<f64> = graw.iter().zip(&h).map(|(a, b)| a + b).collect();
        let mut q: Vec<f64> = p.iter().zip(&t).map(|(a, b)| a - step * b).collect();
        for &(j, d) in &changes {
            q[j] += d;
        }
        q.iter_mut().for_each(|v| *v *= scale);
        let mut want = vec![0.0; n];
        conv(&mut plan, &q, &mut want);
        let peak = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (a, b) in u.iter().zip(&want) {
            assert!((a - b).abs() < 1e-13 * peak, "{a} vs {b}");
        }
    }

    #[test]
    fn kernel_grid_is_the_compliance_at_every_wavevector() {
        // Odd and even sides: every entry is the compliance at its own |q| (times 1/N), bit for
        // bit, the mirrored half of each column included.
        for (nx, ny) in [(6, 5), (5, 8), (4, 1), (3, 2)] {
            let s = Surface::new(vec![0.0; nx * ny], nx, ny, 1e-6, 3e-6).unwrap();
            let compliance = |q: f64| 2.0 / q + 1e-9 * q.sqrt();
            let kernel = kernel_grid(&s, &compliance).unwrap();
            let (qx, qy) = wavenumbers(nx, ny, s.dx, s.dy);
            let inv_n = 1.0 / (nx * ny) as f64;
            for kx in 0..nx / 2 + 1 {
                for ky in 0..ny {
                    let want = if kx == 0 && ky == 0 {
                        0.0
                    } else {
                        compliance(qx[kx].hypot(qy[ky])) * inv_n
                    };
                    assert_eq!(kernel[kx * ny + ky].to_bits(), want.to_bits(), "{nx}x{ny}");
                }
            }
        }
    }

    #[test]
    fn a_kernel_spanning_eight_decades_is_solved_in_double_precision() {
        // Full contact on h = a cos(2π x/L) under a compliance 1e-8 of the half-space's at
        // |q| < 1.5 q1 (the surface's mode q1 = 2π/L among them) and the half-space's above: in
        // single precision the rounding of the other modes (≈ 1e-7 of a direction, amplified
        // 1e8 in K t) would swamp the steps (14 iterations); in double precision (rounding
        // amplified to ≈ 1e-8) the first step solves it and the second confirms, at the exact
        // pressure p0 + (a/K(q1)) cos(2π x/L).
        let (n, dx, a, e_star) = (32, 1e-6, 1e-9, 1e6);
        let q1 = 2.0 * PI / (n as f64 * dx);
        let phase = |i: usize| 2.0 * PI * (i % n) as f64 / n as f64;
        let h = (0..n * n).map(|i| a * phase(i).cos()).collect();
        let s = Surface::new(h, n, n, dx, dx).unwrap();
        let k = move |q: f64| 2.0 / (q * e_star) * if q < 1.5 * q1 { 1e-8 } else { 1.0 };
        let p1 = a / k(q1);
        let sol = solve_with_compliance(&s, k, 2.0 * p1, &BemSettings::default()).unwrap();
        assert_eq!(sol.convergence.status, Termination::Converged);
        assert!(sol.convergence.iterations <= 2, "{:?}", sol.convergence);
        for (i, p) in sol.pressure.iter().enumerate() {
            let exact = p1 * (2.0 + phase(i).cos());
            assert!((p - exact).abs() < 1e-7 * p1, "{i}: {p} vs {exact}");
        }
    }

    #[test]
    fn flat_surface_is_in_full_contact_at_the_nominal_pressure() {
        let s = Surface::new(vec![1e-6; 16], 4, 4, 1e-6, 1e-6).unwrap();
        let sol = solve_with_compliance(&s, |q| 2.0 / q, 5.0, &BemSettings::default()).unwrap();
        assert_eq!(sol.convergence.status, Termination::Converged);
        assert_eq!(sol.convergence.iterations, 0);
        assert!(sol.pressure.iter().all(|&p| p == 5.0));
        assert_eq!(sol.area_fraction.value, 1.0);
    }
}
