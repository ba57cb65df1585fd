//! Sliding friction (notes.md, "Sliding friction"): the scene keys, Persson's theory under a
//! friction traction μσ along x (uncoupled approximation), the checks and d_min under sliding.

use crate::common::run;

const PAPER: &str = "examples/paper-rubber-on-steel.toml";

/// `--friction` outside 0..=10, an unknown `--shear-tail` and the half-normal rule with
/// friction are input errors (exit 2) naming the key.
#[test]
fn friction_and_shear_tail_reject_bad_values() {
    for (args, key) in [
        (vec!["--friction", "11"], "load.friction"),
        (vec!["--friction", "-0.1"], "load.friction"),
        (vec!["--shear-tail", "rayleigh"], "criteria.shear_tail"),
        (
            vec!["--friction", "0.5", "--shear-tail", "half-normal"],
            "criteria.shear_tail",
        ),
    ] {
        let mut all = vec!["check", PAPER];
        all.extend(args.iter());
        let o = run(&all);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(key), "{args:?}: {err}");
    }
}
