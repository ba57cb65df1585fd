//! Benchmark: a two-layer check with d_min (rubber 10 µm on an epoxy primer 10 µm on steel,
//! examples/rubber-epoxy-primer-steel.toml: bond-shear at both interfaces, substrate-yield,
//! min-thickness of the rubber) against the one-layer check of the same rubber on the same
//! steel (the paper's roughness, p0 = 0.1 MPa). Medians of full checks (engine set-up,
//! evaluation, checks, d_min search), run alternately, and the median of their ratios.
//!
//! Run: `cargo run --release --example bench_stack_check`
//!
//! With `-- one N` or `-- two N` it runs N checks of one kind, untimed, for an instruction
//! count per check: `valgrind --tool=callgrind target/release/examples/bench_stack_check two 3`
//! less the same with `two 1`, halved (the first check's set-up and warm-up cancel).

use coatcheck::check::stack::StackChecker;
use coatcheck::check::{Checker, Design};
use coatcheck::layer::Bilayer;
use coatcheck::material::Library;
use coatcheck::scene::Scene;
use std::path::PathBuf;

#[path = "common/pairs.rs"]
mod pairs;

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let lib = Library::builtin().expect("bundled library");
    let path = root.join("examples/rubber-epoxy-primer-steel.toml");
    let scene = Scene::load(Some(&path), &[], &lib).expect("example scene");
    let (spectrum, _) = scene.roughness.spectrum().expect("model spectrum");
    let stack = scene.stack_design();
    let rubber = &stack.layers[0];
    let one = Design {
        layers: Bilayer::new(rubber.material, stack.substrate),
        pressure: stack.pressure,
        yield_strength: stack.yield_strength,
        bond_strength: rubber.bond_strength,
        friction: 0.0,
        criteria: stack.criteria,
    };
    // One full check of each kind (engine set-up, evaluation, checks, d_min search): the
    // engine evaluations of its d_min search.
    let run_one = || {
        let c = Checker::new(&spectrum, one.clone(), scene.settings).expect("valid design");
        let out = c.run(rubber.thickness).expect("check runs");
        out.min_thickness.expect("d_min asked for").evaluations
    };
    let run_two = || {
        let c = StackChecker::new(&spectrum, stack.clone(), scene.settings).expect("valid stack");
        let out = c.run().expect("check runs");
        out.min_thickness.expect("d_min asked for").evaluations
    };
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [which, n] = args.as_slice() {
        let n: usize = n.parse().expect("a number of checks");
        for _ in 0..n {
            match which.as_str() {
                "one" => run_one(),
                "two" => run_two(),
                _ => panic!("usage: bench_stack_check [one|two N]"),
            };
        }
        return;
    }
    // The two checks alternate, so that both see the same load on a shared machine; the ratio
    // is the median of the per-pair ratios. The first 4 pairs warm up.
    let reps = 41;
    let (mut one_evals, mut two_evals) = (0, 0);
    let times = pairs::alternating(4, reps, || one_evals = run_one(), || two_evals = run_two());
    let one_us = pairs::median(times.iter().map(|t| t.0).collect());
    let two_us = pairs::median(times.iter().map(|t| t.1).collect());
    let ratio = pairs::median(times.iter().map(|t| t.1 / t.0).collect());
    println!(
        "one-layer check + d_min (rubber on steel):          {one_us:10.0} µs ({one_evals} d_min evaluations)"
    );
    println!(
        "two-layer check + d_min (rubber on epoxy on steel): {two_us:10.0} µs ({two_evals} d_min evaluations)"
    );
    println!("ratio two-layer / one-layer (median of {reps} alternating pairs): {ratio:.2}");
}
