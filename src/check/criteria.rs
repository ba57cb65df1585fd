//! The judging rules shared by Persson's checks ([`super::Checker`]) and the exact ones
//! ([`crate::verify`]): the limit of a strength, an upper check's margin and verdict, and which
//! level the substrate-yield check judges.

use super::{CheckKind, CheckResult};
use crate::prec::Estimate;

/// The limit a strength sets: strength / safety factor.
pub fn limit(strength: f64, safety_factor: f64) -> f64 {
    strength / safety_factor
}

/// The unused fraction of an upper limit: 1 − value/limit (≥ 0 passes).
pub fn margin(value: f64, limit: f64) -> f64 {
    1.0 - value / limit
}

/// An upper limit is met when the value does not exceed it.
pub fn passes(value: f64, limit: f64) -> bool {
    value <= limit
}

/// The substrate-yield level: the larger of the interface normal stress's ε-peak and the mean
/// pressure in real contact p0·A0/A governs (the peak on a tie). `value` reads the level of
/// either.
pub fn yield_governing<T>(peak: T, mean: T, value: impl Fn(&T) -> f64) -> T {
    if value(&peak) >= value(&mean) {
        peak
    } else {
        mean
    }
}

/// A stress check against an upper limit.
pub fn upper_check(kind: CheckKind, value: Estimate, limit: f64) -> CheckResult {
    CheckResult {
        kind,
        value,
        limit: Some(limit),
        margin: Some(margin(value.value, limit)),
        pass: passes(value.value, limit),
        undecided: (value.value - limit).abs() <= value.err,
    }
}
