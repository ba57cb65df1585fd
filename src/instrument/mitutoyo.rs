//! Mitutoyo SurfTest spreadsheet export (.xlsx, one profile). An .xlsx file is a ZIP archive
//! of XML parts (ECMA-376 / ISO 29500): `xl/workbook.xml` lists the sheets with their
//! relationship ids, `xl/_rels/workbook.xml.rels` maps those to the sheets' parts,
//! `xl/sharedStrings.xml` holds the text of cells of type `s`; a sheet's `sheetData` has rows
//! of cells `<c r="E1" t="…"><v>…</v></c>`.
//!
//! SurfTest layout (as SurfaceTopography reads it): on the sheet `DATA`, column E the position
//! and column F the height, one point per row; column A the roughness parameters
//! (`Ra 0.018 µm`), whose unit is the height unit; on the sheet `Certificate`, the cell right
//! of `Cut-Off` (e.g. `0.08mm`), whose unit is the position unit. The pixel size is the mean
//! step of the positions, which must be uniform (see `uniform_step`).

use std::path::Path;

use super::xml::{self, Element};
use super::zip::{self, Archive};
use super::{Reading, bad, uniform_step};
use crate::Error;
use crate::units::{Dim, to_si};

pub(crate) fn sniff(b: &[u8]) -> bool {
    b.starts_with(zip::MAGIC)
        && Archive::open(Path::new(""), b).is_ok_and(|a| a.find("xl/workbook.xml").is_some())
}

/// A cell: column letters, row number, text, and whether it holds text (else a number).
struct Cell {
    col: String,
    row: usize,
    text: String,
    is_text: bool,
}

/// The cells of the sheet named `name`, in document order.
fn sheet_cells(
    path: &Path,
    archive: &Archive,
    workbook: &Element,
    rels: &Element,
    shared: &[String],
    name: &str,
) -> Result<Vec<Cell>, Error> {
    let id = workbook
        .child("sheets")
        .and_then(|s| s.children.iter().find(|c| c.attr("name") == Some(name)))
        .and_then(|s| s.attr("id"))
        .ok_or_else(|| bad(path, format!("xl/workbook.xml: no sheet named '{name}'")))?;
    let target = rels
        .children
        .iter()
        .find(|r| r.attr("Id") == Some(id))
        .and_then(|r| r.attr("Target"))
        .ok_or_else(|| {
            bad(
                path,
                format!("xl/_rels/workbook.xml.rels: no relationship '{id}'"),
            )
        })?;
    let member = match target.strip_prefix('/') {
        Some(abs) => abs.to_string(),
        None => format!("xl/{target}"),
    };
    let sheet = xml::parse(path, &member, &archive.extract_named(&member, "sheet")?)?;
    let mut cells = Vec::new();
    for row in sheet.child("sheetData").map_or(&[][..], |d| &d.children) {
        for c in row.children.iter().filter(|c| c.name == "c") {
            let r = c.attr("r").unwrap_or("");
            let split = r.find(|ch: char| ch.is_ascii_digit()).unwrap_or(r.len());
            let (col, num) = r.split_at(split);
            let row_no = num
                .parse()
                .map_err(|_| bad(path, format!("{member}: cell reference '{r}'")))?;
            let (text, is_text) = match c.attr("t") {
                Some("s") => {
                    let t = c.text_at(&["v"]).unwrap_or("");
                    let s = t
                        .parse::<usize>()
                        .ok()
                        .and_then(|i| shared.get(i))
                        .ok_or_else(|| {
                            bad(
                                path,
                                format!("{member}, cell {r}: shared string '{t}' does not exist"),
                            )
                        })?;
                    (s.clone(), true)
                }
                Some("inlineStr") => (c.at(&["is"]).map(all_text).unwrap_or_default(), true),
                Some("str") => (c.text_at(&["v"]).unwrap_or("").to_string(), true),
                _ => (c.text_at(&["v"]).unwrap_or("").to_string(), false),
            };
            cells.push(Cell {
                col: col.to_string(),
                row: row_no,
                text,
                is_text,
            });
        }
    }
    Ok(cells)
}

/// The text of all `t` elements under `e` (a shared string may be split in formatted runs).
fn all_text(e: &Element) -> String {
    let mut s = if e.name == "t" {
        e.text.clone()
    } else {
        String::new()
    };
    for c in &e.children {
        s.push_str(&all_text(c));
    }
    s
}

/// The unit after a leading number, e.g. `mm` in `0.08mm` or `µm` in `Ra 0.018 µm`.
fn unit_after_number(text: &str) -> Option<String> {
    let words: Vec<&str> = text.split_whitespace().collect();
    if let [_, value, unit, ..] = words[..]
        && value.parse::<f64>().is_ok()
    {
        return Some(unit.to_string());
    }
    let t = text.trim();
    let split = t.find(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == '+'))?;
    (split > 0 && t[..split].parse::<f64>().is_ok()).then(|| t[split..].trim().to_string())
}

pub(crate) fn read(path: &Path, b: &[u8]) -> Result<Reading, Error> {
    let archive = Archive::open(path, b)?;
    let workbook = xml::parse(
        path,
        "xl/workbook.xml",
        &archive.extract_named("xl/workbook.xml", "not an .xlsx file")?,
    )?;
    let rels_name = "xl/_rels/workbook.xml.rels";
    let rels = xml::parse(
        path,
        rels_name,
        &archive.extract_named(rels_name, "not an .xlsx file")?,
    )?;
    let shared: Vec<String> = match archive.find("xl/sharedStrings.xml") {
        Some(e) => xml::parse(path, "xl/sharedStrings.xml", &archive.extract(e)?)?
            .children
            .iter()
            .map(all_text)
            .collect(),
        None => Vec::new(),
    };
    let data = sheet_cells(path, &archive, &workbook, &rels, &shared, "DATA")?;
    let cert = sheet_cells(path, &archive, &workbook, &rels, &shared, "Certificate")?;
    let cut_off = cert
        .iter()
        .position(|c| c.text.trim().eq_ignore_ascii_case("Cut-Off"))
        .and_then(|i| cert.get(i + 1).filter(|n| n.row == cert[i].row))
        .ok_or_else(|| bad(path, "sheet 'Certificate': no cell right of 'Cut-Off'"))?;
    let x_unit = unit_after_number(&cut_off.text).ok_or_else(|| {
        bad(
            path,
            format!(
                "sheet 'Certificate', cell {}{}: cut-off '{}' has no unit",
                cut_off.col, cut_off.row, cut_off.text
            ),
        )
    })?;
    let z_unit = data
        .iter()
        .filter(|c| c.col == "A" && c.is_text)
        .find_map(|c| unit_after_number(&c.text))
        .unwrap_or_else(|| x_unit.clone());
    let scale = |unit: &str| {
        to_si(1.0, unit, Dim::Length(1))
            .map_err(|e| bad(path, format!("unit '{unit}' of the profile: {e}")))
    };
    let (sx, sz) = (scale(&x_unit)?, scale(&z_unit)?);
    let column = |col: &str| -> Result<Vec<f64>, Error> {
        data.iter()
            .filter(|c| c.col == col && !c.text.trim().is_empty())
            .map(|c| {
                c.text
                    .trim()
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite() && !c.is_text)
                    .ok_or_else(|| {
                        bad(
                            path,
                            format!(
                                "sheet 'DATA', cell {col}{}: '{}' is not a number",
                                c.row, c.text
                            ),
                        )
                    })
            })
            .collect()
    };
    let (x, z) = (column("E")?, column("F")?);
    let n = z.len();
    if x.len() != n || n < 2 {
        return Err(bad(
            path,
            format!(
                "sheet 'DATA': {} positions (column E) and {n} heights (column F); expected as \
                 many, at least 2",
                x.len()
            ),
        ));
    }
    let dx = uniform_step(&x).map_err(|i| {
        bad(
            path,
            format!(
                "sheet 'DATA': position {} (column E) is off the uniform grid",
                i + 1
            ),
        )
    })?;
    Ok(super::profile_reading(
        "mitutoyo",
        "mitutoyo".into(),
        dx * sx,
        z.into_iter().map(|v| v * sz).collect(),
        z_unit,
    ))
}
