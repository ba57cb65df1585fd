//! The one writer of output files and of standard output.
//!
//! A file is written the way trusted tools write it:
//! - a regular file (or a new one) is written to a temporary file in the target's directory,
//!   synced, and renamed over the target only when complete, so the target is either the old
//!   file or the whole new one, never a partial one;
//! - a symbolic link is written through: the file it points to is replaced, the link stays;
//! - a target that exists and is not a regular file (a FIFO, `/dev/stdout`, a device node) is
//!   opened and written straight into; renaming over it would replace the node itself;
//! - a new file gets the mode the umask leaves of 0666 (as `>` in a shell); a replaced file keeps
//!   its mode;
//! - the temporary file is removed on every error path, on unwinding, and on SIGINT, SIGTERM and
//!   SIGHUP: live temporary paths are kept in a registry that a signal-watching thread empties
//!   (removing the files) before the process ends by the same signal.
//!
//! Standard output ([`stdout`]) reports write errors (a full disk) as [`Error::Io`] on
//! `<stdout>`; a reader that went away (`| head -1`) is a broken pipe, which
//! [`is_broken_pipe`] recognises so that the command line can end quietly.

use super::finite::Finite;
use crate::error::Error;
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard, Once};

/// Temporary files being written, removed by the signal watcher before the process ends.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Distinguishes temporary files of one process.
static SERIAL: AtomicU64 = AtomicU64::new(0);

/// Symbolic links followed before giving up (as the kernel's ELOOP limit).
const MAX_LINKS: usize = 40;

fn live() -> MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Start the thread that removes live temporary files on SIGINT, SIGTERM or SIGHUP and then
/// ends the process by that signal (its default action). Once per process.
fn watch_signals() {
    static START: Once = Once::new();
    START.call_once(|| {
        use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
        let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
            return;
        };
        std::thread::spawn(move || {
            if let Some(sig) = signals.forever().next() {
                // Held to the end: no new temporary file can be created after the sweep.
                let paths = live();
                for p in paths.iter() {
                    let _ = std::fs::remove_file(p);
                }
                let _ = signal_hook::low_level::emulate_default_handler(sig);
                std::process::exit(128 + sig);
            }
        });
    });
}

/// A temporary file in the registry; dropping it removes the file (unless it was renamed).
struct Temp {
    path: PathBuf,
    renamed: bool,
}

impl Temp {
    /// Create `.NAME.PID.N.tmp` next to `target`, with the mode a new file gets.
    fn create(target: &Path) -> std::io::Result<(Self, File)> {
        watch_signals();
        let dir = match target.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let name = target
            .file_name()
            .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
        let mut opts = OpenOptions::new();
        opts.write(true).create_new(true);
        #[cfg(unix)]
        std::os::unix::fs::OpenOptionsExt::mode(&mut opts, 0o666);
        loop {
            let n = SERIAL.fetch_add(1, Ordering::Relaxed);
            let path = dir.join(format!(".{name}.{}.{n}.tmp", std::process::id()));
            let mut registry = live();
            match opts.open(&path) {
                Ok(file) => {
                    registry.push(path.clone());
                    return Ok((
                        Temp {
                            path,
                            renamed: false,
                        },
                        file,
                    ));
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
                Err(e) => return Err(e),
            }
        }
    }

    fn rename_to(mut self, target: &Path) -> std::io::Result<()> {
        let mut registry = live();
        std::fs::rename(&self.path, target)?;
        self.renamed = true;
        registry.retain(|p| p != &self.path);
        Ok(())
    }
}

impl Drop for Temp {
    fn drop(&mut self) {
        if !self.renamed {
            let mut registry = live();
            let _ = std::fs::remove_file(&self.path);
            registry.retain(|p| p != &self.path);
        }
    }
}

/// The file a path names after following symbolic links (also dangling ones: the file they
/// point to is created). The path itself when it is not a link.
fn resolve_links(path: &Path) -> std::io::Result<PathBuf> {
    let mut p = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let to = std::fs::read_link(&p)?;
                p = match p.parent() {
                    Some(dir) if to.is_relative() => dir.join(to),
                    _ => to,
                };
            }
            _ => return Ok(p),
        }
    }
    Err(std::io::Error::other("too many levels of symbolic links"))
}

fn io_error(path: &Path) -> impl Fn(std::io::Error) -> Error + '_ {
    |source| Error::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Write a text file with `body` (see the module docs for how), refusing it at the first
/// line that shows a non-finite number ([`super::finite`]): the old file stays, and no partial
/// new one is left.
pub fn write_with(
    path: &Path,
    body: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), Error> {
    write_bytes_with(path, |w| {
        let mut guarded = Finite::new(w);
        body(&mut guarded)?;
        guarded.finish()
    })
}

/// Write a binary file (Parquet) with `body` (see the module docs for how).
pub fn write_bytes_with(
    path: &Path,
    body: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), Error> {
    let io = io_error(path);
    match std::fs::metadata(path) {
        Ok(m) if !m.is_file() && !m.is_dir() => {
            let mut w = BufWriter::new(OpenOptions::new().write(true).open(path).map_err(&io)?);
            body(&mut w).and_then(|()| w.flush()).map_err(&io)
        }
        existing => {
            let target = resolve_links(path).map_err(&io)?;
            let (temp, file) = Temp::create(&target).map_err(&io)?;
            if let Ok(m) = existing {
                file.set_permissions(m.permissions()).map_err(&io)?;
            }
            let mut w = BufWriter::new(file);
            body(&mut w).and_then(|()| w.flush()).map_err(&io)?;
            let file = w.into_inner().map_err(|e| io(e.into_error()))?;
            file.sync_all().map_err(&io)?;
            drop(file);
            temp.rename_to(&target).map_err(io)
        }
    }
}

/// Write `contents` to a file (see the module docs for how).
pub fn write_file(path: &Path, contents: &str) -> Result<(), Error> {
    write_with(path, |w| w.write_all(contents.as_bytes()))
}

/// Print `text` on standard output, unless it shows a number that is not finite
/// ([`super::finite`]). A write error is an [`Error::Io`] on `<stdout>`.
pub fn stdout(text: &str) -> Result<(), Error> {
    super::finite_only(text)?;
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(io_error(Path::new("<stdout>")))
}

/// Whether an error is a write to a reader that went away (a closed pipe).
pub fn is_broken_pipe(e: &Error) -> bool {
    matches!(e, Error::Io { source, .. } if source.kind() == std::io::ErrorKind::BrokenPipe)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn replaces_the_file_and_leaves_no_temporaries() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("out.json");
        std::fs::write(&p, "old").unwrap();
        write_file(&p, "new").unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "new");
        assert_eq!(names(dir.path()), ["out.json"]);
        let missing = dir.path().join("no/such/dir/out.json");
        assert!(write_file(&missing, "x").is_err());
    }

    #[test]
    fn a_failing_body_leaves_the_old_file_and_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("out.csv");
        std::fs::write(&p, "old").unwrap();
        let e = write_with(&p, |w| {
            w.write_all(b"partial")?;
            Err(std::io::Error::other("disk on fire"))
        })
        .unwrap_err();
        assert!(e.to_string().contains("disk on fire"), "{e}");
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "old");
        assert_eq!(names(dir.path()), ["out.csv"]);
        assert!(!live().iter().any(|p| p.starts_with(dir.path())));
    }

    /// A text file whose body shows a non-finite number is refused at that line: the error
    /// names the row and column, the old file stays, no temporary is left. A binary body is
    /// not read as text.
    #[test]
    fn a_non_finite_number_is_not_written() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("out.csv");
        std::fs::write(&p, "old").unwrap();
        let e = write_with(&p, |w| {
            w.write_all(b"q,C\n1e5,1e-20\n")?;
            w.write_all(b"2e5,inf\n3e5,1e-21\n")
        })
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("out.csv") && e.contains("2e5 is inf, column C"),
            "{e}"
        );
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "old");
        assert_eq!(names(dir.path()), ["out.csv"]);
        write_bytes_with(&p, |w| w.write_all(b"a,NaN\n")).unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "a,NaN\n");
    }

    #[cfg(unix)]
    #[test]
    fn relative_and_chained_links_are_followed_to_the_file() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("sub")).unwrap();
        std::os::unix::fs::symlink("sub/real.txt", dir.path().join("a")).unwrap();
        std::os::unix::fs::symlink("a", dir.path().join("b")).unwrap();
        // Dangling: the file it points to is created.
        write_file(&dir.path().join("b"), "x").unwrap();
        assert_eq!(
            std::fs::read_to_string(dir.path().join("sub/real.txt")).unwrap(),
            "x"
        );
        assert!(
            std::fs::symlink_metadata(dir.path().join("b"))
                .unwrap()
                .is_symlink()
        );
        std::os::unix::fs::symlink("loop", dir.path().join("loop")).unwrap();
        assert!(write_file(&dir.path().join("loop"), "x").is_err());
    }
}
