//! The roughness of a scene: where it comes from (a measured PSD, heights, or a model of the
//! paper, eqs. 2 and 5), how it is scaled and read, and its spectrum; and the validation of
//! the scene's `roughness.*` keys into it.

use super::keys::{Key, Range, Value};
use super::profile::{ProfileFormat, resolve_conversion, resolve_profile_format};
use super::resolve::Reader;
use crate::error::Error;
use crate::psd::abel::Conversion;
use crate::psd::convention::Convention;
use crate::psd::read::{Column, PsdKind, ReadOptions, read_spectrum};
use crate::psd::{ModelParam, Spectrum};
use crate::tomlin::{Field, Origin, Raw};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// The accepted rms slope of a spectrum, given or computed: a C far off (a wrong unit) fails
/// here, named.
const RMS_SLOPE_RANGE: Range = match Key::RmsSlope.spec().value {
    Value::Quantity(_, range) => range,
    _ => panic!("roughness.rms_slope is a quantity"),
};

/// What a spectrum's wavenumbers and rms slope are expected to be, in messages ([`super::Q_RANGE`]
/// and the range of `roughness.rms_slope`; a unit test holds them together).
const SPECTRUM_Q_EXPECTED: &str = "wavenumbers within 1e-6 to 1e12 1/m (check the q column's unit)";
const SPECTRUM_SLOPE_EXPECTED: &str =
    "an rms slope within 1e-12 to 1e3 (check the C column's unit)";

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
    /// The normalisation of C (default: this tool's; SurfaceTopography's for contact.engineering
    /// downloads).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub convention: Option<Convention>,
    /// contact.engineering downloads: the series.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub series: Option<String>,
    /// How a 1D PSD (file or line scans) becomes the 2D PSD (default: the inverse Abel
    /// transform).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub conversion: Option<Conversion>,
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
            conversion: self.conversion.unwrap_or_default(),
            convention: self.convention,
            series: self.series.clone(),
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
    /// How heights (`roughness.profile`) become a spectrum.
    #[serde(skip_serializing_if = "ProfileFormat::is_default")]
    pub profile: ProfileFormat,
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
                    RoughnessSource::Profile { .. } => Key::Profile,
                    _ => Key::Psd,
                }
                .name();
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
                let conversion = self.psd_format.conversion.unwrap_or_default();
                let (info, psd) = crate::topography::psd_of_file(
                    path,
                    &self.profile.file_options(),
                    &self.profile.psd_options(conversion),
                )?;
                (Spectrum::Tabulated(psd.c2d), info.warnings)
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
        let wavenumbers = Range::Wavenumber;
        if wavenumbers.reject(lo).is_some() || wavenumbers.reject(hi).is_some() {
            return Err(Error::invalid(
                "wavenumber range of the spectrum (1/m)",
                match self.file() {
                    Some(p) => format!("{lo:e} to {hi:e} in {}", p.display()),
                    None => format!("{lo:e} to {hi:e}"),
                },
                SPECTRUM_Q_EXPECTED,
            ));
        }
        let s = match self.scale {
            Some(Scale::RmsSlope(xi)) => base.scaled_to_rms_slope(xi)?,
            Some(Scale::RmsHeight(h)) => base.scaled_to_rms_height(h)?,
            None => base,
        };
        // The same bounds as a given rms slope: C far off (a wrong unit) fails here, named.
        let slope = s.slope_sq().value.sqrt();
        if RMS_SLOPE_RANGE.reject(slope).is_some() {
            return Err(Error::invalid(
                "rms slope of the spectrum",
                match self.file() {
                    Some(p) => format!("{slope:e} for {}", p.display()),
                    None => format!("{slope:e}"),
                },
                SPECTRUM_SLOPE_EXPECTED,
            ));
        }
        Ok((s, warnings))
    }
}

/// The roughness keys, validated.
pub(super) fn resolve_roughness(r: Reader<'_>) -> Result<Roughness, Error> {
    let scale = resolve_scale(r)?;
    let q_min = r.quantity(Key::QMin)?;
    let q_max = r.quantity(Key::QMax)?;
    if let (Some(a), Some(b), Some(f)) = (q_min, q_max, r.field(Key::QMax))
        && a >= b
    {
        return Err(r.error(
            Key::QMax,
            f,
            format!("{b} 1/m is not above q_min = {a} 1/m"),
        ));
    }
    let mut more_files = Vec::new();
    let mut declared_at = None;
    let source = if let Some((key, f)) = [Key::Psd, Key::Profile]
        .into_iter()
        .find_map(|k| r.field(k).map(|f| (k, f)))
    {
        let mut paths = file_list(r, key, f)?.into_iter();
        if let (Origin::File(span), Some(src)) = (&f.origin, r.ctx.file) {
            declared_at = Some((src.path.to_path_buf(), src.line_of(span.start)));
        }
        let first = paths.next().expect("file_list is never empty");
        more_files.extend(paths);
        match key {
            Key::Psd => RoughnessSource::Measured { path: first },
            _ => RoughnessSource::Profile { path: first },
        }
    } else if let Some(f) = r.field(Key::Model) {
        refuse_reading_keys(r)?;
        resolve_model(r, f, scale.is_some())?
    } else {
        return Err(r.ctx.missing(
            &format!(
                "{}, {} or {}",
                Key::Psd.name(),
                Key::Profile.name(),
                Key::Model.name()
            ),
            "give a PSD file (--psd surface.csv), heights (--profile map.csv) or a model (model = \"self-affine\" ...)",
        ));
    };
    Ok(Roughness {
        source,
        more_files,
        scale,
        q_min,
        q_max,
        psd_format: resolve_psd_format(r)?,
        profile: resolve_profile_format(r)?,
        declared_at,
    })
}

fn resolve_scale(r: Reader<'_>) -> Result<Option<Scale>, Error> {
    Ok(match r.quantity(Key::RmsSlope)? {
        Some(xi) => Some(Scale::RmsSlope(xi)),
        None => r.quantity(Key::RmsHeight)?.map(Scale::RmsHeight),
    })
}

/// The file(s) of `roughness.psd` or `roughness.profile`: one path, or a non-empty list of
/// distinct paths (each relative to the scene file).
fn file_list(r: Reader<'_>, key: Key, f: &Field) -> Result<Vec<PathBuf>, Error> {
    let ctx = r.ctx;
    let Raw::List(names) = &f.raw else {
        return Ok(vec![ctx.path(f, key.name())?]);
    };
    if names.is_empty() {
        return Err(r.error(
            key,
            f,
            "empty list (expected one file name or a list of file names)",
        ));
    }
    let mut paths: Vec<PathBuf> = Vec::with_capacity(names.len());
    for name in names {
        if name.trim().is_empty() {
            return Err(r.error(key, f, "an empty file name in the list"));
        }
        let one = Field {
            raw: Raw::Text(name.clone()),
            origin: f.origin.clone(),
        };
        let path = ctx.path(&one, key.name())?;
        if paths.contains(&path) {
            return Err(r.error(key, f, format!("'{name}' is listed twice")));
        }
        paths.push(path);
    }
    Ok(paths)
}

/// A model (`f` is its `roughness.model`): its parameters, each given and each used, within
/// the model's domain; `scaled` says whether rms_slope or rms_height sets its amplitude.
fn resolve_model(r: Reader<'_>, f: &Field, scaled: bool) -> Result<RoughnessSource, Error> {
    let model = r.ctx.text(f, Key::Model.name())?;
    let need = |key: Key| -> Result<f64, Error> {
        match r.field(key) {
            Some(g) => r.quantity_of(key, g),
            None => Err(r.error(key, f, format!("missing (model '{model}' needs it)"))),
        }
    };
    let unused = |keys: &[Key]| -> Result<(), Error> {
        match keys.iter().find_map(|&k| r.field(k).map(|g| (k, g))) {
            Some((k, g)) => Err(r.error(k, g, format!("not a parameter of model '{model}'"))),
            None => Ok(()),
        }
    };
    let (source, built) = match model {
        "self-affine" => {
            unused(&[Key::Width])?;
            let (hurst, q0, q1) = (need(Key::Hurst)?, need(Key::Q0)?, need(Key::Q1)?);
            let roll_off = r.quantity(Key::RollOff)?;
            (
                RoughnessSource::SelfAffine {
                    hurst,
                    q0,
                    q1,
                    roll_off,
                },
                Spectrum::self_affine_checked(hurst, q0, q1, roll_off).map(drop),
            )
        }
        "gaussian" => {
            unused(&[Key::Hurst, Key::Q1, Key::RollOff])?;
            let (q0, width) = (need(Key::Q0)?, need(Key::Width)?);
            (
                RoughnessSource::Gaussian { q0, width },
                Spectrum::gaussian_checked(q0, width).map(drop),
            )
        }
        other => {
            return Err(r.error(
                Key::Model,
                f,
                format!("unknown model '{other}' (expected self-affine or gaussian)"),
            ));
        }
    };
    if !scaled {
        return Err(r.error(
            Key::Model,
            f,
            "a model needs rms_slope or rms_height to set its amplitude",
        ));
    }
    // The model's own domain checks (H in (0, 1], q0 < q_r < q1, a band away from 0),
    // reported at the offending key's line.
    built.map_err(|e| {
        let key = match e.param {
            ModelParam::Hurst => Key::Hurst,
            ModelParam::Q0 => Key::Q0,
            ModelParam::Q1 => Key::Q1,
            ModelParam::RollOff => Key::RollOff,
            ModelParam::Width => Key::Width,
        };
        r.error(key, r.field(key).unwrap_or(f), e.error)
    })?;
    Ok(source)
}

/// How to read a measured PSD file: columns, units and kind.
fn resolve_psd_format(r: Reader<'_>) -> Result<PsdFormat, Error> {
    let text = |key: Key| -> Result<Option<String>, Error> { Ok(r.text(key)?.map(str::to_string)) };
    let column = |key: Key| -> Result<Option<String>, Error> {
        let c = text(key)?;
        if let (Some(c), Some(f)) = (&c, r.field(key)) {
            c.parse::<Column>()
                .map_err(|e| r.error(key, f, e.to_string()))?;
        }
        Ok(c)
    };
    let kind = match (r.field(Key::PsdKind), r.text(Key::PsdKind)?) {
        (Some(f), Some(k)) => Some(match k.to_ascii_lowercase().as_str() {
            "2d" => PsdKind::TwoD,
            "1d" => PsdKind::OneD,
            _ => {
                return Err(r.error(Key::PsdKind, f, format!("'{k}' (expected 2d or 1d)")));
            }
        }),
        _ => None,
    };
    Ok(PsdFormat {
        q_col: column(Key::QCol)?,
        c_col: column(Key::CCol)?,
        q_unit: text(Key::QUnit)?,
        c_unit: text(Key::CUnit)?,
        kind,
        convention: match (r.field(Key::PsdConvention), r.text(Key::PsdConvention)?) {
            (Some(f), Some(c)) => Some(
                c.parse::<Convention>()
                    .map_err(|e| r.error(Key::PsdConvention, f, e))?,
            ),
            _ => None,
        },
        series: text(Key::Series)?,
        conversion: resolve_conversion(r)?,
    })
}

/// The keys that say how to read a measured file (its columns, units, convention, grid and
/// processing): an error naming the first one given with a model, which has no file to read.
fn refuse_reading_keys(r: Reader<'_>) -> Result<(), Error> {
    const READING: [Key; 20] = [
        Key::QCol,
        Key::CCol,
        Key::QUnit,
        Key::CUnit,
        Key::PsdKind,
        Key::PsdConvention,
        Key::Series,
        Key::Conversion,
        Key::Channel,
        Key::HeightKind,
        Key::Dx,
        Key::PixelSize,
        Key::PixelSizeY,
        Key::ZUnit,
        Key::XUnit,
        Key::Periodic,
        Key::Window,
        Key::Detrend,
        Key::PointsPerDecade,
        Key::CutoffPixels,
    ];
    match READING.iter().find_map(|&k| r.field(k).map(|f| (k, f))) {
        Some((key, f)) => Err(r.error(
            key,
            f,
            format!(
                "reads a measured file ({} or {}); this scene's roughness is a model",
                Key::Psd.name(),
                Key::Profile.name()
            ),
        )),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::super::keys::Q_RANGE;
    use super::*;

    #[test]
    fn spectrum_messages_quote_the_key_ranges() {
        assert!(SPECTRUM_Q_EXPECTED.contains(&format!("{:e} to {:e} 1/m", Q_RANGE.0, Q_RANGE.1)));
        let Range::Si(lo, hi) = RMS_SLOPE_RANGE else {
            panic!("roughness.rms_slope has an SI range");
        };
        assert!(SPECTRUM_SLOPE_EXPECTED.contains(&format!("{lo:e} to {hi:e}")));
    }
}
