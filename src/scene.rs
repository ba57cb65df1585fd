//! A scene: one coating design to judge, read from a TOML file and/or command-line flags (flags
//! override the file). Every physical value accepts units (`"10 um"`, `"0.1 MPa"`, `"1e5 1/m"`);
//! a bare number is SI.
//!
//! ```toml
//! [roughness]            # psd = "surface.csv" (relative to this file), or a model:
//! model = "self-affine"  # eq. (2): hurst, q0, q1, optional roll_off
//! hurst = 1
//! q0 = "1e5 1/m"
//! q1 = "1e8 1/m"
//! rms_slope = 1          # or rms_height = "1 um"; q_min, q_max restrict measured data
//! [film]
//! material = "paper-rubber"  # or youngs_modulus = "1 MPa", poisson_ratio = 0.5
//! thickness = "10 um"
//! [substrate]
//! material = "paper-steel"   # or youngs_modulus, poisson_ratio, yield_strength
//! [bond]
//! material = "epoxy"         # or shear_strength = "10 MPa"
//! [load]
//! pressure = "0.1 MPa"
//! [criteria]                 # optional
//! epsilon = 1e-6
//! safety_factor = 1
//! checks = ["bond-shear", "substrate-yield", "min-thickness"]
//! [numerics]                 # optional
//! rtol = 1e-8
//! ```
//!
//! Several measurements of one part are listed together, `psd = ["scan-a.csv", "scan-b.csv"]`
//! (or `profile = [...]`): the check runs on each file's spectrum and reports the worst, naming
//! the file ([`Roughness::each_file`]). A top-level `coatcheck_version = "0.1.0"` pins the
//! version the design was qualified with; a different running version gives a warning
//! ([`Scene::version_warning`]).
//!
//! The Gaussian band (eq. 5) is `model = "gaussian"` with `q0` and `width`. A substrate given by
//! name may still set `yield_strength` (the grade's value overrides the library's). Unknown keys
//! and contradictions (psd and a model, a material and explicit moduli, rms slope and height) are
//! errors naming the keys and the line. A flag for one alternative (e.g. `--psd`) replaces the
//! file's other alternative (e.g. its model).

use crate::check::{CheckKind, Checks, Criteria, Design};
use crate::error::Error;
use crate::layer::{Bilayer, Elastic};
use crate::material::{Bond, Kind, Library, Material};
use crate::prec::Settings;
use crate::psd::Spectrum;
use crate::psd::read::{Column, PsdKind, ReadOptions, read_spectrum};
use crate::tomlin::{Ctx, Field, Origin, Raw, Source};
use crate::units::Dim;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The scene as written (file and flags), before validation.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawScene {
    pub schema_version: Option<Field>,
    pub coatcheck_version: Option<Field>,
    pub roughness: RawRoughness,
    pub film: RawFilm,
    pub substrate: RawSubstrate,
    pub bond: RawBond,
    pub load: RawLoad,
    pub criteria: RawCriteria,
    pub numerics: RawNumerics,
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawRoughness {
    pub psd: Option<Field>,
    pub profile: Option<Field>,
    pub model: Option<Field>,
    pub hurst: Option<Field>,
    pub q0: Option<Field>,
    pub q1: Option<Field>,
    pub roll_off: Option<Field>,
    pub width: Option<Field>,
    pub rms_slope: Option<Field>,
    pub rms_height: Option<Field>,
    pub q_min: Option<Field>,
    pub q_max: Option<Field>,
    pub q_col: Option<Field>,
    pub c_col: Option<Field>,
    pub q_unit: Option<Field>,
    pub c_unit: Option<Field>,
    pub psd_kind: Option<Field>,
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawFilm {
    pub material: Option<Field>,
    pub youngs_modulus: Option<Field>,
    pub poisson_ratio: Option<Field>,
    pub thickness: Option<Field>,
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawSubstrate {
    pub material: Option<Field>,
    pub youngs_modulus: Option<Field>,
    pub poisson_ratio: Option<Field>,
    pub yield_strength: Option<Field>,
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawBond {
    pub material: Option<Field>,
    pub shear_strength: Option<Field>,
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawLoad {
    pub pressure: Option<Field>,
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawCriteria {
    pub epsilon: Option<Field>,
    pub safety_factor: Option<Field>,
    pub checks: Option<Field>,
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawNumerics {
    pub rtol: Option<Field>,
}

/// The scene keys that can be set from the command line, with their flags.
pub const FLAG_KEYS: &[(&str, &str)] = &[
    ("roughness.psd", "--psd"),
    ("roughness.profile", "--profile"),
    ("roughness.model", "--model"),
    ("roughness.hurst", "--hurst"),
    ("roughness.q0", "--q0"),
    ("roughness.q1", "--q1"),
    ("roughness.roll_off", "--roll-off"),
    ("roughness.width", "--width"),
    ("roughness.rms_slope", "--rms-slope"),
    ("roughness.rms_height", "--rms-height"),
    ("roughness.q_min", "--q-min"),
    ("roughness.q_max", "--q-max"),
    ("roughness.q_col", "--q-col"),
    ("roughness.c_col", "--c-col"),
    ("roughness.q_unit", "--q-unit"),
    ("roughness.c_unit", "--c-unit"),
    ("roughness.psd_kind", "--psd-kind"),
    ("film.material", "--film"),
    ("film.youngs_modulus", "--film-youngs-modulus"),
    ("film.poisson_ratio", "--film-poisson-ratio"),
    ("film.thickness", "--thickness"),
    ("substrate.material", "--substrate"),
    ("substrate.youngs_modulus", "--substrate-youngs-modulus"),
    ("substrate.poisson_ratio", "--substrate-poisson-ratio"),
    ("substrate.yield_strength", "--yield-strength"),
    ("bond.material", "--bond"),
    ("bond.shear_strength", "--shear-strength"),
    ("load.pressure", "--pressure"),
    ("criteria.epsilon", "--epsilon"),
    ("criteria.safety_factor", "--safety-factor"),
    ("criteria.checks", "--checks"),
    ("numerics.rtol", "--rtol"),
];

/// Mutually exclusive alternatives: a flag for a key of one alternative clears the file's keys
/// of the others; keys of two alternatives together are a contradiction.
const EXCLUSIVE: &[&[&[&str]]] = &[
    &[
        &[
            "roughness.psd",
            "roughness.q_min",
            "roughness.q_max",
            "roughness.q_col",
            "roughness.c_col",
            "roughness.q_unit",
            "roughness.c_unit",
            "roughness.psd_kind",
        ],
        &["roughness.profile"],
        &[
            "roughness.model",
            "roughness.hurst",
            "roughness.q0",
            "roughness.q1",
            "roughness.roll_off",
            "roughness.width",
        ],
    ],
    &[&["roughness.rms_slope"], &["roughness.rms_height"]],
    &[
        &["film.material"],
        &["film.youngs_modulus", "film.poisson_ratio"],
    ],
    &[
        &["substrate.material"],
        &["substrate.youngs_modulus", "substrate.poisson_ratio"],
    ],
    &[&["bond.material"], &["bond.shear_strength"]],
];

/// Every key of the scene with its slot (`all_keys!(self, &)` or `all_keys!(self, &mut)`).
macro_rules! all_keys {
    ($s:ident, $($r:tt)+) => {
        [
            ("roughness.psd", $($r)+ $s.roughness.psd),
            ("roughness.profile", $($r)+ $s.roughness.profile),
            ("roughness.model", $($r)+ $s.roughness.model),
            ("roughness.hurst", $($r)+ $s.roughness.hurst),
            ("roughness.q0", $($r)+ $s.roughness.q0),
            ("roughness.q1", $($r)+ $s.roughness.q1),
            ("roughness.roll_off", $($r)+ $s.roughness.roll_off),
            ("roughness.width", $($r)+ $s.roughness.width),
            ("roughness.rms_slope", $($r)+ $s.roughness.rms_slope),
            ("roughness.rms_height", $($r)+ $s.roughness.rms_height),
            ("roughness.q_min", $($r)+ $s.roughness.q_min),
            ("roughness.q_max", $($r)+ $s.roughness.q_max),
            ("roughness.q_col", $($r)+ $s.roughness.q_col),
            ("roughness.c_col", $($r)+ $s.roughness.c_col),
            ("roughness.q_unit", $($r)+ $s.roughness.q_unit),
            ("roughness.c_unit", $($r)+ $s.roughness.c_unit),
            ("roughness.psd_kind", $($r)+ $s.roughness.psd_kind),
            ("film.material", $($r)+ $s.film.material),
            ("film.youngs_modulus", $($r)+ $s.film.youngs_modulus),
            ("film.poisson_ratio", $($r)+ $s.film.poisson_ratio),
            ("film.thickness", $($r)+ $s.film.thickness),
            ("substrate.material", $($r)+ $s.substrate.material),
            ("substrate.youngs_modulus", $($r)+ $s.substrate.youngs_modulus),
            ("substrate.poisson_ratio", $($r)+ $s.substrate.poisson_ratio),
            ("substrate.yield_strength", $($r)+ $s.substrate.yield_strength),
            ("bond.material", $($r)+ $s.bond.material),
            ("bond.shear_strength", $($r)+ $s.bond.shear_strength),
            ("load.pressure", $($r)+ $s.load.pressure),
            ("criteria.epsilon", $($r)+ $s.criteria.epsilon),
            ("criteria.safety_factor", $($r)+ $s.criteria.safety_factor),
            ("criteria.checks", $($r)+ $s.criteria.checks),
            ("numerics.rtol", $($r)+ $s.numerics.rtol),
        ]
    };
}

impl RawScene {
    /// Every key with its value.
    pub fn fields(&self) -> [(&'static str, &Option<Field>); 32] {
        all_keys!(self, &)
    }

    fn slot(&mut self, key: &str) -> Option<&mut Option<Field>> {
        all_keys!(self, &mut)
            .into_iter()
            .find(|(k, _)| *k == key)
            .map(|(_, f)| f)
    }

    fn get(&self, key: &str) -> Option<&Field> {
        self.fields()
            .into_iter()
            .find(|(k, _)| *k == key)
            .and_then(|(_, f)| f.as_ref())
    }

    /// Set `key` from a command-line flag, replacing the file's value and the file's keys of
    /// the other alternatives of its group.
    pub fn set_flag(&mut self, key: &str, text: &str) {
        let flag = FLAG_KEYS
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, f)| *f)
            .unwrap_or("--flag");
        for group in EXCLUSIVE {
            if let Some(mine) = group.iter().position(|alt| alt.contains(&key)) {
                for (i, alt) in group.iter().enumerate() {
                    if i == mine {
                        continue;
                    }
                    for other in alt.iter() {
                        if let Some(slot) = self.slot(other)
                            && slot.as_ref().is_some_and(|f| !f.is_flag())
                        {
                            *slot = None;
                        }
                    }
                }
            }
        }
        if let Some(slot) = self.slot(key) {
            *slot = Some(Field::flag(flag, text));
        }
    }
}

/// Where the roughness comes from.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum RoughnessSource {
    /// A measured PSD file (columns q [1/m], C [m^4] unless its header says otherwise).
    Measured { path: PathBuf },
    /// Measured heights (line scans or a height map with its metadata line), turned into a PSD
    /// by the `coatcheck psd` pipeline with its defaults.
    Profile { path: PathBuf },
    /// Eq. (2).
    SelfAffine {
        hurst: f64,
        q0: f64,
        q1: f64,
        roll_off: Option<f64>,
    },
    /// Eq. (5).
    Gaussian { q0: f64, width: f64 },
}

/// How the spectrum is scaled.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Scale {
    RmsSlope(f64),
    /// m.
    RmsHeight(f64),
}

/// How to read a measured PSD file (keys roughness.q_col, c_col, q_unit, c_unit, psd_kind);
/// unset fields fall back to the file's header (`crate::psd::read`).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct PsdFormat {
    /// Column of q: a 1-based number or a header name.
    pub q_col: Option<String>,
    /// Column of C.
    pub c_col: Option<String>,
    /// Unit of q, e.g. `1/um`.
    pub q_unit: Option<String>,
    /// Unit of C, e.g. `um^4` (2D) or `nm^3` (1D).
    pub c_unit: Option<String>,
    /// A 2D PSD (m^4) or a 1D PSD from line scans (m^3), converted by the inverse Abel transform.
    pub kind: Option<PsdKind>,
}

impl PsdFormat {
    fn options(&self) -> Result<ReadOptions, Error> {
        let col = |c: &Option<String>| c.as_deref().map(str::parse::<Column>).transpose();
        Ok(ReadOptions {
            q_col: col(&self.q_col)?,
            c_col: col(&self.c_col)?,
            q_unit: self.q_unit.clone(),
            c_unit: self.c_unit.clone(),
            kind: self.kind,
            ..ReadOptions::default()
        })
    }
}

/// The roughness of a scene.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Roughness {
    /// The roughness (the first file when the scene lists several).
    pub source: RoughnessSource,
    /// The further files of a measured `source` when the scene lists several (same kind, same
    /// scaling and q-range); empty otherwise.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub more_files: Vec<PathBuf>,
    pub scale: Option<Scale>,
    pub q_min: Option<f64>,
    pub q_max: Option<f64>,
    pub psd_format: PsdFormat,
    /// The scene file and line that named the file(s), for messages about unreadable files.
    #[serde(skip)]
    pub declared_at: Option<(PathBuf, usize)>,
}

impl Roughness {
    /// The measured file of `source` (`None` for a model).
    pub fn file(&self) -> Option<&Path> {
        match &self.source {
            RoughnessSource::Measured { path } | RoughnessSource::Profile { path } => Some(path),
            _ => None,
        }
    }

    /// One roughness per listed file (the scene's roughness itself when it has one file or a
    /// model).
    pub fn each_file(&self) -> Vec<Roughness> {
        let one = |source: RoughnessSource| Roughness {
            source,
            more_files: Vec::new(),
            ..self.clone()
        };
        let mut all = vec![one(self.source.clone())];
        for path in &self.more_files {
            all.push(one(match &self.source {
                RoughnessSource::Profile { .. } => RoughnessSource::Profile { path: path.clone() },
                _ => RoughnessSource::Measured { path: path.clone() },
            }));
        }
        all
    }

    /// A file that cannot be read, or whose data do not fit the scene's q-range, is reported
    /// at the scene line that named it.
    fn locate(&self, e: Error) -> Error {
        match (e, &self.declared_at) {
            (e @ Error::Invalid { .. }, Some((scene, line))) => Error::Input {
                path: scene.clone(),
                line: *line,
                msg: format!(
                    "{}: {e}",
                    self.file()
                        .map_or(String::new(), |p| p.display().to_string())
                ),
            },
            (Error::Io { path, source }, Some((scene, line))) => {
                let key = match self.source {
                    RoughnessSource::Profile { .. } => "roughness.profile",
                    _ => "roughness.psd",
                };
                Error::Input {
                    path: scene.clone(),
                    line: *line,
                    msg: format!("{key}: cannot read {}: {source}", path.display()),
                }
            }
            (e, _) => e,
        }
    }

    /// The spectrum of `source` (read, restricted to [q_min, q_max], scaled) with the reader's
    /// warnings. A scene that lists several files is run file by file: [`Roughness::each_file`].
    pub fn spectrum(&self) -> Result<(Spectrum, Vec<String>), Error> {
        self.spectrum_unlocated().map_err(|e| self.locate(e))
    }

    fn spectrum_unlocated(&self) -> Result<(Spectrum, Vec<String>), Error> {
        let (base, warnings) = match &self.source {
            RoughnessSource::Measured { path } => {
                let (t, w) = read_spectrum(path, &self.psd_format.options()?)?;
                let t = if self.q_min.is_some() || self.q_max.is_some() {
                    t.restricted(self.q_min, self.q_max)?
                } else {
                    t
                };
                (Spectrum::Tabulated(t), w)
            }
            RoughnessSource::Profile { path } => {
                let (_, psd) =
                    crate::topography::psd_of_file(path, &Default::default(), &Default::default())?;
                (Spectrum::Tabulated(psd.c2d), vec![])
            }
            RoughnessSource::SelfAffine {
                hurst,
                q0,
                q1,
                roll_off,
            } => (Spectrum::self_affine(*hurst, *q0, *q1, *roll_off)?, vec![]),
            RoughnessSource::Gaussian { q0, width } => (Spectrum::gaussian(*q0, *width)?, vec![]),
        };
        let (lo, hi) = base.support();
        if q_out_of_range(lo) || q_out_of_range(hi) {
            return Err(Error::invalid(
                "wavenumber range of the spectrum (1/m)",
                match self.file() {
                    Some(p) => format!("{lo:e} to {hi:e} in {}", p.display()),
                    None => format!("{lo:e} to {hi:e}"),
                },
                "wavenumbers within 1e-6 to 1e12 1/m (check the q column's unit)",
            ));
        }
        let s = match self.scale {
            Some(Scale::RmsSlope(xi)) => base.scaled_to_rms_slope(xi)?,
            Some(Scale::RmsHeight(h)) => base.scaled_to_rms_height(h)?,
            None => base,
        };
        // The same bounds as a given rms slope: C far off (a wrong unit) fails here, named.
        let slope = s.slope_sq().value.sqrt();
        if let Some(&(_, lo, hi)) = RANGES.iter().find(|(k, _, _)| *k == "roughness.rms_slope")
            && !(lo..=hi).contains(&slope)
        {
            return Err(Error::invalid(
                "rms slope of the spectrum",
                match self.file() {
                    Some(p) => format!("{slope:e} for {}", p.display()),
                    None => format!("{slope:e}"),
                },
                "an rms slope within 1e-12 to 1e3 (check the C column's unit)",
            ));
        }
        Ok((s, warnings))
    }
}

/// A validated scene, SI units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Scene {
    /// The scene file, if any.
    pub file: Option<PathBuf>,
    /// The coatcheck version the design was qualified with (`coatcheck_version`), if pinned.
    pub coatcheck_version: Option<String>,
    pub roughness: Roughness,
    pub film: Material,
    /// Film thickness (m); may be absent when only a sweep is asked for.
    pub thickness: Option<f64>,
    pub substrate: Material,
    pub bond: Bond,
    /// Nominal pressure p0 (Pa).
    pub pressure: f64,
    pub criteria: Criteria,
    pub settings: Settings,
}

impl Scene {
    /// A warning when the scene pins a coatcheck version other than this one.
    pub fn version_warning(&self) -> Option<String> {
        let pinned = self.coatcheck_version.as_deref()?;
        let running = env!("CARGO_PKG_VERSION");
        (pinned != running).then(|| {
            format!(
                "the scene pins coatcheck_version = \"{pinned}\" but this is coatcheck {running}: re-qualify the design and update the pin"
            )
        })
    }

    /// One scene per roughness file (the scene itself when it has one file or a model).
    pub fn each_file(&self) -> Vec<Scene> {
        self.roughness
            .each_file()
            .into_iter()
            .map(|roughness| Scene {
                roughness,
                ..self.clone()
            })
            .collect()
    }

    /// The design (without thickness) for [`crate::check::Checker`].
    pub fn design(&self) -> Design {
        Design {
            layers: Bilayer::new(self.film.elastic, self.substrate.elastic),
            pressure: self.pressure,
            yield_strength: self.substrate.yield_strength,
            bond_strength: self.bond.shear_strength,
            criteria: self.criteria,
        }
    }

    /// Read a scene file (if any), apply flag overrides `(key, text)`, and validate.
    pub fn load(
        file: Option<&Path>,
        overrides: &[(&str, String)],
        library: &Library,
    ) -> Result<Scene, Error> {
        let text = match file {
            Some(p) => Some(std::fs::read_to_string(p).map_err(|source| Error::Io {
                path: p.to_path_buf(),
                source,
            })?),
            None => None,
        };
        let src = file
            .zip(text.as_deref())
            .map(|(path, text)| Source { path, text });
        let mut raw: RawScene = match &src {
            Some(s) => s.parse()?,
            None => RawScene::default(),
        };
        for (key, value) in overrides {
            raw.set_flag(key, value);
        }
        let ctx = Ctx { file: src.as_ref() };
        resolve(&raw, ctx, library, file)
    }
}

/// Validate a raw scene.
pub fn resolve(
    raw: &RawScene,
    ctx: Ctx<'_>,
    library: &Library,
    file: Option<&Path>,
) -> Result<Scene, Error> {
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
    let coatcheck_version = match &raw.coatcheck_version {
        Some(v) => {
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
            Some(text.to_string())
        }
        None => None,
    };
    for group in EXCLUSIVE {
        let given: Vec<(&str, &Field)> = group
            .iter()
            .filter_map(|alt| alt.iter().find_map(|k| raw.get(k).map(|f| (*k, f))))
            .collect();
        if given.len() > 1 {
            let (k1, _) = given[0];
            let (k2, f2) = given[1];
            return Err(ctx.error(
                &f2.origin,
                k2,
                format!("contradicts {k1} (give one of them, not both)"),
            ));
        }
    }
    let roughness = resolve_roughness(&raw.roughness, ctx)?;
    let film = resolve_material(
        ctx,
        library,
        "film",
        raw.film.material.as_ref(),
        raw.film.youngs_modulus.as_ref(),
        raw.film.poisson_ratio.as_ref(),
        None,
        Kind::Film,
    )?;
    let thickness = match &raw.film.thickness {
        Some(f) => Some(ranged(ctx, f, "film.thickness", Dim::Length(1))?),
        None => None,
    };
    let substrate = resolve_material(
        ctx,
        library,
        "substrate",
        raw.substrate.material.as_ref(),
        raw.substrate.youngs_modulus.as_ref(),
        raw.substrate.poisson_ratio.as_ref(),
        raw.substrate.yield_strength.as_ref(),
        Kind::Substrate,
    )?;
    let bond = match (&raw.bond.material, &raw.bond.shear_strength) {
        (Some(f), _) => {
            let name = ctx.text(f, "bond.material")?;
            library
                .bond(name)
                .map_err(|e| ctx.error(&f.origin, "bond.material", e))?
                .clone()
        }
        (None, Some(f)) => Bond {
            name: "custom".into(),
            shear_strength: ranged(ctx, f, "bond.shear_strength", Dim::Pressure)?,
            source: "given in the scene".into(),
        },
        (None, None) => {
            return Err(ctx.missing(
                "bond.material or bond.shear_strength",
                "name a bond (coatcheck materials) or give its shear strength, e.g. --shear-strength \"10 MPa\"",
            ));
        }
    };
    let pressure = match &raw.load.pressure {
        Some(f) => ranged(ctx, f, "load.pressure", Dim::Pressure)?,
        None => {
            return Err(ctx.missing(
                "load.pressure",
                "give the nominal pressure, e.g. --pressure \"0.1 MPa\"",
            ));
        }
    };
    let mut criteria = Criteria::default();
    if let Some(f) = &raw.criteria.epsilon {
        let e = ctx.quantity(f, "criteria.epsilon", Dim::Dimensionless)?;
        if !(e > 0.0 && e < 1.0) {
            return Err(ctx.error(
                &f.origin,
                "criteria.epsilon",
                format!("{e} (expected 0 < epsilon < 1)"),
            ));
        }
        criteria.epsilon = e;
    }
    if let Some(f) = &raw.criteria.safety_factor {
        let s = ctx.quantity(f, "criteria.safety_factor", Dim::Dimensionless)?;
        if s < 1.0 {
            return Err(ctx.error(
                &f.origin,
                "criteria.safety_factor",
                format!("{s} (expected a safety factor >= 1)"),
            ));
        }
        criteria.safety_factor = s;
    }
    if let Some(f) = &raw.criteria.checks {
        let mut checks = Checks::none();
        let names = ctx.list(f, "criteria.checks")?;
        if names.is_empty() {
            return Err(ctx.error(
                &f.origin,
                "criteria.checks",
                "empty (expected at least one check)",
            ));
        }
        for n in names {
            let c = CheckKind::from_name(&n).ok_or_else(|| {
                ctx.error(
                    &f.origin,
                    "criteria.checks",
                    format!("unknown check '{n}' (expected bond-shear, substrate-yield or min-thickness)"),
                )
            })?;
            checks.enable(c);
        }
        criteria.checks = checks;
    }
    if criteria.checks.substrate_yield && substrate.yield_strength.is_none() {
        return Err(ctx.missing(
            "substrate.yield_strength",
            &format!(
                "substrate '{}' has no yield strength: give one or leave substrate-yield out of criteria.checks",
                substrate.name
            ),
        ));
    }
    let mut settings = Settings::default();
    if let Some(f) = &raw.numerics.rtol {
        let r = ctx.quantity(f, "numerics.rtol", Dim::Dimensionless)?;
        if !(1e-13..=1e-2).contains(&r) {
            return Err(ctx.error(
                &f.origin,
                "numerics.rtol",
                format!("{r} (expected 1e-13 <= rtol <= 1e-2)"),
            ));
        }
        settings.rtol = r;
    }
    Ok(Scene {
        file: file.map(Path::to_path_buf),
        coatcheck_version,
        roughness,
        film,
        thickness,
        substrate,
        bond,
        pressure,
        criteria,
        settings,
    })
}

fn resolve_roughness(r: &RawRoughness, ctx: Ctx<'_>) -> Result<Roughness, Error> {
    let wavenumber = |f: &Option<Field>, key: &str| -> Result<Option<f64>, Error> {
        f.as_ref()
            .map(|f| wavenumber_in_range(ctx, f, key))
            .transpose()
    };
    let scale = match (&r.rms_slope, &r.rms_height) {
        (Some(f), _) => Some(Scale::RmsSlope(ranged(
            ctx,
            f,
            "roughness.rms_slope",
            Dim::Dimensionless,
        )?)),
        (None, Some(f)) => Some(Scale::RmsHeight(ranged(
            ctx,
            f,
            "roughness.rms_height",
            Dim::Length(1),
        )?)),
        (None, None) => None,
    };
    let q_min = wavenumber(&r.q_min, "roughness.q_min")?;
    let q_max = wavenumber(&r.q_max, "roughness.q_max")?;
    if let (Some(a), Some(b), Some(f)) = (q_min, q_max, &r.q_max)
        && a >= b
    {
        return Err(ctx.error(
            &f.origin,
            "roughness.q_max",
            format!("{b} 1/m is not above q_min = {a} 1/m"),
        ));
    }
    let mut more_files = Vec::new();
    let mut declared_at = None;
    let source = if let Some((f, key)) = r
        .psd
        .as_ref()
        .map(|f| (f, "roughness.psd"))
        .or_else(|| r.profile.as_ref().map(|f| (f, "roughness.profile")))
    {
        let mut paths = file_list(ctx, f, key)?.into_iter();
        if let (Origin::File(span), Some(src)) = (&f.origin, ctx.file) {
            declared_at = Some((src.path.to_path_buf(), src.line_of(span.start)));
        }
        let first = paths.next().expect("file_list is never empty");
        more_files.extend(paths);
        if key == "roughness.psd" {
            RoughnessSource::Measured { path: first }
        } else {
            RoughnessSource::Profile { path: first }
        }
    } else if let Some(f) = &r.model {
        let model = ctx.text(f, "roughness.model")?;
        let need = |g: &Option<Field>, key: &str, dim: Dim| -> Result<f64, Error> {
            match g {
                Some(g) if dim == Dim::Length(-1) => wavenumber_in_range(ctx, g, key),
                Some(g) => ctx.positive(g, key, dim),
                None => Err(ctx.error(
                    &f.origin,
                    key,
                    format!("missing (model '{model}' needs it)"),
                )),
            }
        };
        let unused = |g: &Option<Field>, key: &str| -> Result<(), Error> {
            match g {
                Some(g) => Err(ctx.error(
                    &g.origin,
                    key,
                    format!("not a parameter of model '{model}'"),
                )),
                None => Ok(()),
            }
        };
        let src = match model {
            "self-affine" => {
                unused(&r.width, "roughness.width")?;
                RoughnessSource::SelfAffine {
                    hurst: need(&r.hurst, "roughness.hurst", Dim::Dimensionless)?,
                    q0: need(&r.q0, "roughness.q0", Dim::Length(-1))?,
                    q1: need(&r.q1, "roughness.q1", Dim::Length(-1))?,
                    roll_off: wavenumber(&r.roll_off, "roughness.roll_off")?,
                }
            }
            "gaussian" => {
                for (g, k) in [
                    (&r.hurst, "roughness.hurst"),
                    (&r.q1, "roughness.q1"),
                    (&r.roll_off, "roughness.roll_off"),
                ] {
                    unused(g, k)?;
                }
                RoughnessSource::Gaussian {
                    q0: need(&r.q0, "roughness.q0", Dim::Length(-1))?,
                    width: need(&r.width, "roughness.width", Dim::Length(-1))?,
                }
            }
            other => {
                return Err(ctx.error(
                    &f.origin,
                    "roughness.model",
                    format!("unknown model '{other}' (expected self-affine or gaussian)"),
                ));
            }
        };
        if scale.is_none() {
            return Err(ctx.error(
                &f.origin,
                "roughness.model",
                "a model needs rms_slope or rms_height to set its amplitude",
            ));
        }
        // The model's own domain checks (H in (0, 1], q0 < q_r < q1, a band away from 0),
        // reported at the offending key's line.
        let built = match &src {
            RoughnessSource::SelfAffine {
                hurst,
                q0,
                q1,
                roll_off,
            } => Spectrum::self_affine(*hurst, *q0, *q1, *roll_off).map(drop),
            RoughnessSource::Gaussian { q0, width } => Spectrum::gaussian(*q0, *width).map(drop),
            _ => Ok(()),
        };
        if let Err(e) = built {
            let (key, field) = match &e {
                Error::Invalid { what, .. } if what.starts_with("Hurst") => {
                    ("roughness.hurst", &r.hurst)
                }
                Error::Invalid { what: "q0", .. } => ("roughness.q0", &r.q0),
                Error::Invalid { what: "q1", .. } => ("roughness.q1", &r.q1),
                Error::Invalid { what, .. } if what.starts_with("roll-off") => {
                    ("roughness.roll_off", &r.roll_off)
                }
                Error::Invalid { what, .. } if what.starts_with("Gaussian width") => {
                    ("roughness.width", &r.width)
                }
                _ => ("roughness.model", &r.model),
            };
            let origin = field.as_ref().map_or(&f.origin, |g| &g.origin);
            return Err(ctx.error(origin, key, e));
        }
        src
    } else {
        return Err(ctx.missing(
            "roughness.psd, roughness.profile or roughness.model",
            "give a PSD file (--psd surface.csv), heights (--profile map.csv) or a model (model = \"self-affine\" ...)",
        ));
    };
    let text = |f: &Option<Field>, key: &str| -> Result<Option<String>, Error> {
        f.as_ref()
            .map(|f| ctx.text(f, key).map(str::to_string))
            .transpose()
    };
    let column = |f: &Option<Field>, key: &str| -> Result<Option<String>, Error> {
        let c = text(f, key)?;
        if let (Some(c), Some(f)) = (&c, f) {
            c.parse::<Column>()
                .map_err(|e| ctx.error(&f.origin, key, e.to_string()))?;
        }
        Ok(c)
    };
    let kind = match (&r.psd_kind, text(&r.psd_kind, "roughness.psd_kind")?) {
        (Some(f), Some(k)) => Some(match k.to_ascii_lowercase().as_str() {
            "2d" => PsdKind::TwoD,
            "1d" => PsdKind::OneD,
            _ => {
                return Err(ctx.error(
                    &f.origin,
                    "roughness.psd_kind",
                    format!("'{k}' (expected 2d or 1d)"),
                ));
            }
        }),
        _ => None,
    };
    let psd_format = PsdFormat {
        q_col: column(&r.q_col, "roughness.q_col")?,
        c_col: column(&r.c_col, "roughness.c_col")?,
        q_unit: text(&r.q_unit, "roughness.q_unit")?,
        c_unit: text(&r.c_unit, "roughness.c_unit")?,
        kind,
    };
    Ok(Roughness {
        source,
        more_files,
        scale,
        q_min,
        q_max,
        psd_format,
        declared_at,
    })
}

/// Accepted ranges of scene values (SI): far wider than any coating design, and well inside the
/// floating-point range of the contact integrals. A value beyond them is a typo or a wrong
/// unit, rejected at its line rather than overflowing later.
pub const RANGES: &[(&str, f64, f64)] = &[
    ("film.thickness", 1e-10, 10.0),
    ("load.pressure", 1.0, 1e12),
    ("bond.shear_strength", 1.0, 1e12),
    ("substrate.yield_strength", 1.0, 1e12),
    ("film.youngs_modulus", 1.0, 1e13),
    ("substrate.youngs_modulus", 1.0, 1e13),
    ("roughness.rms_slope", 1e-12, 1e3),
    ("roughness.rms_height", 1e-15, 1.0),
];

/// A value > 0 within its [`RANGES`] entry.
fn ranged(ctx: Ctx<'_>, f: &Field, key: &str, dim: Dim) -> Result<f64, Error> {
    let v = ctx.positive(f, key, dim)?;
    if let Some(&(_, lo, hi)) = RANGES.iter().find(|(k, _, _)| *k == key)
        && !(lo..=hi).contains(&v)
    {
        return Err(ctx.error(
            &f.origin,
            key,
            format!("{v:e} (SI) is outside the accepted range {lo:e} to {hi:e}; check the value and its unit"),
        ));
    }
    Ok(v)
}

/// The wavenumbers the tool models (1/m): wavelengths 2π/q from about 6 pm to 6000 km. Far
/// outside any surface, and well inside the floating-point range of the moments of C(q)
/// (q^4 C, q^6 C); a value beyond them is a typo or a wrong unit.
pub const Q_RANGE: (f64, f64) = (1e-6, 1e12);

fn q_out_of_range(q: f64) -> bool {
    !(Q_RANGE.0..=Q_RANGE.1).contains(&q)
}

fn wavenumber_in_range(ctx: Ctx<'_>, f: &Field, key: &str) -> Result<f64, Error> {
    let q = ctx.positive(f, key, Dim::Length(-1))?;
    if q_out_of_range(q) {
        return Err(ctx.error(
            &f.origin,
            key,
            format!(
                "{q:e} 1/m is outside the wavenumbers this tool models ({:e} to {:e} 1/m); check the value and its unit",
                Q_RANGE.0, Q_RANGE.1
            ),
        ));
    }
    Ok(q)
}

/// The file(s) of `roughness.psd` or `roughness.profile`: one path, or a non-empty list of
/// distinct paths (each relative to the scene file).
fn file_list(ctx: Ctx<'_>, f: &Field, key: &str) -> Result<Vec<PathBuf>, Error> {
    let Raw::List(names) = &f.raw else {
        return Ok(vec![ctx.path(f, key)?]);
    };
    if names.is_empty() {
        return Err(ctx.error(
            &f.origin,
            key,
            "empty list (expected one file name or a list of file names)",
        ));
    }
    let mut paths: Vec<PathBuf> = Vec::with_capacity(names.len());
    for name in names {
        if name.trim().is_empty() {
            return Err(ctx.error(&f.origin, key, "an empty file name in the list"));
        }
        let one = Field {
            raw: Raw::Text(name.clone()),
            origin: f.origin.clone(),
        };
        let path = ctx.path(&one, key)?;
        if paths.contains(&path) {
            return Err(ctx.error(&f.origin, key, format!("'{name}' is listed twice")));
        }
        paths.push(path);
    }
    Ok(paths)
}

#[allow(clippy::too_many_arguments)]
fn resolve_material(
    ctx: Ctx<'_>,
    library: &Library,
    role: &str,
    material: Option<&Field>,
    youngs: Option<&Field>,
    poisson: Option<&Field>,
    yield_strength: Option<&Field>,
    kind: Kind,
) -> Result<Material, Error> {
    let key = |k: &str| format!("{role}.{k}");
    let mut m = match (material, youngs, poisson) {
        (Some(f), _, _) => {
            let name = ctx.text(f, &key("material"))?;
            library
                .material(name)
                .map_err(|e| ctx.error(&f.origin, &key("material"), e))?
                .clone()
        }
        (None, Some(fe), Some(fnu)) => {
            let e = ranged(ctx, fe, &key("youngs_modulus"), Dim::Pressure)?;
            let nu = ctx.quantity(fnu, &key("poisson_ratio"), Dim::Dimensionless)?;
            let elastic = Elastic::new(e, nu)
                .map_err(|err| ctx.error(&fnu.origin, &key("poisson_ratio"), err))?;
            Material {
                name: "custom".into(),
                kind,
                elastic,
                yield_strength: None,
                source: "given in the scene".into(),
            }
        }
        (None, Some(f), None) | (None, None, Some(f)) => {
            return Err(ctx.error(
                &f.origin,
                &format!("{role}.youngs_modulus and {role}.poisson_ratio"),
                "both are needed when no material is named",
            ));
        }
        (None, None, None) => {
            return Err(ctx.missing(
                &key("material"),
                &format!("name a {role} material (coatcheck materials) or give youngs_modulus and poisson_ratio"),
            ));
        }
    };
    if let Some(f) = yield_strength {
        m.yield_strength = Some(ranged(ctx, f, &key("yield_strength"), Dim::Pressure)?);
    }
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = "\
[roughness]
model = \"self-affine\"
hurst = 0.8
q0 = \"0.1 1/um\"
q1 = \"1e8 1/m\"
roll_off = \"2e5 1/m\"
rms_slope = 1
[film]
material = \"paper-rubber\"
thickness = 1e-5
[substrate]
material = \"carbon-steel\"
yield_strength = \"400 MPa\"
[bond]
shear_strength = \"12 MPa\"
[load]
pressure = \"0.1 MPa\"
[criteria]
checks = [\"bond-shear\", \"min-thickness\"]
safety_factor = 1.5
";

    fn load(text: &str, flags: &[(&str, &str)]) -> Result<Scene, Error> {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("scene.toml");
        std::fs::write(&path, text).unwrap();
        let flags: Vec<(&str, String)> = flags.iter().map(|(k, v)| (*k, v.to_string())).collect();
        Scene::load(Some(&path), &flags, &Library::builtin().unwrap())
    }

    #[test]
    fn a_file_scene_in_si() {
        let s = load(SCENE, &[]).unwrap();
        assert_eq!(
            s.roughness.source,
            RoughnessSource::SelfAffine {
                hurst: 0.8,
                q0: 1e5,
                q1: 1e8,
                roll_off: Some(2e5)
            }
        );
        assert_eq!(s.roughness.scale, Some(Scale::RmsSlope(1.0)));
        assert_eq!(s.thickness, Some(1e-5));
        assert_eq!(s.film.elastic.youngs, 1e6);
        assert_eq!(s.substrate.name, "carbon-steel");
        assert_eq!(s.substrate.yield_strength, Some(4e8));
        assert_eq!(s.bond.shear_strength, 1.2e7);
        assert_eq!(s.pressure, 1e5);
        let c = s.criteria;
        assert!(c.checks.bond_shear && !c.checks.substrate_yield && c.checks.min_thickness);
        assert_eq!((c.epsilon, c.safety_factor), (1e-6, 1.5));
        let d = s.design();
        assert_eq!(d.bond_strength, 1.2e7);
    }

    #[test]
    fn flags_override_the_file() {
        let s = load(
            SCENE,
            &[
                ("film.thickness", "50um"),
                ("load.pressure", "2 bar"),
                ("criteria.checks", "substrate-yield"),
                ("bond.material", "epoxy"),
            ],
        )
        .unwrap();
        assert!((s.thickness.unwrap() / 50e-6 - 1.0).abs() < 1e-15);
        assert_eq!(s.pressure, 2e5);
        assert_eq!(s.bond.name, "epoxy");
        let c = s.criteria.checks;
        assert!(!c.bond_shear && c.substrate_yield && !c.min_thickness);
        // A flag for the other alternative replaces the file's model (the path is taken as
        // given, relative to the working directory).
        let s = load(SCENE, &[("roughness.psd", "data/s.csv")]).unwrap();
        assert_eq!(
            s.roughness.source,
            RoughnessSource::Measured {
                path: PathBuf::from("data/s.csv")
            }
        );
        // Explicit film moduli from flags replace the file's material.
        let s = load(
            SCENE,
            &[
                ("film.youngs_modulus", "3MPa"),
                ("film.poisson_ratio", "0.49"),
            ],
        )
        .unwrap();
        assert_eq!((s.film.elastic.youngs, s.film.elastic.poisson), (3e6, 0.49));
    }

    #[test]
    fn psd_paths_are_relative_to_the_scene_file() {
        let text = SCENE
            .replace("model = \"self-affine\"\n", "psd = \"s.csv\"\n")
            .replace("hurst = 0.8\n", "")
            .replace("q0 = \"0.1 1/um\"\n", "")
            .replace("q1 = \"1e8 1/m\"\n", "")
            .replace("roll_off = \"2e5 1/m\"\n", "");
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("scene.toml");
        std::fs::write(&path, &text).unwrap();
        let s = Scene::load(Some(&path), &[], &Library::builtin().unwrap()).unwrap();
        assert_eq!(
            s.roughness.source,
            RoughnessSource::Measured {
                path: dir.path().join("s.csv")
            }
        );
    }

    #[test]
    fn substrate_yield_needs_a_yield_strength() {
        let text = SCENE
            .replace(
                "material = \"carbon-steel\"\n",
                "youngs_modulus = \"200 GPa\"\npoisson_ratio = 0.3\n",
            )
            .replace("yield_strength = \"400 MPa\"\n", "");
        assert!(load(&text, &[]).is_ok(), "bond-shear only needs no yield");
        let e = load(&text, &[("criteria.checks", "substrate-yield")])
            .unwrap_err()
            .to_string();
        assert!(e.contains("substrate.yield_strength"), "{e}");
    }

    #[test]
    fn a_model_needs_its_amplitude_and_parameters() {
        let e = load(&SCENE.replace("rms_slope = 1\n", ""), &[])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(":2:") && e.contains("rms_slope or rms_height"),
            "{e}"
        );
        let e = load(&SCENE.replace("hurst = 0.8\n", ""), &[])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("roughness.hurst") && e.contains("missing"),
            "{e}"
        );
        let e = load(SCENE, &[("roughness.model", "fractal")])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("--model") && e.contains("unknown model 'fractal'"),
            "{e}"
        );
    }
}
