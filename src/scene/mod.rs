//! A scene: one coating design to judge, read from a TOML file and/or command-line flags (flags
//! override the file), validated into SI values. Every physical value accepts units (`"10 um"`, `"0.1 MPa"`, `"1e5 1/m"`);
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
//! friction = 0               # optional: sliding friction coefficient (0 to 10)
//! [criteria]                 # optional
//! epsilon = 1e-6
//! safety_factor = 1
//! checks = ["bond-shear", "substrate-yield", "min-thickness"]
//! shear_tail = "vector"      # or "half-normal" (the paper's; default without friction)
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
//! The Gaussian band (eq. 5) is `model = "gaussian"` with `q0` and `width`. A material or bond
//! given by name may override one of its properties (`film.material = "nbr"` with
//! `film.youngs_modulus = "5 MPa"`; `substrate.yield_strength`; `bond.shear_strength`): the
//! scene lists each as an [`Override`], which every report shows. Unknown keys and contradictions
//! (psd and a model, a material with both moduli, rms slope and height) are errors naming the
//! keys and the line. A flag for one alternative (e.g. `--psd`) replaces the
//! file's other alternative (e.g. its model).
//!
//! - `keys`: the table of keys ([`KEYS`]: name, flag, value kind, range, alternatives, help)
//!   and the scene as written ([`RawScene`]).
//! - `resolve`: the validation into a [`Scene`] ([`resolve()`]).
//! - `layers`: the `[[layer]]` tables of a layer stack ([`SceneLayer`]).
//! - `roughness`: the roughness ([`Roughness`]), its spectrum, and the validation of its keys.
//! - `profile`: how heights become a spectrum ([`ProfileFormat`]: `coatcheck psd`'s options
//!   as `roughness.*` keys).

mod keys;
mod layers;
mod profile;
mod resolve;
mod roughness;

pub use keys::{Bound, Choice, KEYS, Key, Q_RANGE, Range, RawLayer, RawScene, Spec, Value};
pub use layers::SceneLayer;
pub use profile::ProfileFormat;
pub use resolve::resolve;
pub use roughness::{PsdFormat, Roughness, RoughnessSource, Scale};

use crate::check::stack::{StackDesign, StackLayer};
use crate::check::{Criteria, Design};
use crate::error::Error;
use crate::layer::Bilayer;
use crate::material::{Bond, Library, Material};
use crate::prec::Settings;
use crate::tomlin::{Ctx, Source};
use serde::Serialize;
use std::path::{Path, PathBuf};

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
    /// The layers of a stack of two or more, top first (`[[layer]]`); empty for a film scene
    /// (one `[[layer]]` is the film). With layers, `film` and `thickness` are the top layer's
    /// and `bond` the bottom layer's.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub layers: Vec<SceneLayer>,
    /// The layer whose minimum thickness is sought (`criteria.thickness_of`; 0 = the top).
    #[serde(skip)]
    pub thickness_of: usize,
    /// Nominal pressure p0 (Pa).
    pub pressure: f64,
    /// Sliding friction coefficient μ (0: static contact).
    pub friction: f64,
    pub criteria: Criteria,
    pub settings: Settings,
    /// The properties of named materials and bond the scene replaces.
    pub overrides: Vec<Override>,
    /// Also judge the design at the worst corner of its materials' ranges (`criteria.robust`,
    /// `--robust`; [`crate::check::robust`]).
    pub robust: bool,
}

/// One property of a named library material or bond replaced by the scene's value.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Override {
    /// The scene key, e.g. `film.youngs_modulus`.
    pub key: &'static str,
    /// The library entry whose property is replaced.
    pub material: String,
    /// The scene's value, SI.
    pub value: f64,
    /// The library's value, SI (`None`: the library gives none).
    pub library_value: Option<f64>,
    /// `Pa`, or `1` for a ratio.
    pub unit: &'static str,
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

    /// Whether the scene is a stack of two or more layers ([`Scene::layers`]).
    pub fn is_stack(&self) -> bool {
        !self.layers.is_empty()
    }

    /// The design (without thickness) for [`crate::check::Checker`].
    pub fn design(&self) -> Design {
        Design {
            layers: Bilayer::new(self.film.elastic, self.substrate.elastic),
            pressure: self.pressure,
            yield_strength: self.substrate.yield_strength,
            bond_strength: self.bond.shear_strength,
            friction: self.friction,
            criteria: self.criteria,
        }
    }

    /// The stack design (layers top first, their bonds, `criteria.thickness_of`) for
    /// [`crate::check::stack::StackChecker`]; a film scene is a stack of one layer.
    pub fn stack_design(&self) -> StackDesign {
        let layers = if self.layers.is_empty() {
            vec![StackLayer {
                name: self.film.name.clone(),
                material: self.film.elastic,
                thickness: self.thickness.unwrap_or(f64::NAN),
                bond_strength: self.bond.shear_strength,
            }]
        } else {
            self.layers
                .iter()
                .map(|l| StackLayer {
                    name: l.name.clone(),
                    material: l.material.elastic,
                    thickness: l.thickness,
                    bond_strength: l.bond.shear_strength,
                })
                .collect()
        };
        StackDesign {
            layers,
            substrate: self.substrate.elastic,
            pressure: self.pressure,
            yield_strength: self.substrate.yield_strength,
            friction: self.friction,
            criteria: self.criteria,
            thickness_of: self.thickness_of,
        }
    }

    /// Read a scene file (if any), apply flag overrides `(key name, text)` (names as in
    /// [`KEYS`], e.g. `film.thickness`), and validate.
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
        for (name, value) in overrides {
            let key = Key::from_name(name).ok_or_else(|| Error::Value {
                origin: "flag overrides".into(),
                msg: format!("'{name}' is not a scene key"),
            })?;
            raw.set_flag(key, value);
        }
        let ctx = Ctx { file: src.as_ref() };
        resolve(&raw, ctx, library, file)
    }
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

    #[test]
    fn a_model_outside_its_domain_is_reported_at_the_offending_key() {
        // (replacement in SCENE, key, line of that key)
        let cases = [
            ("hurst = 0.8", "hurst = 1.5", "roughness.hurst", 3),
            ("q1 = \"1e8 1/m\"", "q1 = \"1e4 1/m\"", "roughness.q1", 5),
            (
                "roll_off = \"2e5 1/m\"",
                "roll_off = \"2e9 1/m\"",
                "roughness.roll_off",
                6,
            ),
        ];
        for (from, to, key, line) in cases {
            let e = load(&SCENE.replace(from, to), &[]).unwrap_err().to_string();
            assert!(e.contains(&format!(":{line}: {key}: invalid")), "{e}");
        }
        let gaussian = SCENE
            .replace("self-affine", "gaussian")
            .replace("hurst = 0.8\n", "")
            .replace("q1 = \"1e8 1/m\"\n", "")
            .replace("roll_off = \"2e5 1/m\"", "width = \"1e5 1/m\"");
        let e = load(&gaussian, &[]).unwrap_err().to_string();
        assert!(
            e.contains(":4: roughness.width: invalid Gaussian width"),
            "{e}"
        );
        // From a flag, the error names the flag.
        let e = load(SCENE, &[("roughness.hurst", "2")])
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--hurst: roughness.hurst: invalid"), "{e}");
    }

    #[test]
    fn values_take_engineering_units() {
        let s = load(
            &SCENE.replace("\"12 MPa\"", "\"0.5 N/mm²\""),
            &[("film.thickness", "1 mil"), ("load.pressure", "2 N/cm^2")],
        )
        .unwrap();
        assert_eq!(s.bond.shear_strength, 5e5);
        assert_eq!(s.thickness, Some(2.54e-5));
        assert_eq!(s.pressure, 2e4);
    }

    #[test]
    fn an_override_of_an_unknown_key_is_an_error() {
        let e = load(SCENE, &[("film.thicknes", "1um")])
            .unwrap_err()
            .to_string();
        assert!(e.contains("'film.thicknes' is not a scene key"), "{e}");
    }
}
