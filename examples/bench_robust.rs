//! Benchmark of `check --robust` on the paper scene (examples/paper-rubber-on-steel.toml): the
//! median time of the nominal judgement (a check with d_min) beside the robust one, with the
//! paper's materials given ranges of every property (the 16 corners of the four elastic
//! constants, each strength at its minimum and maximum: the most `--robust` computes), with
//! ranges of the strengths only (one corner), and with the bond-shear check alone.
//!
//! Run: `cargo run --release --example bench_robust`

#[path = "common/timing.rs"]
mod timing;

use coatcheck::material::Library;
use coatcheck::pipeline::judge;
use coatcheck::scene::Scene;
use std::path::PathBuf;
use timing::median_us;

/// Ranges around the paper's values (film E ±20 %, ν 0.49–0.5, substrate E ±10 %, ν 0.45–0.5,
/// yield 235–300 MPa, bond 8–12 MPa): illustrative widths for the timing only.
const ALL: &[(&str, &str)] = &[
    ("film.youngs_modulus_range", "0.8MPa,1.2MPa"),
    ("film.poisson_ratio_range", "0.49,0.5"),
    ("substrate.youngs_modulus_range", "90GPa,110GPa"),
    ("substrate.poisson_ratio_range", "0.45,0.5"),
    ("substrate.yield_strength_range", "235MPa,300MPa"),
    ("bond.shear_strength_range", "8MPa,12MPa"),
];

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let path = root.join("examples/paper-rubber-on-steel.toml");
    let lib = Library::builtin().unwrap();
    let load = |flags: &[(&str, &str)]| {
        let flags: Vec<(&str, String)> = flags.iter().map(|(k, v)| (*k, v.to_string())).collect();
        Scene::load(Some(&path), &flags, &lib).unwrap()
    };
    let robust = |mut flags: Vec<(&'static str, &'static str)>| {
        flags.push(("criteria.robust", "true"));
        flags
    };
    let bond_only = [("criteria.checks", "bond-shear")];
    let cases: Vec<(&str, Vec<(&str, &str)>)> = vec![
        ("nominal (check with d_min)", vec![]),
        (
            "--robust, every property ranged (16 corners)",
            robust(ALL.to_vec()),
        ),
        (
            "--robust, strengths ranged only (1 corner)",
            robust(ALL[4..].to_vec()),
        ),
        ("nominal, bond-shear only", bond_only.to_vec()),
        (
            "--robust, bond-shear only, every property ranged",
            robust([ALL, &bond_only[..]].concat()),
        ),
    ];
    println!("| run on examples/paper-rubber-on-steel.toml | corners | median (ms) |");
    println!("|---|---:|---:|");
    for (name, flags) in cases {
        let scene = load(&flags);
        let j = judge(&scene, None).unwrap();
        let corners = j.robust.as_ref().map_or(0, |r| r.corners);
        let us = median_us(9, || {
            judge(&scene, None).unwrap();
        });
        println!("| {name} | {corners} | {:.1} |", us / 1e3);
    }
}
