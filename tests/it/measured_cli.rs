//! `check` on measured data: `coatcheck psd`'s options as flags and scene keys for heights
//! (`--profile`), on several instrument formats; PSD conventions and contact.engineering
//! series as flags.

use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_coatcheck");
const DESIGN: [&str; 10] = [
    "--film",
    "paper-rubber",
    "--thickness",
    "10um",
    "--substrate",
    "paper-steel",
    "--bond",
    "epoxy",
    "--pressure",
    "0.1MPa",
];

fn check(args: &[&str]) -> Output {
    Command::new(BIN)
        .arg("check")
        .args(args)
        .args(DESIGN)
        .args(["--format", "json"])
        .output()
        .expect("run coatcheck")
}

fn json(o: &Output) -> serde_json::Value {
    assert!(
        matches!(o.status.code(), Some(0 | 1)),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("json")
}

#[test]
fn check_profile_takes_psd_options_on_several_formats() {
    for (file, extra) in [
        ("x3p-2.x3p", vec!["--detrend", "curvature"]),
        ("di-1.di", vec!["--channel", "Height", "--window", "none"]),
        ("opd-1.opd", vec!["--points-per-decade", "5"]),
        ("dektak-1.csv", vec!["--conversion", "inverse-abel"]),
        ("sur-2.sur", vec!["--cutoff-pixels", "8"]),
        ("mi-1.mi", vec!["--periodic", "false"]),
    ] {
        let path = format!("tests/data/instrument/{file}");
        let mut args = vec!["--profile", path.as_str()];
        args.extend(extra.iter().copied());
        let v = json(&check(&args));
        let profile = &v["scene"]["roughness"]["profile"];
        let key = extra[0].trim_start_matches("--").replace('-', "_");
        if key != "conversion" {
            assert!(!profile[&key].is_null(), "{file}: {key} not in {profile}");
        }
    }
}

#[test]
fn options_change_the_spectrum_and_scene_keys_equal_flags() {
    let x3p = "tests/data/instrument/x3p-2.x3p";
    let plain = json(&check(&["--profile", x3p]));
    let coarse = json(&check(&["--profile", x3p, "--cutoff-pixels", "32"]));
    assert_ne!(plain["tau_peak_pa"], coarse["tau_peak_pa"]);
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("s.toml");
    std::fs::write(
        &scene,
        format!(
            "[roughness]\nprofile = \"{}\"\ncutoff_pixels = 32\n",
            std::fs::canonicalize(x3p).unwrap().display()
        ),
    )
    .unwrap();
    let from_file = json(&check(&[scene.to_str().unwrap()]));
    assert_eq!(from_file["tau_peak_pa"], coarse["tau_peak_pa"]);
    // The channel of a di file as a scene key: another channel, another spectrum.
    std::fs::write(
        &scene,
        format!(
            "[roughness]\nprofile = \"{}\"\nchannel = \"Phase\"\nperiodic = false\n",
            std::fs::canonicalize("tests/data/instrument/di-1.di")
                .unwrap()
                .display()
        ),
    )
    .unwrap();
    // The channel reaches the reader: the phase channel (degrees, not a height) gives an rms
    // slope far outside any surface, an error naming the file.
    let phase = check(&[scene.to_str().unwrap()]);
    assert_eq!(phase.status.code(), Some(2));
    let e = String::from_utf8_lossy(&phase.stderr);
    assert!(e.contains("di-1.di") && e.contains("rms slope"), "{e}");
}

#[test]
fn heights_options_contradict_a_psd_file_and_bad_values_are_named() {
    let o = check(&[
        "--psd",
        "examples/measured-rolloff.csv",
        "--channel",
        "Height",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("roughness.channel"), "{e}");
    let o = check(&[
        "--profile",
        "tests/data/instrument/x3p-2.x3p",
        "--window",
        "hamming",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("--window") && e.contains("hann, none"), "{e}");
}

#[test]
fn check_reads_ce_downloads_and_conventions() {
    let csv = json(&check(&["--psd", "tests/data/ce/ce-power-spectrum.csv"]));
    let txt = json(&check(&["--psd", "tests/data/ce/ce-power-spectrum.txt"]));
    assert_eq!(csv["tau_peak_pa"], txt["tau_peak_pa"]);
    let y = json(&check(&[
        "--psd",
        "tests/data/ce/ce-power-spectrum.txt",
        "--series",
        "1D PSD along y",
    ]));
    assert_ne!(y["tau_peak_pa"], txt["tau_peak_pa"]);
    let o = check(&[
        "--psd",
        "tests/data/ce/ce-power-spectrum.txt",
        "--psd-convention",
        "isotropic",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("roughness.psd_convention"), "{e}");
}
