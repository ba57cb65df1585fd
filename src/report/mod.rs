//! All output: a judged scene ([`mod@check`]), the thickness sweep ([`mod@sweep`]), a batch
//! ([`mod@batch`], [`junit`], [`parquet`]), the exact contact ([`mod@verify`]); human tables use
//! comfy-table with MPa, µm and 4 significant digits ([`sig`]). Files and standard output are
//! written by [`mod@write`], the one writer.

use crate::error::Error;
use comfy_table::{Table, presets::UTF8_FULL_CONDENSED};

pub mod batch;
pub mod check;
pub mod html;
pub mod junit;
pub mod materials;
pub mod parquet;
pub mod plot;
pub mod stack;
pub mod sweep;
pub mod verify;
pub mod write;
pub use check::{csv, human, json, scene};
pub use sweep::{SWEEP, sweep};
pub use write::{is_broken_pipe, stdout, write_file, write_with};

/// Version of the JSON documents' shape (`schema_version`; the schemas in `src/report/schema/`).
pub const SCHEMA_VERSION: u32 = 1;

/// The JSON Schema of `coatcheck check --format json` for one scene.
pub const CHECK_SCHEMA: &str = include_str!("schema/check.schema.json");

/// Output format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Table,
    Json,
    Csv,
}

/// Refuse a report that shows a number that is not finite: no command prints NaN or inf. A
/// table cell or CSV field that reads `NaN`, `inf` or `-inf` is a numerical failure naming its
/// row (the row's first cell: the quantity, or the q or q·d of a data row) and its column.
pub fn finite_only(text: &str) -> Result<(), Error> {
    let cells = |line: &str| -> Vec<String> {
        line.split(['│', '┆', '|', ','])
            .map(|c| c.trim().to_string())
            .filter(|c| !c.is_empty())
            .collect()
    };
    let mut header: Vec<String> = Vec::new();
    for line in text.lines() {
        let row = cells(line);
        if header.is_empty() && row.len() > 1 {
            header = row.clone();
        }
        let bad = row.iter().position(|c| {
            matches!(
                c.to_ascii_lowercase().as_str(),
                "nan" | "inf" | "-inf" | "+inf"
            )
        });
        if let Some(i) = bad {
            let column = header
                .get(i)
                .filter(|_| i > 0)
                .map_or(String::new(), |h| format!(", column {h}"));
            return Err(Error::Numerical {
                what: "the report",
                detail: format!(
                    "{} is {}{column}; a result that is not finite is not printed",
                    row[0], row[i]
                ),
            });
        }
    }
    Ok(())
}

/// `x` with `digits` significant digits: fixed notation for 1e-3 ≤ |x| < 1e6, else scientific.
pub fn sig(x: f64, digits: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    // The exponent after rounding to `digits` (9.9999 → 10.00, not 10.000).
    let e0 = x.abs().log10().floor() as i32;
    let scale = 10f64.powi(digits as i32 - 1 - e0);
    let rounded = (x * scale).round() / scale;
    let e = rounded.abs().log10().floor() as i32;
    if (-3..6).contains(&e) {
        let decimals = (digits as i32 - 1 - e).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{:.*e}", digits - 1, x)
    }
}

/// A Young's modulus in the unit engineers quote it in: GPa from 1 GPa, else MPa from 1 MPa,
/// else kPa ("200.0 GPa", "1.000 MPa").
fn modulus(pa: f64) -> String {
    let (scale, unit) = if pa >= 1e9 {
        (1e9, "GPa")
    } else if pa >= 1e6 {
        (1e6, "MPa")
    } else {
        (1e3, "kPa")
    };
    format!("{} {unit}", sig(pa / scale, 4))
}

fn mpa(pa: f64) -> String {
    sig(pa * 1e-6, 4)
}

fn um(m: f64) -> String {
    sig(m * 1e6, 4)
}

fn table(header: &[&str]) -> Table {
    let mut t = Table::new();
    t.load_preset(UTF8_FULL_CONDENSED);
    t.set_header(header.iter().copied());
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moduli_in_engineering_units() {
        assert_eq!(modulus(200e9), "200.0 GPa");
        assert_eq!(modulus(1e11), "100.0 GPa");
        assert_eq!(modulus(1e6), "1.000 MPa");
        assert_eq!(modulus(3e9), "3.000 GPa");
        assert_eq!(modulus(5e5), "500.0 kPa");
    }

    #[test]
    fn a_report_with_a_non_finite_number_is_refused_naming_it() {
        let table = "┌──────┬─────┐\n│ quantity ┆ Persson ┆ err │\n│ A/A0 ┆ 0.5 ┆ NaN │\n";
        let e = finite_only(table).unwrap_err().to_string();
        assert!(e.contains("A/A0 is NaN, column err"), "{e}");
        let csv = "qd,S,S_err\n1e0,0.5,1e-13\n1e3,inf,1e-13\n";
        let e = finite_only(csv).unwrap_err().to_string();
        assert!(e.contains("1e3 is inf, column S"), "{e}");
        let e = finite_only("key,value\nsigma_max,-inf\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("sigma_max is -inf, column value"), "{e}");
        // Words and numbers that merely contain the letters are fine.
        let fine = "information, infinite film: 1e300 | infinity-norm ┆ nan-free ┆ 0\n";
        assert!(finite_only(fine).is_ok());
    }

    #[test]
    fn significant_digits() {
        assert_eq!(sig(0.0927412, 4), "0.09274");
        assert_eq!(sig(0.357, 4), "0.3570");
        assert_eq!(sig(12.345678, 4), "12.35");
        assert_eq!(sig(1234.6, 4), "1235");
        assert_eq!(sig(2.5e-7, 3), "2.50e-7");
        assert_eq!(sig(3e8, 4), "3.000e8");
        assert_eq!(sig(0.0, 4), "0");
        assert_eq!(sig(9.999999, 4), "10.00");
        assert_eq!(sig(-0.00099996, 4), "-0.001000");
        assert_eq!(sig(0.00099996, 3), "0.00100");
    }
}
