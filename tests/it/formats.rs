//! Every output format of every command round-trips through its schema or its documented shape
//! (README, "Output formats"): JSON against the schemas in `src/report/schema/` (tests/it/schema.rs
//! holds the validator), CSV parsed back with the columns the README lists and each value equal,
//! bit for bit, to the JSON value of the same run (numbers are written in Rust's shortest
//! round-trip form, so parsing them gives the same f64). Tables are checked by the golden
//! recordings and their 100-column test.

use crate::common::{json, run};
use crate::schema::errors;
use serde_json::Value;
use std::collections::BTreeMap;

/// The output of a command that succeeded or judged (exit 0 or 1; 2 for a batch with errors).
fn out(args: &[&str]) -> std::process::Output {
    let o = run(args);
    assert!(
        o.status.code().is_some_and(|c| c <= 2) && !o.stdout.is_empty(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

/// A CSV text as its header and rows (comment lines `#` skipped).
pub(crate) fn parse_csv(text: &[u8]) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_reader(text);
    let head = r.headers().unwrap().iter().map(String::from).collect();
    let rows = r
        .records()
        .map(|x| x.unwrap().iter().map(String::from).collect())
        .collect();
    (head, rows)
}

/// A CSV cell equals a JSON value: empty is null, numbers equal as f64 (bit for bit), text and
/// booleans as written.
pub(crate) fn same(cell: &str, v: &Value, what: &str) {
    match v {
        Value::Null => assert_eq!(cell, "", "{what}"),
        Value::Number(n) => {
            let x: f64 = cell.parse().unwrap_or_else(|_| panic!("{what}: '{cell}'"));
            assert_eq!(
                x.to_bits(),
                n.as_f64().unwrap().to_bits(),
                "{what}: {cell} vs {n}"
            );
        }
        Value::String(s) => assert_eq!(cell, s, "{what}"),
        Value::Bool(b) => assert_eq!(cell, b.to_string(), "{what}"),
        _ => panic!("{what}: a CSV cell cannot hold {v}"),
    }
}

/// A batch record (or a check's JSON) flattened the way the CSV row is: scalars as they are,
/// each check to `<check>_value`, `_limit`, `_utilisation`, `_margin`, `_pass`, each lever to
/// `lever_<name>`, warnings joined by " | ".
pub(crate) fn flatten(record: &Value) -> BTreeMap<String, Value> {
    let mut m = BTreeMap::new();
    for (k, v) in record.as_object().unwrap() {
        match k.as_str() {
            "checks" => {
                for c in v.as_array().unwrap() {
                    let name = c["name"].as_str().unwrap().replace('-', "_");
                    let unit = if c["unit"] == "m" { "_m" } else { "_pa" };
                    m.insert(format!("{name}_value{unit}"), c["value"].clone());
                    m.insert(format!("{name}_limit{unit}"), c["limit"].clone());
                    for key in ["utilisation", "margin", "pass"] {
                        m.insert(format!("{name}_{key}"), c[key].clone());
                    }
                }
            }
            "levers" => {
                for l in v.as_array().unwrap() {
                    let unit = if l["unit"] == "m" { "_m" } else { "_pa" };
                    let name = l["name"].as_str().unwrap();
                    m.insert(format!("lever_{name}{unit}"), l["value"].clone());
                }
            }
            "warnings" => {
                let w: Vec<&str> = v
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|w| w.as_str().unwrap())
                    .collect();
                let joined = if w.is_empty() {
                    Value::Null
                } else {
                    Value::String(w.join(" | "))
                };
                m.insert(k.clone(), joined);
            }
            _ => {
                m.insert(k.clone(), v.clone());
            }
        }
    }
    m
}

/// The CSV row against the flattened JSON: every column the JSON has is equal; a column it does
/// not have (a check that did not run, a lever that does not apply) is empty.
fn row_matches(head: &[String], row: &[String], want: &BTreeMap<String, Value>, what: &str) {
    assert_eq!(head.len(), row.len(), "{what}");
    for (h, cell) in head.iter().zip(row) {
        if h == "seconds" {
            continue; // two runs, two timings
        }
        match want.get(h) {
            Some(v) => same(cell, v, &format!("{what}: {h}")),
            None => assert_eq!(cell, "", "{what}: {h} is not in the JSON"),
        }
    }
}

fn schema(text: &str) -> Value {
    serde_json::from_str(text).unwrap()
}

fn valid(schema: &Value, v: &Value, what: &str) {
    let e = errors(schema, v);
    assert!(e.is_empty(), "{what}:\n{}", e.join("\n"));
}

/// `check DIR`: the batch JSON follows its schema, and the CSV has one row per scene whose every
/// column is the record's value.
#[test]
fn check_batch_json_and_csv() {
    let dir = ["check", "examples/specs/"];
    let j = json(&out(&[dir[0], dir[1], "--format", "json"]));
    valid(&schema(coatcheck::report::BATCH_SCHEMA), &j, "batch JSON");
    let (head, rows) = parse_csv(&out(&[dir[0], dir[1], "--format", "csv"]).stdout);
    let records = j["scenes"].as_array().unwrap();
    assert_eq!(rows.len(), records.len());
    let keys: Vec<String> = records[0].as_object().unwrap().keys().cloned().collect();
    for k in keys
        .iter()
        .filter(|k| !["checks", "levers"].contains(&k.as_str()))
    {
        assert!(head.contains(k), "the CSV lacks the record's {k}");
    }
    for (row, rec) in rows.iter().zip(records) {
        row_matches(&head, row, &flatten(rec), rec["scene"].as_str().unwrap());
    }
}

/// `check SCENE`: JSON by its schema; the CSV is the batch's shape (same header) with one row,
/// its values those of the JSON (the exact check's under `verify`).
#[test]
fn check_one_scene_json_and_csv() {
    let batch_head = parse_csv(&out(&["check", "examples/specs/", "--format", "csv"]).stdout).0;
    let check_schema = schema(coatcheck::report::CHECK_SCHEMA);
    for scene in [
        &["examples/specs/paper-film-too-thin.toml"][..],
        &["examples/specs/lining-two-scans.toml"],
        &["examples/height-map-film.toml", "--verify"],
    ] {
        let args = |f: &'static str| {
            let mut a = vec!["check"];
            a.extend(scene);
            a.extend(["--format", f]);
            a
        };
        let j = json(&out(&args("json")));
        valid(&check_schema, &j, &format!("{scene:?}"));
        let (head, rows) = parse_csv(&out(&args("csv")).stdout);
        assert_eq!(head, batch_head, "{scene:?}: one CSV shape");
        assert_eq!(rows.len(), 1);
        let mut want = flatten(&j);
        want.insert("scene".into(), Value::String(scene[0].into()));
        let governing = j["checks"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["name"] == j["governing_check"])
            .unwrap();
        want.insert("utilisation".into(), governing["utilisation"].clone());
        want.insert("margin".into(), governing["margin"].clone());
        want.insert(
            "files".into(),
            j["files"].as_array().map_or(1, Vec::len).into(),
        );
        want.insert(
            "verdict".into(),
            j.get("verdict_with_verify")
                .unwrap_or(&j["verdict"])
                .clone(),
        );
        if let Some(v) = j.get("verify") {
            want.insert("verify_verdict".into(), v["verdict"].clone());
            for k in [
                "area_fraction",
                "mean_contact_pressure_pa",
                "tau_peak_pa",
                "sigma_peak_interface_pa",
            ] {
                want.insert(format!("verify_{k}"), v[k].clone());
            }
            let x = &j["exact"];
            for k in ["min_thickness_m", "min_thickness_m_err"] {
                want.insert(format!("verify_{k}"), x[k].clone());
            }
            if x["surface"] == "realisations" {
                want.insert("verify_realisations".into(), x["realisations"].clone());
            }
        }
        row_matches(&head, &rows[0], &want, &format!("{scene:?}"));
    }
}

/// `check --sweep-thickness`: JSON by its schema; the CSV columns are `thickness_m` and the
/// sweep keys, each row the JSON's.
#[test]
fn check_sweep_json_and_csv() {
    let base = [
        "check",
        "examples/paper-rubber-on-steel.toml",
        "--sweep-thickness",
        "0.1um:1mm:7",
        "--format",
    ];
    let with = |f: &'static str| {
        let mut a = base.to_vec();
        a.push(f);
        a
    };
    let j = json(&out(&with("json")));
    valid(&schema(coatcheck::report::SWEEP_SCHEMA), &j, "sweep JSON");
    let (head, rows) = parse_csv(&out(&with("csv")).stdout);
    let mut want_head = vec!["thickness_m".to_string()];
    want_head.extend(
        coatcheck::report::SWEEP
            .iter()
            .map(|(_, k, _)| k.to_string()),
    );
    assert_eq!(head, want_head);
    let list = j["sweep"].as_array().unwrap();
    assert_eq!(rows.len(), 7);
    for (row, point) in rows.iter().zip(list) {
        for (h, cell) in head.iter().zip(row) {
            same(cell, &point[h], h);
        }
    }
    // The spectrum used is the check's: the same h_rms and rms slope, bit for bit.
    let check = json(&out(&[
        "check",
        "examples/paper-rubber-on-steel.toml",
        "--format",
        "json",
    ]));
    for key in ["h_rms_m", "rms_slope"] {
        assert_eq!(j[key], check[key], "{key}");
    }
    let table = String::from_utf8(out(&base[..4]).stdout).unwrap();
    assert!(
        table.starts_with("spectrum used: h_rms = 2.690 µm, rms slope = 1.000."),
        "{table}"
    );
    // Under sliding the sliding columns follow, in the schema too.
    let mut sliding = with("json");
    sliding.extend(["--friction", "0.5"]);
    let j = json(&out(&sliding));
    valid(
        &schema(coatcheck::report::SWEEP_SCHEMA),
        &j,
        "sliding sweep JSON",
    );
    assert!(j["sweep"][0]["tau_peak_static_pa"].as_f64().unwrap() > 0.0);
}

/// `verify`: JSON by its schema (no CSV: the fields go to `--fields FILE`).
#[test]
fn verify_json_follows_its_schema() {
    let o = out(&[
        "verify",
        "examples/data/height-map.csv",
        "--film",
        "2MPa,0.5",
        "--substrate",
        "200GPa,0.3",
        "--thickness",
        "3um",
        "--pressure",
        "0.1MPa",
        "--format",
        "json",
    ]);
    let v = json(&o);
    valid(&schema(coatcheck::report::VERIFY_SCHEMA), &v, "verify JSON");
    // The keys of quantities that `check` reports too are the check's.
    for k in [
        "area_fraction",
        "sigma_rms_top_pa",
        "thickness_m",
        "pressure_pa",
    ] {
        assert!(v[k].is_number(), "{k}");
    }
}

/// `psd`: JSON by its schema; the CSV spectrum (`q (1/m),C (m^4)[,C1D (m^3)]`) is the JSON's
/// arrays, and the summary CSV (with `--output`) its summary.
#[test]
fn psd_json_and_csv() {
    let psd_schema = schema(coatcheck::report::PSD_SCHEMA);
    for (input, lines) in [
        ("examples/data/height-map.csv", false),
        ("examples/data/line-scans.csv", true),
    ] {
        let j = json(&out(&["psd", input, "--format", "json"]));
        valid(&psd_schema, &j, input);
        let (head, rows) = parse_csv(&out(&["psd", input, "--format", "csv"]).stdout);
        let mut want = vec!["q (1/m)", "C (m^4)"];
        if lines {
            want.push("C1D (m^3)");
        }
        assert_eq!(head, want, "{input}");
        let keys = ["q_per_m", "c_m4", "c1d_m3"];
        assert_eq!(rows.len(), j["q_per_m"].as_array().unwrap().len());
        for (i, row) in rows.iter().enumerate() {
            for (cell, key) in row.iter().zip(keys) {
                same(cell, &j[key][i], &format!("{input} {key}[{i}]"));
            }
        }
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("c.csv");
        let o = out(&[
            "psd",
            input,
            "--format",
            "csv",
            "--output",
            file.to_str().unwrap(),
        ]);
        let (head, rows) = parse_csv(&o.stdout);
        assert_eq!(head, ["quantity", "value", "unit"]);
        let summary = j["summary"].as_object().unwrap();
        assert_eq!(rows.len(), summary.len());
        for row in &rows {
            same(&row[1], &summary[&row[0]], &row[0]);
        }
    }
}

/// `response`: JSON by its schema; the CSV (`qd,S,S_err,f,f_err,g,g_err`) is the JSON.
#[test]
fn response_json_and_csv() {
    let args = |f: &'static str| {
        vec![
            "response",
            "--film",
            "1MPa,0.5",
            "--substrate",
            "200GPa,0.3",
            "--qd",
            "1e-3:1e3:13",
            "--format",
            f,
        ]
    };
    let j = json(&out(&args("json")));
    valid(
        &schema(coatcheck::report::RESPONSE_SCHEMA),
        &j,
        "response JSON",
    );
    let (head, rows) = parse_csv(&out(&args("csv")).stdout);
    assert_eq!(
        head,
        [
            "qd", "S", "S_err", "f", "f_err", "g", "g_err", "g_t", "g_t_err", "f_t", "f_t_err",
            "h", "h_err"
        ]
    );
    let list = j.as_array().unwrap();
    assert_eq!(rows.len(), list.len());
    for (row, point) in rows.iter().zip(list) {
        for (h, cell) in head.iter().zip(row) {
            same(cell, &point[h], h);
        }
    }
}

/// A named material with one property overridden: the scene reports the override in the table
/// and JSON, and the design is judged with the overriding value (the same numbers as the
/// material written out in full with that value).
#[test]
fn a_material_property_override_is_used_and_reported() {
    let dir = tempfile::tempdir().unwrap();
    let base = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/paper-rubber-on-steel.toml"
    ))
    .unwrap();
    let scene = |film: &str, bond: &str| {
        base.replace("material = \"paper-rubber\"", film)
            .replace("material = \"epoxy\"", bond)
    };
    let write = |name: &str, text: String| {
        let p = dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        p.to_str().unwrap().to_string()
    };
    let over = write(
        "over.toml",
        scene(
            "material = \"paper-rubber\"\nyoungs_modulus = \"3 MPa\"",
            "material = \"epoxy\"\nshear_strength = \"4 MPa\"",
        ),
    );
    let full = write(
        "full.toml",
        scene(
            "youngs_modulus = \"3 MPa\"\npoisson_ratio = 0.5",
            "shear_strength = \"4 MPa\"",
        ),
    );
    let j = json(&out(&["check", &over, "--format", "json"]));
    valid(
        &schema(coatcheck::report::CHECK_SCHEMA),
        &j,
        "override JSON",
    );
    let o = &j["scene"]["overrides"];
    assert_eq!(o.as_array().unwrap().len(), 2, "{o}");
    assert_eq!(o[0]["key"], "film.youngs_modulus");
    assert_eq!(o[0]["material"], "paper-rubber");
    assert_eq!(o[0]["value"], 3e6);
    assert_eq!(o[0]["library_value"], 1e6);
    assert_eq!(o[1]["key"], "bond.shear_strength");
    assert_eq!(o[1]["value"], 4e6);
    assert_eq!(j["scene"]["film"]["name"], "paper-rubber");
    let f = json(&out(&["check", &full, "--format", "json"]));
    for k in ["area_fraction", "tau_peak_pa", "min_thickness_m"] {
        assert_eq!(j[k], f[k], "{k}");
    }
    assert_eq!(j["checks"], f["checks"]);
    let table = String::from_utf8(out(&["check", &over]).stdout).unwrap();
    assert!(
        table.contains("film.youngs_modulus = 3.000 MPa (library paper-rubber: 1.000 MPa)"),
        "{table}"
    );
    assert!(table.contains("bond.shear_strength = 4.000 MPa (library epoxy: 10.00 MPa)"));
}
