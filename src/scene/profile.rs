//! How a scene's heights (`roughness.profile`) become a spectrum: `coatcheck psd`'s options as
//! `roughness.*` keys (channel, kind, dx, pixel sizes, units, periodic, window, detrend, bins,
//! cut-off), read into [`ProfileFormat`]; unset fields take `coatcheck psd`'s defaults.

use super::keys::Key;
use super::resolve::Reader;
use crate::error::Error;
use crate::psd::abel::Conversion;
use crate::topography::HeightFileOptions;
use crate::topography::io::HeightKind;
use crate::topography::spectrum::{Detrend, PsdOptions, Window};
use serde::Serialize;

/// `coatcheck psd`'s reading and processing options, from the scene (lengths in m).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct ProfileFormat {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub channel: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kind: Option<HeightKind>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dx: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pixel_size: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pixel_size_y: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub z_unit: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub x_unit: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub periodic: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub window: Option<Window>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detrend: Option<Detrend>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub points_per_decade: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cutoff_pixels: Option<f64>,
}

impl ProfileFormat {
    /// Nothing set: `coatcheck psd`'s defaults.
    pub fn is_default(&self) -> bool {
        *self == ProfileFormat::default()
    }

    /// How to read the height file.
    pub fn file_options(&self) -> HeightFileOptions {
        HeightFileOptions {
            kind: self.kind,
            dx: self.dx,
            pixel_size: self.pixel_size,
            pixel_size_y: self.pixel_size_y,
            x_unit: self.x_unit.clone(),
            z_unit: self.z_unit.clone(),
            periodic: self.periodic,
            channel: self.channel.clone(),
        }
    }

    /// How to compute the spectrum, with the 1D→2D `conversion` of line scans.
    pub fn psd_options(&self, conversion: Conversion) -> PsdOptions {
        let d = PsdOptions::default();
        PsdOptions {
            detrend: self.detrend,
            window: self.window,
            points_per_decade: self.points_per_decade.unwrap_or(d.points_per_decade),
            cutoff_pixels: self.cutoff_pixels.unwrap_or(d.cutoff_pixels),
            conversion,
        }
    }
}

/// One of `names` (case-insensitive) for `key`, else an error listing them.
fn choice<T: Copy>(r: Reader<'_>, key: Key, names: &[(&str, T)]) -> Result<Option<T>, Error> {
    let (Some(f), Some(text)) = (r.field(key), r.text(key)?) else {
        return Ok(None);
    };
    let want = text.trim().to_ascii_lowercase();
    match names.iter().find(|(n, _)| *n == want) {
        Some(&(_, v)) => Ok(Some(v)),
        None => Err(r.error(
            key,
            f,
            format!(
                "'{text}' (expected {})",
                names.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
            ),
        )),
    }
}

/// `roughness.conversion`: how a 1D PSD (file or line scans) becomes the 2D PSD.
pub(super) fn resolve_conversion(r: Reader<'_>) -> Result<Option<Conversion>, Error> {
    choice(
        r,
        Key::Conversion,
        &[
            ("inverse-abel", Conversion::InverseAbel),
            ("pi-q-shortcut", Conversion::PiQShortcut),
        ],
    )
}

/// The heights' keys, validated.
pub(super) fn resolve_profile_format(r: Reader<'_>) -> Result<ProfileFormat, Error> {
    let text = |key: Key| -> Result<Option<String>, Error> { Ok(r.text(key)?.map(str::to_string)) };
    let kind = choice(
        r,
        Key::HeightKind,
        &[
            ("auto", None),
            ("lines", Some(HeightKind::Lines)),
            ("map", Some(HeightKind::Map)),
        ],
    )?
    .flatten();
    let points_per_decade = match (
        r.field(Key::PointsPerDecade),
        r.quantity(Key::PointsPerDecade)?,
    ) {
        (Some(f), Some(n)) if n.fract() != 0.0 => {
            return Err(r.error(
                Key::PointsPerDecade,
                f,
                format!("{n} (expected a whole number)"),
            ));
        }
        (_, n) => n.map(|n| n as usize),
    };
    let periodic = r
        .field(Key::Periodic)
        .map(|f| r.ctx.boolean(f, Key::Periodic.name()))
        .transpose()?;
    Ok(ProfileFormat {
        channel: text(Key::Channel)?,
        kind,
        dx: r.quantity(Key::Dx)?,
        pixel_size: r.quantity(Key::PixelSize)?,
        pixel_size_y: r.quantity(Key::PixelSizeY)?,
        z_unit: text(Key::ZUnit)?,
        x_unit: text(Key::XUnit)?,
        periodic,
        window: choice(
            r,
            Key::Window,
            &[("hann", Window::Hann), ("none", Window::None)],
        )?,
        detrend: choice(
            r,
            Key::Detrend,
            &[
                ("mean", Detrend::Mean),
                ("tilt", Detrend::Tilt),
                ("curvature", Detrend::Curvature),
            ],
        )?,
        points_per_decade,
        cutoff_pixels: r.quantity(Key::CutoffPixels)?,
    })
}
