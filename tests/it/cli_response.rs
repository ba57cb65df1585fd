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

/// `--layer`: two layers of one material on a half-space of it (a homogeneous solid) give the
/// closed forms of notes.md, S = 1, f_k = (1 + q z_k)e^{−q z_k}, g_k = q z_k e^{−q z_k}, in the
/// columns q, S, f1, g1, f2, g2 (each followed by its error, STACK_RTOL of the value), and
/// g_t = (1 − x)e^{−x}, f_t = x e^{−x}, h = e^{−x} in g_t1, f_t1, h1, g_t2, … (STACK_RTOL of the
/// value, of h/100 for g_t near its zero at x = 1); and one
/// layer equals the `--film` form at q·d = q d (within the two kernels' error bounds).
#[test]
fn stack_columns_and_limits() {
    let (code, out, _) = run(&[
        "response",
        "--layer",
        "3GPa,0.35,10um",
        "--layer",
        "3GPa,0.35,20um",
        "--substrate",
        "3GPa,0.35",
        "--q",
        "1e3,1e5,3e5",
        "--format",
        "csv",
    ]);
    assert_eq!(code, 0);
    let mut lines = out.lines();
    assert_eq!(
        lines.next(),
        Some(
            "q,S,S_err,f1,f1_err,g1,g1_err,f2,f2_err,g2,g2_err,g_t1,g_t1_err,f_t1,f_t1_err,h1,\
             h1_err,g_t2,g_t2_err,f_t2,f_t2_err,h2,h2_err"
        )
    );
    let rtol = coatcheck::layer::stack::STACK_RTOL;
    for line in lines {
        let row: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        let q = row[0];
        let mut want = vec![1.0];
        for z in [10e-6, 30e-6] {
            let x: f64 = q * z;
            want.extend([(1.0 + x) * (-x).exp(), x * (-x).exp()]);
        }
        // g_t = (1 − x)e^{−x}, f_t = x e^{−x}, h = e^{−x} (notes.md, "Sliding friction"); g_t's
        // error relative to max(|g_t|, h/100).
        for (k, z) in [10e-6, 30e-6].into_iter().enumerate() {
            let x: f64 = q * z;
            let e = (-x).exp();
            for (j, (w, floor)) in [((1.0 - x) * e, 0.01 * e), (x * e, 0.0), (e, 0.0)]
                .into_iter()
                .enumerate()
            {
                let (v, err) = (row[11 + 6 * k + 2 * j], row[12 + 6 * k + 2 * j]);
                assert!(
                    (v - w).abs() <= 1e-13 * w.abs().max(floor),
                    "tangential column {j} of interface {k} at q = {q}: {v} vs {w}"
                );
                let h = row[15 + 6 * k];
                let bound = if j == 0 {
                    v.abs().max(0.01 * h)
                } else {
                    v.abs()
                };
                assert_eq!(err, rtol * bound, "{line}");
            }
        }
        for (k, w) in want.iter().enumerate() {
            let (v, e) = (row[1 + 2 * k], row[2 + 2 * k]);
            assert!(
                (v - w).abs() <= rtol * w,
                "column {k} at q = {q}: {v} vs {w}"
            );
            assert_eq!(e, rtol * v.abs());
        }
    }
    let col = |args: &[&str]| -> Vec<f64> {
        let (code, out, _) = run(args);
        assert_eq!(code, 0);
        let row = out.lines().nth(1).expect("one row").to_string();
        row.split(',').map(|v| v.parse().unwrap()).collect()
    };
    let one = col(&[
        "response",
        "--layer",
        "1MPa,0.5,10um",
        "--substrate",
        "200GPa,0.3",
        "--q",
        "1e5",
        "--format",
        "csv",
    ]);
    let film = col(&[
        "response",
        "--film",
        "1MPa,0.5",
        "--substrate",
        "200GPa,0.3",
        "--qd",
        "1",
        "--format",
        "csv",
    ]);
    for k in [1, 3, 5] {
        assert!(
            (one[k] - film[k]).abs() <= 2.0 * rtol * film[k],
            "column {k}: {} vs {}",
            one[k],
            film[k]
        );
    }
}

/// Deep interfaces: where f_k and g_k leave f64's normal range (q·z ≳ 708) their error is at
/// least the smallest subnormal, so a value rounded to 0 is reported as 0 ± 5e-324, never
/// 0 ± 0; above it the error stays relative.
#[test]
fn stack_errors_cover_the_flush_below_the_normal_range() {
    let (code, out, _) = run(&[
        "response",
        "--layer",
        "3GPa,0.35,10um",
        "--layer",
        "3GPa,0.35,20um",
        "--substrate",
        "3GPa,0.35",
        "--q",
        "1e6,2.4e7,1e8",
        "--format",
        "csv",
    ]);
    assert_eq!(code, 0);
    let rtol = coatcheck::layer::stack::STACK_RTOL;
    let tiny = f64::from_bits(1);
    let mut flushed = 0;
    for line in out.lines().skip(1) {
        let row: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        for k in 0..5 {
            let (v, e) = (row[1 + 2 * k], row[2 + 2 * k]);
            if v.abs() < f64::MIN_POSITIVE {
                assert_eq!(e, rtol * v.abs() + tiny, "{line}");
                flushed += 1;
            } else {
                assert_eq!(e, rtol * v.abs(), "{line}");
            }
        }
    }
    assert!(flushed >= 4, "the deep rows reach the subnormals: {out}");
}

/// Bad stacks: a layer without thickness, 11 layers, `--layer` with `--qd`, no `--q`: exit 2
/// with a message naming the flag.
#[test]
fn stack_bad_input() {
    let eleven: Vec<&str> = std::iter::repeat_n(["--layer", "1MPa,0.5,1um"], 11)
        .flatten()
        .collect();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["--layer", "1MPa,0.5", "--q", "1"], "--layer"),
        ([eleven.as_slice(), &["--q", "1"]].concat(), "layers"),
        (vec!["--layer", "1MPa,0.5,1um", "--qd", "1"], "--qd"),
        (vec!["--layer", "1MPa,0.5,1um"], "--q"),
        (vec!["--layer", "1MPa,0.5,1um", "--q=-1"], "--q"),
    ];
    for (args, names) in cases {
        let all = [&["response", "--substrate", "200GPa,0.3"], args.as_slice()].concat();
        let (code, _, err) = run(&all);
        assert_eq!(code, 2, "{all:?}");
        assert!(err.contains(names), "{all:?}: {err}");
    }
}

/// The tangential columns for identical materials against the closed forms of notes.md
/// ("Sliding friction"): g_t = (1 − x)e^{−x}, f_t = x e^{−x}, h = e^{−x}, to 1e-13 relative
/// (g_t absolute in units of e^{−x} near its zero at x = 1), each error column equal to the
/// stated bound.
#[test]
fn tangential_columns_match_identical_material_limits() {
    let (code, out, _) = run(&[
        "response",
        "--film",
        "1MPa,0.3",
        "--substrate",
        "1MPa,0.3",
        "--qd",
        "1e-6,0.1,1,3,30",
        "--format",
        "csv",
    ]);
    assert_eq!(code, 0);
    let mut lines = out.lines();
    assert_eq!(
        lines.next().unwrap(),
        "qd,S,S_err,f,f_err,g,g_err,g_t,g_t_err,f_t,f_t_err,h,h_err"
    );
    let rtol = coatcheck::layer::tangential::TANGENTIAL_RTOL;
    for l in lines {
        let r: Vec<f64> = l.split(',').map(|v| v.parse().unwrap()).collect();
        let x = r[0];
        let e = (-x).exp();
        for (col, want, scale) in [(7, (1.0 - x) * e, e), (9, x * e, x * e), (11, e, e)] {
            assert!(
                (r[col] - want).abs() <= 1e-13 * scale,
                "x = {x}, col {col}: {r:?}"
            );
            assert!(
                r[col + 1] >= rtol * r[col].abs() && r[col + 1] <= rtol * scale.max(r[col].abs())
            );
        }
    }
}
