//! `coatcheck response` from the outside: values, formats, and bad input (exit 2).

use std::process::Command;

fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_coatcheck"))
        .args(args)
        .output()
        .expect("binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn csv_reproduces_the_notes_table() {
    let (code, out, _) = run(&[
        "response",
        "--film",
        "1MPa,0.5",
        "--substrate",
        "1e11 Pa,0.5",
        "--qd",
        "0.1,1,10",
        "--format",
        "csv",
    ]);
    assert_eq!(code, 0);
    let rows: Vec<Vec<f64>> = out
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let want = [
        [0.1, 6.6488081104e-4, 0.99508591419, 0.098526500004],
        [1.0, 0.24059022762, 0.80396367594, 0.45638307583],
        [10.0, 0.99999908899, 9.9878763764e-4, 9.0798876490e-4],
    ];
    for (row, w) in rows.iter().zip(want) {
        // Columns qd, S, S_err, f, f_err, g, g_err; each err is KERNEL_RTOL of its value.
        assert!(((row[0] - w[0]) / w[0]).abs() < 1e-10, "{row:?}");
        for k in 1..4 {
            let (v, e) = (row[2 * k - 1], row[2 * k]);
            assert!(((v - w[k]) / w[k]).abs() < 1e-10, "{row:?}");
            assert_eq!(e, coatcheck::prec::KERNEL_RTOL * v.abs(), "{row:?}");
        }
    }
}

#[test]
fn range_and_json() {
    let (code, out, _) = run(&[
        "response",
        "--film",
        "2MPa,0.49985",
        "--substrate",
        "200GPa,0.3",
        "--qd",
        "1e-8:1e4:13",
        "--format",
        "json",
    ]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v.as_array().unwrap().len(), 13);
    assert!(
        v.as_array()
            .unwrap()
            .iter()
            .all(|r| r["S"].as_f64().unwrap() > 0.0
                && r["S_err"].as_f64().unwrap() > 0.0
                && r["g_err"].as_f64().unwrap() >= 0.0)
    );
}

#[test]
fn bad_input_exits_2_with_a_message() {
    for args in [
        vec![
            "response",
            "--film",
            "1MPa,0.7",
            "--substrate",
            "1e11,0.5",
            "--qd",
            "1",
        ],
        vec![
            "response",
            "--film",
            "1 furlong,0.5",
            "--substrate",
            "1e11,0.5",
            "--qd",
            "1",
        ],
        vec![
            "response",
            "--film",
            "1MPa",
            "--substrate",
            "1e11,0.5",
            "--qd",
            "1",
        ],
        vec![
            "response",
            "--film",
            "1MPa,0.5",
            "--substrate",
            "1e11,0.5",
            "--qd",
            "10:1:5",
        ],
    ] {
        let (code, out, err) = run(&args);
        assert_eq!(code, 2, "{args:?}");
        assert!(out.is_empty());
        assert!(
            err.starts_with("coatcheck: ") && err.lines().count() == 1,
            "{err}"
        );
    }
}
