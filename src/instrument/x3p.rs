//! ISO 25178-72 XML 3D surface profile (X3P, formerly ISO 5436-2): a ZIP archive holding
//! `main.xml` and, usually, the heights in a binary member (`bindata/data.bin`).
//!
//! `main.xml` gives, in Record1, the feature type (`SUR` a map, `PRF` a profile), the axes
//! CX, CY (incremental, `AxisType` I, with `Increment` the pixel size in metres) and CZ
//! (absolute, `AxisType` A, `DataType` I, L, F or D: 16- or 32-bit signed integers, 32- or
//! 64-bit floats, little-endian; optional `Increment` and `Offset`: the height in metres is
//! raw · increment plus offset); in Record3 the grid (`SizeX`, `SizeY`, `SizeZ` = 1) and either a
//! `DataLink` (`PointDataLink`, the binary member, x fastest; optional `ValidPointsLink`, one
//! bit per point, least-significant bit first, 1 = measured) or a `DataList` of `Datum`
//! elements (an empty one is not measured). A NaN height is not measured either.

use std::path::Path;

use super::xml::{self, Element};
use super::zip::{self, Archive};
use super::{Channel, Reading, bad};
use crate::Error;

pub(crate) fn sniff(b: &[u8]) -> bool {
    b.starts_with(zip::MAGIC)
        && Archive::open(Path::new(""), b).is_ok_and(|a| a.find("main.xml").is_some())
}

pub(crate) fn read(path: &Path, b: &[u8]) -> Result<Reading, Error> {
    let archive = Archive::open(path, b)?;
    let main = archive.extract_named("main.xml", "not an X3P file")?;
    let doc = xml::parse(path, "main.xml", &main)?;
    let axes = doc
        .at(&["Record1", "Axes"])
        .ok_or_else(|| bad(path, "main.xml: no Record1/Axes"))?;
    let feature = doc.text_at(&["Record1", "FeatureType"]).unwrap_or("SUR");
    if feature != "SUR" && feature != "PRF" {
        return Err(bad(
            path,
            format!("main.xml: FeatureType '{feature}' (expected SUR, a map, or PRF, a profile)"),
        ));
    }
    let dx = lateral_increment(path, axes, "CX")?;
    let size = |name: &str| -> Result<usize, Error> {
        let text = doc
            .text_at(&["Record3", "MatrixDimension", name])
            .ok_or_else(|| bad(path, format!("main.xml: no Record3/MatrixDimension/{name}")))?;
        text.parse::<usize>()
            .ok()
            .filter(|&n| n >= 1)
            .ok_or_else(|| {
                bad(
                    path,
                    format!("main.xml: {name} '{text}' (expected an integer >= 1)"),
                )
            })
    };
    let (nx, ny, nz) = (size("SizeX")?, size("SizeY")?, size("SizeZ")?);
    if nz != 1 {
        return Err(bad(
            path,
            format!("main.xml: SizeZ = {nz} (expected 1: layered data are not supported)"),
        ));
    }
    let dy = if ny == 1 && axes.child("CY").is_none() {
        dx
    } else {
        lateral_increment(path, axes, "CY")?
    };
    let cz = axes
        .child("CZ")
        .ok_or_else(|| bad(path, "main.xml: no Record1/Axes/CZ"))?;
    if let Some(t) = cz.text_at(&["AxisType"]).filter(|&t| t != "A") {
        return Err(bad(
            path,
            format!("main.xml: CZ AxisType '{t}' (expected A, absolute heights)"),
        ));
    }
    let number = |name: &str, default: f64| -> Result<f64, Error> {
        cz.text_at(&[name]).map_or(Ok(default), |t| {
            t.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(path, format!("main.xml: CZ {name} '{t}' is not a number")))
        })
    };
    let (increment, offset) = (number("Increment", 1.0)?, number("Offset", 0.0)?);
    let data_type = cz.text_at(&["DataType"]).unwrap_or("D");
    let record3 = doc
        .child("Record3")
        .ok_or_else(|| bad(path, "main.xml: no Record3"))?;
    let raw = match record3.child("DataLink") {
        Some(link) => linked_points(path, &archive, link, data_type, nx * ny)?,
        None => listed_points(path, record3, nx * ny)?,
    };
    let z = raw
        .into_iter()
        .map(|v| {
            if v.is_finite() {
                v * increment + offset
            } else {
                f64::NAN
            }
        })
        .collect();
    Ok(Reading {
        format: "x3p",
        channels: vec![Channel {
            name: "x3p".into(),
            nx,
            ny,
            dx,
            dy,
            z,
            unit_in_file: "m".into(),
            is_height: true,
        }],
    })
}

/// The pixel size of the incremental axis `name` (CX or CY), m.
fn lateral_increment(path: &Path, axes: &Element, name: &str) -> Result<f64, Error> {
    let axis = axes
        .child(name)
        .ok_or_else(|| bad(path, format!("main.xml: no Record1/Axes/{name}")))?;
    match axis.text_at(&["AxisType"]) {
        Some("I") => {}
        t => {
            return Err(bad(
                path,
                format!(
                    "main.xml: {name} AxisType '{}' (expected I, incremental: point lists with \
                     absolute x, y are not supported)",
                    t.unwrap_or("")
                ),
            ));
        }
    }
    let text = axis.text_at(&["Increment"]).unwrap_or("");
    text.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v > 0.0)
        .ok_or_else(|| {
            bad(
                path,
                format!("main.xml: {name} Increment '{text}' (expected > 0)"),
            )
        })
}

/// Heights from the binary member named by `PointDataLink`, NaN where `ValidPointsLink` says
/// a point was not measured.
fn linked_points(
    path: &Path,
    archive: &Archive,
    link: &Element,
    data_type: &str,
    n: usize,
) -> Result<Vec<f64>, Error> {
    let width = match data_type {
        "I" => 2,
        "L" | "F" => 4,
        "D" => 8,
        t => {
            return Err(bad(
                path,
                format!("main.xml: CZ DataType '{t}' (expected I, L, F or D)"),
            ));
        }
    };
    let member = link
        .text_at(&["PointDataLink"])
        .ok_or_else(|| bad(path, "main.xml: DataLink has no PointDataLink"))?;
    let entry = archive.find(member).ok_or_else(|| {
        bad(
            path,
            format!("the archive has no member '{member}' (PointDataLink)"),
        )
    })?;
    if entry.size() != n.saturating_mul(width) {
        return Err(bad(
            path,
            format!(
                "'{member}' holds {} bytes; the grid of {n} points of type {data_type} needs {}",
                entry.size(),
                n.saturating_mul(width)
            ),
        ));
    }
    let data = archive.extract(entry)?;
    let mut z: Vec<f64> = match data_type {
        "I" => data
            .chunks_exact(2)
            .map(|c| f64::from(i16::from_le_bytes([c[0], c[1]])))
            .collect(),
        "L" => data
            .chunks_exact(4)
            .map(|c| f64::from(i32::from_le_bytes([c[0], c[1], c[2], c[3]])))
            .collect(),
        "F" => data
            .chunks_exact(4)
            .map(|c| f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]])))
            .collect(),
        _ => data
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
            .collect(),
    };
    if let Some(valid) = link.text_at(&["ValidPointsLink"]).filter(|v| !v.is_empty()) {
        let entry = archive.find(valid).ok_or_else(|| {
            bad(
                path,
                format!("the archive has no member '{valid}' (ValidPointsLink)"),
            )
        })?;
        if entry.size() != n.div_ceil(8) {
            return Err(bad(
                path,
                format!(
                    "'{valid}' holds {} bytes; one bit for each of {n} points needs {}",
                    entry.size(),
                    n.div_ceil(8)
                ),
            ));
        }
        let bits = archive.extract(entry)?;
        for (i, v) in z.iter_mut().enumerate() {
            if bits[i / 8] >> (i % 8) & 1 == 0 {
                *v = f64::NAN;
            }
        }
    }
    Ok(z)
}

/// Heights listed in main.xml as `Record3/DataList/Datum`; an empty datum is not measured.
fn listed_points(path: &Path, record3: &Element, n: usize) -> Result<Vec<f64>, Error> {
    let list = record3
        .child("DataList")
        .ok_or_else(|| bad(path, "main.xml: Record3 has neither DataLink nor DataList"))?;
    let data: Vec<&Element> = list.children.iter().filter(|e| e.name == "Datum").collect();
    if data.len() != n {
        return Err(bad(
            path,
            format!(
                "main.xml: DataList has {} Datum elements, the grid has {n} points",
                data.len()
            ),
        ));
    }
    data.iter()
        .enumerate()
        .map(|(i, d)| {
            let t = d.text.trim();
            if t.is_empty() {
                return Ok(f64::NAN);
            }
            t.parse::<f64>().map_err(|_| {
                bad(
                    path,
                    format!("main.xml: Datum {} is '{t}' (expected a number)", i + 1),
                )
            })
        })
        .collect()
}
