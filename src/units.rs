//! Physical values with units at the edges (`50um`, `0.1 MPa`, `2e11`, `200GPa`, `1e5 1/m`,
//! `um^4`). Everything inside the crate is SI; a bare number is taken as SI.
//!
//! A unit is an optional `1/`, an SI prefix (n, u or µ, m, c, k, M, G, T), a base (`m` or `Pa`)
//! and an optional power (`^4`, `^-1`, `4`, or superscripts `⁴`, `⁻¹`). The micro sign may be
//! either code point (U+00B5 or Greek U+03BC). `micron` (or `microns`) is `um` and `mil` is
//! 25.4 µm, both with powers; `psi`, `bar` and a force per area (`N/mm²`, `N/mm^2`, `kN/mm2`,
//! `N/m2`) are accepted for pressure.

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

/// `unit` without whitespace, with each run of superscripts (`⁻¹`, `²`, `⁴`) written as a
/// `^` power (`^-1`, `^2`, `^4`).
fn normalized(unit: &str) -> String {
    let mut out = String::with_capacity(unit.len() + 2);
    let mut in_power = false;
    for c in unit.chars().filter(|c| !c.is_whitespace()) {
        let ascii = match c {
            '⁻' => Some('-'),
            '⁺' => Some('+'),
            '⁰' => Some('0'),
            '¹' => Some('1'),
            '²' => Some('2'),
            '³' => Some('3'),
            '⁴'..='⁹' => char::from_digit(c as u32 - '⁰' as u32, 10),
            _ => None,
        };
        match ascii {
            Some(a) => {
                if !in_power {
                    out.push('^');
                }
                out.push(a);
            }
            None => out.push(c),
        }
        in_power = ascii.is_some();
    }
    out
}

/// Split a power off a unit body: `um^-1` → (`um`, −1), `m4` → (`m`, 4), `Pa` → (`Pa`, 1).
/// `None` when the power is not an integer.
fn split_power(body: &str) -> Option<(&str, i32)> {
    if let Some(i) = body.find('^') {
        return Some((&body[..i], body[i + 1..].parse::<i32>().ok()?));
    }
    let base = body.trim_end_matches(|c: char| c.is_ascii_digit());
    if base.len() < body.len() && !base.is_empty() {
        Some((base, body[base.len()..].parse::<i32>().ok()?))
    } else {
        Some((body, 1))
    }
}

/// A force per area, `<prefix>N/<prefix>m^2` (e.g. `N/mm^2` = 1 MPa): `Some(value in Pa)`, or
/// `None` when `u` is not of that form.
fn force_per_area(value: f64, u: &str) -> Option<f64> {
    let (force, area) = u.split_once('/')?;
    let n = prefix_exponent(force.strip_suffix('N')?)?;
    let (length, power) = split_power(area)?;
    let m = prefix_exponent(length.strip_suffix('m')?)?;
    (power == 2).then(|| apply_exponent(value, n - 2 * m))
}

/// A length unit outside the SI prefixes, as `value` in it converted to m^`power`:
/// `micron`/`microns` (1 µm) and `mil` (25.4 µm = 254e-7 m exactly; 254^k is exact in f64 for
/// |k| <= 6, so a power of a mil costs two roundings). `None` for other names.
fn named_length(value: f64, name: &str, power: i32) -> Option<f64> {
    match name {
        "micron" | "microns" => Some(apply_exponent(value, -6 * power)),
        "mil" => {
            let mils = 254f64.powi(power.abs());
            let v = if power >= 0 {
                value * mils
            } else {
                value / mils
            };
            Some(apply_exponent(v, -7 * power))
        }
        _ => None,
    }
}

/// Scale factor to SI of `unit` (which must have dimension `dim`).
pub fn unit_scale(unit: &str, dim: Dim) -> Result<f64, UnitError> {
    to_si(1.0, unit, dim)
}

/// `value` in `unit` converted to SI.
pub fn to_si(value: f64, unit: &str, dim: Dim) -> Result<f64, UnitError> {
    let u = normalized(unit);
    if u.is_empty() {
        return Ok(value);
    }
    let wrong = || UnitError::WrongDimension {
        unit: unit.to_string(),
        expected: dim,
    };
    let unknown = || UnitError::UnknownUnit(unit.to_string());
    if let Some(pa) = force_per_area(value, &u) {
        return if dim == Dim::Pressure {
            Ok(pa)
        } else {
            Err(wrong())
        };
    }
    let (inverse, body) = match u.strip_prefix("1/").or_else(|| u.strip_prefix('/')) {
        Some(rest) => (true, rest),
        None => (false, u.as_str()),
    };
    let (base_with_prefix, power) = split_power(body).ok_or_else(unknown)?;
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
    if let Some(v) = named_length(value, base_with_prefix, power) {
        return match dim {
            Dim::Length(k) if k == power => Ok(v),
            _ => Err(wrong()),
        };
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

    /// Each spelling against the same value written in the ASCII form (or exactly in SI): the
    /// conversions are definitions, so the comparisons are exact except where stated.
    #[test]
    fn unicode_and_engineering_spellings() {
        let q = |t: &str, dim: Dim| parse_quantity(t, dim).unwrap();
        let len = Dim::Length(1);
        let wavenumber = Dim::Length(-1);
        // Both micro signs: U+00B5 (micro sign) and U+03BC (Greek mu).
        assert_eq!(q("10 \u{b5}m", len), 1e-5);
        assert_eq!(q("10 \u{3bc}m", len), 1e-5);
        assert_eq!(q("2 \u{3bc}m\u{207b}\u{b9}", wavenumber), 2e6);
        // Superscript powers.
        assert_eq!(q("1e5 m\u{207b}\u{b9}", wavenumber), 1e5);
        assert_eq!(q("1e5 m⁻¹", wavenumber), q("1e5 m^-1", wavenumber));
        assert_eq!(q("3 m³", Dim::Length(3)), 3.0);
        assert_eq!(q("3 m⁴", Dim::Length(4)), 3.0);
        assert_eq!(q("1 nm³", Dim::Length(3)), q("1 nm^3", Dim::Length(3)));
        assert_eq!(q("1 µm⁴", Dim::Length(4)), q("1 um^4", Dim::Length(4)));
        assert_eq!(q("2 mm²", Dim::Length(2)), 2e-6);
        // Force per area: 1 N/mm² = 1 MPa.
        assert_eq!(q("0.5 N/mm^2", Dim::Pressure), 5e5);
        assert_eq!(q("0.5 N/mm²", Dim::Pressure), 5e5);
        assert_eq!(q("0.5 N / mm2", Dim::Pressure), 5e5);
        assert_eq!(q("210 kN/mm²", Dim::Pressure), 2.1e11);
        assert_eq!(q("7 N/m²", Dim::Pressure), 7.0);
        // micron(s) = µm, with powers and inverses.
        assert_eq!(q("10 micron", len), q("10 um", len));
        assert_eq!(q("3 microns", len), q("3 um", len));
        assert_eq!(q("2 1/micron", wavenumber), 2e6);
        assert_eq!(q("1 micron^4", Dim::Length(4)), q("1 um^4", Dim::Length(4)));
        // mil = 25.4 µm: one mil is the double nearest 2.54e-5; powers within 2 ulp.
        assert_eq!(q("1 mil", len), 2.54e-5);
        assert_eq!(q("4 mil", len), 1.016e-4);
        let close = |a: f64, b: f64| (a - b).abs() <= 4.5e-16 * b.abs();
        assert!(close(q("1 mil^4", Dim::Length(4)), 2.54e-5f64.powi(4)));
        assert!(close(q("1 1/mil", wavenumber), 1.0 / 2.54e-5));
        assert!(close(q("1 mil⁻¹", wavenumber), 39370.07874015748));
    }

    #[test]
    fn new_spellings_keep_their_dimension() {
        let wrong = |t: &str, dim: Dim| {
            assert!(
                matches!(
                    parse_quantity(t, dim),
                    Err(UnitError::WrongDimension { .. })
                ),
                "{t} as {dim}"
            )
        };
        wrong("1 N/mm^2", Dim::Length(1));
        wrong("1 mil", Dim::Pressure);
        wrong("1 micron", Dim::Length(-1));
        wrong("1 m⁴", Dim::Length(3));
        wrong("1 m⁻¹", Dim::Length(1));
        assert_eq!(
            parse_quantity("1 N/mm^3", Dim::Pressure),
            Err(UnitError::UnknownUnit("N/mm^3".into()))
        );
        assert_eq!(
            parse_quantity("1 mils", Dim::Length(1)),
            Err(UnitError::UnknownUnit("mils".into()))
        );
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
