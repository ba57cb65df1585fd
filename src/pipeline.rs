//! From a scene to its verdict, the one road every `check` takes (one scene, a batch,
//! `--verify`, a film or a layer stack): the spectrum of each roughness file, a [`Checker`]
//! (a film) or a [`StackChecker`] (`[[layer]]` tables) on it, the outcome at the scene's
//! thickness, optionally the exact check on the height map, or on realisations of the scene's
//! spectrum when it has no map ([`crate::exact`]), and the worst file when the scene
//! lists several. No physics of its own (paper App. B, eqs. B8–B12
//! through [`crate::check`]).
//!
//! The worst file: a failing file before a passing one, then the smallest margin of the
//! governing check.

use crate::bem::{BemSettings, Boundary, Surface};
use crate::check::levers::{Lever, levers};
use crate::check::robust::{self, Robust};
use crate::check::stack::{StackChecker, StackOutcome};
use crate::check::stack_levers::stack_levers;
use crate::check::stack_robust::{self, StackRobust};
use crate::check::{CheckKind, CheckResult, Checker, MinThickness, Outcome};
use crate::error::Error;
use crate::exact::min_thickness::ExactMinThickness;
use crate::exact::realisations::Grid;
use crate::exact::stack::on_stack_surface;
use crate::exact::stack_realisations::{StackRealisations, on_stack_realisations};
use crate::exact::{ExactOptions, Realisations, on_realisations, on_surface};
use crate::scene::{RoughnessSource, Scene};
use crate::topography::io::{HeightKind, MapOptions, read_height_map, sniff};
use crate::topography::plausible::{edge_mismatch_map, periodic_warning};
use crate::verify::Verification;
use crate::verify::boundary::BoundaryDecision;
use crate::verify_stack::StackVerification;
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

/// The exact check of `check --verify`: the height map (or the spectrum file of the
/// realisations) and what the boundary elements found.
#[derive(Debug, Clone, PartialEq)]
pub struct Exact {
    /// The height map, or the spectrum file of the realisations (`model` for a model spectrum).
    pub map: PathBuf,
    /// The stress checks and, when min-thickness is enabled, the exact d_min's check (the
    /// means over the realisations when there are realisations).
    pub verification: Verification,
    /// The exact minimum thickness, when min-thickness is enabled.
    pub min_thickness: Option<ExactMinThickness>,
    /// The realisations of a scene without a height map.
    pub realisations: Option<Realisations>,
    /// The boundary of the solves.
    pub boundary: BoundaryDecision,
}

/// The exact check of `check --verify` on a layer stack: the height map and what the boundary
/// elements found at every interface.
#[derive(Debug, Clone, PartialEq)]
pub struct StackExact {
    pub map: PathBuf,
    /// The stress checks at every interface and, when min-thickness is enabled, the exact
    /// d_min's check.
    pub verification: StackVerification,
    /// The exact minimum thickness of the layer `criteria.thickness_of`, when min-thickness is
    /// enabled.
    pub min_thickness: Option<ExactMinThickness>,
    /// The realisations of a scene without a height map.
    pub realisations: Option<StackRealisations>,
    /// The boundary of the solves.
    pub boundary: BoundaryDecision,
}

/// The outcome of a film or of a layer stack.
#[derive(Debug, Clone, PartialEq)]
pub enum Verdict {
    Film(Outcome),
    Stack(StackOutcome),
}

impl Verdict {
    pub fn pass(&self) -> bool {
        match self {
            Verdict::Film(o) => o.pass,
            Verdict::Stack(o) => o.pass,
        }
    }

    /// The check that decides the verdict.
    pub fn governing(&self) -> Option<CheckKind> {
        match self {
            Verdict::Film(o) => o.governing,
            Verdict::Stack(o) => o.governing().map(|c| c.result.kind),
        }
    }

    /// The margin of the governing check (`None` when it has no limit).
    pub fn margin(&self) -> Option<f64> {
        match self {
            Verdict::Film(o) => governing_margin(o),
            Verdict::Stack(o) => o.governing().and_then(|c| c.result.margin),
        }
    }

    pub fn min_thickness(&self) -> Option<&MinThickness> {
        match self {
            Verdict::Film(o) => o.min_thickness.as_ref(),
            Verdict::Stack(o) => o.min_thickness.as_ref(),
        }
    }

    /// The warnings of the outcome (the checks', the theory's, the data's).
    pub fn warnings_mut(&mut self) -> &mut Vec<String> {
        match self {
            Verdict::Film(o) => &mut o.warnings,
            Verdict::Stack(o) => &mut o.warnings,
        }
    }

    /// The governing check's name; in a stack, with where it applies ("bond-shear at primer").
    pub fn governing_name(&self) -> Option<String> {
        match self {
            Verdict::Film(o) => o.governing.map(|k| k.name().to_string()),
            Verdict::Stack(o) => o
                .governing()
                .map(|c| format!("{} at {}", c.result.kind.name(), c.at)),
        }
    }

    /// Every check with where it applies (`None` for a film's).
    pub fn checks(&self) -> Vec<(Option<&str>, &CheckResult)> {
        match self {
            Verdict::Film(o) => o.checks.iter().map(|c| (None, c)).collect(),
            Verdict::Stack(o) => o
                .checks
                .iter()
                .map(|c| (Some(c.at.as_str()), &c.result))
                .collect(),
        }
    }

    /// The film's outcome (`None` for a stack).
    pub fn film(&self) -> Option<&Outcome> {
        match self {
            Verdict::Film(o) => Some(o),
            Verdict::Stack(_) => None,
        }
    }

    /// Sort key: failing before passing, then the smaller margin (none = worst).
    fn severity(&self) -> (bool, f64) {
        (self.pass(), self.margin().unwrap_or(f64::NEG_INFINITY))
    }
}

/// A judged scene: the outcome of its worst roughness file.
#[derive(Debug, Clone, PartialEq)]
pub struct Judged {
    /// The scene, with the roughness of the worst file.
    pub scene: Scene,
    pub outcome: Verdict,
    /// Every file's verdict, in the scene's order, when the scene lists several.
    pub files: Vec<FileVerdict>,
    /// The readers' warnings, every file's.
    pub read_warnings: Vec<String>,
    /// The version pin's, the readers' and the outcome's warnings.
    pub warnings: Vec<String>,
    /// The exact check of a film, when asked for.
    pub exact: Option<Exact>,
    /// The exact check of a layer stack, when asked for.
    pub stack_exact: Option<StackExact>,
    /// What alone would make a failing design pass (empty when it passes).
    pub levers: Vec<Lever>,
    /// The design at the worst corner of its materials' ranges (`--robust`), on the worst file.
    pub robust: Option<Robust>,
    /// The same for a layer stack.
    pub stack_robust: Option<StackRobust>,
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
        self.outcome.pass()
            && self.exact.as_ref().is_none_or(|e| e.verification.pass)
            && self
                .stack_exact
                .as_ref()
                .is_none_or(|e| e.verification.pass)
            && self.robust.as_ref().is_none_or(|r| r.pass)
            && self.stack_robust.as_ref().is_none_or(|r| r.pass)
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
            msg: "a layer stack ([[layer]] tables) has its own checker (pipeline::stack_checker)"
                .into(),
        });
    }
    let (spectrum, warnings) = scene.roughness.spectrum()?;
    Ok((
        Checker::new(&spectrum, scene.design(), scene.settings)?,
        warnings,
    ))
}

/// The checker of a layer-stack scene with one roughness file, and its reader's warnings.
pub fn stack_checker(scene: &Scene) -> Result<(StackChecker, Vec<String>), Error> {
    let (spectrum, warnings) = scene.roughness.spectrum()?;
    Ok((
        StackChecker::new(&spectrum, scene.stack_design(), scene.settings)?,
        warnings,
    ))
}

/// The verdict on one roughness file of a scene, with the reader's warnings.
fn run_one(scene: &Scene) -> Result<(Verdict, Vec<String>), Error> {
    if scene.is_stack() {
        let (checker, warnings) = stack_checker(scene)?;
        return Ok((Verdict::Stack(checker.run()?), warnings));
    }
    let thickness = scene.thickness.ok_or_else(|| Error::Value {
        origin: origin(scene),
        msg: "film.thickness is missing; give the film thickness (thickness = \"10 um\" under [film], or --thickness 10um)".into(),
    })?;
    let (checker, warnings) = checker(scene)?;
    Ok((Verdict::Film(checker.run(thickness)?), warnings))
}

/// Judge a scene at its thickness on each of its roughness files and report the worst; with
/// `exact`, also solve the contact on the scene's height map and judge the exact fields (the
/// default [`ExactOptions`] with these solver settings).
pub fn judge(scene: &Scene, exact: Option<&BemSettings>) -> Result<Judged, Error> {
    let opts = exact.map(|&bem| ExactOptions {
        bem,
        ..ExactOptions::default()
    });
    judge_exact(scene, opts.as_ref())
}

/// [`judge`] with the exact check's options: on the height map, or on realisations of the
/// spectrum of a scene without one ([`crate::exact`]).
/// [`judge`] with the exact check's options: on the height map, or on realisations of the
/// spectrum of a scene without one ([`crate::exact`]).
pub fn judge_exact(scene: &Scene, exact: Option<&ExactOptions>) -> Result<Judged, Error> {
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
            let (outcome, warnings) = run_one(&s)?;
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
                pass: o.pass(),
                governing: o.governing(),
                margin: o.margin(),
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
            let (pa, ma) = a.severity();
            let (pb, mb) = b.severity();
            pa.cmp(&pb).then(ma.total_cmp(&mb))
        })
        .expect("a scene has at least one roughness");
    let named = |w: &String| match (several, scene.roughness.file()) {
        (true, Some(f)) => format!("{}: {w}", f.display()),
        _ => w.clone(),
    };
    warnings.extend(outcome.warnings_mut().iter().map(named));
    // The reading's warnings travel with the outcome into every report format.
    outcome.warnings_mut().splice(0..0, own_reads);
    let mut exact_warnings = Vec::new();
    let (exact, stack_exact) = match (&outcome, exact) {
        (_, None) => (None, None),
        (Verdict::Film(film), Some(opts)) => {
            let x = exact_check(&scene, film, film.thickness, opts, &mut exact_warnings)?;
            (Some(x), None)
        }
        (Verdict::Stack(_), Some(opts)) => {
            let x = stack_exact_check(&scene, opts, &mut exact_warnings)?;
            (None, Some(x))
        }
    };
    outcome
        .warnings_mut()
        .extend(exact_warnings.iter().cloned());
    warnings.extend(exact_warnings);
    let levers = match &outcome {
        Verdict::Film(o) if !o.pass => {
            let (spectrum, _) = scene.roughness.spectrum()?;
            levers(&spectrum, &scene.design(), scene.settings, o)?
        }
        Verdict::Stack(o) if !o.pass => {
            let (spectrum, _) = scene.roughness.spectrum()?;
            stack_levers(&spectrum, &scene.stack_design(), scene.settings, o)?
        }
        _ => Vec::new(),
    };
    let (robust, stack_robust) = match (&outcome, scene.robust) {
        (_, false) => (None, None),
        (Verdict::Film(film), true) => (Some(robust::judge_scene(&scene, film.thickness)?), None),
        (Verdict::Stack(_), true) => (None, Some(stack_robust::judge_scene(&scene)?)),
    };
    Ok(Judged {
        scene,
        outcome,
        files,
        read_warnings,
        warnings,
        exact,
        stack_exact,
        levers,
        robust,
        stack_robust,
    })
}

/// The exact check of `check --verify` on a layer stack: on the scene's height map, or on
/// realisations of its spectrum when the roughness is a spectrum or a model, judged at every
/// interface, with the exact minimum thickness ([`crate::exact::stack`]).
fn stack_exact_check(
    scene: &Scene,
    opts: &ExactOptions,
    warnings: &mut Vec<String>,
) -> Result<StackExact, Error> {
    let design = scene.stack_design();
    if let RoughnessSource::Profile { path } = &scene.roughness.source {
        let (surface, mismatch) = scene_map(path)?;
        let (boundary, bem) = map_boundary(opts, path, mismatch, warnings);
        let (verification, min_thickness) =
            on_stack_surface(&surface, &design, scene.friction, &bem)?;
        return Ok(StackExact {
            map: path.clone(),
            verification,
            min_thickness,
            realisations: None,
            boundary,
        });
    }
    let (spectrum, _) = scene.roughness.spectrum()?;
    let (boundary, opts) = synthesised(opts);
    let (verification, min_thickness, realisations) =
        on_stack_realisations(&spectrum, &design, scene.friction, &opts)?;
    warnings.extend(unresolved_warning(&realisations.grid));
    Ok(StackExact {
        map: spectrum_source(scene),
        verification,
        min_thickness,
        realisations: Some(realisations),
        boundary,
    })
}

/// The spectrum file of the realisations (`model` for a model spectrum).
fn spectrum_source(scene: &Scene) -> PathBuf {
    scene
        .roughness
        .file()
        .map_or_else(|| PathBuf::from("model"), Path::to_path_buf)
}

/// The warning that the realisations' grid leaves part of the slope variance out.
fn unresolved_warning(grid: &Grid) -> Option<String> {
    let share = grid.unresolved_slope_share;
    (share > 0.0).then(|| {
        format!(
            "the realisations' {n} x {n} grid holds the spectrum up to q = {q:.4e} 1/m of \
             {hi:.4e} 1/m: {pct:.3} % of the slope variance lies above it and is not in the \
             exact solves (raise --realisation-grid)",
            n = grid.n,
            q = grid.q_nyquist,
            hi = grid.q_high,
            pct = 100.0 * share
        )
    })
}

/// The exact check of `check --verify`: on the scene's height map, or on realisations of its
/// spectrum when the roughness is a spectrum or a model.
fn exact_check(
    scene: &Scene,
    outcome: &Outcome,
    thickness: f64,
    opts: &ExactOptions,
    warnings: &mut Vec<String>,
) -> Result<Exact, Error> {
    let design = scene.design();
    if let RoughnessSource::Profile { path } = &scene.roughness.source {
        let (surface, mismatch) = scene_map(path)?;
        let (boundary, bem) = map_boundary(opts, path, mismatch, warnings);
        let (verification, min_thickness) = on_surface(&surface, &design, thickness, &bem)?;
        return Ok(Exact {
            map: path.clone(),
            verification,
            min_thickness,
            realisations: None,
            boundary,
        });
    }
    let (spectrum, _) = scene.roughness.spectrum()?;
    let (boundary, opts) = synthesised(opts);
    let (verification, min_thickness, realisations) =
        on_realisations(&spectrum, &design, thickness, &outcome.evaluation, &opts)?;
    warnings.extend(unresolved_warning(&realisations.grid));
    Ok(Exact {
        map: spectrum_source(scene),
        verification,
        min_thickness,
        realisations: Some(realisations),
        boundary,
    })
}

/// The boundary of the solves on synthesised (periodic) realisations, and the options with it.
fn synthesised(opts: &ExactOptions) -> (BoundaryDecision, ExactOptions) {
    let boundary = BoundaryDecision::synthesised(opts.boundary);
    let bem = BemSettings {
        boundary: boundary.boundary,
        ..opts.bem
    };
    (boundary, ExactOptions { bem, ..*opts })
}

/// The boundary of the exact solve on a map of edge mismatch `mismatch` and the solver settings
/// with it; a map solved as periodic whose edges do not join is warned about.
fn map_boundary(
    opts: &ExactOptions,
    path: &Path,
    mismatch: f64,
    warnings: &mut Vec<String>,
) -> (BoundaryDecision, BemSettings) {
    let boundary = BoundaryDecision::from_ratio(opts.boundary, mismatch);
    if boundary.boundary == Boundary::Periodic {
        warnings.extend(periodic_warning(path, mismatch));
    }
    let bem = BemSettings {
        boundary: boundary.boundary,
        ..opts.bem
    };
    (boundary, bem)
}

/// The height map behind `check --verify` (it must be a height map, not line scans) with its
/// edge mismatch (it is solved as one period of a periodic surface).
fn scene_map(path: &Path) -> Result<(Surface, f64), Error> {
    if sniff(path)? == Some(HeightKind::Lines) {
        return Err(Error::Input {
            path: path.to_path_buf(),
            line: 1,
            msg: "--verify needs a height map (a matrix of heights), not line scans".into(),
        });
    }
    let opts = MapOptions {
        periodic: Some(true),
        ..MapOptions::default()
    };
    let map = read_height_map(path, &opts)?;
    Ok((Surface::from_height_map(&map)?, edge_mismatch_map(&map)))
}
