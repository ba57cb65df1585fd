//! Physical values with units at the edges (`50um`, `0.1 MPa`, `2e11`, `200GPa`, `1e5 1/m`,
//! `um^4`). Everything inside the crate is SI; a bare number is taken as SI.
//!
//! A unit is an optional `1/`, an SI prefix (n, u or µ, m, c, k, M, G, T), a base (`m` or `Pa`)
//! and an optional power (`^4`, `^-1`, `4`); `psi` and `bar` are accepted for pressure.

use std::fmt;

/// The physical dimension a value must have: a power of length, or a pressure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dim {
    /// m^k (k = 1 length, −1 wavenumber, 3 for a 1D PSD, 4 for a 2D PSD).
    Length(i32),
    /// Pa.
    Pressure,
    /// A pure number.
    Dimensionless,
}

impl fmt::Display for Dim {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Dim::Length(1) => write!(f, "a length (m, mm, um, nm)"),
            Dim::Length(-1) => write!(f, "a wavenumber (1/m, 1/um, ...)"),
            Dim::Length(k) => write!(f, "m^{k} (or um^{k}, nm^{k})"),
            Dim::Pressure => write!(f, "a pressure (Pa, kPa, MPa, GPa, psi, bar)"),
            Dim::Dimensionless => write!(f, "a plain number"),
        }
    }
}

/// Why a value or unit was rejected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UnitError {
    #[error("'{0}' is not a number")]
    NotANumber(String),
    #[error("unknown unit '{0}'")]
    UnknownUnit(String),
    #[error("unit '{unit}' is not {expected}")]
    WrongDimension { unit: String, expected: Dim },
}

/// Decimal exponent of an SI prefix.
fn prefix_exponent(p: &str) -> Option<i32> {
    Some(match p {
        "" => 0,
        "n" => -9,
        "u" | "µ" | "μ" => -6,
        "m" => -3,
        "c" => -2,
        "k" => 3,
        "M" => 6,
        "G" => 9,
        "T" => 12,
        _ => return None,
    })
}

/// 10^e applied to `value` with one correctly rounded operation (10^|e| is exact for |e| <= 22):
/// `10 um` is exactly 1e-5 m, not 9.999999999999999e-6.
fn apply_exponent(value: f64, e: i32) -> f64 {
    if e >= 0 {
        value * 10f64.powi(e)
    } else {
        value / 10f64.powi(-e)
    }
}

/// Scale factor to SI of `unit` (which must have dimension `dim`).
pub fn unit_scale(unit: &str, dim: Dim) -> Result<f64, UnitError> {
    to_si(1.0, unit, dim)
}

/// `value` in `unit` converted to SI.
pub fn to_si(value: f64, unit: &str, dim: Dim) -> Result<f64, UnitError> {
    let u: String = unit.chars().filter(|c| !c.is_whitespace()).collect();
    if u.is_empty() {
        return Ok(value);
    }
    let wrong = || UnitError::WrongDimension {
        unit: unit.to_string(),
        expected: dim,
    };
    let unknown = || UnitError::UnknownUnit(unit.to_string());
    let (inverse, body) = match u.strip_prefix("1/").or_else(|| u.strip_prefix('/')) {
        Some(rest) => (true, rest),
        None => (false, u.as_str()),
    };
    // Split off a power: "^-1", "^4", or a trailing digit run ("m4").
    let (base_with_prefix, power) = match body.find('^') {
        Some(i) => (
            &body[..i],
            body[i + 1..].parse::<i32>().map_err(|_| unknown())?,
        ),
        None => {
            let digits = body.trim_end_matches(|c: char| c.is_ascii_digit());
            if digits.len() < body.len() && !digits.is_empty() {
                (
                    digits,
                    body[digits.len()..].parse::<i32>().map_err(|_| unknown())?,
                )
            } else {
                (body, 1)
            }
        }
    };
    let power = if inverse { -power } else { power };
    match base_with_prefix {
        "psi" | "bar" => {
            if dim != Dim::Pressure || power != 1 {
                return Err(wrong());
            }
            return Ok(value
                * if base_with_prefix == "psi" {
                    6894.757293168361
                } else {
                    1e5
                });
        }
        _ => {}
    }
    for (base, is_pressure) in [("Pa", true), ("m", false)] {
        if let Some(prefix) = base_with_prefix.strip_suffix(base) {
            let Some(exponent) = prefix_exponent(prefix) else {
                continue;
            };
            return match (is_pressure, dim) {
                (true, Dim::Pressure) if power == 1 => Ok(apply_exponent(value, exponent)),
                (false, Dim::Length(k)) if k == power => {
                    Ok(apply_exponent(value, exponent * power))
                }
                _ => Err(wrong()),
            };
        }
    }
    Err(unknown())
}

/// Parse a value with an optional unit, e.g. `50um`, `0.1 MPa`, `1e5 1/m`, `2e11`.
pub fn parse_quantity(text: &str, dim: Dim) -> Result<f64, UnitError> {
    let t = text.trim();
    // The number is the longest prefix that parses as f64.
    let mut split = 0;
    for (i, _) in t.char_indices().chain(std::iter::once((t.len(), ' '))) {
        if t[..i].parse::<f64>().is_ok() {
            split = i;
        }
    }
    if split == 0 {
        return Err(UnitError::NotANumber(text.to_string()));
    }
    let value: f64 = t[..split]
        .parse()
        .map_err(|_| UnitError::NotANumber(text.to_string()))?;
    let unit = t[split..].trim();
    if dim == Dim::Dimensionless {
        return if unit.is_empty() {
            Ok(value)
        } else {
            Err(UnitError::WrongDimension {
                unit: unit.to_string(),
                expected: dim,
            })
        };
    }
    to_si(value, unit, dim)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_with_units() {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-15 * b.abs();
        assert!(close(
            parse_quantity("50um", Dim::Length(1)).unwrap(),
            50e-6
        ));
        assert!(close(
            parse_quantity("50 µm", Dim::Length(1)).unwrap(),
            50e-6
        ));
        assert!(close(
            parse_quantity("0.1 MPa", Dim::Pressure).unwrap(),
            1e5
        ));
        assert!(close(
            parse_quantity("200GPa", Dim::Pressure).unwrap(),
            2e11
        ));
        assert!(close(
            parse_quantity("2e11 Pa", Dim::Pressure).unwrap(),
            2e11
        ));
        assert!(close(parse_quantity("2e11", Dim::Pressure).unwrap(), 2e11));
        assert!(close(
            parse_quantity("1e5 1/m", Dim::Length(-1)).unwrap(),
            1e5
        ));
        assert!(close(
            parse_quantity("3 1/um", Dim::Length(-1)).unwrap(),
            3e6
        ));
        assert!(close(
            parse_quantity("2 um^-1", Dim::Length(-1)).unwrap(),
            2e6
        ));
        assert!(close(
            parse_quantity("1 um^4", Dim::Length(4)).unwrap(),
            1e-24
        ));
        assert!(close(
            parse_quantity("1 nm^3", Dim::Length(3)).unwrap(),
            1e-27
        ));
        assert!(close(
            parse_quantity("1 psi", Dim::Pressure).unwrap(),
            6894.757293168361
        ));
        assert!(close(
            parse_quantity("0.5", Dim::Dimensionless).unwrap(),
            0.5
        ));
    }

    #[test]
    fn rejections_say_why() {
        assert_eq!(
            parse_quantity("abc", Dim::Pressure),
            Err(UnitError::NotANumber("abc".into()))
        );
        assert_eq!(
            parse_quantity("1 furlong", Dim::Length(1)),
            Err(UnitError::UnknownUnit("furlong".into()))
        );
        assert!(matches!(
            parse_quantity("1 MPa", Dim::Length(1)),
            Err(UnitError::WrongDimension { .. })
        ));
        assert!(matches!(
            parse_quantity("1 um", Dim::Length(-1)),
            Err(UnitError::WrongDimension { .. })
        ));
        assert!(matches!(
            parse_quantity("1 m", Dim::Dimensionless),
            Err(UnitError::WrongDimension { .. })
        ));
    }
}
