//! Gwyddion's plain-text matrix export: a header of `# Key: value` lines (`# Channel:` the
//! channel's name, `# Width:` and `# Height:` the physical size along x and y with their unit,
//! `# Value units:` the unit of the values), then one row of the map per line, values
//! separated by blanks, x along the line. Gwyddion translates the labels; those of its user
//! interface languages are accepted. `nan` marks a point that was not measured.

use std::path::Path;

use super::{Channel, Reading, bad_line};
use crate::Error;
use crate::units::{Dim, to_si};

const CHANNEL: &[&str] = &[
    "Channel",
    "Kanál",
    "Kanal",
    "Canal",
    "Canale",
    "チャネル",
    "채널",
    "Канал",
];
const WIDTH: &[&str] = &[
    "Width",
    "Šířka",
    "Breite",
    "Anchura",
    "Largeur",
    "Larghezza",
    "幅",
    "폭",
    "Largura",
    "Ширина",
];
const HEIGHT: &[&str] = &[
    "Height",
    "Výška",
    "Höhe",
    "Altura",
    "Hauteur",
    "Altezza",
    "高さ",
    "높이",
    "Высота",
];
const VALUE_UNITS: &[&str] = &[
    "Value units",
    "Jednotky hodnot",
    "Einheiten",
    "Unités",
    "unità valore",
    "値の単位",
    "값 단위",
    "Unidades de valor",
    "Единицы измерения",
];

/// The header line's label (one of `labels`) and value, for a line `# Label: value` (the
/// Japanese translation uses a full-width colon).
fn field<'a>(line: &'a str, labels: &[&str]) -> Option<&'a str> {
    let rest = line.strip_prefix('#')?.trim_start();
    labels.iter().find_map(|l| {
        let after = rest.strip_prefix(l)?.trim_start();
        after
            .strip_prefix(':')
            .or_else(|| after.strip_prefix('：'))
            .map(str::trim)
    })
}

pub(crate) fn sniff(b: &[u8]) -> bool {
    let head = &b[..b.len().min(4096)];
    let text = match std::str::from_utf8(head) {
        Ok(t) => t,
        Err(e) => std::str::from_utf8(&head[..e.valid_up_to()]).unwrap_or_default(),
    };
    let header: Vec<&str> = text
        .trim_start_matches('\u{feff}')
        .lines()
        .take_while(|l| l.starts_with('#'))
        .collect();
    header.iter().any(|l| field(l, WIDTH).is_some())
        && header.iter().any(|l| field(l, HEIGHT).is_some())
}

/// A length with its unit, e.g. `12.34 µm`, in metres.
fn length(path: &Path, no: usize, what: &str, text: &str) -> Result<f64, Error> {
    let split = text
        .find(|c: char| !(c.is_ascii_digit() || "+-.eE".contains(c)))
        .unwrap_or(text.len());
    let (num, unit) = text.split_at(split);
    let value = num.trim().parse::<f64>().ok();
    match value.map(|v| to_si(v, unit.trim(), Dim::Length(1))) {
        Some(Ok(v)) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(bad_line(
            path,
            no,
            format!("{what} '{text}' (expected a length > 0 with its unit, e.g. '10 µm')"),
        )),
    }
}

pub(crate) fn read(path: &Path, b: &[u8]) -> Result<Reading, Error> {
    let text = std::str::from_utf8(b).map_err(|e| {
        bad_line(
            path,
            1,
            format!("not UTF-8 text (byte {})", e.valid_up_to()),
        )
    })?;
    let text = text.trim_start_matches('\u{feff}');
    let (mut name, mut width, mut height, mut unit) = (None, None, None, None);
    let mut z = Vec::new();
    let (mut nx, mut ny, mut last) = (0, 0, 0);
    for (i, line) in text.lines().enumerate() {
        let no = i + 1;
        last = no;
        let line = line.trim();
        if line.starts_with('#') {
            if let Some(v) = field(line, CHANNEL) {
                name = Some(v.to_string());
            } else if let Some(v) = field(line, WIDTH) {
                width = Some(length(path, no, "Width", v)?);
            } else if let Some(v) = field(line, HEIGHT) {
                height = Some(length(path, no, "Height", v)?);
            } else if let Some(v) = field(line, VALUE_UNITS) {
                unit = Some(v.to_string());
            }
            continue;
        }
        if line.is_empty() {
            continue;
        }
        let before = z.len();
        for tok in line.split_whitespace() {
            let v = if tok.eq_ignore_ascii_case("nan") {
                f64::NAN
            } else {
                tok.parse::<f64>()
                    .map_err(|_| bad_line(path, no, format!("'{tok}' is not a number")))?
            };
            z.push(v);
        }
        let count = z.len() - before;
        if ny == 0 {
            nx = count;
        } else if count != nx {
            return Err(bad_line(
                path,
                no,
                format!("{count} values, the rows above have {nx} (truncated file?)"),
            ));
        }
        ny += 1;
    }
    let (Some(width), Some(height)) = (width, height) else {
        return Err(bad_line(
            path,
            1,
            "the header needs '# Width:' and '# Height:' lines (Gwyddion's export)",
        ));
    };
    if ny == 0 {
        return Err(bad_line(path, last, "no rows of values after the header"));
    }
    let unit = unit.unwrap_or_else(|| "m".into());
    let scale = to_si(1.0, &unit, Dim::Length(1)).ok();
    if let Some(s) = scale {
        z.iter_mut().for_each(|v| *v *= s);
    }
    Ok(Reading {
        format: "gwyddion-txt",
        channels: vec![Channel {
            name: name.unwrap_or_else(|| "gwyddion-txt".into()),
            nx,
            ny,
            dx: width / nx as f64,
            dy: height / ny as f64,
            z,
            unit_in_file: unit,
            is_height: scale.is_some(),
        }],
    })
}
