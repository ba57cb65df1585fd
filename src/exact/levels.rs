//! The exact minimum-thickness search from coarse to fine: the full non-monotone-safe search
//! ([`crate::check::min_thickness`]) runs once, on the coarsest copy of the map (every fourth
//! pixel, N/4, when that has at least [`MIN_COARSE_SIDE`] pixels a side; else every second,
//! N/2, when the map has at least 32; else the map), and each finer copy (N/2, then N) only re-locates the pass/fail crossing near the
//! next coarser one's, inheriting the scan of the level searched in full where the two agree.
//!
//! On a finer level:
//! 1. the first thickness is the next coarser d_min, shifted by the difference between the two
//!    coarser levels' d_min when there are two (the map's own d_min moves about as much again);
//!    its solve starts from the next coarser level's solved pressure at the nearest thickness,
//!    each pixel repeated 2 × 2;
//! 2. Newton steps on ln u against ln d (the slope the secant through the next coarser level's
//!    final bracket, then through this level's last two points) step across the crossing,
//!    aimed [`NARROW_OVERSHOOT`] times the tolerance beyond it so that they close a bracket,
//!    for at most [`NARROW_STEPS`] solves. They must stay inside the full search's last scan
//!    step (its first failing sample and the passing sample above it), where that search found
//!    a single crossing; a step outside it, a passing point below a failing one, or no bracket
//!    after those steps falls back to the full search on this level;
//! 3. the bracket is refined by ITP ([`crate::check::itp`]) until its half-width in ln d is
//!    [`crate::check::D_MIN_RTOL`]'s or at most [`GRID_SHARE`] of the bracket's distance to
//!    the next coarser d_min, whichever is wider. On the map itself, the reported error of
//!    d_min adds the grid difference |d_min(N) − d_min(N/2)|, which is at least that distance:
//!    a bracket error below a quarter of it changes the total by less than a quarter, and
//!    refining further would spend solves on digits the grid does not hold;
//! 4. the scan is inherited only if η, the largest difference of ln u between this level and
//!    the level searched in full over this level's solves (that level's ln u interpolated
//!    linearly in ln d between its samples), could not turn any of its passing verdicts: with
//!    every utilisation allowed to be e^{[`LEVEL_SAFETY`]·η} times that level's, every scan
//!    sample above its first failing one (raised by the narrow-band guard's headroom
//!    [`crate::check::GUARD_RESOLVED`] when above [`crate::check::PEAK_GUARD`], what the guard
//!    leaves unresolved at a maximum) and the largest utilisation a widened step's interior can
//!    hold ([`crate::check::WIDE_STEPS`]: below/(level/√2) = 0.85) must stay at most 1.
//!    Checked after every solve of this level; otherwise this level gets the full search (its
//!    solves so far kept as warm starts), and the levels after it inherit its scan.
//!
//! A finer level can therefore not miss a failing band that the full search on it would find,
//! unless its utilisation differs from the scanned level's by more than e^{3η} somewhere away
//! from the crossing: the levels are the same surface, and η measures their difference where it
//! matters most, at the largest utilisations. This is an argument from the levels' agreement,
//! not a proof; a failing band that only the finest grid resolves would need the full search.

use super::min_thickness::Solve;
use crate::bem::Surface;
use crate::check::checker::scan_range;
use crate::check::itp::{Bracket, refine};
use crate::check::min_thickness::crossing_estimate;
use crate::check::{
    D_MIN_RTOL, GUARD_RESOLVED, MinThickness, PEAK_GUARD, Utilisation, WIDE_STEPS,
    search_min_thickness,
};
use crate::error::Error;

/// The smallest side (pixels) of a quarter-resolution level: on coarser grids the levels differ
/// too much for the scan to be inherited (on the bundled 128² map the 32² level's was not).
pub const MIN_COARSE_SIDE: usize = 128;
/// Solved pressure fields kept for warm starts (the newest; a search moves locally in ln d).
const WARM_KEEP: usize = 4;
/// The factor on η, the observed difference of ln u between two levels, when a coarser scan's
/// verdicts are inherited (Roache's two-grid safety factor).
pub const LEVEL_SAFETY: f64 = 3.0;
/// Newton steps a finer level takes to bracket the crossing before it falls back to the full
/// search.
pub const NARROW_STEPS: usize = 4;
/// How far beyond the Newton estimate a step aims, in units of the bracket tolerance.
pub const NARROW_OVERSHOOT: f64 = 1.0;
/// A finer level's bracket stops at this fraction of its distance to the coarser d_min.
pub const GRID_SHARE: f64 = 0.25;

/// One level's solves: the warm starts, the counts, and the samples (ln d, utilisation) in
/// evaluation order.
pub(crate) struct Solver<'f, 'a> {
    solve: &'f mut Solve<'a>,
    warm: Vec<(f64, Vec<f64>)>,
    /// The coarser level's pressure nearest the first thickness, each pixel repeated 2 × 2.
    seed: Option<Vec<f64>>,
    pub(crate) solves: usize,
    pub(crate) iterations: usize,
    pub(crate) samples: Vec<(f64, Utilisation)>,
}

impl<'f, 'a> Solver<'f, 'a> {
    pub(crate) fn new(solve: &'f mut Solve<'a>) -> Self {
        Self {
            solve,
            warm: Vec::new(),
            seed: None,
            solves: 0,
            iterations: 0,
            samples: Vec::new(),
        }
    }

    /// The utilisation at ln d = `x` on `surface`, warm-started from the nearest thickness
    /// solved before on this level (else from the seed).
    pub(crate) fn at(&mut self, surface: &Surface, x: f64) -> Result<Utilisation, Error> {
        let start = self
            .warm
            .iter()
            .min_by(|a, b| (a.0 - x).abs().total_cmp(&(b.0 - x).abs()))
            .map(|(_, p)| p.as_slice())
            .or(self.seed.as_deref());
        let (u, pressure, its) = (self.solve)(surface, x.exp(), start)?;
        self.solves += 1;
        self.iterations += its;
        if self.warm.len() == WARM_KEEP {
            self.warm.remove(0);
        }
        self.warm.push((x, pressure));
        self.samples.push((x, u));
        Ok(u)
    }

    /// Moves to the next finer level (`coarse` the level just searched, of which the next is
    /// twice the resolution), seeding its first solve near ln d = `x` when given.
    fn finer(&mut self, coarse: &Surface, x: Option<f64>) {
        self.seed = x.and_then(|x| {
            self.warm
                .iter()
                .min_by(|a, b| (a.0 - x).abs().total_cmp(&(b.0 - x).abs()))
                .map(|(_, p)| repeat_pixels(p, coarse.nx, coarse.ny))
        });
        self.warm.clear();
        self.samples.clear();
    }
}

/// A field of nx × ny pixels on the grid of twice the resolution, each pixel repeated 2 × 2
/// (the coarser map holds every second pixel of the finer one, [`crate::verify::half`]).
fn repeat_pixels(p: &[f64], nx: usize, ny: usize) -> Vec<f64> {
    (0..2 * ny)
        .flat_map(|iy| (0..2 * nx).map(move |ix| p[(iy / 2) * nx + ix / 2]))
        .collect()
}

/// The full search on one level ([`crate::check::search_min_thickness`]).
pub(crate) fn full(surface: &Surface, solver: &mut Solver<'_, '_>) -> Result<MinThickness, Error> {
    let (lo, hi) = scan_range(surface.q_low(), q_grid_max(surface));
    search_min_thickness(lo, hi, |d| solver.at(surface, d.ln()))
}

/// The largest wavenumber on the grid, |(π/dx, π/dy)| (1/m).
fn q_grid_max(surface: &Surface) -> f64 {
    (std::f64::consts::PI / surface.dx).hypot(std::f64::consts::PI / surface.dy)
}

/// A level searched: its result and its samples.
pub(crate) struct Searched {
    pub(crate) search: MinThickness,
    samples: Vec<(f64, Utilisation)>,
}

/// The searches on `levels` (coarse to fine, each twice the resolution of the one before):
/// the full search on the first, the narrow one on the others where it can be inherited
/// (module docs). Returns each level's search.
pub(crate) fn search_levels(
    levels: &[&Surface],
    solver: &mut Solver<'_, '_>,
) -> Result<Vec<MinThickness>, Error> {
    let mut done: Vec<Searched> = Vec::new();
    // The last level searched in full: the scan the finer levels inherit.
    let mut scanned = 0;
    for (i, &surface) in levels.iter().enumerate() {
        let search = match done.last() {
            None => full(surface, solver)?,
            Some(coarse) => {
                let before = done.len().checked_sub(2).map(|j| &done[j].search);
                let guess = first_guess(&coarse.search, before);
                solver.finer(levels[i - 1], guess);
                let levels = (&done[scanned], coarse);
                match guess
                    .map(|x| narrow(surface, solver, levels, x))
                    .transpose()?
                {
                    Some(Some(m)) => m,
                    _ => {
                        // The narrow search's solves stay as warm starts, not as scan samples.
                        solver.samples.clear();
                        scanned = i;
                        full(surface, solver)?
                    }
                }
            }
        };
        done.push(Searched {
            search,
            samples: std::mem::take(&mut solver.samples),
        });
    }
    Ok(done.into_iter().map(|s| s.search).collect())
}

/// The first thickness (ln d) of a finer level: the coarser d_min, shifted by its difference to
/// the level before when there is one; `None` when the coarser search found no crossing.
fn first_guess(coarse: &MinThickness, before: Option<&MinThickness>) -> Option<f64> {
    if coarse.all_pass_to_floor {
        return None;
    }
    let x = coarse.thickness?.value.ln();
    let shift = before
        .and_then(|b| b.thickness.filter(|_| !b.all_pass_to_floor))
        .map_or(0.0, |b| x - b.value.ln());
    Some(x + shift)
}

/// A full search's last scan step [x_fail, x_pass] (ln d) and the largest utilisation its scan
/// leaves possible above it (module docs, step 4).
struct Scan {
    x_fail: f64,
    x_pass: f64,
    worst: f64,
}

impl Scan {
    /// The scan of a full search's samples: the first failing sample, the passing ones
    /// evaluated before it (after a failing start, the bulk bound evaluated next).
    fn of(samples: &[(f64, Utilisation)]) -> Option<Self> {
        let k = samples.iter().position(|s| s.1.value > 1.0)?;
        let x_fail = samples[k].0;
        let scan = if k == 0 {
            samples.get(1..2)?
        } else {
            &samples[..k]
        };
        let x_pass = scan
            .iter()
            .map(|s| s.0)
            .filter(|&x| x > x_fail)
            .min_by(f64::total_cmp)?;
        let wide = WIDE_STEPS
            .iter()
            .map(|w| w.below * std::f64::consts::SQRT_2 / w.level)
            .fold(0.0, f64::max);
        let worst = scan
            .iter()
            .map(|s| match s.1.value {
                u if u > PEAK_GUARD => u + GUARD_RESOLVED * (1.0 - u),
                u => u,
            })
            .fold(wide, f64::max);
        Some(Self {
            x_fail,
            x_pass,
            worst,
        })
    }
}

/// The slope of ln u against ln d at a level's crossing: the secant through its final
/// bracket's ends, the nearest samples on either side of its d_min e^`xc`.
fn crossing_slope(samples: &[(f64, Utilisation)], xc: f64) -> Option<f64> {
    let end = |fails: bool| {
        samples
            .iter()
            .filter(|s| (s.1.value > 1.0) == fails && (s.0 < xc) == fails)
            .min_by(|a, b| (a.0 - xc).abs().total_cmp(&(b.0 - xc).abs()))
            .map(|s| (s.0, s.1.value.ln()))
    };
    let (f, p) = (end(true)?, end(false)?);
    let slope = (p.1 - f.1) / (p.0 - f.0);
    (slope < 0.0 && slope.is_finite()).then_some(slope)
}

impl Scan {
    /// Whether the scan's passing verdicts hold on a level whose ln u differs from the scanned
    /// level's by at most `eta` (module docs, step 4).
    fn inherits(&self, eta: f64) -> bool {
        self.worst * (LEVEL_SAFETY * eta).exp() <= 1.0
    }
}

/// |ln u − ln u of `samples`| at the sample `s` of another level (infinite where either
/// utilisation is 0 or `samples` do not reach it).
fn differs(samples: &[(f64, Utilisation)], s: (f64, Utilisation)) -> f64 {
    match interpolate(samples, s.0) {
        Some(y) if s.1.value > 0.0 => (s.1.value.ln() - y).abs(),
        _ => f64::INFINITY,
    }
}

/// ln u of `samples` at `x`, linear in ln d between the nearest samples on either side.
fn interpolate(samples: &[(f64, Utilisation)], x: f64) -> Option<f64> {
    let finite = || {
        samples
            .iter()
            .filter(|s| s.1.value > 0.0)
            .map(|s| (s.0, s.1.value.ln()))
    };
    let below = finite()
        .filter(|s| s.0 <= x)
        .max_by(|a, b| a.0.total_cmp(&b.0))?;
    let above = finite()
        .filter(|s| s.0 >= x)
        .min_by(|a, b| a.0.total_cmp(&b.0))?;
    if above.0 == below.0 {
        return Some(below.1);
    }
    Some(below.1 + (above.1 - below.1) * (x - below.0) / (above.0 - below.0))
}

/// The search on a finer level near the crossing of the next coarser level, from ln d = `x0`
/// (module docs); `levels` are the last level searched in full, whose scan is inherited, and
/// the next coarser one. `None` when the scan cannot be inherited.
fn narrow(
    surface: &Surface,
    solver: &mut Solver<'_, '_>,
    (scanned, coarse): (&Searched, &Searched),
    x0: f64,
) -> Result<Option<MinThickness>, Error> {
    let Some(xc) = coarse.search.thickness.map(|d| d.value.ln()) else {
        return Ok(None);
    };
    let (Some(scan), Some(mut slope)) = (
        Scan::of(&scanned.samples),
        crossing_slope(&coarse.samples, xc),
    ) else {
        return Ok(None);
    };
    let eps = 0.5 * D_MIN_RTOL.ln_1p();
    let mut x = x0.clamp(scan.x_fail, scan.x_pass);
    // The thickest failing point and the thinnest passing one, as (ln d, ln u).
    let mut fail: Option<(f64, f64)> = None;
    let mut pass: Option<(f64, f64)> = None;
    let mut governing = None;
    for step in 0..NARROW_STEPS {
        let u = solver.at(surface, x)?;
        let y = u.value.ln();
        if !scan.inherits(differs(&scanned.samples, (x, u))) {
            return Ok(None);
        }
        if u.value > 1.0 {
            governing = u.kind;
            fail = Some(fail.map_or((x, y), |f| if x > f.0 { (x, y) } else { f }));
        } else {
            pass = Some(pass.map_or((x, y), |p| if x < p.0 { (x, y) } else { p }));
        }
        match (fail, pass) {
            (Some(f), Some(p)) if f.0 >= p.0 => return Ok(None),
            (Some(_), Some(_)) => break,
            _ if step + 1 == NARROW_STEPS => return Ok(None),
            _ => {}
        }
        if let [.., a, b] = solver.samples[..] {
            let s = (b.1.value.ln() - a.1.value.ln()) / (b.0 - a.0);
            if s < 0.0 && s.is_finite() {
                slope = s;
            }
        }
        let aim = NARROW_OVERSHOOT * eps;
        x -= y / slope - if y > 0.0 { aim } else { -aim };
        if !(scan.x_fail..=scan.x_pass).contains(&x) {
            return Ok(None);
        }
    }
    let (Some(f), Some(p)) = (fail, pass) else {
        return Ok(None);
    };
    let gap = (f.0 - xc).max(xc - p.0).max(0.0);
    let above = solver
        .samples
        .iter()
        .filter(|s| s.0 > p.0 && s.1.value > 0.0)
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|s| (s.0, s.1.value.ln()));
    let b = refine(
        Bracket {
            x_fail: f.0,
            y_fail: f.1,
            x_pass: p.0,
            y_pass: p.1,
        },
        above,
        eps.max(GRID_SHARE * gap),
        |x| {
            let u = solver.at(surface, x)?;
            if u.value > 1.0 {
                governing = u.kind;
            }
            Ok(u.value.ln())
        },
    )?;
    let eta = solver
        .samples
        .iter()
        .map(|&s| differs(&scanned.samples, s))
        .fold(0.0, f64::max);
    if !scan.inherits(eta) {
        return Ok(None);
    }
    let u_rel_err = solver
        .samples
        .iter()
        .map(|s| s.1.rel_err)
        .fold(0.0, f64::max);
    let (lo, hi) = scan_range(surface.q_low(), q_grid_max(surface));
    Ok(Some(MinThickness {
        thickness: Some(crossing_estimate(&b, u_rel_err)),
        governing,
        floor: lo,
        bulk: hi,
        all_pass_to_floor: false,
        evaluations: solver.samples.len(),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::CheckKind;

    /// Flat surfaces of 64², 32² and 16² pixels with the same extent (the levels of a 64² map).
    fn levels() -> Vec<Surface> {
        [16, 32, 64]
            .iter()
            .map(|&n| Surface::new(vec![0.0; n * n], n, n, 64e-6 / n as f64, 64e-6 / n as f64))
            .collect::<Result<_, _>>()
            .unwrap()
    }

    /// A synthetic utilisation (d0/d)^1.3 with d0 = 1 µm on the coarser levels and `shift`·d0 on
    /// the 64² level, times `factor` there; counts the solves of each level.
    fn searches(shift: f64, factor: f64) -> (Vec<MinThickness>, MinThickness, usize) {
        let u = move |s: &Surface, d: f64| {
            let (d0, k) = if s.nx == 64 {
                (shift * 1e-6, factor)
            } else {
                (1e-6, 1.0)
            };
            k * (d0 / d).powf(1.3)
        };
        let mut solve = |s: &Surface, d: f64, _: Option<&[f64]>| {
            let util = Utilisation {
                value: u(s, d),
                rel_err: 0.0,
                kind: Some(CheckKind::BondShear),
            };
            Ok((util, vec![1.0; s.nx * s.ny], 1))
        };
        let surfaces = levels();
        let refs: Vec<&Surface> = surfaces.iter().collect();
        let mut solver = Solver::new(&mut solve);
        let m = search_levels(&refs, &mut solver).unwrap();
        let mut fine = Solver::new(&mut solve);
        let reference = full(&surfaces[2], &mut fine).unwrap();
        (m, reference, fine.solves)
    }

    /// Where the finer levels agree with the coarsest, they find the full search's crossing
    /// (within the two bracket errors) in a few solves each; the finest level's first solve
    /// is the coarser d_min shifted by the coarser levels' difference.
    #[test]
    fn levels_that_agree_find_the_full_search_crossing_in_few_solves() {
        let (m, reference, full_solves) = searches(1.004, 1.0);
        let (a, b) = (m[2].thickness.unwrap(), reference.thickness.unwrap());
        assert!((a.value - b.value).abs() <= a.err + b.err, "{a:?} vs {b:?}");
        assert!((a.value - 1.004e-6).abs() <= a.err, "{a:?}");
        assert!(m[1].evaluations <= 3 && m[2].evaluations <= 3, "{m:?}");
        assert!(full_solves >= 8, "{full_solves}");
        // Half a quarter of the distance to the coarser d_min: the bracket may be that wide.
        let gap = (1.004f64).ln() - (m[1].thickness.unwrap().value / 1e-6).ln();
        assert!(a.err <= 1.05 * (GRID_SHARE * gap).max(0.5 * D_MIN_RTOL) * a.value);
    }

    /// A finer level whose utilisation differs from the coarser one's by a factor 1.1 where it
    /// was solved (η = ln 1.1, e^{3η} = 1.33) could fail where the coarser scan passed with
    /// 0.85: it gets the full search, with the full search's answer.
    #[test]
    fn levels_that_differ_get_the_full_search() {
        let (m, reference, _) = searches(1.0, 1.1);
        assert_eq!(m[2].thickness, reference.thickness);
        assert_eq!(m[2].evaluations, reference.evaluations);
        // 1.003: η = 0.003, less than the 0.0052 of a d_min shifted by 0.4 % (the test above,
        // the same coarser levels), whose scan was inherited.
        let (m, reference, _) = searches(1.0, 1.003);
        let (a, b) = (m[2].thickness.unwrap(), reference.thickness.unwrap());
        assert!((a.value - b.value).abs() <= a.err + b.err, "{a:?} vs {b:?}");
        assert!(m[2].evaluations <= 4, "{m:?}");
    }

    #[test]
    fn repeated_pixels_fill_each_two_by_two_block() {
        let p = repeat_pixels(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], 3, 2);
        assert_eq!(
            p,
            [
                1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 5.0, 5.0,
                6.0, 6.0, 4.0, 4.0, 5.0, 5.0, 6.0, 6.0
            ]
        );
    }
}
