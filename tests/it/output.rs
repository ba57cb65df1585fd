//! How output reaches files and standard output: through symbolic links, straight into FIFOs
//! and `/dev/stdout`, with the umask's mode, without temporary files left by an error or a
//! signal; standard output errors are exit 2, a closed pipe a quiet end.
#![cfg(unix)]

use crate::common::run;
use std::io::{BufRead, BufReader};
use std::os::unix::fs::{FileTypeExt, PermissionsExt};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const SCENE: &str = "examples/paper-rubber-on-steel.toml";

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_coatcheck")
}

/// The report `check SCENE` prints on standard output.
fn report() -> Vec<u8> {
    let o = run(&["check", SCENE]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    o.stdout
}

/// Names of the hidden temporary files in `dir`.
fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.') && n.ends_with("tmp"))
        .collect()
}

#[test]
fn output_through_a_symlink_replaces_its_target_and_keeps_the_link() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("t.txt");
    let link = dir.path().join("l.txt");
    std::fs::write(&target, "old").unwrap();
    std::os::unix::fs::symlink("t.txt", &link).unwrap();
    let o = run(&["check", SCENE, "--output", link.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    assert!(o.stdout.is_empty());
    assert!(std::fs::symlink_metadata(&link).unwrap().is_symlink());
    assert_eq!(std::fs::read(&target).unwrap(), report());
    assert!(temporaries(dir.path()).is_empty());
}

#[test]
fn output_into_a_fifo_is_written_straight_into_it() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let o = run(&["check", SCENE, "--output", fifo.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    assert_eq!(reader.join().unwrap(), report());
    assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
    assert!(temporaries(dir.path()).is_empty());
}

#[test]
fn output_to_dev_stdout_prints_the_report() {
    let o = run(&["check", SCENE, "--output", "/dev/stdout"]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    assert_eq!(o.stdout, report());
}

/// Run `coatcheck ARGS` under `umask MASK` (through the shell, which sets it for the child).
fn run_with_umask(mask: &str, args: &[&str]) -> std::process::Output {
    Command::new("sh")
        .arg("-c")
        .arg(format!("umask {mask} && exec \"$0\" \"$@\""))
        .arg(bin())
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap()
}

#[test]
fn new_files_get_the_umasks_mode_and_replaced_files_keep_theirs() {
    let dir = tempfile::tempdir().unwrap();
    let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o7777;
    let new = dir.path().join("new.txt");
    let o = run_with_umask("027", &["check", SCENE, "--output", new.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    assert_eq!(mode(&new), 0o640);
    let o = run_with_umask("022", &["check", SCENE, "--output", new.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    assert_eq!(mode(&new), 0o640, "a replaced file keeps its mode");
    let old = dir.path().join("old.txt");
    std::fs::write(&old, "old").unwrap();
    std::fs::set_permissions(&old, std::fs::Permissions::from_mode(0o604)).unwrap();
    let o = run_with_umask("077", &["check", SCENE, "--output", old.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    assert_eq!(mode(&old), 0o604);
    assert_eq!(std::fs::read(&old).unwrap(), report());
}

#[test]
fn a_full_standard_output_is_exit_2_with_a_message() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let o = Command::new(bin())
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["check", SCENE])
        .stdout(full)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("<stdout>") && err.contains("No space left"),
        "{err}"
    );
}

#[test]
fn a_closed_pipe_ends_quietly() {
    let mut child = Command::new(bin())
        .args([
            "response",
            "--film",
            "1MPa,0.5",
            "--substrate",
            "200GPa,0.3",
            "--qd",
            "1e-3:1e3:100000",
            "--format",
            "csv",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut out = BufReader::new(child.stdout.take().unwrap());
    let mut line = String::new();
    out.read_line(&mut line).unwrap();
    assert_eq!(
        line,
        "qd,S,S_err,f,f_err,g,g_err,g_t,g_t_err,f_t,f_t_err,h,h_err\n"
    );
    drop(out);
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(err.is_empty(), "{err}");
}

#[test]
fn sigterm_while_writing_leaves_no_temporary_and_no_partial_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("big.csv");
    let mut child = Command::new(bin())
        .args([
            "synth",
            "--n",
            "2048",
            "--pixel-size",
            "1um",
            "--rms-height",
            "1um",
            "--q0",
            "1e4",
            "--q1",
            "1e6",
            "-o",
            out.to_str().unwrap(),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Wait until the temporary file is being written, then stop the run.
    let start = Instant::now();
    while temporaries(dir.path()).is_empty() {
        assert!(
            child.try_wait().unwrap().is_none(),
            "synth ended before its temporary file was seen"
        );
        assert!(start.elapsed() < Duration::from_secs(120));
        std::thread::sleep(Duration::from_millis(2));
    }
    let killed = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = child.wait().unwrap();
    use std::os::unix::process::ExitStatusExt;
    assert_eq!(status.signal(), Some(15), "{status:?}");
    assert!(
        temporaries(dir.path()).is_empty(),
        "{:?}",
        temporaries(dir.path())
    );
    assert!(!out.exists());
}

/// Every output goes through the one guard against NaN and inf (`report::finite`): standard
/// output through `report::stdout` (or, streamed, a `report::finite::Finite` writer), files through
/// `report::write_with` (text, checked line by line) or `write_bytes_with` (Parquet). By
/// construction: no source file outside `report/write.rs` opens standard output or a file for
/// writing, or prints to standard output, other than through those (test modules aside: they start at
/// `#[cfg(test)]`).
#[test]
fn every_output_goes_through_the_finite_guard() {
    fn sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                sources(&p, out);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&root, &mut files);
    assert!(files.len() > 50);
    let forbidden = [
        "io::stdout()",
        "File::create",
        "fs::write(",
        "OpenOptions",
        "println!",
        "print!(",
    ];
    let mut found = Vec::new();
    for f in files {
        if f.ends_with("report/write.rs") {
            continue;
        }
        let text = std::fs::read_to_string(&f).unwrap();
        let code = text.split("#[cfg(test)]").next().unwrap();
        for (i, line) in code.lines().enumerate() {
            // Messages on standard error are not reports.
            let line = line.replace("eprintln!", "");
            let streamed = line.contains("Finite::new(std::io::stdout()");
            if !streamed && forbidden.iter().any(|p| line.contains(p)) {
                found.push(format!("{}:{}: {}", f.display(), i + 1, line.trim()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "output around the guard:\n{}",
        found.join("\n")
    );
}
