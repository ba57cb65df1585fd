//! The `[[layer]]` tables of a layer stack, top first, validated into [`SceneLayer`]s (SI), and
//! `criteria.thickness_of`, the layer whose minimum thickness is sought.
//!
//! ```toml
//! [[layer]]
//! name = "rubber"
//! material = "paper-rubber"   # or youngs_modulus, poisson_ratio
//! thickness = "10 um"
//! bond = "chemlok-type"       # the bond to what lies below: a bond by name, or "5 MPa"
//! youngs_modulus_range = ["4 MPa", "8 MPa"]  # optional, for --robust (replaces the library's;
//!                                            # likewise poisson_ratio_range and the bond's
//!                                            # shear_strength_range)
//! [[layer]]
//! name = "primer"
//! material = "epoxy-primer"
//! thickness = "10 um"
//! bond = "epoxy"
//! ```
//!
//! A scene gives either `[film]` (with `[bond]`) or `[[layer]]` tables, not both. One
//! `[[layer]]` is the `[film]` scene itself (its material, thickness and bond become the film's;
//! see [`super::resolve()`]): the same numbers to the last bit.

use super::keys::{Key, RawLayer};
use crate::error::Error;
use crate::layer::Elastic;
use crate::material::{Bond, Kind, Library, Material, Ranges, SpanOf, read_span};
use crate::tomlin::{Ctx, Field, Raw};
use crate::units::{Dim, parse_quantity};
use serde::Serialize;

/// One layer of a stack: its name, material, thickness (m) and the bond to what lies below.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SceneLayer {
    pub name: String,
    pub material: Material,
    pub thickness: f64,
    pub bond: Bond,
}

/// `layer[k].field`, k from 1 (top), as messages name a layer's keys.
fn key_name(k: usize, field: &str) -> String {
    format!("layer[{k}].{field}")
}

/// The layers of a stack (empty when the scene has no `[[layer]]`).
pub(super) fn resolve_layers(
    raw: &[RawLayer],
    ctx: Ctx<'_>,
    library: &Library,
) -> Result<Vec<SceneLayer>, Error> {
    if raw.len() > crate::layer::stack::MAX_LAYERS {
        return Err(ctx.missing(
            "layer",
            &format!(
                "{} [[layer]] tables given; a stack has at most {}",
                raw.len(),
                crate::layer::stack::MAX_LAYERS
            ),
        ));
    }
    let layers: Vec<SceneLayer> = raw
        .iter()
        .enumerate()
        .map(|(i, l)| resolve_layer(i + 1, l, ctx, library))
        .collect::<Result<_, _>>()?;
    for (i, a) in layers.iter().enumerate() {
        if layers[..i].iter().any(|b| b.name == a.name) {
            let f = raw[i].name.as_ref().expect("only given names can repeat");
            return Err(ctx.error(
                &f.origin,
                &key_name(i + 1, "name"),
                format!("'{}' names two layers (give each its own name)", a.name),
            ));
        }
    }
    Ok(layers)
}

fn resolve_layer(
    k: usize,
    l: &RawLayer,
    ctx: Ctx<'_>,
    library: &Library,
) -> Result<SceneLayer, Error> {
    let name = match &l.name {
        Some(f) => ctx.text(f, &key_name(k, "name"))?.to_string(),
        None => format!("layer {k}"),
    };
    let mut material = match (&l.material, &l.youngs_modulus, &l.poisson_ratio) {
        (Some(f), None, None) => {
            let key = key_name(k, "material");
            let m = library
                .material(ctx.text(f, &key)?)
                .map_err(|e| ctx.error(&f.origin, &key, e))?;
            m.clone()
        }
        (Some(_), Some(f), _) | (Some(_), None, Some(f)) => {
            return Err(ctx.error(
                &f.origin,
                &key_name(k, "youngs_modulus"),
                format!(
                    "contradicts {} (give one of them, not both)",
                    key_name(k, "material")
                ),
            ));
        }
        (None, Some(fe), Some(fnu)) => {
            let e = ctx.positive(fe, &key_name(k, "youngs_modulus"), Dim::Pressure)?;
            let nu = ctx.quantity(fnu, &key_name(k, "poisson_ratio"), Dim::Dimensionless)?;
            let elastic = Elastic::new(e, nu)
                .map_err(|err| ctx.error(&fnu.origin, &key_name(k, "poisson_ratio"), err))?;
            Material {
                name: "custom".into(),
                kind: Kind::Film,
                elastic,
                yield_strength: None,
                source: "given in the scene".into(),
                ranges: Ranges::default(),
            }
        }
        (None, Some(f), None) | (None, None, Some(f)) => {
            return Err(ctx.error(
                &f.origin,
                &format!(
                    "{} and {}",
                    key_name(k, "youngs_modulus"),
                    key_name(k, "poisson_ratio")
                ),
                "both are needed when no material is named",
            ));
        }
        (None, None, None) => {
            return Err(ctx.missing(
                &key_name(k, "material"),
                "name a material (coatcheck materials) or give youngs_modulus and poisson_ratio",
            ));
        }
    };
    let thickness = match &l.thickness {
        Some(f) => thickness(k, f, ctx)?,
        None => {
            return Err(ctx.missing(
                &key_name(k, "thickness"),
                "give each layer's thickness, e.g. thickness = \"10 um\"",
            ));
        }
    };
    let mut bond = match &l.bond {
        Some(f) => bond(k, f, ctx, library)?,
        None => {
            return Err(ctx.missing(
                &key_name(k, "bond"),
                "give the bond of each layer to what lies below: a bond by name (coatcheck \
                 materials) or its shear strength, e.g. bond = \"10 MPa\"",
            ));
        }
    };
    scene_ranges(k, l, ctx, &mut material, &mut bond)?;
    Ok(SceneLayer {
        name,
        material,
        thickness,
        bond,
    })
}

/// The layer's scene ranges (`youngs_modulus_range`, `poisson_ratio_range`,
/// `shear_strength_range`), each replacing the library's range of its property and holding its
/// nominal value, as `film.*_range` and `bond.shear_strength_range` do for a film.
fn scene_ranges(
    k: usize,
    l: &RawLayer,
    ctx: Ctx<'_>,
    material: &mut Material,
    bond: &mut Bond,
) -> Result<(), Error> {
    let (e, nu, shear) = (
        material.elastic.youngs,
        material.elastic.poisson,
        bond.shear_strength,
    );
    let fields = [
        (
            &l.youngs_modulus_range,
            "youngs_modulus_range",
            Dim::Pressure,
            SpanOf::Positive,
            e,
            &mut material.ranges.youngs_modulus,
        ),
        (
            &l.poisson_ratio_range,
            "poisson_ratio_range",
            Dim::Dimensionless,
            SpanOf::Poisson,
            nu,
            &mut material.ranges.poisson_ratio,
        ),
        (
            &l.shear_strength_range,
            "shear_strength_range",
            Dim::Pressure,
            SpanOf::Positive,
            shear,
            &mut bond.ranges.strength,
        ),
    ];
    for (field, name, dim, of, nominal, slot) in fields {
        if let Some(f) = field {
            *slot = Some(read_span(&ctx, f, &key_name(k, name), dim, of, nominal)?);
        }
    }
    Ok(())
}

/// A layer's thickness, within `film.thickness`'s range.
fn thickness(k: usize, f: &Field, ctx: Ctx<'_>) -> Result<f64, Error> {
    let key = key_name(k, "thickness");
    let v = ctx.positive(f, &key, Dim::Length(1))?;
    match Key::Thickness.range().and_then(|r| r.reject(v)) {
        Some(why) => Err(ctx.error(&f.origin, &key, why)),
        None => Ok(v),
    }
}

/// A bond: a shear strength (a number in Pa or a pressure with its unit), else a library bond
/// by name.
fn bond(k: usize, f: &Field, ctx: Ctx<'_>, library: &Library) -> Result<Bond, Error> {
    let key = key_name(k, "bond");
    let strength = match &f.raw {
        Raw::Number(_) => Some(ctx.positive(f, &key, Dim::Pressure)?),
        Raw::Text(t) if parse_quantity(t, Dim::Pressure).is_ok() => {
            Some(ctx.positive(f, &key, Dim::Pressure)?)
        }
        _ => None,
    };
    if let Some(s) = strength {
        return match Key::ShearStrength.range().and_then(|r| r.reject(s)) {
            Some(why) => Err(ctx.error(&f.origin, &key, why)),
            None => Ok(Bond {
                name: "custom".into(),
                shear_strength: s,
                source: "given in the scene".into(),
                ranges: Ranges::default(),
            }),
        };
    }
    let name = ctx.text(f, &key)?;
    library
        .bond(name)
        .cloned()
        .map_err(|e| ctx.error(&f.origin, &key, e))
}

/// The index of the layer `criteria.thickness_of` names (0, the top layer, when not given).
pub(super) fn thickness_of(
    layers: &[SceneLayer],
    field: Option<&Field>,
    ctx: Ctx<'_>,
) -> Result<usize, Error> {
    let Some(f) = field else {
        return Ok(0);
    };
    let key = Key::ThicknessOf.name();
    let name = ctx.text(f, key)?;
    layers.iter().position(|l| l.name == name).ok_or_else(|| {
        let names: Vec<&str> = layers.iter().map(|l| l.name.as_str()).collect();
        ctx.error(
            &f.origin,
            key,
            format!(
                "no layer is named '{name}' (the layers: {})",
                if names.is_empty() {
                    "none: the scene has no [[layer]] tables".to_string()
                } else {
                    names.join(", ")
                }
            ),
        )
    })
}
