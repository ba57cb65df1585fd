//! Golden outputs: every example and README command (tables, JSON, CSV, JUnit and the files they
//! write) compared byte for byte with the recordings in `tests/golden/`, so that a refactor
//! keeps behaviour. Timings are the only thing masked. `COATCHECK_BLESS=1 cargo test --test it
//! golden` rewrites the recordings.

use std::fmt::Write as _;
use std::path::Path;
use std::process::Command;

/// Timings (`time="0.012"` in JUnit, `(0.03 s)` in batch summaries, `in 0.02 s` in solver status, `"seconds": 0.01` in JSON
/// and the last column of a CSV whose header ends in `seconds`) replaced by `#`.
pub(crate) fn mask_timings(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut seconds_column = false;
    for line in text.split_inclusive('\n') {
        if line.starts_with("--- ") {
            seconds_column = false;
        }
        match line.rfind(',') {
            Some(i) if seconds_column => {
                out.push_str(&line[..=i]);
                out.push_str("#\n");
            }
            _ => out.push_str(&mask_line(line)),
        }
        if line.trim_end().ends_with(",seconds") {
            seconds_column = true;
        }
    }
    out
}

fn mask_line(line: &str) -> String {
    let mut s = line.to_string();
    for (open, close) in [("time=\"", "\""), ("\"seconds\": ", ",")] {
        let mut from = 0;
        while let Some(i) = s[from..].find(open) {
            let start = from + i + open.len();
            let end = s[start..]
                .find(close)
                .map_or(s.trim_end().len(), |j| start + j);
            s.replace_range(start..end, "#");
            from = start + 1;
        }
    }
    let mut from = 0;
    while let Some(i) = s[from..].find(" in ") {
        let start = from + i + 4;
        match s[start..].find(" s") {
            Some(j) if s[start..start + j].parse::<f64>().is_ok() => {
                s.replace_range(start..start + j, "#");
            }
            _ => {}
        }
        from = start;
    }
    if let Some(i) = s.rfind(" s)")
        && let Some(j) = s[..i].rfind('(')
        && s[j + 1..i].parse::<f64>().is_ok()
    {
        s.replace_range(j + 1..i, "#");
    }
    s
}

fn record(args: &str, out_dir: &Path) -> String {
    let root = env!("CARGO_MANIFEST_DIR");
    let out = out_dir.display().to_string();
    let argv: Vec<String> = args
        .split_whitespace()
        .map(|a| a.replace("{out}", &out))
        .collect();
    let o = Command::new(env!("CARGO_BIN_EXE_coatcheck"))
        .current_dir(root)
        .args(&argv)
        .output()
        .expect("run coatcheck");
    let mut text = format!("$ coatcheck {args}\nexit: {:?}\n", o.status.code());
    text += "--- stdout\n";
    text += &String::from_utf8_lossy(&o.stdout);
    text += "--- stderr\n";
    text += &String::from_utf8_lossy(&o.stderr);
    let mut files: Vec<_> = std::fs::read_dir(out_dir)
        .expect("output directory")
        .map(|e| e.expect("entry").path())
        .collect();
    files.sort();
    for f in files {
        let name = f.file_name().expect("name").to_string_lossy().into_owned();
        let body = std::fs::read(&f).expect("read output file");
        let _ = write!(text, "--- file {name}\n{}", String::from_utf8_lossy(&body));
    }
    mask_timings(&text.replace(&out, "{out}"))
}

#[test]
fn examples_and_readme_commands_match_their_recordings() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    let cases = std::fs::read_to_string(root.join("cases.txt")).expect("cases.txt");
    let bless = std::env::var_os("COATCHECK_BLESS").is_some();
    let mut failed = Vec::new();
    for line in cases.lines() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let (name, args) = line.split_once(':').expect("name: arguments");
        let dir = tempfile::tempdir().expect("temp dir");
        let got = record(args.trim(), dir.path());
        let path = root.join(format!("{name}.txt"));
        if bless {
            std::fs::write(&path, &got).expect("write recording");
            continue;
        }
        let want = std::fs::read_to_string(&path).unwrap_or_default();
        if got != want {
            let at = got
                .lines()
                .zip(want.lines())
                .position(|(a, b)| a != b)
                .unwrap_or(got.lines().count().min(want.lines().count()));
            failed.push(format!(
                "{name}: differs from line {}:\n  got:  {}\n  want: {}",
                at + 1,
                got.lines().nth(at).unwrap_or("<end>"),
                want.lines().nth(at).unwrap_or("<end>")
            ));
        }
    }
    assert!(failed.is_empty(), "{}", failed.join("\n"));
}

/// Every human output (the recordings of the commands without `--format json|csv`, checked
/// against the binary by the test above) fits 100 columns on standard output.
#[test]
fn human_outputs_fit_100_columns() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    let cases = std::fs::read_to_string(root.join("cases.txt")).expect("cases.txt");
    let mut wide = Vec::new();
    let mut tables = 0;
    for line in cases
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
    {
        let (name, args) = line.split_once(':').expect("name: arguments");
        if args.contains("--format json") || args.contains("--format csv") {
            continue;
        }
        let text = std::fs::read_to_string(root.join(format!("{name}.txt"))).expect("recording");
        let stdout = text
            .split_once("--- stdout\n")
            .and_then(|(_, rest)| rest.split_once("--- stderr\n"))
            .map(|(out, _)| out)
            .expect("a stdout section");
        tables += usize::from(stdout.contains('┆'));
        for l in stdout.lines() {
            let n = l.chars().count();
            if n > 100 {
                wide.push(format!("{name}: {n} columns: {l}"));
            }
        }
    }
    assert!(tables >= 15, "only {tables} recordings with a table");
    assert!(wide.is_empty(), "{}", wide.join("\n"));
}

#[test]
fn timings_are_masked_and_nothing_else() {
    assert_eq!(
        mask_line("<testsuites name=\"x\" time=\"0.039\">\n"),
        "<testsuites name=\"x\" time=\"#\">\n"
    );
    assert_eq!(
        mask_line("6 scenes: 2 passed (0.03 s)\n"),
        "6 scenes: 2 passed (# s)\n"
    );
    assert_eq!(mask_line("  \"seconds\": 0.01,\n"), "  \"seconds\": #,\n");
    assert_eq!(
        mask_line("Converged after 19 iterations in 0.03 s (rms gap)\n"),
        "Converged after 19 iterations in # s (rms gap)\n"
    );
    assert_eq!(mask_line("written in 3 files\n"), "written in 3 files\n");
    assert_eq!(mask_line("d = 3 (see note s)\n"), "d = 3 (see note s)\n");
    assert_eq!(
        mask_timings("a,seconds\nx,0.5\n\"y,z\",1e-3\n--- file j\nq,2\n"),
        "a,seconds\nx,#\n\"y,z\",#\n--- file j\nq,2\n"
    );
}
