//! A bracketed root finder: the ITP method (Oliveira & Takahashi 2020, "An enhancement of the
//! bisection method average performance preserving minmax optimality", ACM TOMS 47(1)) with
//! inverse quadratic interpolation as its estimate.
//!
//! It refines a bracket [x_fail, x_pass] of a crossing of y(x) through 0 (y > 0 fails, y ≤ 0
//! passes) until it is at most 2·eps wide. Each step projects the estimate onto an interval
//! around the midpoint that shrinks like bisection's, so it never takes more steps than
//! bisection plus one. An estimate within δ of a bracket end is moved to 4δ from it (at most
//! 0.95·2·eps), so that it lands across the crossing and closes the bracket: a smooth function
//! needs two or three steps.

use crate::error::Error;

/// A bracket of a crossing: y(x_fail) > 0 ≥ y(x_pass), in either order of x.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bracket {
    pub x_fail: f64,
    pub y_fail: f64,
    pub x_pass: f64,
    pub y_pass: f64,
}

/// Narrow `b` (with x_fail < x_pass) to a width of at most 2·eps by the ITP method. `above` is a
/// further point (x, y) beyond x_pass for the first interpolation; `f` gives y(x). Non-finite y
/// are used for the bracket but not for the interpolation.
pub fn refine(
    b: Bracket,
    above: Option<(f64, f64)>,
    eps: f64,
    mut f: impl FnMut(f64) -> Result<f64, Error>,
) -> Result<Bracket, Error> {
    let Bracket {
        mut x_fail,
        mut y_fail,
        mut x_pass,
        mut y_pass,
    } = b;
    // The interpolation's points (x, y), newest last.
    let mut recent: Vec<(f64, f64)> = above
        .into_iter()
        .chain([(x_pass, y_pass), (x_fail, y_fail)])
        .filter(|p| p.1.is_finite())
        .collect();
    let n_max = ((x_pass - x_fail) / (2.0 * eps)).log2().ceil().max(0.0) as i32 + 1;
    let mut j = 0;
    while x_pass - x_fail > 2.0 * eps {
        let w = x_pass - x_fail;
        let half = 0.5 * (x_fail + x_pass);
        let r = (eps * 2f64.powi(n_max - j) - 0.5 * w).max(0.0);
        let falsi = (y_fail.is_finite() && y_pass.is_finite() && y_fail > y_pass)
            .then(|| (x_fail * y_pass - x_pass * y_fail) / (y_pass - y_fail));
        let guess = inverse_quadratic(&recent)
            .filter(|x| *x > x_fail && *x < x_pass)
            .or(falsi)
            .unwrap_or(half);
        let near = (guess - x_fail).min(x_pass - guess);
        let c = (4.0 * near).clamp(0.01 * eps, 1.9 * eps).min(0.5 * w);
        let x = half + (guess.clamp(x_fail + c, x_pass - c) - half).clamp(-r, r);
        let y = f(x)?;
        if y > 0.0 {
            (x_fail, y_fail) = (x, y);
        } else {
            (x_pass, y_pass) = (x, y);
        }
        if y.is_finite() {
            recent.push((x, y));
        }
        j += 1;
    }
    Ok(Bracket {
        x_fail,
        y_fail,
        x_pass,
        y_pass,
    })
}

/// The zero of the inverse quadratic through the last three points (x, y) (x as a quadratic
/// in y), when their y are distinct.
pub(super) fn inverse_quadratic(points: &[(f64, f64)]) -> Option<f64> {
    let [(x0, y0), (x1, y1), (x2, y2)] = *points.get(points.len().checked_sub(3)?..)? else {
        return None;
    };
    if y0 == y1 || y1 == y2 || y0 == y2 {
        return None;
    }
    let x = x0 * y1 * y2 / ((y0 - y1) * (y0 - y2))
        + x1 * y0 * y2 / ((y1 - y0) * (y1 - y2))
        + x2 * y0 * y1 / ((y2 - y0) * (y2 - y1));
    x.is_finite().then_some(x)
}
