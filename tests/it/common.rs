//! Helpers shared by the command-line tests.

use std::process::{Command, Output};

/// Run the `coatcheck` binary in the repository root (so bundled example paths work).
pub fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_coatcheck"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .output()
        .expect("run coatcheck")
}

/// Standard output parsed as JSON.
pub fn json(o: &Output) -> serde_json::Value {
    serde_json::from_slice(&o.stdout).expect("JSON on stdout")
}

/// Writes `text` to `dir/name`; returns the path as a string for a command line.
pub fn write_text(dir: &std::path::Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

/// `coatcheck check <args> --format json`, which must not exit with an input error (code < 2),
/// parsed.
pub fn check_json(args: &[&str]) -> serde_json::Value {
    let mut argv = vec!["check"];
    argv.extend(args);
    argv.extend(["--format", "json"]);
    let o = run(&argv);
    assert!(o.status.code().is_some_and(|c| c < 2), "{argv:?}: {o:?}");
    json(&o)
}
