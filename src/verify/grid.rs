//! The grid error of an exact number: the same number computed on the map (N pixels a side), on
//! the map at half the resolution (every second pixel, N/2) and at a quarter (N/4), combined as
//! in a grid-convergence study (Richardson extrapolation with Roache's safety factors of the
//! grid convergence index).
//!
//! With e1 = x(N/2) − x(N) and e2 = x(N/4) − x(N/2), the observed ratio r = e2/e1 is 2^p for a
//! number converging at order p. The contact area converges at first order in the pixel size
//! once the grid resolves the contact spots (pixels are counted in or out along the spots'
//! perimeters; `examples/bench_bem.rs` measures it), so a faster observed rate is not yet the
//! asymptotic one and r is capped at 2 in the extrapolation. Three cases:
//! - r in [[`R_MIN`], [`R_MAX`]] (converging, at an observed order between 1/3 and 2): the
//!   error of x(N) against the continuum limit is Richardson's |e1|/(min(r, 2) − 1) times a
//!   safety factor, [`SAFETY_THREE`] when the observed order is within [`ORDER_TOL`] of 1 (the
//!   sequence behaves as the asymptotic theory says), [`SAFETY_TWO`] otherwise;
//! - otherwise (differences that do not shrink, change sign, or shrink implausibly fast: the
//!   sequence is not in its asymptotic regime and no rate can be trusted) [`SAFETY_TWO`] ×
//!   max(|e1|, |e2|);
//! - a map too small for a quarter-resolution map (fewer than 64 pixels a side) gets
//!   [`SAFETY_TWO`] × |e1|, one too small to halve (fewer than 32) NaN.
//!
//! A/A0 counts pixels: a count cannot resolve less than one pixel, so equal counts at two
//! resolutions only say that they agree within a pixel of the coarser map. Its grid error
//! ([`area_grid_error`]) is therefore at least the area fraction of one pixel of the
//! half-resolution map.
//!
//! This is an estimate, not a proof: for A/A0 it covered the difference to a finer parent of
//! the same surface in every case of `tests/it/exact.rs` (self-affine maps over seeds, loads
//! and film thicknesses, from the first-order regime down to contact spots a few pixels wide).
//! The factor 1.25 alone on every converging sequence missed 2 of its first 48 cases (by up to
//! 1.43×, both at an observed order of 1.4 or more), as Roache's rule expects; without the
//! one-pixel floor one of 48 further cases was missed (the same count at all three
//! resolutions, a contact of three coarse pixels).

/// Smallest observed ratio e2/e1 taken as convergence (order 1/3).
pub const R_MIN: f64 = 1.25;
/// Largest observed ratio e2/e1 taken as convergence (order 2).
pub const R_MAX: f64 = 4.0;
/// How far the observed order may lie from 1 for the smaller safety factor.
pub const ORDER_TOL: f64 = 0.25;
/// Safety factor on the three-level estimate at the expected order (Roache's for three grids).
pub const SAFETY_THREE: f64 = 1.25;
/// Safety factor off the expected order or on two levels (Roache's for two grids).
pub const SAFETY_TWO: f64 = 3.0;

/// The grid error of `fine` from its values at half and at a quarter of the resolution, when
/// those maps exist (module docs).
pub fn grid_error(fine: f64, half: Option<f64>, quarter: Option<f64>) -> f64 {
    let Some(half) = half else {
        return f64::NAN;
    };
    let e1 = half - fine;
    let Some(quarter) = quarter else {
        return SAFETY_TWO * e1.abs();
    };
    let e2 = quarter - half;
    let r = e2 / e1;
    if (R_MIN..=R_MAX).contains(&r) {
        let safety = if (r.log2() - 1.0).abs() <= ORDER_TOL {
            SAFETY_THREE
        } else {
            SAFETY_TWO
        };
        safety * e1.abs() / (r.min(2.0) - 1.0)
    } else {
        SAFETY_TWO * e1.abs().max(e2.abs())
    }
}

/// The grid error of A/A0 (`fine`, counted on `pixels` pixels): [`grid_error`], at least one
/// pixel of the half-resolution map (4/`pixels`) when that map exists (module docs).
pub fn area_grid_error(fine: f64, half: Option<f64>, quarter: Option<f64>, pixels: usize) -> f64 {
    let e = grid_error(fine, half, quarter);
    match half {
        Some(_) => e.max(4.0 / pixels as f64),
        None => e,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_order_convergence_gives_richardsons_error_with_the_safety_factor() {
        // x(h) = 1 + c h: the continuum error of x(N) is c h = e1.
        let x = |h: f64| 1.0 + 0.01 * h;
        let e = grid_error(x(1.0), Some(x(2.0)), Some(x(4.0)));
        assert!((e - SAFETY_THREE * 0.01).abs() < 1e-15, "{e}");
        // Order 1.5 observed: capped at first and off the expected order, 3 e1, not e1/1.83.
        let y = |h: f64| 1.0 + 0.01 * h.powf(1.5);
        let e = grid_error(y(1.0), Some(y(2.0)), Some(y(4.0)));
        let e1 = y(2.0) - y(1.0);
        assert!((e - SAFETY_TWO * e1).abs() < 1e-15, "{e}");
        // Order 0.5 (r = √2): Richardson's e1/(√2 − 1), off the expected order (to 1e-12
        // relative: r comes from differences of values near 1).
        let z = |h: f64| 1.0 + 0.01 * h.sqrt();
        let e = grid_error(z(1.0), Some(z(2.0)), Some(z(4.0)));
        let e1 = z(2.0) - z(1.0);
        let want = SAFETY_TWO * e1 / (2f64.sqrt() - 1.0);
        assert!((e - want).abs() < 1e-12 * want, "{e}");
    }

    #[test]
    fn oscillating_or_missing_levels_fall_back_to_the_two_grid_factor() {
        assert!((grid_error(1.0, Some(1.1), Some(1.15)) - SAFETY_TWO * 0.1).abs() < 1e-15);
        // Shrinking implausibly fast (r = 10): not asymptotic, the larger difference counts.
        assert!((grid_error(1.0, Some(1.01), Some(1.11)) - SAFETY_TWO * 0.1).abs() < 1e-14);
        let e = grid_error(1.0, Some(1.1), Some(1.0));
        assert!((e - SAFETY_TWO * 0.1).abs() < 1e-15, "{e}");
        assert!((grid_error(1.0, Some(1.1), None) - SAFETY_TWO * 0.1).abs() < 1e-15);
        assert!(grid_error(1.0, None, None).is_nan());
        // Equal values at every level: no grid error seen; equal at N and N/2 alone is no
        // convergence.
        assert_eq!(grid_error(1.0, Some(1.0), Some(1.0)), 0.0);
        assert!((grid_error(1.0, Some(1.0), Some(1.2)) - SAFETY_TWO * 0.2).abs() < 1e-15);
        // A/A0 equal at every level is known to a pixel of the half-resolution map.
        assert_eq!(
            area_grid_error(0.5, Some(0.5), Some(0.5), 64 * 64),
            1.0 / 1024.0
        );
        assert!(area_grid_error(0.5, None, None, 64 * 64).is_nan());
    }
}
