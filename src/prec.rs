//! Numerical settings and tolerances, kept in one place.
//!
//! Every integral or solver in the crate returns an [`Estimate`]: the value, a
//! bound-like estimate of its absolute numerical error and how the computation
//! ended ([`Termination`]). Nothing returns a bare `f64` that could hide a failure.
//!
//! All quantities are SI (Pa, m, 1/m, m^4); units are converted only at the edges.

use serde::Serialize;

/// Machine epsilon for `f64`, named for readability in error budgets.
pub const EPS: f64 = f64::EPSILON;

/// Default relative tolerance of the contact integrals (area, rms stresses).
pub const DEFAULT_RTOL: f64 = 1e-8;

/// Relative tolerance of the engine inside the minimum-thickness search: d_min is wanted to
/// 0.2 % in d, and a utilisation error of 1e-6 moves it by 1e-6/|d ln u/d ln d| (included in
/// its error estimate), while thin films on noisy spectra would need a refined grid at 1e-8.
pub const SEARCH_RTOL: f64 = 1e-6;

/// Relative error bound of the layer kernels S, f, g (`layer`): the worst measured against a
/// 100-digit solution over the reference grid is 1.1e-13 (S) and 2.9e-14 (f, g); the test
/// `kernels_match_high_precision_reference` asserts this bound, and outputs quote it as the
/// kernels' error estimate.
pub const KERNEL_RTOL: f64 = 2e-13;

/// How closely the tabulated kernels (`layer::KernelTable`) must match the exact ones, relative
/// to the largest value on each panel; checked when a table is built. Small against
/// [`KERNEL_RTOL`], so the kernels' error bound holds for the tabulated values too.
pub const TABLE_RTOL: f64 = 2e-14;

/// The smallest positive f64, 2^−1074 ≈ 4.9e−324: a result that rounds into the subnormal
/// range, or to 0 below it, is within this of its true value.
pub const SMALLEST_SUBNORMAL: f64 = f64::from_bits(1);

/// Absolute error (Pa) below which an interface stress (σ_rms or τ_rms at z = d) counts as
/// converged whatever its relative error: four subnormal steps, 2e−323 Pa. The interface stresses
/// fall like e^{−q_L d} (at most f(q_L d)·σ_top, σ_top the top-surface stress) and the engine
/// resolves them to rtol while they are normal numbers (it scales the integrals by e^{2 q_L d});
/// below f64's normal range (2.2e−308) the value and its error estimate round into the subnormals
/// or to 0, a relative error no grid refines, and an error of a few subnormal steps is 1e−320 of
/// any stress a film carries or a check resolves. The reported error still bounds the true one.
pub const INTERFACE_ATOL: f64 = 4.0 * SMALLEST_SUBNORMAL;

/// Default exceedance probability that defines a "peak" value (fraction of the interface).
pub const DEFAULT_EPSILON: f64 = 1e-6;

/// How a numerical computation ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Termination {
    /// The error estimate is within the requested tolerance.
    Converged,
    /// The computation finished but the error estimate exceeds the requested tolerance.
    ToleranceNotReached,
    /// A closed form or exact limit was used; the error is rounding only.
    Exact,
}

/// A computed value with an estimate of its absolute numerical error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Estimate {
    pub value: f64,
    /// Estimated absolute error (non-negative).
    pub err: f64,
    pub status: Termination,
}

impl Estimate {
    pub fn new(value: f64, err: f64, status: Termination) -> Self {
        Self {
            value,
            err: err.abs(),
            status,
        }
    }

    /// A value known to rounding: error of a few ulps.
    pub fn exact(value: f64) -> Self {
        Self::new(value, 4.0 * EPS * value.abs(), Termination::Exact)
    }

    /// Relative error estimate (`err / |value|`, or `err` when the value is 0).
    pub fn rel_err(&self) -> f64 {
        if self.value == 0.0 {
            self.err
        } else {
            self.err / self.value.abs()
        }
    }

    /// Apply a smooth map `y = h(x)` with derivative `dh` at `x`, propagating the error
    /// to first order and adding rounding of the result.
    pub fn map(self, h: impl Fn(f64) -> f64, dh: impl Fn(f64) -> f64) -> Self {
        let value = h(self.value);
        let err = dh(self.value).abs() * self.err + 4.0 * EPS * value.abs();
        Self {
            value,
            err,
            status: self.status,
        }
    }

    /// The worse of two terminations (used when combining estimates).
    pub fn worst(a: Termination, b: Termination) -> Termination {
        use Termination::*;
        match (a, b) {
            (ToleranceNotReached, _) | (_, ToleranceNotReached) => ToleranceNotReached,
            (Converged, _) | (_, Converged) => Converged,
            _ => Exact,
        }
    }
}

/// Settings of the contact integrals.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Settings {
    /// Requested relative accuracy of G(q1), the rms stresses and A/A0.
    pub rtol: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self { rtol: DEFAULT_RTOL }
    }
}
