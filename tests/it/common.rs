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
