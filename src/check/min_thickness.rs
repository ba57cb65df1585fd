//! The minimum-thickness search: why scan, then refine.
//!
//! τ_rms(d) is not monotone: it rises as the film thins and falls to 0 as d → 0 (a vanishing film
//! has a frictionless top), so pass/fail in d can change more than once and a bisection on the
//! whole range can land inside a failing band. [`Checker::min_thickness`] therefore
//! 1. starts at q_L·d = [`SCAN_START_QD`] = 10 (q_L the spectrum's lowest wavenumber). Every
//!    mode of a thicker film has qd ≥ 10, where |f| and |g| only decrease with qd (|g| peaks at
//!    qd ≤ 2.1) and |S⁻² − 1| ≤ 1.8e-6 (test `thick_films_only_relax_beyond_the_scan_start`):
//!    the interface stresses fall as d grows and A/A0 moves by a few 1e-6 at most, so when
//!    u ≤ 1 − [`THICK_SLACK`] there, every thicker film passes. Otherwise the bulk bound
//!    d_hi = 50/q_L is evaluated too: f, g decay like (1 + qd)e^{−qd}, at most twice that on a
//!    stiff substrate, so at q_L·d = 50 the interface stresses are below 1e-19 of the surface
//!    ones and S(qd) = 1 to rounding: every thicker film behaves the same. If d_hi fails, no
//!    thickness passes;
//! 2. steps down in ln d and stops at the first failing thickness (the largest failing sample).
//!    Only the upper end of the failing region matters for d_min, so nothing thinner is
//!    evaluated. The base step is 1/[`POINTS_PER_DECADE`] of a decade; it is widened, to at
//!    most 0.75 decade while the utilisation u (value/limit) stays below 0.15 over the step, or
//!    0.5 decade below 0.3 ([`WIDE_STEPS`]), with u extrapolated log-linearly from the last two
//!    samples at a growth rate of ln u per unit of ln d of at least [`MIN_GROWTH`] (aimed at
//!    [`WIDE_AIM`] of the threshold). A widened step that lands above its threshold is redone
//!    with base steps (its sample is reused).
//!    A thick film's utilisation is flat (its interface stresses are exponentially small) and
//!    these steps cross it in a few evaluations instead of eight per decade. Why a failing band
//!    cannot hide inside a widened step whose ends are below its threshold: with P and S frozen,
//!    τ_rms² = Σ_q w_q g²(qd) with w_q ≥ 0, and |g| is unimodal in ln(qd), above a quarter of
//!    its maximum on a stretch at least 1.90 wide and above half of it on one at least 1.32
//!    wide (the narrowest pair: a ν = 0 film on a rigid substrate; test
//!    `wide_steps_are_narrower_than_the_shear_kernel`), more than the steps (1.73 and 1.15 in
//!    ln d). Any such superlevel set through a point d* is at least as wide, so for every mode
//!    one end of a step around d* sees |g| ≥ c·|g(q d*)| (c = 1/4, 1/2), and the larger end
//!    utilisation is at least c·u(d*)/√2 (0.177, 0.354): a failing point (u > 1) inside would
//!    put an end above the threshold (0.15, 0.3); test `few_mode_shear_bands_match_a_dense_scan`
//!    checks this on random spectra. The substrate-yield values go through |f|, monotone in qd,
//!    and through S (in P and G), which has at most one turn in qd (test
//!    `s_turns_at_most_once_and_f_never_rises`: 88 pairs from E0/E1 = 1e-8 to 1e8, ν 0 to 0.5;
//!    22 of them turn once, none twice);
//! 3. guards against a failing band narrower than the step: at every sampled local maximum of
//!    u above [`PEAK_GUARD`] it maximises u between the neighbouring samples by successive
//!    parabolic interpolation (golden-section steps where the parabola does not help) and treats
//!    the first failing point as a failing sample. It stops, after at least one evaluation, when
//!    the parabola through the best three points promises less than [`GUARD_RESOLVED`] of the
//!    remaining headroom 1 − u (a smooth maximum below 1 costs one or two evaluations);
//! 4. refines the pass/fail crossing in ln d until the bracket's relative width is at most
//!    [`D_MIN_RTOL`], by the ITP method (Oliveira & Takahashi 2020: a projection onto a shrinking
//!    interval around the midpoint; never more steps than bisection plus one) with inverse
//!    quadratic interpolation on ln u as its estimate (the scan sample above the bracket is its
//!    third point from the start). An estimate within δ of a bracket end is moved to 4δ from
//!    it, so that it lands across the crossing and closes the bracket: a smooth utilisation
//!    needs two or three steps. d_min is the bracket's geometric midpoint; its error is the
//!    distance to the bracket's upper end plus the shift of the crossing by the utilisation's
//!    own relative error, δu/|d ln u/d ln d|;
//! 5. stops at the floor d_lo = max(1 nm, min(1e-6/q_L, 1e-4/q_hi)): a film thinner than 1 nm
//!    is not a continuum, and when the floor is above 1 nm every mode of the spectrum has
//!    q·d ≤ 1e-4 there, the thin-film limit in which the interface stresses only fall further
//!    as d → 0 (τ ∝ g → q·d). When every sample down to d_lo passes, d_min is reported as d_lo
//!    with `all_pass_to_floor` set (and a warning naming the floor).
//!
//! ## Under sliding
//! With friction μ > 0 (the vector rule, [`crate::tail`]) the bond-shear value is the peak τ* of
//! |(m + X, Y)|, m = μp0 the same at every d, sx² = Σ_q w_q [g²/2 + μ² k_x(qd)] and
//! sy² = Σ_q w_q [g²/2 + μ² k_y(qd)] (k_x = ((g_t + h)/2)² + (g_t − h)²/8, k_y = (g_t − h)²/8,
//! `src/contact/sliding.rs`; the same w_q ≥ 0 as τ_rms², P and S frozen as in step 2), and
//! the interface σ_rms² gains μ² f_t²/2 per mode. Step 2's argument carries over with one more
//! factor. Proven:
//! - sy ≤ sx at every d: k_x = k_y + ((g_t + h)/2)² ≥ k_y, and the static halves are equal;
//! - P(|τ| > R) is nondecreasing in sy (given X, |τ| > R is |Y| > √(R² − (m + X)²)) and in m
//!   (given Y, d/dm P(|m + X| > r) = [φ((r − m)/sx) − φ((r + m)/sx)]/sx ≥ 0 as |r − m| ≤ r + m),
//!   so τ* is; with sy = 0 (the folded normal) it is nondecreasing in sx at every R ≥ m, and
//!   τ* > m (P(|τ| > m) ≥ P(X > 0) = ½ > ε); τ* is homogeneous of degree 1 in (m, sx, sy);
//! - hence, with T_f(m, s) the folded normal's peak and λ ≤ 1, T_f(m, λs) = λT_f(m/λ, s) ≥
//!   λT_f(m, s), and T_f(m, sx) ≤ τ*(m, sx, sy) ≤ τ*(m, sx, sx);
//! - if at an end d_i, sx_i ≥ (c/√2)·sx* (what a kernel with the superlevel property of step 2
//!   gives for one end), then τ*_i ≥ T_f(m, sx_i) ≥ (c/√2) T_f(m, sx*) ≥ (c/√2)/ρ(ε) · τ*(m,
//!   sx*, sy*), with ρ(ε) = sup over m of τ*(m, s, s)/T_f(m, s).
//!
//! Tested, not proven (`check::tests_sliding`, over q·d 1e-8 … 1e4 at 100 points per decade,
//! substrate/film modulus ratios 1e-8 … 1e8 every decade, ν 0, 0.25, 0.5 on both sides): every
//! step no longer than a widened step sees at one end at least the step's level of the largest
//! value inside, for |g| (to q·d = 700; worst 0.32 and 0.59), for √k_x (0.49 and 0.70; it
//! is not monotone) and for f_t (0.55 and 0.74); beyond
//! q·d = 10 k_x and f_t only fall (step 1); |f| only
//! falls ([`crate::layer`]'s test, as for the static search). ρ(ε) is attained at m = 0, where
//! it is √(−2 ln ε)/k_ε ([`crate::tail::anisotropy_spread`]: 1.075 at ε = 1e-6, 1.178 at 1e-2,
//! 1.30 at 0.1; m from 1e-3 to 1e3, ε from 1e-300 to 0.49). τ* is nondecreasing in sx at any
//! sy (step 1; m 0 … 100, sx/sy 1e-2 … 1e2). The normal-stress peak satisfies
//! peak(p0, λσ) ≥ λ peak(p0, σ) (p0/σ 1e-3 … 1e3, ε 1e-12 … 0.3).
//!
//! So a failing point inside a widened step puts one end above (c/√2)/ρ(ε), and the search
//! lowers each widened step's threshold to level/(√2 ρ(ε)) where that is below it
//! ([`search_min_thickness_spread`]): for ε ≤ 0.0101 (ρ ≤ 1.1785) the thresholds are unchanged;
//! above it they fall (0.135 and 0.27 at ε = 0.1), where the old ones could let a band through.
//! Without friction (either rule) the shear peak is proportional to τ_rms and ρ = 1. The
//! substrate-yield value under sliding goes through σ_rms² = Σ w_q (f² + μ² f_t²/2): |f| only
//! falls and f_t has the property above, so one end has σ_i ≥ (c/√2)σ* and its peak at least
//! (c/√2) of the failing one, without ρ.
//!
//! The search reads the vector peak at a thickness by one Newton step in φ = √(−2 ln P) from
//! L = min(limit, τ_hi) ([`crate::tail::ShearVector::peak_from`]), not by τ* itself. That read
//! is on the same side of the limit (u = 1) as τ*, but φ is not convex everywhere above τ*, so
//! it can land below τ*: by at most [`crate::tail::one_step_shortfall`] = 0.06/ln²ε of it when
//! sy ≤ sx, as here (measured over m/sx, sy/sx ≤ 1, every start and ε from 1e-300 to 0.49:
//! 1.2e-4 at ε = 1e-6, 1.2e-3 at 1e-2, 0.025 at 0.3, 0.064 at 0.49; test
//! `one_step_peaks_fall_short_of_the_peak_by_at_most_the_bound`). An end whose true
//! utilisation is just above a widened step's threshold could then read below it, and above
//! ε = 0.0101, where the thresholds are the bound itself, the step would be taken over a
//! failing band (test `one_step_reads_near_a_threshold_are_solved`, which constructs one).
//! So the search's reads are exact with respect to every level it compares with
//! (`decision_levels`: the widened steps' thresholds and [`PEAK_GUARD`]): where the one-step
//! read lies below a level t by less than the shortfall, read ≥ (1 − shortfall)·t, the true
//! utilisation might be above t and the peak is solved instead (`checker::read_vector_peak`);
//! below that, the true utilisation is below t. The start's comparison with 1 −
//! [`THICK_SLACK`] is left to the one-step read: from a level within 1e-5 of τ* it falls short
//! by at most 2.3e-11 (same test), far inside the slack's margin over the A/A0 drift of step 1.
//!
//! The friction floor. Under sliding the bond-shear peak never falls below the mean shear
//! m = μp0 (τ* > m, above), however thick the film: its utilisation is a floor u_f = m/limit,
//! the same at every d, plus an excess that grows as the film thins. Where the floor makes up
//! most of u, step 2's log-linear extrapolation of u itself sees a growth rate near 0 (so
//! [`MIN_GROWTH`]) and then a steep turn: on a measured PSD whose u sits at u_f = 0.05 for two
//! decades, a widened step lands above its threshold and is redone with base steps. So the
//! search is given the floor, and where u < 2u_f at both of the last two samples (and above
//! u_f) it extrapolates the excess u − u_f log-linearly instead, at the excess's growth rate
//! clamped to [[`MIN_GROWTH`], [`MAX_EXCESS_GROWTH`]], aiming u_f + excess at the step's
//! target (`scan_step`); elsewhere the plain rule holds. The floor only chooses step
//! lengths: every decision (a widened step's threshold, the guard, pass or fail) still
//! compares u itself, so the argument above holds whatever floor is given (test
//! `the_friction_floor_moves_no_crossing`).
//!
//! Each evaluation during the search requests only what the enabled checks need (bond-shear:
//! τ_rms; substrate-yield: A/A0 and σ_rms at the interface), reusing one [`crate::contact::Engine`] per spectrum.
//!
//!
//! The crossing of step 4 is refined by [`super::itp::refine`].

use super::itp::{Bracket, refine};
use super::*;
use crate::error::Error;
use crate::prec::Termination;

/// The minimum-thickness search on [lo, hi] (module docs, steps 1–5) for a utilisation
/// function `util(d) = (max over checks of value/limit, the check attaining it)`; a thickness
/// fails when its utilisation exceeds 1.
pub fn search_min_thickness(
    lo: f64,
    hi: f64,
    util: impl FnMut(f64) -> Result<Utilisation, Error>,
) -> Result<MinThickness, Error> {
    search_min_thickness_spread(lo, hi, 1.0, 0.0, util)
}

/// [`search_min_thickness`] for a utilisation whose peak may fall, between a failing point and
/// the better end of a widened step, by `spread` ≥ 1 more than its rms does (module docs,
/// "Under sliding"): each widened step's threshold is lowered to at most
/// level/(√2·spread). A spread up to 1.178 leaves the thresholds as they are. `floor` ≥ 0 is a
/// utilisation no thickness goes below (module docs, "The friction floor"; 0 for none): it
/// steers the widened steps' lengths only.
pub fn search_min_thickness_spread(
    lo: f64,
    hi: f64,
    spread: f64,
    floor: f64,
    mut util: impl FnMut(f64) -> Result<Utilisation, Error>,
) -> Result<MinThickness, Error> {
    let mut evaluations = 0usize;
    // The largest relative error of any utilisation used.
    let mut u_rel_err = 0.0f64;
    let mut util = |x: f64| -> Result<Sample, Error> {
        evaluations += 1;
        let u = util(x.exp())?;
        u_rel_err = u_rel_err.max(u.rel_err);
        Ok(Sample {
            x,
            u: u.value,
            kind: u.kind,
        })
    };
    let result = |thickness, governing, all_pass_to_floor, evaluations| MinThickness {
        thickness,
        governing,
        floor: lo,
        bulk: hi,
        all_pass_to_floor,
        evaluations,
    };
    // The scan starts at q_L·d = SCAN_START_QD; the bulk bound is needed only when that fails
    // or nearly does (module docs, step 1).
    let start = util((hi * SCAN_START_QD / BULK_QD).clamp(lo, hi).ln())?;
    if start.kind.is_none() {
        // No stress check enabled: every thickness passes.
        return Ok(result(Some(Estimate::exact(lo)), None, true, 1));
    }
    // Samples from the top, and the first failing one with the passing sample above it.
    let mut samples = Vec::new();
    if start.u > 1.0 - THICK_SLACK && start.x < hi.ln() {
        let top = util(hi.ln())?;
        if top.u > 1.0 {
            return Ok(result(None, top.kind, false, 2));
        }
        samples.push(top);
    } else if start.u > 1.0 {
        return Ok(result(None, start.kind, false, 1));
    }
    samples.push(start);
    let mut failing: Option<(Sample, Sample)> = (start.u > 1.0).then(|| (start, samples[0]));
    let (x_lo, h) = (lo.ln(), std::f64::consts::LN_10 / POINTS_PER_DECADE);
    // A sample that a widened step found above its threshold: the stretch above it may hide
    // a failing band, so it is scanned again with base steps down to that sample (reused).
    let mut pending: Option<Sample> = None;
    while failing.is_none() {
        let cur = samples[samples.len() - 1];
        if cur.x <= x_lo {
            break;
        }
        let above = samples.len().checked_sub(2).map(|i| samples[i]);
        let ((step, below), floor) = match pending {
            Some(p) => ((h, f64::INFINITY), p.x),
            None => (scan_step(above, cur, h, spread, floor), x_lo),
        };
        let x = (cur.x - step).max(floor);
        let next = match pending.take_if(|p| p.x == x) {
            Some(p) => p,
            None => {
                let s = util(x)?;
                if s.u >= below {
                    pending = Some(s);
                    continue;
                }
                s
            }
        };
        samples.push(next);
        if next.u > 1.0 {
            failing = Some((next, cur));
        } else if let Some(a) = above {
            // A sampled local maximum: look between the neighbours for a narrow failing band.
            if cur.u > a.u && cur.u >= next.u && cur.u > PEAK_GUARD {
                failing = peak_guard(next, cur, a, &mut util)?;
            }
        }
    }
    let Some((fail, pass)) = failing else {
        return Ok(result(Some(Estimate::exact(lo)), None, true, evaluations));
    };
    let mut governing = fail.kind;
    // The interpolation's points: the scan sample above the bracket, then the bracket's ends.
    let above = samples
        .iter()
        .filter(|s| s.x > pass.x)
        .min_by(|a, b| a.x.total_cmp(&b.x))
        .map(|s| (s.x, s.u.ln()));
    let b = refine(
        Bracket {
            x_fail: fail.x,
            y_fail: fail.u.ln(),
            x_pass: pass.x,
            y_pass: pass.u.ln(),
        },
        above,
        0.5 * D_MIN_RTOL.ln_1p(),
        |x| {
            let s = util(x)?;
            if s.u > 1.0 {
                governing = s.kind;
            }
            Ok(s.u.ln())
        },
    )?;
    Ok(result(
        Some(crossing_estimate(&b, u_rel_err)),
        governing,
        false,
        evaluations,
    ))
}

/// d_min from a final bracket `b` in ln d of the pass/fail crossing (module docs, step 4): the
/// geometric midpoint, with the distance to the bracket's upper end plus the shift of the
/// crossing by the utilisation's relative error `u_rel_err` as its error.
pub(crate) fn crossing_estimate(b: &Bracket, u_rel_err: f64) -> Estimate {
    let (x_fail, y_fail, x_pass, y_pass) = (b.x_fail, b.y_fail, b.x_pass, b.y_pass);
    let mid = (0.5 * (x_fail + x_pass)).exp();
    // The geometric midpoint is nearer the bracket's lower end: its distance to the upper one
    // bounds the bracket error.
    let bracket = x_pass.exp() - mid;
    // The utilisations' own errors shift the crossing by δ(ln u)/|d ln u/d ln d| in ln d, with
    // δ(ln u) = −ln(1 − relative error), the larger side; the slope is the secant over the
    // final bracket.
    let slope = (y_fail - y_pass) / (x_pass - x_fail);
    let shift = mid * (-(-u_rel_err.min(0.5)).ln_1p() / slope.abs()).exp_m1();
    Estimate::new(mid, bracket + shift, Termination::Converged)
}

/// One sample of the minimum-thickness search: x = ln d, the utilisation and its check.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Sample {
    pub(super) x: f64,
    pub(super) u: f64,
    pub(super) kind: Option<CheckKind>,
}

type Util<'a> = dyn FnMut(f64) -> Result<Sample, Error> + 'a;

/// The scan's next step down in ln d after `cur` (module docs, step 2) and the utilisation
/// its end must stay below (infinite for the base step `h`): the longest of the [`WIDE_STEPS`]
/// over which the extrapolated u stays below [`WIDE_AIM`] of the step's threshold
/// ([`wide_threshold`] at `spread`), else `h`. u is extrapolated log-linearly in ln d, at the
/// growth rate from the last two samples (at least [`MIN_GROWTH`]); where both lie between
/// `floor` and twice it, as the floor plus the excess u − floor extrapolated so (module docs,
/// "The friction floor").
fn scan_step(above: Option<Sample>, cur: Sample, h: f64, spread: f64, floor: f64) -> (f64, f64) {
    let near_floor = |s: Sample| s.u > floor && s.u < 2.0 * floor;
    match above {
        Some(a) if near_floor(a) && near_floor(cur) => {
            extrapolated_step(above, cur, h, spread, floor)
        }
        _ => extrapolated_step(above, cur, h, spread, 0.0),
    }
}

/// [`scan_step`]'s step for u extrapolated as `floor` (below both samples) plus the excess
/// u − floor, log-linear in ln d; with a floor > 0, at a growth rate of at most
/// [`MAX_EXCESS_GROWTH`].
fn extrapolated_step(
    above: Option<Sample>,
    cur: Sample,
    h: f64,
    spread: f64,
    floor: f64,
) -> (f64, f64) {
    let base = (h, f64::INFINITY);
    let excess = cur.u - floor;
    let rate = match above {
        _ if excess <= 0.0 => return base,
        None => MIN_GROWTH,
        Some(a) if a.u > floor => {
            let rate = ((excess / (a.u - floor)).ln() / (a.x - cur.x)).max(MIN_GROWTH);
            if floor > 0.0 {
                rate.min(MAX_EXCESS_GROWTH)
            } else {
                rate
            }
        }
        Some(_) => return base,
    };
    WIDE_STEPS
        .iter()
        .map(|w| (w, wide_threshold(w, spread)))
        .filter(|&(_, below)| cur.u < below && WIDE_AIM * below > floor)
        .map(|(w, below)| {
            let longest = w.decades * std::f64::consts::LN_10;
            let aim = WIDE_AIM * below - floor;
            (((aim / excess).ln() / rate).min(longest), below)
        })
        .fold(base, |best, s| if s.0 > best.0 { s } else { best })
}

/// The utilisation a widened step's ends must stay below when the peak may fall by `spread`
/// more than the rms (module docs, "Under sliding"): `w.below`, lowered to
/// w.level/(√2·spread) where that is smaller.
pub(super) fn wide_threshold(w: &WideStep, spread: f64) -> f64 {
    w.below.min(w.level / (std::f64::consts::SQRT_2 * spread))
}

/// The utilisation levels, other than 1, that the search compares samples with at `spread`
/// (module docs, "Under sliding"): the widened steps' thresholds ([`wide_threshold`]) and
/// [`PEAK_GUARD`]. A utilisation that is an estimate must lie on the same side of each of them
/// (and of 1) as the true utilisation for the argument that no failing band is missed to hold.
pub(super) fn decision_levels(spread: f64) -> [f64; 3] {
    [
        wide_threshold(&WIDE_STEPS[0], spread),
        wide_threshold(&WIDE_STEPS[1], spread),
        PEAK_GUARD,
    ]
}

/// The narrow-band guard (module docs, step 3) at a sampled local maximum `mid` between the
/// samples `lo` and `hi` (lo.x < mid.x < hi.x): successive parabolic interpolation for the
/// maximum of the utilisation, stopping at the first failing point, else once the parabola
/// through the best three points promises less than [`GUARD_RESOLVED`] of the remaining
/// headroom (after at least one evaluation), or the bracket is 1e-3 wide in ln d, or after
/// [`GUARD_MAX_STEPS`] evaluations (the golden-section search it replaces took 13). Returns the
/// failing point and the nearest passing point above it.
pub(super) fn peak_guard(
    mut lo: Sample,
    mut mid: Sample,
    mut hi: Sample,
    f: &mut Util<'_>,
) -> Result<Option<(Sample, Sample)>, Error> {
    let mut seen = vec![lo, mid, hi];
    let mut evaluated = false;
    while hi.x - lo.x > 1e-3 && seen.len() < 3 + GUARD_MAX_STEPS {
        let w = hi.x - lo.x;
        let vertex = parabola_vertex(lo, mid, hi);
        if evaluated && vertex.is_none_or(|v| v.1 - mid.u <= GUARD_RESOLVED * (1.0 - mid.u)) {
            break;
        }
        // The wider side of the bracket, for a golden-section step when the parabola is flat
        // or its vertex too close to the best point.
        let side = if hi.x - mid.x >= mid.x - lo.x {
            hi.x
        } else {
            lo.x
        };
        let golden = mid.x + 0.381_966 * (side - mid.x);
        let sep = 0.05 * w;
        let x = match vertex {
            Some((xv, _)) if (xv - mid.x).abs() >= sep => xv.clamp(lo.x + sep, hi.x - sep),
            _ => golden,
        };
        let s = f(x)?;
        evaluated = true;
        if s.u > 1.0 {
            let above = seen
                .iter()
                .filter(|p| p.x > x)
                .min_by(|a, b| a.x.total_cmp(&b.x))
                .copied()
                .unwrap_or(hi);
            return Ok(Some((s, above)));
        }
        seen.push(s);
        if s.u > mid.u {
            if s.x < mid.x {
                hi = mid;
            } else {
                lo = mid;
            }
            mid = s;
        } else if s.x < mid.x {
            lo = s;
        } else {
            hi = s;
        }
    }
    Ok(None)
}

/// The vertex (x, value) of the parabola through three samples, when it opens downwards.
fn parabola_vertex(a: Sample, b: Sample, c: Sample) -> Option<(f64, f64)> {
    let ab = (b.u - a.u) / (b.x - a.x);
    let bc = (c.u - b.u) / (c.x - b.x);
    let curv = (bc - ab) / (c.x - a.x);
    if curv.is_nan() || curv >= 0.0 {
        return None;
    }
    let x = 0.5 * (a.x + b.x) - 0.5 * ab / curv;
    Some((x, a.u + ab * (x - a.x) + curv * (x - a.x) * (x - b.x))).filter(|v| v.0.is_finite())
}
