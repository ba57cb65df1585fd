//! All output: a judged scene ([`mod@check`]), the thickness sweep ([`mod@sweep`]), a batch
//! ([`mod@batch`], [`junit`], [`parquet`]), the exact contact ([`mod@verify`]); human tables use
//! comfy-table with MPa, µm and 4 significant digits ([`sig`]). Files and standard output are
//! written by [`mod@write`], the one writer.

use crate::error::Error;
use comfy_table::{ContentArrangement, Table, presets::UTF8_FULL_CONDENSED};

pub mod batch;
pub mod check;
pub mod finite;
pub mod html;
pub mod html_stack;
pub mod junit;
pub mod materials;
pub mod parquet;
pub mod plot;
pub mod robust;
pub mod stack;
pub mod stack_robust;
pub mod stack_sweep;
pub mod sweep;
pub mod verify;
pub mod verify_stack;
pub mod write;
pub use check::{human, json, scene};
pub use sweep::{SWEEP, sweep};
pub use write::{is_broken_pipe, stdout, write_file, write_with};

/// Version of the JSON documents' shape (`schema_version`; the schemas in `src/report/schema/`).
pub const SCHEMA_VERSION: u32 = 1;

/// The JSON Schema of `coatcheck check --format json` for one scene.
pub const CHECK_SCHEMA: &str = include_str!("schema/check.schema.json");
/// The JSON Schema of a batch (`coatcheck check DIR --format json`); its `record` is also the
/// shape of every `check --format csv` row.
pub const BATCH_SCHEMA: &str = include_str!("schema/batch.schema.json");
/// The JSON Schema of `coatcheck check --sweep-thickness --format json`.
pub const SWEEP_SCHEMA: &str = include_str!("schema/sweep.schema.json");
/// The JSON Schema of `coatcheck verify --format json`.
pub const VERIFY_SCHEMA: &str = include_str!("schema/verify.schema.json");
/// The JSON Schema of `coatcheck psd --format json`.
pub const PSD_SCHEMA: &str = include_str!("schema/psd.schema.json");
/// The JSON Schema of `coatcheck materials --format json`.
pub const MATERIALS_SCHEMA: &str = include_str!("schema/materials.schema.json");
/// The JSON Schema of `coatcheck response --format json`.
pub const RESPONSE_SCHEMA: &str = include_str!("schema/response.schema.json");

/// Output format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Table,
    Json,
    Csv,
}

/// Refuse a report that shows a number that is not finite: no command prints NaN or inf
/// ([`finite`], the one guard every output goes through).
pub fn finite_only(text: &str) -> Result<(), Error> {
    finite::check_text(text)
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
pub fn modulus(pa: f64) -> String {
    let (scale, unit) = if pa >= 1e9 {
        (1e9, "GPa")
    } else if pa >= 1e6 {
        (1e6, "MPa")
    } else {
        (1e3, "kPa")
    };
    format!("{} {unit}", sig(pa / scale, 4))
}

/// A stress in MPa, 4 significant digits (the number only).
pub fn mpa(pa: f64) -> String {
    sig(pa * 1e-6, 4)
}

/// A length in µm, 4 significant digits (the number only).
pub fn um(m: f64) -> String {
    sig(m * 1e6, 4)
}

/// A check's margin (unused fraction of its limit; < 0 fails) as the tables show it: "+62.1 %".
pub fn margin_cell(margin: Option<f64>) -> String {
    margin.map_or("-".into(), |m| format!("{:+.1} %", 100.0 * m))
}

/// A check's utilisation (value/limit, or d_min/d for the thickness: 1 − margin) as the tables
/// show it: "37.9 %".
pub fn utilisation_cell(margin: Option<f64>) -> String {
    margin.map_or("-".into(), |m| format!("{:.1} %", 100.0 * (1.0 - m)))
}

/// Columns every human table and line of prose fits in.
pub const WIDTH: usize = 100;

/// A human table: the one look of every command's tables, at most [`WIDTH`] columns wide
/// (cells wrap at spaces when the content would be wider).
pub fn table(header: &[&str]) -> Table {
    let mut t = Table::new();
    t.load_preset(UTF8_FULL_CONDENSED)
        .set_content_arrangement(ContentArrangement::Dynamic)
        .set_width(WIDTH as u16);
    t.set_header(header.iter().copied());
    t
}

/// `text` wrapped at spaces to lines of at most [`WIDTH`] characters; a line keeps its leading
/// spaces and its continuation lines are indented two more (a word longer than a line stays
/// whole).
pub fn wrap(text: &str) -> String {
    let mut out = Vec::new();
    for para in text.split('\n') {
        let body = para.trim_start_matches(' ');
        let indent = " ".repeat(para.len() - body.len());
        let mut line = indent.clone();
        let mut empty = true;
        for word in body.split(' ') {
            let len = line.chars().count();
            if !empty && len + 1 + word.chars().count() > WIDTH {
                out.push(std::mem::replace(&mut line, format!("{indent}  {word}")));
            } else {
                if !empty {
                    line.push(' ');
                }
                line += word;
            }
            empty = false;
        }
        out.push(line);
    }
    out.join("\n")
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
    fn prose_wraps_at_the_width_and_keeps_every_word() {
        let text = "word ".repeat(60) + "end";
        let w = wrap(&text);
        assert!(w.lines().all(|l| l.chars().count() <= WIDTH), "{w}");
        assert!(
            w.lines()
                .skip(1)
                .all(|l| l.starts_with("  word") || l.starts_with("  end"))
        );
        assert_eq!(
            w.split_whitespace().collect::<Vec<_>>(),
            text.split_whitespace().collect::<Vec<_>>()
        );
        assert_eq!(wrap("short\nlines"), "short\nlines");
        let item = wrap(&format!("  - {}", "x ".repeat(60)));
        assert!(item.starts_with("  - x") && item.lines().nth(1).unwrap().starts_with("    x"));
        let t = format!("{}", {
            let mut t = table(&["a", "b"]);
            t.add_row(vec!["x".to_string(), "long words ".repeat(30)]);
            t
        });
        assert!(t.lines().all(|l| l.chars().count() <= WIDTH), "{t}");
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
