//! Gwyddion native files (.gwy, the "GWYP" serialisation documented in Gwyddion's user guide,
//! "Gwyddion native file format"). After the magic `GWYP`, one serialised object: its type
//! name (NUL-terminated), its data size (u32, little-endian), then its components, each a name
//! (NUL-terminated), a type character and a value: `b` bool and `c` char (1 byte), `i` i32,
//! `q` i64, `d` f64, `s` NUL-terminated string, `o` an object; `C`, `I`, `Q`, `D`, `S`, `O`
//! arrays of those (a u32 count, then the items).
//!
//! The top object is a `GwyContainer`; each channel N is its component `/N/data`, a
//! `GwyDataField` with `xres`, `yres` (points), `xreal`, `yreal` (physical size), `si_unit_xy`,
//! `si_unit_z` (`GwySIUnit` objects whose `unitstr` is the unit) and `data` (xres·yres doubles,
//! x fastest); `/N/data/title` names it and `/N/mask`, when present, is a field whose values
//! above 0.5 mark points taken out (read as not measured, as SurfaceTopography does).
//! Values and sizes are in base SI units whatever prefix a unit string carries (Gwyddion
//! ignores it on reading): a field is a height map when its z unit is a length.

use std::path::Path;

use super::bytes::{Le, grid_points};
use super::{Channel, Reading, bad};
use crate::Error;
use crate::units::{Dim, to_si};

const MAGIC: &[u8] = b"GWYP";
/// Deepest nesting of objects accepted (Gwyddion's files nest 3 or 4 levels).
const MAX_DEPTH: usize = 32;

pub(crate) fn sniff(b: &[u8]) -> bool {
    b.starts_with(MAGIC)
}

/// A component's value; arrays of numbers are kept as their place in the file.
enum Value {
    Int(i64),
    Double(f64),
    Str(String),
    Object(Object),
    Doubles { at: usize, n: usize },
    Other,
}

struct Object {
    name: String,
    components: Vec<(String, Value)>,
}

impl Object {
    fn get(&self, key: &str) -> Option<&Value> {
        self.components
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v)
    }
}

/// A NUL-terminated string at `at`, and the offset after it.
fn cstring(le: &Le, at: usize, what: &str) -> Result<(String, usize), Error> {
    let rest = le.b.get(at..).unwrap_or_default();
    let end = rest.iter().position(|&c| c == 0).ok_or_else(|| {
        bad(
            le.path,
            format!("byte {at}: {what} is not NUL-terminated before the end of the file (truncated file?)"),
        )
    })?;
    Ok((
        String::from_utf8_lossy(&rest[..end]).into_owned(),
        at + end + 1,
    ))
}

/// The object at `at`, and the offset after it.
fn object(le: &Le, at: usize, depth: usize) -> Result<(Object, usize), Error> {
    if depth > MAX_DEPTH {
        return Err(bad(
            le.path,
            format!("byte {at}: objects nested deeper than {MAX_DEPTH}"),
        ));
    }
    let (name, at) = cstring(le, at, "object name")?;
    let size = le.u32(at, "object size")? as usize;
    let start = at + 4;
    let end = start
        .checked_add(size)
        .filter(|&e| e <= le.b.len())
        .ok_or_else(|| {
            bad(
                le.path,
                format!(
                    "byte {at}: object '{name}' claims {size} bytes, the file ends at byte {} \
                     (truncated file?)",
                    le.b.len()
                ),
            )
        })?;
    let mut components = Vec::new();
    let mut p = start;
    while p < end {
        let (key, q) = cstring(le, p, "component name")?;
        let ty = le.slice(q, 1, "component type")?[0];
        let (value, next) = component(le, q + 1, ty, &key, depth)?;
        components.push((key, value));
        p = next;
    }
    if p != end {
        return Err(bad(
            le.path,
            format!(
                "byte {p}: the components of object '{name}' overrun its size ({size} bytes from byte {start})"
            ),
        ));
    }
    Ok((Object { name, components }, end))
}

/// The value of type `ty` at `at` (of component `key`), and the offset after it.
fn component(le: &Le, at: usize, ty: u8, key: &str, depth: usize) -> Result<(Value, usize), Error> {
    let array = |width: usize| -> Result<(usize, usize), Error> {
        let n = le.u32(at, "array length")? as usize;
        le.slice(at + 4, n.saturating_mul(width), &format!("array '{key}'"))?;
        Ok((n, at + 4 + n * width))
    };
    Ok(match ty {
        b'b' | b'c' => (Value::Other, le.slice(at, 1, key).map(|_| at + 1)?),
        b'i' => (Value::Int(le.i32(at, key)?.into()), at + 4),
        b'q' => (
            Value::Int(i64::from_le_bytes(
                le.slice(at, 8, key)?.try_into().expect("8"),
            )),
            at + 8,
        ),
        b'd' => (Value::Double(le.f64(at, key)?), at + 8),
        b's' => {
            let (s, next) = cstring(le, at, key)?;
            (Value::Str(s), next)
        }
        b'o' => {
            let (o, next) = object(le, at, depth + 1)?;
            (Value::Object(o), next)
        }
        b'C' => (Value::Other, array(1)?.1),
        b'I' => (Value::Other, array(4)?.1),
        b'Q' => (Value::Other, array(8)?.1),
        b'D' => {
            let (n, next) = array(8)?;
            (Value::Doubles { at: at + 4, n }, next)
        }
        b'S' | b'O' => {
            let n = le.u32(at, "array length")?;
            let mut p = at + 4;
            for _ in 0..n {
                p = if ty == b'S' {
                    cstring(le, p, key)?.1
                } else {
                    object(le, p, depth + 1)?.1
                };
            }
            (Value::Other, p)
        }
        t => {
            return Err(bad(
                le.path,
                format!(
                    "byte {}: component '{key}' has type '{}' (expected one of bciqdsoCIQDSO)",
                    at - 1,
                    t as char
                ),
            ));
        }
    })
}

pub(crate) fn read(path: &Path, b: &[u8]) -> Result<Reading, Error> {
    let le = Le { path, b };
    if !b.starts_with(MAGIC) {
        return Err(bad(path, "byte 0: expected the Gwyddion signature 'GWYP'"));
    }
    let (top, _) = object(&le, 4, 0)?;
    if top.name != "GwyContainer" {
        return Err(bad(
            path,
            format!(
                "byte 4: the top object is '{}' (expected GwyContainer)",
                top.name
            ),
        ));
    }
    let mut fields: Vec<(usize, &Object)> = top
        .components
        .iter()
        .filter_map(|(k, v)| {
            let n = k.strip_prefix('/')?.strip_suffix("/data")?.parse().ok()?;
            match v {
                Value::Object(o) if o.name == "GwyDataField" => Some((n, o)),
                _ => None,
            }
        })
        .collect();
    fields.sort_by_key(|(n, _)| *n);
    if fields.is_empty() {
        return Err(bad(
            path,
            "no channel: the container has no '/N/data' GwyDataField",
        ));
    }
    let channels = fields
        .into_iter()
        .map(|(n, field)| {
            let mask = match top.get(&format!("/{n}/mask")) {
                Some(Value::Object(m)) if m.name == "GwyDataField" => Some(m),
                _ => None,
            };
            let title = match top.get(&format!("/{n}/data/title")) {
                Some(Value::Str(s)) => s.clone(),
                _ => format!("/{n}/data"),
            };
            channel(&le, n, field, mask, title)
        })
        .collect::<Result<_, _>>()?;
    Ok(Reading {
        format: "gwy",
        channels,
    })
}

/// The unit string of the `GwySIUnit` component `key` of `field` (empty: dimensionless).
fn unit(field: &Object, key: &str) -> String {
    match field.get(key) {
        Some(Value::Object(u)) => match u.get("unitstr") {
            Some(Value::Str(s)) => s.clone(),
            _ => String::new(),
        },
        _ => String::new(),
    }
}

/// The values of the data field `field` of channel `n`, checked against its resolution.
fn values(le: &Le, n: usize, field: &Object) -> Result<(usize, usize, Vec<f64>), Error> {
    let path = le.path;
    let int = |key: &str| match field.get(key) {
        Some(Value::Int(v)) => Ok(*v),
        _ => Err(bad(
            path,
            format!("channel /{n}/data has no integer '{key}'"),
        )),
    };
    let (nx, ny) = (int("xres")?, int("yres").unwrap_or(1));
    let Some(Value::Doubles { at, n: count }) = field.get("data") else {
        return Err(bad(
            path,
            format!("channel /{n}/data has no double array 'data'"),
        ));
    };
    let points = grid_points(path, nx, ny, 8, *at, le.b.len())?;
    if points != *count {
        return Err(bad(
            path,
            format!(
                "byte {}: channel /{n}/data holds {count} values, xres × yres = {nx} × {ny}",
                at - 4
            ),
        ));
    }
    let z = le.b[*at..at + 8 * points]
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
        .collect();
    Ok((nx as usize, ny as usize, z))
}

fn channel(
    le: &Le,
    n: usize,
    field: &Object,
    mask: Option<&Object>,
    name: String,
) -> Result<Channel, Error> {
    let path = le.path;
    let (nx, ny, mut z) = values(le, n, field)?;
    let real = |key: &str| match field.get(key) {
        Some(Value::Double(v)) if v.is_finite() && *v != 0.0 => Ok(v.abs()),
        Some(Value::Double(v)) => Err(bad(
            path,
            format!("channel /{n}/data: {key} = {v} (expected a finite size)"),
        )),
        _ => Err(bad(
            path,
            format!("channel /{n}/data has no double '{key}'"),
        )),
    };
    let xreal = real("xreal")?;
    let yreal = if ny == 1 && field.get("yreal").is_none() {
        xreal / nx as f64
    } else {
        real("yreal")?
    };
    let xy_unit = unit(field, "si_unit_xy");
    to_si(1.0, &xy_unit, Dim::Length(1)).map_err(|e| {
        bad(
            path,
            format!("channel /{n}/data: lateral unit '{xy_unit}': {e}"),
        )
    })?;
    let z_unit = unit(field, "si_unit_z");
    let is_height = !z_unit.is_empty() && to_si(1.0, &z_unit, Dim::Length(1)).is_ok();
    if let Some(m) = mask {
        let (mx, my, m) = values(le, n, m)?;
        if (mx, my) != (nx, ny) {
            return Err(bad(
                path,
                format!("mask /{n}/mask is {mx} × {my}, its channel {nx} × {ny}"),
            ));
        }
        z.iter_mut()
            .zip(m)
            .filter(|(_, m)| *m > 0.5)
            .for_each(|(v, _)| *v = f64::NAN);
    }
    Ok(Channel {
        name,
        nx,
        ny,
        dx: xreal / nx as f64,
        dy: yreal / ny as f64,
        z,
        unit_in_file: z_unit,
        is_height,
    })
}
