//! Validation of a [`RawScene`] into a [`Scene`] (SI units): each value read as its key's
//! table entry says, contradictions between alternatives, materials and bond looked up in the
//! library, criteria and numerics. Errors name the key and its line (or flag).

use super::keys::{Choice, Key, RawScene, Value};
use super::layers::{resolve_layers, thickness_of};
use super::roughness::resolve_roughness;
use super::{Override, Scene};
use crate::check::{CheckKind, Checks, Criteria, ShearTail};
use crate::error::Error;
use crate::layer::Elastic;
use crate::material::{Bond, Kind, Library, Material, Ranges, Span, SpanOf, read_span};
use crate::prec::Settings;
use crate::tomlin::{Ctx, Field};
use crate::units::Dim;
use std::path::Path;

/// The raw scene read through the key table: values with their units and ranges checked,
/// errors at the key's line or flag.
#[derive(Clone, Copy)]
pub(super) struct Reader<'a> {
    pub raw: &'a RawScene,
    pub ctx: Ctx<'a>,
}

impl Reader<'_> {
    pub fn field(&self, key: Key) -> Option<&Field> {
        self.raw.get(key)
    }

    /// An error about `key`, given at `f`.
    pub fn error(&self, key: Key, f: &Field, msg: impl std::fmt::Display) -> Error {
        self.ctx.error(&f.origin, key.name(), msg)
    }

    /// The value of quantity `key` in SI, within its range.
    pub fn quantity(&self, key: Key) -> Result<Option<f64>, Error> {
        self.field(key)
            .map(|f| self.quantity_of(key, f))
            .transpose()
    }

    /// `f` read as the value of quantity `key`.
    pub fn quantity_of(&self, key: Key, f: &Field) -> Result<f64, Error> {
        key.quantity_of(f, self.ctx)
    }

    /// The text of `key`.
    pub fn text(&self, key: Key) -> Result<Option<&str>, Error> {
        self.field(key)
            .map(|f| self.ctx.text(f, key.name()))
            .transpose()
    }
}

/// Validate a raw scene.
pub fn resolve(
    raw: &RawScene,
    ctx: Ctx<'_>,
    library: &Library,
    file: Option<&Path>,
) -> Result<Scene, Error> {
    let r = Reader { raw, ctx };
    check_schema_version(raw, ctx)?;
    let coatcheck_version = pinned_version(raw, ctx)?;
    check_contradictions(r)?;
    let roughness = resolve_roughness(r)?;
    let mut overrides = Vec::new();
    let mut layers = resolve_layers(&raw.layers, ctx, library)?;
    let thickness_of = thickness_of(&layers, r.field(Key::ThicknessOf), ctx)?;
    let (film, thickness, bond) = match layers.first() {
        None => (
            resolve_material(r, library, Role::FILM, &mut overrides)?,
            r.quantity(Key::Thickness)?,
            resolve_bond(r, library, &mut overrides)?,
        ),
        Some(top) => {
            check_no_film_keys(r)?;
            let bottom = layers.last().expect("a first layer");
            (
                top.material.clone(),
                Some(top.thickness),
                bottom.bond.clone(),
            )
        }
    };
    // One layer is the [film] scene itself.
    if layers.len() == 1 {
        layers.clear();
    }
    let substrate = resolve_material(r, library, Role::SUBSTRATE, &mut overrides)?;
    let pressure = r.quantity(Key::Pressure)?.ok_or_else(|| {
        ctx.missing(
            Key::Pressure.name(),
            "give the nominal pressure, e.g. --pressure \"0.1 MPa\"",
        )
    })?;
    let friction = r.quantity(Key::Friction)?.unwrap_or(0.0);
    let criteria = resolve_criteria(r)?;
    if friction > 0.0
        && criteria.shear_tail == Some(ShearTail::HalfNormal)
        && let Some(f) = r.field(Key::ShearTail)
    {
        return Err(r.error(
            Key::ShearTail,
            f,
            format!(
                "half-normal with {} = {friction} (expected vector: with friction the shear has \
                 a mean, and the paper's half-normal rule does not apply)",
                Key::Friction.name()
            ),
        ));
    }
    if criteria.checks.substrate_yield && substrate.yield_strength.is_none() {
        return Err(ctx.missing(
            Key::YieldStrength.name(),
            &format!(
                "substrate '{}' has no yield strength: give one or leave substrate-yield out of {}",
                substrate.name,
                Key::Checks.name()
            ),
        ));
    }
    let mut settings = Settings::default();
    if let Some(rtol) = r.quantity(Key::Rtol)? {
        settings.rtol = rtol;
    }
    let robust = match r.field(Key::Robust) {
        Some(f) => ctx.boolean(f, Key::Robust.name())?,
        None => false,
    };
    Ok(Scene {
        file: file.map(Path::to_path_buf),
        coatcheck_version,
        roughness,
        film,
        thickness,
        substrate,
        bond,
        layers,
        thickness_of,
        pressure,
        friction,
        criteria,
        settings,
        overrides,
        robust,
    })
}

/// A stack's layers are its film and bonds: `[film]` and `[bond]` keys (or their flags) beside
/// `[[layer]]` tables are a contradiction.
fn check_no_film_keys(r: Reader<'_>) -> Result<(), Error> {
    let film_keys = [
        Key::FilmMaterial,
        Key::FilmYoungsModulus,
        Key::FilmPoissonRatio,
        Key::Thickness,
        Key::BondMaterial,
        Key::ShearStrength,
    ];
    match film_keys.iter().find_map(|&k| r.field(k).map(|f| (k, f))) {
        Some((k, f)) => Err(r.error(
            k,
            f,
            "contradicts the [[layer]] tables (a stack gives each layer's material, thickness \
             and bond in its [[layer]] table)",
        )),
        None => Ok(()),
    }
}

fn check_schema_version(raw: &RawScene, ctx: Ctx<'_>) -> Result<(), Error> {
    if let Some(v) = &raw.schema_version {
        let n = ctx.quantity(v, "schema_version", Dim::Dimensionless)?;
        if n != 1.0 {
            return Err(ctx.error(
                &v.origin,
                "schema_version",
                format!("{n} (this build reads scene schema_version = 1)"),
            ));
        }
    }
    Ok(())
}

/// The coatcheck version the scene pins (`major.minor.patch`), if any.
fn pinned_version(raw: &RawScene, ctx: Ctx<'_>) -> Result<Option<String>, Error> {
    let Some(v) = &raw.coatcheck_version else {
        return Ok(None);
    };
    let text = ctx.text(v, "coatcheck_version")?.trim();
    let valid = text.split('.').count() == 3
        && text
            .split('.')
            .all(|p| !p.is_empty() && p.chars().all(|c| c.is_ascii_digit()));
    if !valid {
        return Err(ctx.error(
            &v.origin,
            "coatcheck_version",
            format!(
                "'{text}' (expected a version like \"{}\")",
                env!("CARGO_PKG_VERSION")
            ),
        ));
    }
    Ok(Some(text.to_string()))
}

/// Keys of two alternatives of one choice: the first given key of the second alternative is
/// reported, naming the first alternative's. A named material or bond with one property of its
/// other alternative is an override, not a contradiction.
fn check_contradictions(r: Reader<'_>) -> Result<(), Error> {
    for choice in Choice::ALL {
        let alt_of = |k: Key| k.spec().alt.filter(|(c, _)| *c == choice).map(|(_, a)| a);
        let last = Key::ALL
            .iter()
            .filter_map(|&k| alt_of(k))
            .max()
            .unwrap_or(0);
        let mut given = (0..=last).filter_map(|alt| {
            Key::ALL
                .iter()
                .filter(|&&k| alt_of(k) == Some(alt))
                .find_map(|&k| r.field(k).map(|f| (k, f)))
        });
        if let (Some((k1, _)), Some((k2, f2))) = (given.next(), given.next()) {
            let properties = Key::ALL
                .iter()
                .filter(|&&k| alt_of(k) == Some(1) && r.field(k).is_some())
                .count();
            let named = matches!(choice, Choice::Film | Choice::Substrate | Choice::Bond);
            if named && properties == 1 {
                continue;
            }
            let why = if named {
                "a named material may override one property; give the material or all its \
                 properties, not both"
            } else {
                "give one of them, not both"
            };
            return Err(r.error(k2, f2, format!("contradicts {} ({why})", k1.name())));
        }
    }
    Ok(())
}

/// The keys of a film or a substrate.
struct Role {
    name: &'static str,
    kind: Kind,
    material: Key,
    youngs: Key,
    poisson: Key,
    yield_strength: Option<Key>,
    /// The range keys of E, ν and the yield strength.
    ranges: [Option<Key>; 3],
}

impl Role {
    const FILM: Role = Role {
        name: "film",
        kind: Kind::Film,
        material: Key::FilmMaterial,
        youngs: Key::FilmYoungsModulus,
        poisson: Key::FilmPoissonRatio,
        yield_strength: None,
        ranges: [
            Some(Key::FilmYoungsModulusRange),
            Some(Key::FilmPoissonRatioRange),
            None,
        ],
    };
    const SUBSTRATE: Role = Role {
        name: "substrate",
        kind: Kind::Substrate,
        material: Key::SubstrateMaterial,
        youngs: Key::SubstrateYoungsModulus,
        poisson: Key::SubstratePoissonRatio,
        yield_strength: Some(Key::YieldStrength),
        ranges: [
            Some(Key::SubstrateYoungsModulusRange),
            Some(Key::SubstratePoissonRatioRange),
            Some(Key::YieldStrengthRange),
        ],
    };
}

/// A film or substrate: a library material by name (one of whose properties the scene may
/// override, recorded in `overrides`), or Young's modulus and Poisson ratio.
fn resolve_material(
    r: Reader<'_>,
    library: &Library,
    role: Role,
    overrides: &mut Vec<Override>,
) -> Result<Material, Error> {
    let ctx = r.ctx;
    let mut m = match (
        r.field(role.material),
        r.field(role.youngs),
        r.field(role.poisson),
    ) {
        (Some(f), fe, fnu) => {
            let name = ctx.text(f, role.material.name())?;
            let mut m = library
                .material(name)
                .map_err(|e| r.error(role.material, f, e))?
                .clone();
            let (mut e, mut nu) = (m.elastic.youngs, m.elastic.poisson);
            if let Some(fe) = fe {
                e = r.quantity_of(role.youngs, fe)?;
                overrides.push(override_of(role.youngs, &m.name, e, Some(m.elastic.youngs)));
            }
            if let Some(fnu) = fnu {
                nu = r.quantity_of(role.poisson, fnu)?;
                overrides.push(override_of(
                    role.poisson,
                    &m.name,
                    nu,
                    Some(m.elastic.poisson),
                ));
            }
            if let Some(g) = fe.or(fnu) {
                m.elastic = Elastic::new(e, nu).map_err(|err| r.error(role.poisson, g, err))?;
            }
            // An explicit value has no range unless the scene gives one.
            if fe.is_some() {
                m.ranges.youngs_modulus = None;
            }
            if fnu.is_some() {
                m.ranges.poisson_ratio = None;
            }
            m
        }
        (None, Some(fe), Some(fnu)) => {
            let e = r.quantity_of(role.youngs, fe)?;
            let nu = r.quantity_of(role.poisson, fnu)?;
            let elastic = Elastic::new(e, nu).map_err(|err| r.error(role.poisson, fnu, err))?;
            Material {
                name: "custom".into(),
                kind: role.kind,
                elastic,
                yield_strength: None,
                source: "given in the scene".into(),
                ranges: Ranges::default(),
            }
        }
        (None, Some(f), None) | (None, None, Some(f)) => {
            return Err(ctx.error(
                &f.origin,
                &format!("{} and {}", role.youngs.name(), role.poisson.name()),
                "both are needed when no material is named",
            ));
        }
        (None, None, None) => {
            return Err(ctx.missing(
                role.material.name(),
                &format!(
                    "name a {} material (coatcheck materials) or give youngs_modulus and poisson_ratio",
                    role.name
                ),
            ));
        }
    };
    if let Some(key) = role.yield_strength
        && let Some(y) = r.quantity(key)?
    {
        if r.field(role.material).is_some() {
            overrides.push(override_of(key, &m.name, y, m.yield_strength));
        }
        m.yield_strength = Some(y);
        m.ranges.strength = None;
    }
    let [e_key, nu_key, y_key] = role.ranges;
    let nominals = [
        (e_key, Some(m.elastic.youngs)),
        (nu_key, Some(m.elastic.poisson)),
        (y_key, m.yield_strength),
    ];
    let mut spans = [
        m.ranges.youngs_modulus,
        m.ranges.poisson_ratio,
        m.ranges.strength,
    ];
    for (slot, (key, nominal)) in spans.iter_mut().zip(nominals) {
        if let Some(key) = key
            && let Some(span) = scene_span(r, key, nominal)?
        {
            *slot = Some(span);
        }
    }
    [
        m.ranges.youngs_modulus,
        m.ranges.poisson_ratio,
        m.ranges.strength,
    ] = spans;
    Ok(m)
}

/// The scene's range of a property (key `key`, a [`Value::Span`]) around its nominal value
/// (`None`: the property has no value, e.g. no yield strength).
fn scene_span(r: Reader<'_>, key: Key, nominal: Option<f64>) -> Result<Option<Span>, Error> {
    let Some(f) = r.field(key) else {
        return Ok(None);
    };
    let Value::Span(dim) = key.spec().value else {
        unreachable!("{} is not a range", key.name());
    };
    let nominal = nominal.ok_or_else(|| r.error(key, f, "a range of a property with no value"))?;
    let of = match dim {
        Dim::Dimensionless => SpanOf::Poisson,
        _ => SpanOf::Positive,
    };
    read_span(&r.ctx, f, key.name(), dim, of, nominal).map(Some)
}

fn override_of(key: Key, material: &str, value: f64, library_value: Option<f64>) -> Override {
    Override {
        key: key.name(),
        material: material.to_string(),
        value,
        library_value,
        unit: if key.name().ends_with("poisson_ratio") {
            "1"
        } else {
            "Pa"
        },
    }
}

/// The bond: by name from the library (its shear strength possibly overridden), or its shear
/// strength.
fn resolve_bond(
    r: Reader<'_>,
    library: &Library,
    overrides: &mut Vec<Override>,
) -> Result<Bond, Error> {
    let mut bond = named_or_custom_bond(r, library, overrides)?;
    if let Some(span) = scene_span(r, Key::ShearStrengthRange, Some(bond.shear_strength))? {
        bond.ranges.strength = Some(span);
    }
    Ok(bond)
}

/// The bond by name (its shear strength possibly overridden) or its shear strength.
fn named_or_custom_bond(
    r: Reader<'_>,
    library: &Library,
    overrides: &mut Vec<Override>,
) -> Result<Bond, Error> {
    match (r.field(Key::BondMaterial), r.field(Key::ShearStrength)) {
        (Some(f), given) => {
            let name = r.ctx.text(f, Key::BondMaterial.name())?;
            let mut bond = library
                .bond(name)
                .map_err(|e| r.error(Key::BondMaterial, f, e))?
                .clone();
            if let Some(fs) = given {
                let s = r.quantity_of(Key::ShearStrength, fs)?;
                overrides.push(override_of(
                    Key::ShearStrength,
                    &bond.name,
                    s,
                    Some(bond.shear_strength),
                ));
                bond.shear_strength = s;
                bond.ranges.strength = None;
            }
            Ok(bond)
        }
        (None, Some(f)) => Ok(Bond {
            name: "custom".into(),
            shear_strength: r.quantity_of(Key::ShearStrength, f)?,
            source: "given in the scene".into(),
            ranges: Ranges::default(),
        }),
        (None, None) => Err(r.ctx.missing(
            &format!(
                "{} or {}",
                Key::BondMaterial.name(),
                Key::ShearStrength.name()
            ),
            "name a bond (coatcheck materials) or give its shear strength, e.g. --shear-strength \"10 MPa\"",
        )),
    }
}

/// Exceedance probability, safety factor and the checks to run (defaults where not given).
fn resolve_criteria(r: Reader<'_>) -> Result<Criteria, Error> {
    let mut criteria = Criteria::default();
    if let Some(e) = r.quantity(Key::Epsilon)? {
        criteria.epsilon = e;
    }
    if let Some(s) = r.quantity(Key::SafetyFactor)? {
        criteria.safety_factor = s;
    }
    if let Some(f) = r.field(Key::Checks) {
        let names = r.ctx.list(f, Key::Checks.name())?;
        if names.is_empty() {
            return Err(r.error(Key::Checks, f, "empty (expected at least one check)"));
        }
        let mut checks = Checks::none();
        for n in names {
            let c = CheckKind::from_name(&n).ok_or_else(|| {
                r.error(
                    Key::Checks,
                    f,
                    format!("unknown check '{n}' (expected bond-shear, substrate-yield or min-thickness)"),
                )
            })?;
            checks.enable(c);
        }
        criteria.checks = checks;
    }
    if let Some(f) = r.field(Key::ShearTail) {
        let name = r.ctx.text(f, Key::ShearTail.name())?;
        criteria.shear_tail = Some(ShearTail::from_name(name).ok_or_else(|| {
            r.error(
                Key::ShearTail,
                f,
                format!("unknown rule '{name}' (expected half-normal or vector)"),
            )
        })?);
    }
    Ok(criteria)
}
