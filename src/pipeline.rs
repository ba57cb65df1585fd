//! From a scene to its verdict, the one road every `check` takes (one scene, a batch,
//! `--verify`): the spectrum of each roughness file, a [`Checker`] on it, the outcome at the
//! scene's thickness, optionally the exact check on the height map ([`crate::verify`]), and the
//! worst file when the scene lists several. No physics of its own (paper App. B, eqs. B8–B12
//! through [`crate::check`]).
//!
//! The worst file: a failing file before a passing one, then the smallest margin of the
//! governing check.

use crate::bem::{BemSettings, Surface};
use crate::check::levers::{Lever, levers};
use crate::check::robust::{self, Robust};
use crate::check::{CheckKind, Checker, Outcome};
use crate::error::Error;
use crate::scene::{RoughnessSource, Scene};
use crate::topography::io::{HeightKind, MapOptions, read_height_map, sniff};
use crate::topography::plausible::{edge_mismatch_map, periodic_warning};
use crate::verify::{Verification, verify};
use rayon::prelude::*;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// One roughness file of a scene judged on its own.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FileVerdict {
    pub path: PathBuf,
    pub pass: bool,
    #[serde(rename = "governing_check")]
    pub governing: Option<CheckKind>,
    pub margin: Option<f64>,
}

/// The exact check of `check --verify`: the height map and what the boundary elements found.
#[derive(Debug, Clone, PartialEq)]
pub struct Exact {
    pub map: PathBuf,
    pub verification: Verification,
}

/// A judged scene: the outcome of its worst roughness file.
#[derive(Debug, Clone, PartialEq)]
pub struct Judged {
    /// The scene, with the roughness of the worst file.
    pub scene: Scene,
    pub outcome: Outcome,
    /// Every file's verdict, in the scene's order, when the scene lists several.
    pub files: Vec<FileVerdict>,
    /// The readers' warnings, every file's.
    pub read_warnings: Vec<String>,
    /// The version pin's, the readers' and the outcome's warnings.
    pub warnings: Vec<String>,
    /// The exact check, when asked for.
    pub exact: Option<Exact>,
    /// What alone would make a failing design pass (empty when it passes).
    pub levers: Vec<Lever>,
    /// The design at the worst corner of its materials' ranges (`--robust`), on the worst file.
    pub robust: Option<Robust>,
}

impl Judged {
    /// The worst file when the scene lists several.
    pub fn worst_file(&self) -> Option<&Path> {
        if self.files.len() > 1 {
            self.scene.roughness.file()
        } else {
            None
        }
    }

    /// Persson's checks pass, and the exact ones and the robust ones when they were made.
    pub fn pass(&self) -> bool {
        self.outcome.pass
            && self.exact.as_ref().is_none_or(|e| e.verification.pass)
            && self.robust.as_ref().is_none_or(|r| r.pass)
    }
}

/// The margin of the governing check (`None` when it has no limit, e.g. no thickness passes).
pub fn governing_margin(outcome: &Outcome) -> Option<f64> {
    outcome
        .checks
        .iter()
        .find(|c| Some(c.kind) == outcome.governing)
        .and_then(|c| c.margin)
}

/// Sort key of a verdict: failing before passing, then the smaller margin (none = worst).
fn severity(outcome: &Outcome) -> (bool, f64) {
    (
        outcome.pass,
        governing_margin(outcome).unwrap_or(f64::NEG_INFINITY),
    )
}

fn origin(scene: &Scene) -> String {
    scene
        .file
        .as_ref()
        .map_or("scene".into(), |p| p.display().to_string())
}

/// The checker of a scene with one roughness file, and its reader's warnings.
pub fn checker(scene: &Scene) -> Result<(Checker, Vec<String>), Error> {
    if scene.is_stack() {
        return Err(Error::Value {
            origin: origin(scene),
            msg: "a layer stack ([[layer]] tables) is checked on its own: coatcheck check SCENE \
                  (not in a batch, a sweep or the HTML report)"
                .into(),
        });
    }
    let (spectrum, warnings) = scene.roughness.spectrum()?;
    Ok((
        Checker::new(&spectrum, scene.design(), scene.settings)?,
        warnings,
    ))
}

/// Judge a scene at its thickness on each of its roughness files and report the worst; with
/// `exact`, also solve the contact on the scene's height map and judge the exact fields.
pub fn judge(scene: &Scene, exact: Option<&BemSettings>) -> Result<Judged, Error> {
    let thickness = scene.thickness.ok_or_else(|| Error::Value {
        origin: origin(scene),
        msg: "film.thickness is missing; give the film thickness (thickness = \"10 um\" under [film], or --thickness 10um)".into(),
    })?;
    if exact.is_some() && !scene.roughness.more_files.is_empty() {
        return Err(Error::Value {
            origin: "--verify".into(),
            msg: "runs on one height map; this scene lists several (give one with --profile)"
                .into(),
        });
    }
    let runs = scene
        .each_file()
        .into_par_iter()
        .map(|s| {
            let (checker, warnings) = checker(&s)?;
            let outcome = checker.run(thickness)?;
            Ok((s, outcome, warnings))
        })
        .collect::<Result<Vec<_>, Error>>()?;
    let several = runs.len() > 1;
    let files: Vec<FileVerdict> = if several {
        runs.iter()
            .map(|(s, o, _)| FileVerdict {
                path: s
                    .roughness
                    .file()
                    .map(Path::to_path_buf)
                    .unwrap_or_default(),
                pass: o.pass,
                governing: o.governing,
                margin: governing_margin(o),
            })
            .collect()
    } else {
        Vec::new()
    };
    let read_warnings: Vec<String> = runs.iter().flat_map(|(_, _, w)| w.clone()).collect();
    let mut warnings: Vec<String> = scene.version_warning().into_iter().collect();
    warnings.extend(read_warnings.iter().cloned());
    let (scene, mut outcome, own_reads) = runs
        .into_iter()
        .min_by(|(_, a, _), (_, b, _)| {
            let (pa, ma) = severity(a);
            let (pb, mb) = severity(b);
            pa.cmp(&pb).then(ma.total_cmp(&mb))
        })
        .expect("a scene has at least one roughness");
    let named = |w: &String| match (several, scene.roughness.file()) {
        (true, Some(f)) => format!("{}: {w}", f.display()),
        _ => w.clone(),
    };
    warnings.extend(outcome.warnings.iter().map(named));
    // The reading's warnings travel with the outcome into every report format.
    outcome.warnings.splice(0..0, own_reads);
    let mut exact_warnings = Vec::new();
    let exact = exact
        .map(|settings| {
            let (map, surface, mismatch) = scene_map(&scene)?;
            exact_warnings.extend(periodic_warning(&map, mismatch));
            let design = scene.design();
            let verification = verify(&surface, &design, thickness, settings)?;
            Ok::<_, Error>(Exact { map, verification })
        })
        .transpose()?;
    outcome.warnings.extend(exact_warnings.iter().cloned());
    warnings.extend(exact_warnings);
    let levers = if outcome.pass {
        Vec::new()
    } else {
        let (spectrum, _) = scene.roughness.spectrum()?;
        levers(&spectrum, &scene.design(), scene.settings, &outcome)?
    };
    let robust = scene
        .robust
        .then(|| robust::judge_scene(&scene, thickness))
        .transpose()?;
    Ok(Judged {
        scene,
        outcome,
        files,
        read_warnings,
        warnings,
        exact,
        levers,
        robust,
    })
}

/// The map behind `check --verify`: the scene's height file, which must be a height map, with
/// its edge mismatch (it is solved as one period of a periodic surface).
fn scene_map(scene: &Scene) -> Result<(PathBuf, Surface, f64), Error> {
    let RoughnessSource::Profile { path } = &scene.roughness.source else {
        return Err(Error::Value {
            origin: scene
                .file
                .as_ref()
                .map_or("--verify".to_string(), |p| p.display().to_string()),
            msg: "--verify solves the contact on the measured surface: give the roughness as a \
                  height map (roughness.profile or --profile), not as a spectrum or a model"
                .into(),
        });
    };
    if sniff(path)? == Some(HeightKind::Lines) {
        return Err(Error::Input {
            path: path.clone(),
            line: 1,
            msg: "--verify needs a height map (a matrix of heights), not line scans".into(),
        });
    }
    let opts = MapOptions {
        periodic: Some(true),
        ..MapOptions::default()
    };
    let map = read_height_map(path, &opts)?;
    Ok((
        path.clone(),
        Surface::from_height_map(&map)?,
        edge_mismatch_map(&map),
    ))
}
