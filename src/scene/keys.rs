//! The scene's keys, each defined once in [`KEYS`]: its name in the TOML file (`section.field`),
//! its command-line flag, how its value is read (text, files, names, or a quantity with its
//! dimension and accepted range), the alternative it belongs to (keys of two alternatives
//! contradict each other) and its help text. The TOML reader, the flag overrides, the range
//! checks and `coatcheck check`'s flags are all derived from this table.
//!
//! [`RawScene`] holds the values as written (file and flags), one slot per key, before
//! validation.

use crate::error::Error;
use crate::tomlin::{Ctx, Field};
use crate::units::Dim;
use serde::Deserialize;
use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, Visitor};
use std::fmt;
use std::sync::OnceLock;

/// The wavenumbers the tool models (1/m): wavelengths 2π/q from about 6 pm to 6000 km. Far
/// outside any surface, and well inside the floating-point range of the moments of C(q)
/// (q^4 C, q^6 C); a value beyond them is a typo or a wrong unit.
pub const Q_RANGE: (f64, f64) = (1e-6, 1e12);

/// One end of an interval of plain numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bound {
    Inclusive(f64),
    Exclusive(f64),
    Unbounded,
}

/// The values a quantity key accepts (its value is always finite).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Range {
    /// Any finite value; its meaning is checked where it is used (a Poisson ratio by
    /// [`crate::layer::Elastic::new`]).
    Finite,
    /// Any value > 0; the roughness model checks its domain.
    Positive,
    /// A value > 0 within `[lo, hi]` (SI): far wider than any coating design, and well inside
    /// the floating-point range of the contact integrals. A value beyond them is a typo or a
    /// wrong unit, rejected at its line rather than overflowing later.
    Si(f64, f64),
    /// A wavenumber > 0 within [`Q_RANGE`].
    Wavenumber,
    /// A plain number between two bounds, `expected` saying so in messages.
    Plain {
        lo: Bound,
        hi: Bound,
        expected: &'static str,
    },
}

impl Range {
    /// `None` when `v` (> 0 where the range asks for it, already checked) is accepted, else
    /// why not.
    pub fn reject(&self, v: f64) -> Option<String> {
        let above = |b: Bound| match b {
            Bound::Inclusive(lo) => v >= lo,
            Bound::Exclusive(lo) => v > lo,
            Bound::Unbounded => true,
        };
        let below = |b: Bound| match b {
            Bound::Inclusive(hi) => v <= hi,
            Bound::Exclusive(hi) => v < hi,
            Bound::Unbounded => true,
        };
        match *self {
            Range::Finite | Range::Positive => None,
            Range::Si(lo, hi) => (!(lo..=hi).contains(&v)).then(|| {
                format!(
                    "{v:e} (SI) is outside the accepted range {lo:e} to {hi:e}; check the value and its unit"
                )
            }),
            Range::Wavenumber => (!(Q_RANGE.0..=Q_RANGE.1).contains(&v)).then(|| {
                format!(
                    "{v:e} 1/m is outside the wavenumbers this tool models ({:e} to {:e} 1/m); check the value and its unit",
                    Q_RANGE.0, Q_RANGE.1
                )
            }),
            Range::Plain { lo, hi, expected } => {
                (!(above(lo) && below(hi))).then(|| format!("{v} (expected {expected})"))
            }
        }
    }

    /// Whether the value must be > 0 before its range is looked at.
    pub fn positive(&self) -> bool {
        matches!(self, Range::Positive | Range::Si(..) | Range::Wavenumber)
    }
}

/// How a key's value is read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// A string: a name, a model, a column, a unit.
    Text,
    /// One file name or a list of them (relative to the scene file, or to the working
    /// directory when given as a flag).
    Files,
    /// A list of names (a TOML array, or a comma-separated string).
    Names,
    /// A physical value of dimension `Dim` (a number is SI, a string may carry a unit).
    Quantity(Dim, Range),
    /// The range `[min, max]` of a material property of dimension `Dim` (a list of two values,
    /// or `min,max` from a flag), read by [`crate::material::read_span`].
    Span(Dim),
    /// Yes or no: `true`/`false` in the file; the flag alone means yes (`--flag=false`: no).
    Switch,
}

/// Mutually exclusive alternatives: keys of two alternatives of one choice contradict each
/// other, and a flag for a key of one alternative clears the file's keys of the others.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Choice {
    /// 0: a measured PSD (with its reading options and q-range), 1: heights, 2: a model.
    Roughness,
    /// 0: an rms slope, 1: an rms height.
    Amplitude,
    /// 0: a film material by name, 1: its moduli.
    Film,
    /// 0: a substrate material by name, 1: its moduli.
    Substrate,
    /// 0: a bond by name, 1: its shear strength.
    Bond,
}

impl Choice {
    pub const ALL: [Choice; 5] = [
        Choice::Roughness,
        Choice::Amplitude,
        Choice::Film,
        Choice::Substrate,
        Choice::Bond,
    ];
}

/// One scene key.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spec {
    /// `section.field`, as in the TOML file and in messages.
    pub name: &'static str,
    /// The command-line flag, with its dashes.
    pub flag: &'static str,
    pub value: Value,
    /// The choice and the alternative (numbered from 0) this key belongs to, if any.
    pub alt: Option<(Choice, u8)>,
    /// One line for `--help`.
    pub help: &'static str,
}

/// The key enum [`Key`] (one variant per table row, in table order) and the table [`KEYS`].
macro_rules! key_table {
    ($($key:ident => $spec:expr,)+) => {
        /// A scene key; [`Key::spec`] is its row of [`KEYS`].
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Key {
            $($key,)+
        }

        impl Key {
            /// Every key, in table order.
            pub const ALL: &'static [Key] = &[$(Key::$key,)+];
        }

        /// Every scene key, in the order of the TOML sections and of `--help`.
        pub const KEYS: &[Spec] = &[$($spec,)+];
    };
}

const fn quantity(dim: Dim, range: Range) -> Value {
    Value::Quantity(dim, range)
}

const WAVENUMBER: Value = Value::Quantity(Dim::Length(-1), Range::Wavenumber);
const PSD_FILE: Option<(Choice, u8)> = Some((Choice::Roughness, 0));
const MODEL: Option<(Choice, u8)> = Some((Choice::Roughness, 2));
const HEIGHTS: Option<(Choice, u8)> = Some((Choice::Roughness, 1));

key_table! {
    Psd => Spec {
        name: "roughness.psd",
        flag: "--psd",
        value: Value::Files,
        alt: PSD_FILE,
        help: "Measured PSD file (columns q [1/m], C [m^4]); relative to the working directory",
    },
    Profile => Spec {
        name: "roughness.profile",
        flag: "--profile",
        value: Value::Files,
        alt: HEIGHTS,
        help: "Measured heights (line scans or a height map, as `coatcheck psd` reads them); \
               the PSD is computed with the `coatcheck psd` defaults",
    },
    Model => Spec {
        name: "roughness.model",
        flag: "--model",
        value: Value::Text,
        alt: MODEL,
        help: "Roughness model: self-affine (eq. 2) or gaussian (eq. 5)",
    },
    Hurst => Spec {
        name: "roughness.hurst",
        flag: "--hurst",
        value: quantity(Dim::Dimensionless, Range::Positive),
        alt: MODEL,
        help: "Hurst exponent H of the self-affine model",
    },
    Q0 => Spec {
        name: "roughness.q0",
        flag: "--q0",
        value: WAVENUMBER,
        alt: MODEL,
        help: "Lowest wavenumber q0 of the model (or centre of the Gaussian band), e.g. \"1e5 1/m\"",
    },
    Q1 => Spec {
        name: "roughness.q1",
        flag: "--q1",
        value: WAVENUMBER,
        alt: MODEL,
        help: "Short-wavelength cut-off q1 of the self-affine model",
    },
    RollOff => Spec {
        name: "roughness.roll_off",
        flag: "--roll-off",
        value: WAVENUMBER,
        alt: MODEL,
        help: "Roll-off wavenumber q_r of the self-affine model (flat below it)",
    },
    Width => Spec {
        name: "roughness.width",
        flag: "--width",
        value: WAVENUMBER,
        alt: MODEL,
        help: "Width Q of the Gaussian band",
    },
    RmsSlope => Spec {
        name: "roughness.rms_slope",
        flag: "--rms-slope",
        value: quantity(Dim::Dimensionless, Range::Si(1e-12, 1e3)),
        alt: Some((Choice::Amplitude, 0)),
        help: "Scale the spectrum to this rms slope",
    },
    RmsHeight => Spec {
        name: "roughness.rms_height",
        flag: "--rms-height",
        value: quantity(Dim::Length(1), Range::Si(1e-15, 1.0)),
        alt: Some((Choice::Amplitude, 1)),
        help: "Scale the spectrum to this rms height, e.g. 1um",
    },
    QMin => Spec {
        name: "roughness.q_min",
        flag: "--q-min",
        value: WAVENUMBER,
        alt: PSD_FILE,
        help: "Use measured data only above this wavenumber",
    },
    QMax => Spec {
        name: "roughness.q_max",
        flag: "--q-max",
        value: WAVENUMBER,
        alt: PSD_FILE,
        help: "Use measured data only below this wavenumber",
    },
    QCol => Spec {
        name: "roughness.q_col",
        flag: "--q-col",
        value: Value::Text,
        alt: PSD_FILE,
        help: "PSD file: column of q (1-based number or header name; default: detected from the header)",
    },
    CCol => Spec {
        name: "roughness.c_col",
        flag: "--c-col",
        value: Value::Text,
        alt: PSD_FILE,
        help: "PSD file: column of C",
    },
    QUnit => Spec {
        name: "roughness.q_unit",
        flag: "--q-unit",
        value: Value::Text,
        alt: PSD_FILE,
        help: "PSD file: unit of q (e.g. 1/um), overriding the header's",
    },
    CUnit => Spec {
        name: "roughness.c_unit",
        flag: "--c-unit",
        value: Value::Text,
        alt: PSD_FILE,
        help: "PSD file: unit of C (e.g. um^4 for a 2D PSD, nm^3 for a 1D PSD), overriding the header's",
    },
    PsdKind => Spec {
        name: "roughness.psd_kind",
        flag: "--psd-kind",
        value: Value::Text,
        alt: PSD_FILE,
        help: "PSD file: 2d (C in m^4) or 1d (C1D in m^3 from line scans, converted exactly by the \
               inverse Abel transform); default from the unit of C, else 2d",
    },
    PsdConvention => Spec {
        name: "roughness.psd_convention",
        flag: "--psd-convention",
        value: Value::Text,
        alt: PSD_FILE,
        help: "PSD file: normalisation of C: coatcheck (default), persson (1D two-sided) or \
               surfacetopography (contact.engineering: 2D (2π)² and 1D π times coatcheck's)",
    },
    Series => Spec {
        name: "roughness.series",
        flag: "--series",
        value: Value::Text,
        alt: PSD_FILE,
        help: "contact.engineering download: the series to read, NAME or 'SUBJECT: NAME' \
               (default: q/π × 2D PSD, else 1D PSD along x)",
    },
    Conversion => Spec {
        name: "roughness.conversion",
        flag: "--conversion",
        value: Value::Text,
        alt: None,
        help: "1D PSD files and line scans: inverse-abel (exact, default) or pi-q-shortcut \
               (C = C1D/(πq), exact only for H = 1)",
    },
    Channel => Spec {
        name: "roughness.channel",
        flag: "--channel",
        value: Value::Text,
        alt: HEIGHTS,
        help: "Heights from an instrument file: the channel, by name or 1-based number \
               (default: the first height channel)",
    },
    HeightKind => Spec {
        name: "roughness.kind",
        flag: "--kind",
        value: Value::Text,
        alt: HEIGHTS,
        help: "Heights: auto (default), lines (line scans) or map (a height map)",
    },
    Dx => Spec {
        name: "roughness.dx",
        flag: "--dx",
        value: quantity(Dim::Length(1), Range::Si(1e-13, 1.0)),
        alt: HEIGHTS,
        help: "Line scans without an x column: sample spacing, e.g. 0.5um",
    },
    PixelSize => Spec {
        name: "roughness.pixel_size",
        flag: "--pixel-size",
        value: quantity(Dim::Length(1), Range::Si(1e-13, 1.0)),
        alt: HEIGHTS,
        help: "Height map: pixel size (along x, and y unless --pixel-size-y), e.g. 1um",
    },
    PixelSizeY => Spec {
        name: "roughness.pixel_size_y",
        flag: "--pixel-size-y",
        value: quantity(Dim::Length(1), Range::Si(1e-13, 1.0)),
        alt: HEIGHTS,
        help: "Height map: pixel size along y (between rows), if different from x",
    },
    ZUnit => Spec {
        name: "roughness.z_unit",
        flag: "--z-unit",
        value: Value::Text,
        alt: HEIGHTS,
        help: "Heights: unit of the heights (m, um, nm), overriding the file's",
    },
    XUnit => Spec {
        name: "roughness.x_unit",
        flag: "--x-unit",
        value: Value::Text,
        alt: HEIGHTS,
        help: "Line scans: unit of the x column",
    },
    Periodic => Spec {
        name: "roughness.periodic",
        flag: "--periodic",
        value: Value::Text,
        alt: HEIGHTS,
        help: "Heights: true if the data are one period of a periodic surface (no window)",
    },
    Window => Spec {
        name: "roughness.window",
        flag: "--window",
        value: Value::Text,
        alt: HEIGHTS,
        help: "Heights: window, hann or none (default: hann, none for periodic data)",
    },
    Detrend => Spec {
        name: "roughness.detrend",
        flag: "--detrend",
        value: Value::Text,
        alt: HEIGHTS,
        help: "Heights: trend removed first, mean, tilt or curvature (default: tilt, mean for \
               periodic data)",
    },
    PointsPerDecade => Spec {
        name: "roughness.points_per_decade",
        flag: "--points-per-decade",
        value: quantity(
            Dim::Dimensionless,
            Range::Plain {
                lo: Bound::Inclusive(1.0),
                hi: Bound::Inclusive(1000.0),
                expected: "a whole number of bins per decade, 1 to 1000",
            },
        ),
        alt: HEIGHTS,
        help: "Heights: log-spaced q bins per decade (default 10)",
    },
    CutoffPixels => Spec {
        name: "roughness.cutoff_pixels",
        flag: "--cutoff-pixels",
        value: quantity(
            Dim::Dimensionless,
            Range::Plain {
                lo: Bound::Inclusive(2.0),
                hi: Bound::Inclusive(1e6),
                expected: "a wavelength of at least 2 pixels (Nyquist)",
            },
        ),
        alt: HEIGHTS,
        help: "Heights: shortest wavelength kept, in pixels (default 4; 2 = Nyquist)",
    },
    FilmMaterial => Spec {
        name: "film.material",
        flag: "--film",
        value: Value::Text,
        alt: Some((Choice::Film, 0)),
        help: "Film material (name from `coatcheck materials`)",
    },
    FilmYoungsModulus => Spec {
        name: "film.youngs_modulus",
        flag: "--film-youngs-modulus",
        value: quantity(Dim::Pressure, Range::Si(1.0, 1e13)),
        alt: Some((Choice::Film, 1)),
        help: "Film Young's modulus (instead of a material name, or overriding the named material's)",
    },
    FilmPoissonRatio => Spec {
        name: "film.poisson_ratio",
        flag: "--film-poisson-ratio",
        value: quantity(Dim::Dimensionless, Range::Finite),
        alt: Some((Choice::Film, 1)),
        help: "Film Poisson ratio (with --film-youngs-modulus)",
    },
    FilmYoungsModulusRange => Spec {
        name: "film.youngs_modulus_range",
        flag: "--film-youngs-modulus-range",
        value: Value::Span(Dim::Pressure),
        alt: None,
        help: "Range of the film's Young's modulus for --robust, MIN,MAX (replaces the material's)",
    },
    FilmPoissonRatioRange => Spec {
        name: "film.poisson_ratio_range",
        flag: "--film-poisson-ratio-range",
        value: Value::Span(Dim::Dimensionless),
        alt: None,
        help: "Range of the film's Poisson ratio for --robust, MIN,MAX (replaces the material's)",
    },
    Thickness => Spec {
        name: "film.thickness",
        flag: "--thickness",
        value: quantity(Dim::Length(1), Range::Si(1e-10, 10.0)),
        alt: None,
        help: "Film thickness d, e.g. 10um",
    },
    SubstrateMaterial => Spec {
        name: "substrate.material",
        flag: "--substrate",
        value: Value::Text,
        alt: Some((Choice::Substrate, 0)),
        help: "Substrate material (name from `coatcheck materials`)",
    },
    SubstrateYoungsModulus => Spec {
        name: "substrate.youngs_modulus",
        flag: "--substrate-youngs-modulus",
        value: quantity(Dim::Pressure, Range::Si(1.0, 1e13)),
        alt: Some((Choice::Substrate, 1)),
        help: "Substrate Young's modulus (instead of a material name, or overriding the named material's)",
    },
    SubstratePoissonRatio => Spec {
        name: "substrate.poisson_ratio",
        flag: "--substrate-poisson-ratio",
        value: quantity(Dim::Dimensionless, Range::Finite),
        alt: Some((Choice::Substrate, 1)),
        help: "Substrate Poisson ratio (with --substrate-youngs-modulus)",
    },
    YieldStrength => Spec {
        name: "substrate.yield_strength",
        flag: "--yield-strength",
        value: quantity(Dim::Pressure, Range::Si(1.0, 1e12)),
        alt: None,
        help: "Substrate yield strength (overrides the material's)",
    },
    SubstrateYoungsModulusRange => Spec {
        name: "substrate.youngs_modulus_range",
        flag: "--substrate-youngs-modulus-range",
        value: Value::Span(Dim::Pressure),
        alt: None,
        help: "Range of the substrate's Young's modulus for --robust, MIN,MAX (replaces the material's)",
    },
    SubstratePoissonRatioRange => Spec {
        name: "substrate.poisson_ratio_range",
        flag: "--substrate-poisson-ratio-range",
        value: Value::Span(Dim::Dimensionless),
        alt: None,
        help: "Range of the substrate's Poisson ratio for --robust, MIN,MAX (replaces the material's)",
    },
    YieldStrengthRange => Spec {
        name: "substrate.yield_strength_range",
        flag: "--yield-strength-range",
        value: Value::Span(Dim::Pressure),
        alt: None,
        help: "Range of the substrate's yield strength for --robust, MIN,MAX (replaces the material's)",
    },
    BondMaterial => Spec {
        name: "bond.material",
        flag: "--bond",
        value: Value::Text,
        alt: Some((Choice::Bond, 0)),
        help: "Bond (name from `coatcheck materials`)",
    },
    ShearStrength => Spec {
        name: "bond.shear_strength",
        flag: "--shear-strength",
        value: quantity(Dim::Pressure, Range::Si(1.0, 1e12)),
        alt: Some((Choice::Bond, 1)),
        help: "Bond shear strength (instead of a bond name, or overriding the named bond's)",
    },
    ShearStrengthRange => Spec {
        name: "bond.shear_strength_range",
        flag: "--shear-strength-range",
        value: Value::Span(Dim::Pressure),
        alt: None,
        help: "Range of the bond's shear strength for --robust, MIN,MAX (replaces the bond's)",
    },
    Pressure => Spec {
        name: "load.pressure",
        flag: "--pressure",
        value: quantity(Dim::Pressure, Range::Si(1.0, 1e12)),
        alt: None,
        help: "Nominal pressure p0, e.g. \"0.1 MPa\"",
    },
    Friction => Spec {
        name: "load.friction",
        flag: "--friction",
        value: quantity(
            Dim::Dimensionless,
            Range::Plain {
                lo: Bound::Inclusive(0.0),
                hi: Bound::Inclusive(crate::check::MAX_FRICTION),
                expected: "a friction coefficient 0 <= mu <= 10",
            },
        ),
        alt: None,
        help: "Sliding friction coefficient mu: the contact carries mu times its pressure along x \
               (default 0: static contact, as in the paper)",
    },
    Epsilon => Spec {
        name: "criteria.epsilon",
        flag: "--epsilon",
        value: quantity(
            Dim::Dimensionless,
            Range::Plain {
                lo: Bound::Exclusive(0.0),
                hi: Bound::Exclusive(1.0),
                expected: "0 < epsilon < 1",
            },
        ),
        alt: None,
        help: "Exceedance probability that defines a peak value (default 1e-6)",
    },
    SafetyFactor => Spec {
        name: "criteria.safety_factor",
        flag: "--safety-factor",
        value: quantity(
            Dim::Dimensionless,
            Range::Plain {
                lo: Bound::Inclusive(1.0),
                hi: Bound::Unbounded,
                expected: "a safety factor >= 1",
            },
        ),
        alt: None,
        help: "Safety factor: limits are strengths divided by it (default 1)",
    },
    Checks => Spec {
        name: "criteria.checks",
        flag: "--checks",
        value: Value::Names,
        alt: None,
        help: "Checks to run, comma-separated (default: bond-shear,substrate-yield,min-thickness)",
    },
    ThicknessOf => Spec {
        name: "criteria.thickness_of",
        flag: "--thickness-of",
        value: Value::Text,
        alt: None,
        help: "The layer of a stack whose minimum thickness is sought, by name (default the top layer)",
    },
    ShearTail => Spec {
        name: "criteria.shear_tail",
        flag: "--shear-tail",
        value: Value::Text,
        alt: None,
        help: "Peak interface shear rule: half-normal (the paper's, default without friction) or \
               vector (|tau| of the shear vector; default and the only rule with friction)",
    },
    Robust => Spec {
        name: "criteria.robust",
        flag: "--robust",
        value: Value::Switch,
        alt: None,
        help: "Also judge the design at the worst corner of its materials' ranges of E, nu and \
               strengths (robust verdict, governing corner, d_min range)",
    },
    Rtol => Spec {
        name: "numerics.rtol",
        flag: "--rtol",
        value: quantity(
            Dim::Dimensionless,
            Range::Plain {
                lo: Bound::Inclusive(1e-13),
                hi: Bound::Inclusive(1e-2),
                expected: "1e-13 <= rtol <= 1e-2",
            },
        ),
        alt: None,
        help: "Relative tolerance of the contact integrals (default 1e-8)",
    },
}

impl Key {
    /// The key's row of [`KEYS`].
    pub const fn spec(self) -> &'static Spec {
        &KEYS[self as usize]
    }

    /// `section.field`.
    pub fn name(self) -> &'static str {
        self.spec().name
    }

    /// The command-line flag, with its dashes.
    pub fn flag(self) -> &'static str {
        self.spec().flag
    }

    /// The key named `section.field`.
    pub fn from_name(name: &str) -> Option<Key> {
        Key::ALL.iter().copied().find(|k| k.name() == name)
    }

    /// The accepted range of a quantity key.
    pub fn range(self) -> Option<Range> {
        match self.spec().value {
            Value::Quantity(_, range) => Some(range),
            _ => None,
        }
    }

    /// `f` read as the value of this quantity key: its dimension, > 0 where its range asks
    /// for it, within its range; errors name the key at `f`'s line or flag.
    pub fn quantity_of(self, f: &Field, ctx: Ctx<'_>) -> Result<f64, Error> {
        let Value::Quantity(dim, range) = self.spec().value else {
            unreachable!("{} is not a quantity", self.name());
        };
        let v = if range.positive() {
            ctx.positive(f, self.name(), dim)?
        } else {
            ctx.quantity(f, self.name(), dim)?
        };
        match range.reject(v) {
            Some(why) => Err(ctx.error(&f.origin, self.name(), why)),
            None => Ok(v),
        }
    }

    /// `text`, given to another command's `flag`, read as the value of this quantity key (as
    /// [`Key::quantity_of`]): every command accepts the scene's ranges.
    pub fn parse_flag(self, flag: &'static str, text: &str) -> Result<f64, Error> {
        self.quantity_of(&Field::flag(flag, text), Ctx { file: None })
    }

    /// The TOML section and the field within it.
    fn section_and_field(self) -> (&'static str, &'static str) {
        self.name()
            .split_once('.')
            .expect("every key is section.field")
    }
}

/// The scene as written (file and flags), before validation: one slot per [`Key`], and the
/// two top-level keys that pin versions.
#[derive(Debug, Clone)]
pub struct RawScene {
    pub schema_version: Option<Field>,
    pub coatcheck_version: Option<Field>,
    values: Vec<Option<Field>>,
    /// The `[[layer]]` tables of a layer stack, top first (empty for a `[film]` scene).
    pub layers: Vec<RawLayer>,
}

/// One `[[layer]]` table as written: a material by name or its moduli, a thickness, an
/// optional name, the bond to what lies below (a bond by name or a shear strength), and
/// optional ranges of the layer's moduli and its bond's strength.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLayer {
    pub name: Option<Field>,
    pub material: Option<Field>,
    pub youngs_modulus: Option<Field>,
    pub poisson_ratio: Option<Field>,
    pub thickness: Option<Field>,
    pub bond: Option<Field>,
    /// Ranges for `--robust`, MIN,MAX, replacing the library's: the layer's E and ν and its
    /// bond's shear strength.
    pub youngs_modulus_range: Option<Field>,
    pub poisson_ratio_range: Option<Field>,
    pub shear_strength_range: Option<Field>,
}

impl Default for RawScene {
    fn default() -> Self {
        RawScene {
            schema_version: None,
            coatcheck_version: None,
            values: vec![None; KEYS.len()],
            layers: Vec::new(),
        }
    }
}

impl RawScene {
    /// The value of `key`, if given.
    pub fn get(&self, key: Key) -> Option<&Field> {
        self.values[key as usize].as_ref()
    }

    /// Every key with its value, in table order.
    pub fn fields(&self) -> impl Iterator<Item = (Key, Option<&Field>)> {
        Key::ALL.iter().map(|&k| (k, self.get(k)))
    }

    /// Set `key` from its command-line flag, replacing the file's value and the file's keys of
    /// the other alternatives of its choice.
    pub fn set_flag(&mut self, key: Key, text: &str) {
        if let Some((choice, mine)) = key.spec().alt {
            for &other in Key::ALL {
                let slot = &mut self.values[other as usize];
                if matches!(other.spec().alt, Some((c, a)) if c == choice && a != mine)
                    && slot.as_ref().is_some_and(|f| !f.is_flag())
                {
                    *slot = None;
                }
            }
        }
        self.values[key as usize] = Some(Field::flag(key.flag(), text));
    }
}

/// The names the TOML reader accepts: at the top level, and in each section with its keys.
struct Names {
    top: Vec<&'static str>,
    sections: Vec<Section>,
}

struct Section {
    name: &'static str,
    fields: Vec<&'static str>,
    keys: Vec<Key>,
}

/// The top-level keys besides the sections.
const SCHEMA_VERSION: &str = "schema_version";
const COATCHECK_VERSION: &str = "coatcheck_version";
/// The array of tables of a layer stack, `[[layer]]`.
const LAYER: &str = "layer";

fn names() -> &'static Names {
    static NAMES: OnceLock<Names> = OnceLock::new();
    NAMES.get_or_init(|| {
        let mut sections: Vec<Section> = Vec::new();
        for &key in Key::ALL {
            let (section, field) = key.section_and_field();
            let i = match sections.iter().position(|s| s.name == section) {
                Some(i) => i,
                None => {
                    sections.push(Section {
                        name: section,
                        fields: Vec::new(),
                        keys: Vec::new(),
                    });
                    sections.len() - 1
                }
            };
            sections[i].fields.push(field);
            sections[i].keys.push(key);
        }
        let mut top = vec![SCHEMA_VERSION, COATCHECK_VERSION];
        top.extend(sections.iter().map(|s| s.name));
        top.push(LAYER);
        Names { top, sections }
    })
}

/// A key of a TOML table, as its position among `names`; any other key is an unknown field
/// (reported by serde at the key's line, naming the keys expected).
struct KeyOf(&'static [&'static str]);

impl<'de> DeserializeSeed<'de> for KeyOf {
    type Value = usize;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<usize, D::Error> {
        d.deserialize_identifier(self)
    }
}

impl Visitor<'_> for KeyOf {
    type Value = usize;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("field identifier")
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<usize, E> {
        self.0
            .iter()
            .position(|n| *n == v)
            .ok_or_else(|| E::unknown_field(v, self.0))
    }
}

impl<'de> Deserialize<'de> for RawScene {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_struct("RawScene", &names().top, SceneVisitor)
    }
}

struct SceneVisitor;

impl<'de> Visitor<'de> for SceneVisitor {
    type Value = RawScene;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("struct RawScene")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<RawScene, A::Error> {
        let names = names();
        let mut raw = RawScene::default();
        while let Some(i) = map.next_key_seed(KeyOf(&names.top))? {
            match names.top[i] {
                SCHEMA_VERSION => raw.schema_version = Some(map.next_value()?),
                COATCHECK_VERSION => raw.coatcheck_version = Some(map.next_value()?),
                LAYER => raw.layers = map.next_value()?,
                _ => map.next_value_seed(SectionSeed {
                    section: &names.sections[i - 2],
                    raw: &mut raw,
                })?,
            }
        }
        Ok(raw)
    }
}

/// Reads one TOML section's keys into their slots.
struct SectionSeed<'r> {
    section: &'static Section,
    raw: &'r mut RawScene,
}

impl<'de> DeserializeSeed<'de> for SectionSeed<'_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_struct(self.section.name, &self.section.fields, self)
    }
}

impl<'de> Visitor<'de> for SectionSeed<'_> {
    type Value = ();

    /// Serde's wording for a table of keys, e.g. `struct RawFilm` for `[film]`.
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut name = self.section.name.chars();
        let first = name.next().map(|c| c.to_ascii_uppercase());
        write!(
            f,
            "struct Raw{}{}",
            first.unwrap_or_default(),
            name.as_str()
        )
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        while let Some(i) = map.next_key_seed(KeyOf(&self.section.fields))? {
            self.raw.values[self.section.keys[i] as usize] = Some(map.next_value()?);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_flags_are_unique_and_well_formed() {
        for (i, a) in KEYS.iter().enumerate() {
            assert!(a.flag.starts_with("--"), "{}", a.flag);
            assert_eq!(a.name.matches('.').count(), 1, "{}", a.name);
            assert!(!a.help.ends_with('.'), "{}: help is one line", a.name);
            for b in &KEYS[i + 1..] {
                assert_ne!(a.name, b.name);
                assert_ne!(a.flag, b.flag);
            }
        }
        for &k in Key::ALL {
            assert_eq!(Key::from_name(k.name()), Some(k));
        }
    }

    #[test]
    fn every_choice_has_two_alternatives_numbered_from_zero() {
        for choice in Choice::ALL {
            let mut alts: Vec<u8> = KEYS
                .iter()
                .filter_map(|s| s.alt.filter(|(c, _)| *c == choice).map(|(_, a)| a))
                .collect();
            alts.sort();
            alts.dedup();
            assert!(alts.len() >= 2, "{choice:?}");
            assert!(alts.iter().enumerate().all(|(i, a)| usize::from(*a) == i));
        }
    }

    #[test]
    fn ranges_bound_as_stated() {
        let r = Key::Thickness.range().unwrap();
        assert!(r.reject(1e-10).is_none() && r.reject(10.0).is_none());
        assert!(r.reject(9e-11).is_some() && r.reject(10.5).is_some());
        let eps = Key::Epsilon.range().unwrap();
        assert!(eps.reject(0.0).is_some() && eps.reject(1.0).is_some());
        assert!(eps.reject(1e-300).is_none() && eps.reject(0.999).is_none());
        let sf = Key::SafetyFactor.range().unwrap();
        assert!(sf.reject(1.0).is_none() && sf.reject(1e300).is_none());
        assert!(sf.reject(0.999).is_some());
        let mu = Key::Friction.range().unwrap();
        assert!(mu.reject(0.0).is_none() && mu.reject(10.0).is_none());
        assert!(mu.reject(-1e-300).is_some() && mu.reject(10.000001).is_some());
        let q = Key::Q0.range().unwrap();
        assert!(q.reject(Q_RANGE.0).is_none() && q.reject(Q_RANGE.1).is_none());
        assert!(q.reject(Q_RANGE.1 * 1.01).is_some());
    }

    #[test]
    fn a_flag_clears_the_files_other_alternatives_only() {
        let src = crate::tomlin::Source {
            path: std::path::Path::new("s.toml"),
            text: "[roughness]\nmodel = \"self-affine\"\nhurst = 0.8\nrms_slope = 1\n\
                   [film]\nthickness = 1e-5\n",
        };
        let mut raw: RawScene = src.parse().unwrap();
        assert!(raw.get(Key::Hurst).is_some() && raw.get(Key::Thickness).is_some());
        raw.set_flag(Key::QMin, "1e5");
        raw.set_flag(Key::Hurst, "0.5");
        // The flag for q_min cleared the file's model keys; a flag for the model then keeps
        // the q_min flag (a contradiction reported when the scene is resolved).
        assert!(raw.get(Key::Model).is_none());
        assert!(raw.get(Key::QMin).is_some_and(Field::is_flag));
        assert!(raw.get(Key::Hurst).is_some_and(Field::is_flag));
        assert!(raw.get(Key::RmsSlope).is_some() && raw.get(Key::Thickness).is_some());
    }
}
