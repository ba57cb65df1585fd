//! The text readers (spectra, line scans, height maps) under hostile input, through the
//! binary: endless or oversized input, a map cut short, flat or overflowing heights, old Mac
//! line ends. Each must end with exit 2 and a message naming the file (and the line where one
//! is at fault), or read as its plain counterpart does.

use crate::common::run;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

const SCENE: [&str; 10] = [
    "--film",
    "natural-rubber",
    "--substrate",
    "carbon-steel",
    "--bond",
    "epoxy",
    "--pressure",
    "0.1MPa",
    "--thickness",
    "20um",
];

fn write(dir: &Path, name: &str, text: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// Run, expecting exit 2 within 20 s and a one-line message containing every needle.
fn fails_with(args: &[&str], needles: &[&str]) {
    let t = Instant::now();
    let o = run(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        t.elapsed() < Duration::from_secs(20),
        "{args:?} took {:?}",
        t.elapsed()
    );
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: '{err}' lacks '{n}'");
    }
}

#[test]
fn dev_zero_is_refused_quickly_as_a_spectrum_and_as_heights() {
    let psd: Vec<&str> = ["check", "--psd", "/dev/zero"]
        .into_iter()
        .chain(SCENE)
        .collect();
    fails_with(&psd, &["/dev/zero:1:", "NUL byte", "not a text table"]);
    fails_with(&["psd", "/dev/zero"], &["/dev/zero:1:", "NUL byte"]);
    fails_with(
        &["psd", "/dev/zero", "--dx", "1um"],
        &["/dev/zero:1:", "NUL byte"],
    );
    fails_with(
        &["psd", "/dev/zero", "--pixel-size", "1um"],
        &["/dev/zero:1:", "NUL byte"],
    );
}

#[test]
fn oversized_inputs_are_refused_with_their_limit() {
    let dir = tempfile::tempdir().unwrap();
    // 65 MiB of valid rows: past the 64 MiB limit of a spectrum file.
    let row = b"1e5,1e-20\n";
    let big: Vec<u8> = row.iter().copied().cycle().take(65 << 20).collect();
    let p = write(dir.path(), "big.csv", &big);
    let args: Vec<&str> = ["check", "--psd", p.to_str().unwrap()]
        .into_iter()
        .chain(SCENE)
        .collect();
    fails_with(&args, &["big.csv:", "larger than 64 MiB"]);
    // A map whose metadata asks for 10⁵ x 10⁵ heights (80 GB) is refused at that line.
    let p = write(
        dir.path(),
        "huge.csv",
        b"# coatcheck height map: nx = 100000, ny = 100000, dx = 1e-6 m\n1,2,3,4\n",
    );
    fails_with(
        &["psd", p.to_str().unwrap()],
        &["huge.csv:1:", "at most 67108864 heights"],
    );
}

fn map_text(ny_meta: usize, rows: usize) -> String {
    let mut t = format!("# coatcheck height map: nx = 16, ny = {ny_meta}, dx = 1e-6 m\n");
    for iy in 0..rows {
        let row: Vec<String> = (0..16)
            .map(|ix| format!("{}e-7", (ix * 7 + iy * 3) % 5))
            .collect();
        t.push_str(&row.join(","));
        t.push('\n');
    }
    t
}

#[test]
fn a_map_cut_short_or_too_long_for_its_metadata_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "short.csv", map_text(128, 100).as_bytes());
    fails_with(
        &["psd", p.to_str().unwrap()],
        &["short.csv:101:", "after 100 rows", "ny = 128", "incomplete"],
    );
    let p = write(dir.path(), "long.csv", map_text(16, 17).as_bytes());
    fails_with(
        &["psd", p.to_str().unwrap()],
        &["long.csv:18:", "more rows than the metadata's ny = 16"],
    );
    // The same map with its true size reads.
    let p = write(dir.path(), "ok.csv", map_text(100, 100).as_bytes());
    let o = run(&["psd", p.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn flat_or_overflowing_heights_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let flat = format!("{}0\n", "0,".repeat(15)).repeat(16);
    let p = write(dir.path(), "flat.csv", flat.as_bytes());
    fails_with(
        &["psd", p.to_str().unwrap(), "--pixel-size", "1um"],
        &["flat.csv", "flat after detrending"],
    );
    let p = write(
        dir.path(),
        "flat-lines.csv",
        "z (m)\n0\n0\n0\n0\n0\n0\n0\n0\n0\n".as_bytes(),
    );
    fails_with(
        &["psd", p.to_str().unwrap(), "--dx", "1um"],
        &["flat-lines.csv", "flat after detrending"],
    );
    let huge = map_text(16, 16).replace("e-7", "e200");
    let p = write(dir.path(), "huge-z.csv", huge.as_bytes());
    fails_with(&["psd", p.to_str().unwrap()], &["huge-z.csv", "inf"]);
}

#[test]
fn cr_only_line_ends_read_like_lf() {
    let dir = tempfile::tempdir().unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for (name, cmd) in [
        ("examples/measured-rolloff.csv", "check"),
        ("examples/data/height-map.csv", "psd"),
        ("examples/data/line-scans.csv", "psd"),
    ] {
        let lf = std::fs::read_to_string(root.join(name)).unwrap();
        let base = Path::new(name).file_name().unwrap().to_str().unwrap();
        let a = write(dir.path(), &format!("lf-{base}"), lf.as_bytes());
        let b = write(
            dir.path(),
            &format!("cr-{base}"),
            lf.replace('\n', "\r").as_bytes(),
        );
        let out = |p: &Path| {
            let p = p.to_str().unwrap();
            let mut args = vec![cmd];
            if cmd == "check" {
                args.extend(["--psd", p]);
                args.extend(SCENE);
            } else {
                args.push(p);
            }
            args.extend(["--format", "json"]);
            let o = run(&args);
            assert_eq!(
                o.status.code(),
                Some(0),
                "{args:?}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
            String::from_utf8(o.stdout).unwrap().replace(p, "FILE")
        };
        assert_eq!(out(&a), out(&b), "{name}");
    }
}
