//! The materials library: elastic films and substrates (E, ν, optional yield strength) and
//! bonds (shear strength), one TOML file per entry under `materials/`.
//!
//! Each file has `schema_version` (= [`SCHEMA_VERSION`]), `name`, `kind` (`film`, `substrate` or
//! `bond`), values as strings with units parsed by [`crate::units`] (`youngs_modulus = "2 MPa"`,
//! `poisson_ratio = 0.5`, `yield_strength = "250 MPa"`, `shear_strength = "10 MPa"`) and a
//! `source` note. The bundled files are compiled into the binary ([`BUILTIN`]); a directory given
//! with `--materials DIR` adds entries or overrides bundled ones of the same name.
//!
//! A file may give each property's range of values, `youngs_modulus_range = ["4 MPa", "8 MPa"]`,
//! `poisson_ratio_range = [0.4987, 0.4998]`, `yield_strength_range`, `shear_strength_range`
//! (each a [`Span`] that holds the nominal value), with `range_source` saying where the ranges
//! come from (required with any range). `check --robust` judges the design at the worst corner
//! of these ranges ([`crate::check::robust`]).
//!
//! `kind` says what the material is usually used as; any elastic material may be used as film or
//! substrate (the layered solution, eq. (7), holds for either stiffness order), but the
//! substrate-yield check needs a yield strength.

use crate::error::Error;
use crate::layer::Elastic;
use crate::tomlin::{Ctx, Field, Source};
use crate::units::Dim;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The version of the material file format this build reads.
pub const SCHEMA_VERSION: i64 = 1;

/// The bundled material files: (file name, contents).
pub const BUILTIN: &[(&str, &str)] = &[
    (
        "aluminium-alloy.toml",
        include_str!("../materials/aluminium-alloy.toml"),
    ),
    ("brass.toml", include_str!("../materials/brass.toml")),
    (
        "carbon-steel.toml",
        include_str!("../materials/carbon-steel.toml"),
    ),
    (
        "chemlok-type.toml",
        include_str!("../materials/chemlok-type.toml"),
    ),
    ("copper.toml", include_str!("../materials/copper.toml")),
    (
        "cyanoacrylate.toml",
        include_str!("../materials/cyanoacrylate.toml"),
    ),
    ("epdm.toml", include_str!("../materials/epdm.toml")),
    ("epoxy.toml", include_str!("../materials/epoxy.toml")),
    (
        "epoxy-primer.toml",
        include_str!("../materials/epoxy-primer.toml"),
    ),
    ("fkm.toml", include_str!("../materials/fkm.toml")),
    ("glass.toml", include_str!("../materials/glass.toml")),
    (
        "hardened-steel.toml",
        include_str!("../materials/hardened-steel.toml"),
    ),
    (
        "natural-rubber.toml",
        include_str!("../materials/natural-rubber.toml"),
    ),
    ("nbr.toml", include_str!("../materials/nbr.toml")),
    (
        "paper-rubber.toml",
        include_str!("../materials/paper-rubber.toml"),
    ),
    (
        "paper-steel.toml",
        include_str!("../materials/paper-steel.toml"),
    ),
    (
        "polyurethane.toml",
        include_str!("../materials/polyurethane.toml"),
    ),
    ("ptfe.toml", include_str!("../materials/ptfe.toml")),
    (
        "rubber-vulcanised-to-brass.toml",
        include_str!("../materials/rubber-vulcanised-to-brass.toml"),
    ),
    (
        "silicone-pdms.toml",
        include_str!("../materials/silicone-pdms.toml"),
    ),
    (
        "silicone-with-primer.toml",
        include_str!("../materials/silicone-with-primer.toml"),
    ),
    (
        "stainless-steel.toml",
        include_str!("../materials/stainless-steel.toml"),
    ),
];

/// What a library entry is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    Film,
    Substrate,
    Bond,
}

impl std::fmt::Display for Kind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Kind::Film => "film",
            Kind::Substrate => "substrate",
            Kind::Bond => "bond",
        })
    }
}

/// An elastic material (film or substrate).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Material {
    pub name: String,
    pub kind: Kind,
    pub elastic: Elastic,
    /// Yield strength in Pa (substrates; `None` when not given).
    pub yield_strength: Option<f64>,
    pub source: String,
    /// The ranges of E, ν and the yield strength (`strength`), where known.
    #[serde(skip_serializing_if = "Ranges::is_empty")]
    pub ranges: Ranges,
}

/// A bond (adhesive or vulcanised joint) between film and substrate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Bond {
    pub name: String,
    /// Shear strength in Pa.
    pub shear_strength: f64,
    pub source: String,
    /// The range of the shear strength (`strength`), where known.
    #[serde(skip_serializing_if = "Ranges::is_empty")]
    pub ranges: Ranges,
}

/// The values a property may take, `[min, max]` (SI), holding its nominal value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Span {
    pub min: f64,
    pub max: f64,
}

impl Span {
    /// The range of a property given as one value.
    pub fn point(v: f64) -> Self {
        Span { min: v, max: v }
    }

    /// max > min.
    pub fn is_wide(&self) -> bool {
        self.max > self.min
    }
}

/// The ranges of a material's or a bond's properties (`None`: only the nominal value is known),
/// and where they come from.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Ranges {
    pub youngs_modulus: Option<Span>,
    pub poisson_ratio: Option<Span>,
    /// The yield strength of a material, the shear strength of a bond.
    pub strength: Option<Span>,
    /// Where the ranges come from (`range_source`, or the scene for a scene's ranges).
    pub source: Option<String>,
}

impl Ranges {
    /// No range and no source.
    pub fn is_empty(&self) -> bool {
        self.youngs_modulus.is_none()
            && self.poisson_ratio.is_none()
            && self.strength.is_none()
            && self.source.is_none()
    }
}

/// What a range is of, for its checks: a modulus or strength (> 0), or a Poisson ratio (the
/// values [`Elastic::new`] accepts).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpanOf {
    Positive,
    Poisson,
}

/// Read `f` as the range of property `key` whose nominal value is `nominal`: two values,
/// min ≤ max, each valid for the property, holding the nominal value. Errors name `key` at
/// `f`'s line (or flag).
pub fn read_span(
    ctx: &Ctx<'_>,
    f: &Field,
    key: &str,
    dim: Dim,
    of: SpanOf,
    nominal: f64,
) -> Result<Span, Error> {
    let (min, max) = ctx.pair(f, key, dim)?;
    for v in [min, max] {
        let bad = match of {
            SpanOf::Positive => (v <= 0.0).then(|| format!("{v:e} (expected values > 0)")),
            SpanOf::Poisson => Elastic::new(1.0, v).err().map(|e| e.to_string()),
        };
        if let Some(why) = bad {
            return Err(ctx.error(&f.origin, key, why));
        }
    }
    if !(min..=max).contains(&nominal) {
        return Err(ctx.error(
            &f.origin,
            key,
            format!("[{min:e}, {max:e}] does not hold the nominal value {nominal:e}"),
        ));
    }
    Ok(Span { min, max })
}

/// One parsed library file.
#[derive(Debug, Clone, PartialEq)]
pub enum Entry {
    Material(Material),
    Bond(Bond),
}

impl Entry {
    pub fn name(&self) -> &str {
        match self {
            Entry::Material(m) => &m.name,
            Entry::Bond(b) => &b.name,
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEntry {
    schema_version: Field,
    name: Field,
    kind: Field,
    youngs_modulus: Option<Field>,
    poisson_ratio: Option<Field>,
    yield_strength: Option<Field>,
    shear_strength: Option<Field>,
    youngs_modulus_range: Option<Field>,
    poisson_ratio_range: Option<Field>,
    yield_strength_range: Option<Field>,
    shear_strength_range: Option<Field>,
    range_source: Option<Field>,
    source: Field,
}

/// Parse one material file (`path` is used in error messages only).
pub fn parse_entry(text: &str, path: &Path) -> Result<Entry, Error> {
    let src = Source { path, text };
    let raw: RawEntry = src.parse()?;
    let ctx = Ctx { file: Some(&src) };
    let version = ctx.quantity(&raw.schema_version, "schema_version", Dim::Dimensionless)?;
    if version != SCHEMA_VERSION as f64 {
        return Err(ctx.error(
            &raw.schema_version.origin,
            "schema_version",
            format!("{version} (this build reads schema_version = {SCHEMA_VERSION})"),
        ));
    }
    let name = ctx.text(&raw.name, "name")?.trim().to_string();
    if name.is_empty() {
        return Err(ctx.error(&raw.name.origin, "name", "empty (expected a name)"));
    }
    let source = ctx.text(&raw.source, "source")?.trim().to_string();
    if source.is_empty() {
        return Err(ctx.error(
            &raw.source.origin,
            "source",
            "empty (expected where the values come from)",
        ));
    }
    let kind = match ctx.text(&raw.kind, "kind")? {
        "film" => Kind::Film,
        "substrate" => Kind::Substrate,
        "bond" => Kind::Bond,
        other => {
            return Err(ctx.error(
                &raw.kind.origin,
                "kind",
                format!("'{other}' (expected film, substrate or bond)"),
            ));
        }
    };
    let forbid = |f: &Option<Field>, key: &str, why: &str| match f {
        Some(f) => Err(ctx.error(&f.origin, key, why)),
        None => Ok(()),
    };
    let require = |f: &Option<Field>, key: &str| {
        f.clone().ok_or_else(|| Error::Input {
            path: path.to_path_buf(),
            line: 1,
            msg: format!("{key} is missing (a {kind} needs it)"),
        })
    };
    if kind == Kind::Bond {
        for (f, key) in [
            (&raw.youngs_modulus, "youngs_modulus"),
            (&raw.poisson_ratio, "poisson_ratio"),
            (&raw.yield_strength, "yield_strength"),
            (&raw.youngs_modulus_range, "youngs_modulus_range"),
            (&raw.poisson_ratio_range, "poisson_ratio_range"),
            (&raw.yield_strength_range, "yield_strength_range"),
        ] {
            forbid(
                f,
                key,
                "not a property of a bond (expected shear_strength only)",
            )?;
        }
        let f = require(&raw.shear_strength, "shear_strength")?;
        let shear_strength = ctx.positive(&f, "shear_strength", Dim::Pressure)?;
        let strength = raw
            .shear_strength_range
            .as_ref()
            .map(|f| {
                let key = "shear_strength_range";
                read_span(
                    &ctx,
                    f,
                    key,
                    Dim::Pressure,
                    SpanOf::Positive,
                    shear_strength,
                )
            })
            .transpose()?;
        let ranges = Ranges {
            strength,
            source: range_source(&ctx, &raw, strength.is_some())?,
            ..Ranges::default()
        };
        return Ok(Entry::Bond(Bond {
            name,
            shear_strength,
            source,
            ranges,
        }));
    }
    for (f, key) in [
        (&raw.shear_strength, "shear_strength"),
        (&raw.shear_strength_range, "shear_strength_range"),
    ] {
        forbid(f, key, "a bond property (expected kind = \"bond\")")?;
    }
    let fe = require(&raw.youngs_modulus, "youngs_modulus")?;
    let fn_ = require(&raw.poisson_ratio, "poisson_ratio")?;
    let e = ctx.positive(&fe, "youngs_modulus", Dim::Pressure)?;
    let nu = ctx.quantity(&fn_, "poisson_ratio", Dim::Dimensionless)?;
    let elastic =
        Elastic::new(e, nu).map_err(|err| ctx.error(&fn_.origin, "poisson_ratio", err))?;
    let yield_strength = match &raw.yield_strength {
        Some(f) => Some(ctx.positive(f, "yield_strength", Dim::Pressure)?),
        None => None,
    };
    let ranges = solid_ranges(&ctx, &raw, (e, nu, yield_strength))?;
    Ok(Entry::Material(Material {
        name,
        kind,
        elastic,
        yield_strength,
        source,
        ranges,
    }))
}

/// The ranges of a film's or a substrate's properties (`*_range` keys), each holding its
/// nominal value (E, ν and the yield strength, when the file gives one).
fn solid_ranges(
    ctx: &Ctx<'_>,
    raw: &RawEntry,
    (e, nu, yield_strength): (f64, f64, Option<f64>),
) -> Result<Ranges, Error> {
    let span = |f: &Option<Field>, key: &str, dim, of, nominal: Option<f64>| {
        let Some(f) = f else { return Ok(None) };
        let nominal = nominal.ok_or_else(|| {
            ctx.error(
                &f.origin,
                key,
                "a range without its nominal value (give yield_strength too)",
            )
        })?;
        read_span(ctx, f, key, dim, of, nominal).map(Some)
    };
    let (e_key, nu_key, y_key) = (
        "youngs_modulus_range",
        "poisson_ratio_range",
        "yield_strength_range",
    );
    let youngs_modulus = span(
        &raw.youngs_modulus_range,
        e_key,
        Dim::Pressure,
        SpanOf::Positive,
        Some(e),
    )?;
    let poisson_ratio = span(
        &raw.poisson_ratio_range,
        nu_key,
        Dim::Dimensionless,
        SpanOf::Poisson,
        Some(nu),
    )?;
    let strength = span(
        &raw.yield_strength_range,
        y_key,
        Dim::Pressure,
        SpanOf::Positive,
        yield_strength,
    )?;
    let any = youngs_modulus.is_some() || poisson_ratio.is_some() || strength.is_some();
    Ok(Ranges {
        youngs_modulus,
        poisson_ratio,
        strength,
        source: range_source(ctx, raw, any)?,
    })
}

/// The file's `range_source`: required with any range, and only with one.
fn range_source(ctx: &Ctx<'_>, raw: &RawEntry, any_range: bool) -> Result<Option<String>, Error> {
    match (&raw.range_source, any_range) {
        (Some(f), true) => {
            let text = ctx.text(f, "range_source")?.trim();
            if text.is_empty() {
                return Err(ctx.error(
                    &f.origin,
                    "range_source",
                    "empty (expected where the ranges come from)",
                ));
            }
            Ok(Some(text.to_string()))
        }
        (Some(f), false) => Err(ctx.error(
            &f.origin,
            "range_source",
            "no range is given (expected with youngs_modulus_range, poisson_ratio_range or a strength range)",
        )),
        (None, true) => Err(ctx.missing(
            "range_source",
            "give the source of the ranges (datasheet, handbook or paper, and how the range was set)",
        )),
        (None, false) => Ok(None),
    }
}

/// The materials and bonds known to a run, by name.
///
/// The bundled files are parsed on first use, each once: a check names two or three entries,
/// and parsing all twenty took a third of a millisecond of the command's start-up. Entries
/// added with [`Library::insert`] or [`Library::add_dir`] override bundled ones of the same
/// name, of either kind.
#[derive(Debug, Clone, Default)]
pub struct Library {
    /// One slot per [`BUILTIN`] file (none in an empty library), filled on first lookup; a
    /// bundled file that does not parse keeps its error message (the unit tests parse them all).
    bundled: Vec<OnceLock<Result<Entry, String>>>,
    /// Inserted entries, by key.
    added: BTreeMap<String, Entry>,
}

/// Lookup key: lower case, with `_` and spaces read as `-`.
fn key(name: &str) -> String {
    name.trim()
        .to_lowercase()
        .chars()
        .map(|c| if c == '_' || c == ' ' { '-' } else { c })
        .collect()
}

impl Library {
    /// The bundled library. Its files are parsed when first looked up, so a bundled file that
    /// does not parse fails that lookup (or [`Library::entries`]), not this call.
    pub fn builtin() -> Result<Self, Error> {
        Ok(Library {
            bundled: BUILTIN.iter().map(|_| OnceLock::new()).collect(),
            added: BTreeMap::new(),
        })
    }

    /// The bundled library plus (overriding) every `*.toml` file in `dir`.
    pub fn with_dir(dir: Option<&Path>) -> Result<Self, Error> {
        let mut lib = Self::builtin()?;
        if let Some(dir) = dir {
            lib.add_dir(dir)?;
        }
        Ok(lib)
    }

    /// Add (or override) the entries of every `*.toml` file in `dir`.
    pub fn add_dir(&mut self, dir: &Path) -> Result<(), Error> {
        let io = |source| Error::Io {
            path: dir.to_path_buf(),
            source,
        };
        let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
            .map_err(io)?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "toml"))
            .collect();
        files.sort();
        for path in files {
            let text = std::fs::read_to_string(&path).map_err(|source| Error::Io {
                path: path.clone(),
                source,
            })?;
            self.insert(parse_entry(&text, &path)?);
        }
        Ok(())
    }

    /// Add an entry, replacing one of the same name (of either kind).
    pub fn insert(&mut self, entry: Entry) {
        self.added.insert(key(entry.name()), entry);
    }

    /// The keys of the bundled files this library has, in [`BUILTIN`] order (a bundled file is
    /// named after its entry, a unit test).
    fn bundled_keys(&self) -> impl Iterator<Item = &str> {
        BUILTIN
            .iter()
            .take(self.bundled.len())
            .map(|(file, _)| file.trim_end_matches(".toml"))
    }

    /// Bundled file `i`, parsed (once).
    fn parsed(&self, i: usize) -> Result<&Entry, String> {
        let (file, text) = BUILTIN[i];
        self.bundled[i]
            .get_or_init(|| {
                parse_entry(text, &PathBuf::from("materials").join(file)).map_err(|e| e.to_string())
            })
            .as_ref()
            .map_err(Clone::clone)
    }

    /// The entry under key `k`: an inserted one, else the bundled one.
    fn find(&self, k: &str) -> Result<Option<&Entry>, String> {
        if let Some(e) = self.added.get(k) {
            return Ok(Some(e));
        }
        match self.bundled_keys().position(|bk| bk == k) {
            Some(i) => self.parsed(i).map(Some),
            None => Ok(None),
        }
    }

    /// Every entry, materials then bonds, each sorted by name (parses every bundled file).
    pub fn entries(&self) -> Result<Vec<&Entry>, Error> {
        let mut all: BTreeMap<(bool, &str), &Entry> = BTreeMap::new();
        for (i, k) in self.bundled_keys().enumerate() {
            if self.added.contains_key(k) {
                continue;
            }
            let e = self.parsed(i).map_err(|msg| Error::Value {
                origin: "bundled materials library".into(),
                msg,
            })?;
            all.insert((matches!(e, Entry::Bond(_)), k), e);
        }
        for (k, e) in &self.added {
            all.insert((matches!(e, Entry::Bond(_)), k), e);
        }
        Ok(all.into_values().collect())
    }

    /// The names of one kind's entries that parse, for error messages (parses every bundled
    /// file).
    fn names(&self, bond: bool) -> Vec<String> {
        let mut names: Vec<String> = self
            .bundled_keys()
            .chain(self.added.keys().map(String::as_str))
            .filter(|k| matches!(self.find(k), Ok(Some(e)) if matches!(e, Entry::Bond(_)) == bond))
            .map(str::to_string)
            .collect();
        names.sort();
        names.dedup();
        names
    }

    /// An elastic material by name; the error names it and lists close names.
    pub fn material(&self, name: &str) -> Result<&Material, String> {
        let what = match self.find(&key(name))? {
            Some(Entry::Material(m)) => return Ok(m),
            Some(Entry::Bond(_)) => "is a bond, not an elastic material",
            None => "is not in the materials library",
        };
        Err(unknown(name, what, self.names(false).iter()))
    }

    /// A bond by name; the error names it and lists close names.
    pub fn bond(&self, name: &str) -> Result<&Bond, String> {
        let what = match self.find(&key(name))? {
            Some(Entry::Bond(b)) => return Ok(b),
            Some(Entry::Material(_)) => "is an elastic material, not a bond",
            None => "is not in the materials library",
        };
        Err(unknown(name, what, self.names(true).iter()))
    }
}

/// "unknown 'x' ...; close names: a, b" (or all names when none is close).
fn unknown<'a>(name: &str, what: &str, names: impl Iterator<Item = &'a String>) -> String {
    let k = key(name);
    let all: Vec<&String> = names.collect();
    let mut close: Vec<(usize, &String)> = all
        .iter()
        .map(|n| (edit_distance(&k, n), *n))
        .filter(|(d, n)| *d <= 2.max(k.len() / 3) || n.contains(&k) || k.contains(n.as_str()))
        .collect();
    close.sort();
    let (label, list): (&str, Vec<&str>) = if close.is_empty() {
        ("known", all.iter().map(|s| s.as_str()).collect())
    } else {
        (
            "close names",
            close.iter().take(5).map(|(_, n)| n.as_str()).collect(),
        )
    };
    format!("'{name}' {what} ({label}: {})", list.join(", "))
}

/// Levenshtein distance (characters).
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_file_in_materials_is_bundled_and_named_after_its_file() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("materials");
        let mut on_disk: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".toml"))
            .collect();
        on_disk.sort();
        let mut bundled: Vec<String> = BUILTIN.iter().map(|(f, _)| f.to_string()).collect();
        bundled.sort();
        assert_eq!(on_disk, bundled, "materials/*.toml and BUILTIN differ");
        for (file, text) in BUILTIN {
            let on_disk = std::fs::read_to_string(dir.join(file)).unwrap();
            assert_eq!(&on_disk, text);
            let e = parse_entry(text, Path::new(file)).unwrap();
            assert_eq!(format!("{}.toml", e.name()), *file);
            assert_eq!(
                key(e.name()),
                e.name(),
                "{file}: the lookup key is the name"
            );
        }
        let index = std::fs::read_to_string(dir.join("README.md")).unwrap();
        for (file, _) in BUILTIN {
            let name = file.trim_end_matches(".toml");
            assert!(
                index.contains(&format!("| `{name}` |")),
                "{name} not in materials/README.md"
            );
        }
    }

    #[test]
    fn the_library_has_the_required_entries_with_sane_values() {
        let lib = Library::builtin().unwrap();
        for m in [
            "natural-rubber",
            "epdm",
            "nbr",
            "fkm",
            "silicone-pdms",
            "polyurethane",
            "ptfe",
            "paper-rubber",
        ] {
            let m = lib.material(m).unwrap();
            assert_eq!(m.kind, Kind::Film);
            assert!(
                m.elastic.youngs > 1e5 && m.elastic.youngs < 1e10,
                "{}",
                m.name
            );
        }
        for m in [
            "carbon-steel",
            "hardened-steel",
            "stainless-steel",
            "aluminium-alloy",
            "brass",
            "copper",
            "glass",
            "paper-steel",
        ] {
            let m = lib.material(m).unwrap();
            assert_eq!(m.kind, Kind::Substrate);
            assert!(
                m.elastic.youngs > 5e10 && m.elastic.youngs < 3e11,
                "{}",
                m.name
            );
            let y = m.yield_strength.unwrap();
            assert!(y > 5e7 && y < 3e9, "{}", m.name);
        }
        for b in [
            "epoxy",
            "cyanoacrylate",
            "rubber-vulcanised-to-brass",
            "silicone-with-primer",
        ] {
            let b = lib.bond(b).unwrap();
            assert!(
                b.shear_strength > 1e6 && b.shear_strength < 5e7,
                "{}",
                b.name
            );
        }
        // The paper's values exactly.
        let r = lib.material("paper-rubber").unwrap().elastic;
        assert_eq!((r.youngs, r.poisson), (1e6, 0.5));
        let s = lib.material("paper-steel").unwrap().elastic;
        assert_eq!((s.youngs, s.poisson), (1e11, 0.5));
        assert_eq!(lib.bond("epoxy").unwrap().shear_strength, 1e7);
    }

    #[test]
    fn lookups_are_forgiving_and_errors_list_close_names() {
        let lib = Library::builtin().unwrap();
        assert_eq!(
            lib.material("Natural_Rubber").unwrap().name,
            "natural-rubber"
        );
        let e = lib.material("natural-rubbr").unwrap_err();
        assert!(
            e.contains("'natural-rubbr'") && e.contains("natural-rubber"),
            "{e}"
        );
        let e = lib.material("epoxy").unwrap_err();
        assert!(e.contains("is a bond"), "{e}");
        let e = lib.bond("zzzzzzzzzzzzzzzzzzz").unwrap_err();
        assert!(e.contains("known: ") && e.contains("epoxy"), "{e}");
    }

    #[test]
    fn edit_distance_is_levenshtein() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("abc", "abc"), 0);
    }

    #[test]
    fn bad_files_are_rejected_with_the_line() {
        let p = Path::new("m.toml");
        let ok = "schema_version = 1\nname = \"x\"\nkind = \"film\"\nyoungs_modulus = \"1 MPa\"\npoisson_ratio = 0.5\nsource = \"s\"\n";
        assert!(parse_entry(ok, p).is_ok());
        let cases = [
            (ok.replace("1 MPa", "1 furlong"), 4, "unknown unit"),
            (ok.replace("0.5", "0.7"), 5, "Poisson"),
            (
                ok.replace("schema_version = 1", "schema_version = 2"),
                1,
                "schema_version",
            ),
            (ok.replace("source", "sauce"), 6, "unknown field"),
            (ok.replace("\"film\"", "\"liquid\""), 3, "kind"),
            (
                format!("{ok}shear_strength = \"1 MPa\"\n"),
                7,
                "shear_strength",
            ),
        ];
        for (text, line, needle) in cases {
            let e = parse_entry(&text, p).unwrap_err().to_string();
            assert!(e.starts_with(&format!("m.toml:{line}:")), "{e}");
            assert!(e.contains(needle), "{e}");
            assert!(!e.contains('\n'), "{e}");
        }
    }

    #[test]
    fn ranges_are_read_and_bad_ones_are_rejected_at_their_line() {
        let p = Path::new("m.toml");
        let ok = "schema_version = 1\nname = \"x\"\nkind = \"substrate\"\nyoungs_modulus = \"200 GPa\"\npoisson_ratio = 0.29\nyield_strength = \"250 MPa\"\nyoungs_modulus_range = [\"190 GPa\", \"210 GPa\"]\npoisson_ratio_range = [0.28, 0.3]\nyield_strength_range = [\"235 MPa\", 2.6e8]\nrange_source = \"s\"\nsource = \"s\"\n";
        let Entry::Material(m) = parse_entry(ok, p).unwrap() else {
            panic!("a material")
        };
        assert_eq!(
            m.ranges.youngs_modulus,
            Some(Span {
                min: 1.9e11,
                max: 2.1e11
            })
        );
        assert_eq!(
            m.ranges.poisson_ratio,
            Some(Span {
                min: 0.28,
                max: 0.3
            })
        );
        assert_eq!(
            m.ranges.strength,
            Some(Span {
                min: 2.35e8,
                max: 2.6e8
            })
        );
        assert_eq!(m.ranges.source.as_deref(), Some("s"));
        let e_line = "youngs_modulus_range = [\"190 GPa\", \"210 GPa\"]";
        let nu_line = "poisson_ratio_range = [0.28, 0.3]";
        let cases = [
            (
                e_line,
                "youngs_modulus_range = [\"210 GPa\", \"190 GPa\"]",
                7,
                "youngs_modulus_range: min 2.1e11 > max 1.9e11",
            ),
            (
                e_line,
                "youngs_modulus_range = [\"-1 GPa\", \"210 GPa\"]",
                7,
                "youngs_modulus_range: -1e9 (expected values > 0)",
            ),
            (
                e_line,
                "youngs_modulus_range = [\"201 GPa\", \"210 GPa\"]",
                7,
                "does not hold the nominal value",
            ),
            (
                e_line,
                "youngs_modulus_range = [\"190 GPa\"]",
                7,
                "expected a range [min, max]",
            ),
            (
                e_line,
                "youngs_modulus_range = [\"190 GPa\", \"2 furlong\"]",
                7,
                "'2 furlong' is not",
            ),
            (
                nu_line,
                "poisson_ratio_range = [0.28, 0.6]",
                8,
                "poisson_ratio_range: invalid Poisson ratio",
            ),
            (
                nu_line,
                "poisson_ratio_range = [-1.5, 0.3]",
                8,
                "poisson_ratio_range: invalid Poisson ratio",
            ),
            ("range_source = \"s\"\n", "", 0, "range_source is missing"),
        ];
        for (from, to, line, needle) in cases {
            let text = ok.replace(from, to);
            let e = parse_entry(&text, p).unwrap_err().to_string();
            if line > 0 {
                assert!(e.starts_with(&format!("m.toml:{line}:")), "{e}");
            }
            assert!(e.starts_with("m.toml") && e.contains(needle), "{e}");
        }
        // A range of a property the entry does not have, and a range source without ranges.
        let bond = "schema_version = 1\nname = \"b\"\nkind = \"bond\"\nshear_strength = \"10 MPa\"\nsource = \"s\"\n";
        let e = parse_entry(&format!("{bond}yield_strength_range = [1, 2]\n"), p).unwrap_err();
        assert!(
            e.to_string().starts_with("m.toml:6: yield_strength_range"),
            "{e}"
        );
        let e = parse_entry(&format!("{bond}range_source = \"x\"\n"), p).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("m.toml:6: range_source: no range"),
            "{e}"
        );
    }

    #[test]
    fn the_library_has_ranges_with_sources_except_the_papers_values() {
        let lib = Library::builtin().unwrap();
        for e in lib.entries().unwrap() {
            let (name, ranges, strength) = match e {
                Entry::Material(m) => (&m.name, &m.ranges, m.yield_strength),
                Entry::Bond(b) => (&b.name, &b.ranges, Some(b.shear_strength)),
            };
            if name.starts_with("paper-") || name == "epoxy" {
                assert!(ranges.is_empty(), "{name}");
                continue;
            }
            assert!(
                ranges.source.as_ref().is_some_and(|s| s.len() > 40),
                "{name}"
            );
            if let Entry::Material(m) = e {
                let (e_span, nu_span) = (
                    ranges.youngs_modulus.unwrap(),
                    ranges.poisson_ratio.unwrap(),
                );
                assert!(e_span.is_wide() && nu_span.is_wide(), "{name}");
                assert!(
                    (e_span.min..=e_span.max).contains(&m.elastic.youngs),
                    "{name}"
                );
            }
            // Glass's "yield strength" is a rough compressive strength: no range.
            if let Some(strength) = strength
                && name != "glass"
            {
                let s = ranges.strength.unwrap();
                assert!(s.is_wide() && (s.min..=s.max).contains(&strength), "{name}");
            }
        }
    }

    #[test]
    fn a_directory_overrides_bundled_entries() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(
            dir.path().join("epoxy.toml"),
            "schema_version = 1\nname = \"epoxy\"\nkind = \"bond\"\nshear_strength = \"20 MPa\"\nsource = \"my test\"\n",
        )
        .unwrap();
        let lib = Library::with_dir(Some(dir.path())).unwrap();
        assert_eq!(lib.bond("epoxy").unwrap().shear_strength, 2e7);
        assert!(lib.material("paper-rubber").is_ok());
        // An override may change the kind; the listing has the name once, as the new kind.
        std::fs::write(
            dir.path().join("epoxy.toml"),
            "schema_version = 1\nname = \"Epoxy\"\nkind = \"film\"\nyoungs_modulus = \"3 GPa\"\npoisson_ratio = 0.35\nsource = \"my test\"\n",
        )
        .unwrap();
        let lib = Library::with_dir(Some(dir.path())).unwrap();
        assert_eq!(lib.material("epoxy").unwrap().elastic.youngs, 3e9);
        let e = lib.bond("epoxy").unwrap_err();
        assert!(
            e.contains("is an elastic material") && !e.contains("epoxy,"),
            "{e}"
        );
        let names: Vec<&str> = lib.entries().unwrap().iter().map(|e| e.name()).collect();
        assert_eq!(
            names
                .iter()
                .filter(|n| n.eq_ignore_ascii_case("epoxy"))
                .count(),
            1
        );
    }

    #[test]
    fn the_listing_has_every_bundled_entry_materials_first_each_sorted() {
        let lib = Library::builtin().unwrap();
        // A lookup first: the listing takes parsed and unparsed files alike.
        lib.bond("epoxy").unwrap();
        let entries = lib.entries().unwrap();
        assert_eq!(entries.len(), BUILTIN.len());
        let kinds: Vec<bool> = entries
            .iter()
            .map(|e| matches!(e, Entry::Bond(_)))
            .collect();
        assert!(kinds.is_sorted(), "materials, then bonds");
        for w in entries.windows(2) {
            if kinds_eq(w[0], w[1]) {
                assert!(w[0].name() < w[1].name(), "{} {}", w[0].name(), w[1].name());
            }
        }
        for (file, text) in BUILTIN {
            let e = parse_entry(text, Path::new(file)).unwrap();
            assert!(entries.contains(&&e), "{file}");
        }
        assert!(Library::default().entries().unwrap().is_empty());
        assert!(Library::default().material("epoxy").is_err());
    }

    fn kinds_eq(a: &Entry, b: &Entry) -> bool {
        matches!(a, Entry::Bond(_)) == matches!(b, Entry::Bond(_))
    }
}
