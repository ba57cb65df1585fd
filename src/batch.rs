//! Batch runs of `coatcheck check`: the scene files of the arguments, each judged in parallel
//! (rayon) by [`crate::pipeline::judge`], the runs in summary order, and the totals that decide
//! the exit code. No physics of its own; the tables and records are [`crate::report::batch`]'s.
//!
//! Verdicts: `pass`, `fail`, or `error` (the scene could not be evaluated: bad input or a
//! numerical failure; its message names the file and, for file contents, the line). Exit code
//! of a batch ([`Totals::exit_code`]): 0 when every scene passes, 1 when any fails, 2 when any
//! could not be evaluated (the others are still run and reported).

use crate::error::Error;
use crate::material::Library;
use crate::pipeline::{Judged, judge};
use crate::scene::Scene;
use rayon::prelude::*;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The scene files of a batch: each argument is a scene file or a directory, whose `*.toml`
/// entries are taken in name order (not recursing). Every `*.toml` entry but a directory is a
/// scene: one that cannot be read (a dangling symbolic link, no permission) is then that
/// scene's error row rather than silently left out. A directory without scenes is an error.
pub fn scene_files(args: &[PathBuf]) -> Result<Vec<PathBuf>, Error> {
    let mut files = Vec::new();
    for arg in args {
        if !arg.is_dir() {
            files.push(arg.clone());
            continue;
        }
        let io = |source| Error::Io {
            path: arg.clone(),
            source,
        };
        let mut found: Vec<PathBuf> = std::fs::read_dir(arg)
            .map_err(io)?
            .map(|e| e.map(|e| e.path()).map_err(io))
            .collect::<Result<Vec<_>, _>>()?
            .into_iter()
            .filter(|p| !p.is_dir() && p.extension().is_some_and(|x| x == "toml"))
            .collect();
        if found.is_empty() {
            return Err(Error::Value {
                origin: arg.display().to_string(),
                msg: "no scene files (*.toml) in this directory".into(),
            });
        }
        found.sort();
        files.extend(found);
    }
    Ok(files)
}

/// One scene of a batch: its file, how long it took, and its judgement or why it has none.
#[derive(Debug)]
pub struct SceneRun {
    pub file: PathBuf,
    pub seconds: f64,
    pub result: Result<Judged, Error>,
}

impl SceneRun {
    /// `pass`, `fail` or `error`.
    pub fn verdict(&self) -> &'static str {
        match &self.result {
            Ok(j) if j.pass() => "pass",
            Ok(_) => "fail",
            Err(_) => "error",
        }
    }

    /// Summary order: failures (smallest margin first), then scenes that could not be
    /// evaluated, then passes (smallest margin first); ties by file name.
    fn order(&self) -> (u8, f64) {
        match &self.result {
            Ok(j) => {
                let m = j.outcome.margin().unwrap_or(f64::NEG_INFINITY);
                (if j.pass() { 2 } else { 0 }, m)
            }
            Err(_) => (1, 0.0),
        }
    }
}

/// Load and judge one scene file with the flag overrides.
pub fn run_one(file: &Path, overrides: &[(&str, String)], library: &Library) -> SceneRun {
    let start = Instant::now();
    let result = Scene::load(Some(file), overrides, library)
        .and_then(|s| judge(&s, None))
        .map_err(|e| naming(file, e));
    SceneRun {
        file: file.to_path_buf(),
        seconds: start.elapsed().as_secs_f64(),
        result,
    }
}

/// An error that names no file (a range or numerical failure inside the engine, such as a
/// spectrum too narrow to integrate) as an error of the scene `file`: in a batch's messages
/// and rows every error says which scene it is.
pub fn naming(file: &Path, e: Error) -> Error {
    match e {
        Error::Invalid { .. } | Error::Numerical { .. } => Error::Value {
            origin: file.display().to_string(),
            msg: e.to_string(),
        },
        e => e,
    }
}

/// Judge every scene in parallel; `done` is called after each scene (progress). The runs come
/// back in summary order ([`sort`]).
pub fn run_all(
    files: &[PathBuf],
    overrides: &[(&str, String)],
    library: &Library,
    done: &(dyn Fn() + Sync),
) -> Vec<SceneRun> {
    let mut runs: Vec<SceneRun> = files
        .par_iter()
        .map(|f| {
            let r = run_one(f, overrides, library);
            done();
            r
        })
        .collect();
    sort(&mut runs);
    runs
}

/// Failures first (smallest margin first), then errors, then passes; ties by file name.
pub fn sort(runs: &mut [SceneRun]) {
    runs.sort_by(|a, b| {
        let (ga, ma) = a.order();
        let (gb, mb) = b.order();
        ga.cmp(&gb)
            .then(ma.total_cmp(&mb))
            .then_with(|| a.file.cmp(&b.file))
    });
}

/// Counts of a batch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Totals {
    pub scenes: usize,
    pub pass: usize,
    pub fail: usize,
    pub error: usize,
}

impl Totals {
    pub fn of(runs: &[SceneRun]) -> Self {
        let count = |v: &str| runs.iter().filter(|r| r.verdict() == v).count();
        Totals {
            scenes: runs.len(),
            pass: count("pass"),
            fail: count("fail"),
            error: count("error"),
        }
    }

    /// 0 every scene passes, 1 a scene fails, 2 a scene could not be evaluated.
    pub fn exit_code(&self) -> i32 {
        if self.error > 0 {
            2
        } else if self.fail > 0 {
            1
        } else {
            0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directories_give_their_toml_files_in_name_order() {
        let dir = tempfile::tempdir().unwrap();
        for name in ["b.toml", "a.toml", "notes.md", "c.toml.bak"] {
            std::fs::write(dir.path().join(name), "").unwrap();
        }
        std::fs::create_dir(dir.path().join("sub.toml")).unwrap();
        let extra = PathBuf::from("x/given.toml");
        let files = scene_files(&[dir.path().to_path_buf(), extra.clone()]).unwrap();
        assert_eq!(
            files,
            [dir.path().join("a.toml"), dir.path().join("b.toml"), extra]
        );
        let empty = tempfile::tempdir().unwrap();
        let e = scene_files(&[empty.path().to_path_buf()]).unwrap_err();
        assert!(e.to_string().contains("no scene files"), "{e}");
    }

    #[test]
    fn exit_code_is_the_worst_verdict() {
        let t = |pass, fail, error| Totals {
            scenes: pass + fail + error,
            pass,
            fail,
            error,
        };
        assert_eq!(t(3, 0, 0).exit_code(), 0);
        assert_eq!(t(3, 1, 0).exit_code(), 1);
        assert_eq!(t(3, 1, 1).exit_code(), 2);
        assert_eq!(t(0, 0, 1).exit_code(), 2);
    }
}
