//! A layer stack goes the film's way through every output: its one-row CSV, its JUnit XML, its
//! batch rows beside films, its thickness sweep and its HTML report each carry every interface,
//! checked against the JSON of the same run (numbers bit for bit) and the schemas; and the
//! levers of a failing stack, each applied alone, make it pass.

use crate::common::{json, run};
use crate::formats::{flatten, parse_csv, same};
use crate::schema::errors;
use coatcheck::check::levers::{Lever, REL_TOL};
use coatcheck::check::stack::{StackChecker, StackDesign, StackLayer, StackOutcome};
use coatcheck::check::stack_levers::stack_levers;
use coatcheck::check::{Checks, Criteria};
use coatcheck::layer::Elastic;
use coatcheck::prec::Settings;
use coatcheck::psd::Spectrum;
use serde_json::Value;
use std::collections::BTreeMap;

const PRIMER: &str = "examples/rubber-epoxy-primer-steel.toml";
const PTFE: &str = "examples/ptfe-rubber-steel.toml";
const SLIDING: &str = "examples/ptfe-rubber-steel-sliding.toml";

fn out(args: &[&str]) -> std::process::Output {
    let o = run(args);
    assert!(
        o.status.code().is_some_and(|c| c <= 2) && !o.stdout.is_empty(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

fn valid(schema: &str, v: &Value, what: &str) {
    let schema: Value = serde_json::from_str(schema).unwrap();
    let e = errors(&schema, v);
    assert!(e.is_empty(), "{what}:\n{}", e.join("\n"));
}

/// A stack's record (or check JSON) flattened as its CSV row: the film's columns (the
/// bond-shear columns hold the interface with the least margin), then `thickness_of` and
/// `interface<k>_…` for each interface with its bond-shear check.
fn flatten_stack(v: &Value) -> BTreeMap<String, Value> {
    let checks = v["checks"].as_array().unwrap();
    let mut bonds: Vec<&Value> = checks
        .iter()
        .filter(|c| c["name"] == "bond-shear")
        .collect();
    bonds.sort_by(|a, b| {
        let m = |c: &Value| c["margin"].as_f64().unwrap_or(f64::NEG_INFINITY);
        m(a).total_cmp(&m(b))
    });
    let mut film = v.clone();
    let one: Vec<Value> = checks
        .iter()
        .filter(|c| c["name"] != "bond-shear")
        .chain(bonds.first().copied())
        .cloned()
        .collect();
    film["checks"] = Value::Array(one);
    let mut m = flatten(&film);
    m.remove("interfaces");
    for (k, i) in v["interfaces"].as_array().unwrap().iter().enumerate() {
        for (key, x) in i.as_object().unwrap() {
            m.insert(format!("interface{}_{key}", k + 1), x.clone());
        }
        if let Some(c) = checks
            .iter()
            .find(|c| c["name"] == "bond-shear" && c["at"] == i["name"])
        {
            for key in ["limit", "utilisation", "margin", "pass"] {
                let unit = if key == "limit" { "_pa" } else { "" };
                m.insert(
                    format!("interface{}_bond_shear_{key}{unit}", k + 1),
                    c[key].clone(),
                );
            }
        }
    }
    m
}

fn row_matches(head: &[String], row: &[String], want: &BTreeMap<String, Value>, what: &str) {
    assert_eq!(head.len(), row.len(), "{what}");
    for (h, cell) in head.iter().zip(row) {
        if h == "seconds" {
            continue;
        }
        match want.get(h) {
            Some(v) => same(cell, v, &format!("{what}: {h}")),
            None => assert_eq!(cell, "", "{what}: {h} is not in the JSON"),
        }
    }
}

/// `check STACK --format csv`: the film's columns, then `thickness_of` and every interface's,
/// each equal to the JSON of the same run.
#[test]
fn stack_csv_row_is_its_json() {
    let film_head = parse_csv(&out(&["check", "examples/specs/", "--format", "csv"]).stdout).0;
    for scene in [PRIMER, PTFE, SLIDING] {
        let j = json(&out(&["check", scene, "--format", "json"]));
        valid(coatcheck::report::CHECK_SCHEMA, &j, scene);
        let (head, rows) = parse_csv(&out(&["check", scene, "--format", "csv"]).stdout);
        assert_eq!(
            head[..film_head.len()],
            film_head[..],
            "{scene}: the film's columns first"
        );
        let n = j["interfaces"].as_array().unwrap().len();
        assert_eq!(head.len(), film_head.len() + 1 + 24 * n, "{scene}");
        assert_eq!(rows.len(), 1);
        let mut want = flatten_stack(&j);
        want.insert("scene".into(), scene.into());
        want.insert("thickness_of".into(), j["scene"]["thickness_of"].clone());
        let governing = j["checks"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| c["name"] == j["governing_check"])
            .min_by(|a, b| {
                a["margin"]
                    .as_f64()
                    .unwrap()
                    .total_cmp(&b["margin"].as_f64().unwrap())
            })
            .unwrap();
        want.insert("utilisation".into(), governing["utilisation"].clone());
        want.insert("margin".into(), governing["margin"].clone());
        want.insert("files".into(), 1.into());
        for k in ["schema_version", "coatcheck_version", "scene"] {
            assert!(!head.contains(&k.to_string()) || k == "scene");
        }
        row_matches(&head, &rows[0], &want, scene);
        // Every interface is in the row by name.
        for (k, i) in j["interfaces"].as_array().unwrap().iter().enumerate() {
            let col = head
                .iter()
                .position(|h| *h == format!("interface{}_name", k + 1))
                .unwrap();
            assert_eq!(rows[0][col], i["name"].as_str().unwrap());
        }
    }
}

/// `--junit` on a stack: one test case per check and interface, named with where it applies,
/// failing exactly where the JSON's check fails.
#[test]
fn stack_junit_has_a_case_per_check_and_interface() {
    let dir = tempfile::tempdir().unwrap();
    let thin = dir.path().join("thin.toml");
    std::fs::write(
        &thin,
        std::fs::read_to_string(PRIMER).unwrap().replacen(
            "thickness = \"10 um\"",
            "thickness = \"0.5 um\"",
            1,
        ),
    )
    .unwrap();
    for scene in [PRIMER.to_string(), thin.display().to_string()] {
        let xml = dir.path().join("junit.xml");
        let o = run(&["check", &scene, "--junit", xml.to_str().unwrap()]);
        assert!(o.status.code().is_some_and(|c| c <= 1));
        let j = json(&run(&["check", &scene, "--format", "json"]));
        let text = std::fs::read_to_string(&xml).unwrap();
        let checks = j["checks"].as_array().unwrap();
        assert_eq!(text.matches("<testcase ").count(), checks.len(), "{text}");
        for c in checks {
            let name = format!(
                "{} at {}",
                c["name"].as_str().unwrap(),
                c["at"].as_str().unwrap()
            );
            let start = text
                .find(&format!("<testcase name=\"{name}\""))
                .unwrap_or_else(|| panic!("no case {name}: {text}"));
            // The case runs to the next case or the end of its suite.
            let case = &text[start + 1..];
            let end = case
                .find("<testcase ")
                .or_else(|| case.find("</testsuite>"))
                .unwrap_or(case.len());
            let failed = case[..end].contains("<failure");
            assert_eq!(failed, c["pass"] == false, "{name}: {}", &case[..end]);
        }
    }
}

/// A batch mixing films and stacks: its JSON by the schema, a stack's record equal to its own
/// check's JSON on every shared key, and a CSV whose film rows leave the interface columns
/// empty.
#[test]
fn batch_of_films_and_stacks() {
    let dir = tempfile::tempdir().unwrap();
    for f in [
        PRIMER,
        PTFE,
        SLIDING,
        "examples/paper-rubber-on-steel.toml",
        "examples/specs/paper-film-too-thin.toml",
    ] {
        let name = std::path::Path::new(f).file_name().unwrap();
        std::fs::copy(f, dir.path().join(name)).unwrap();
    }
    let d = dir.path().to_str().unwrap();
    let j = json(&out(&["check", d, "--format", "json"]));
    valid(coatcheck::report::BATCH_SCHEMA, &j, "batch");
    let records = j["scenes"].as_array().unwrap();
    assert_eq!(records.len(), 5);
    let (head, rows) = parse_csv(&out(&["check", d, "--format", "csv"]).stdout);
    assert_eq!(rows.len(), 5);
    for (row, rec) in rows.iter().zip(records) {
        let scene = rec["scene"].as_str().unwrap();
        let mut want = if rec.get("interfaces").is_some() {
            flatten_stack(rec)
        } else {
            assert!(rec.get("thickness_of").is_none(), "{scene}");
            flatten(rec)
        };
        want.remove("interfaces");
        row_matches(&head, row, &want, scene);
        if rec.get("interfaces").is_some() {
            let own = json(&out(&["check", scene, "--format", "json"]));
            assert_eq!(rec["interfaces"], own["interfaces"], "{scene}");
            for k in ["verdict", "governing_check", "area_fraction", "tau_peak_pa"] {
                assert_eq!(rec[k], own[k], "{scene}: {k}");
            }
            let checks: Vec<(&Value, &Value)> = own["checks"]
                .as_array()
                .unwrap()
                .iter()
                .map(|c| (&c["name"], &c["at"]))
                .collect();
            let rec_checks: Vec<(&Value, &Value)> = rec["checks"]
                .as_array()
                .unwrap()
                .iter()
                .map(|c| (&c["name"], &c["at"]))
                .collect();
            assert_eq!(checks, rec_checks, "{scene}");
        }
    }
    let table = String::from_utf8(out(&["check", d]).stdout).unwrap();
    assert!(
        table.contains("bond-shear at") || table.contains("min-thickness at"),
        "{table}"
    );
}

/// `--sweep-thickness` on a stack varies the layer `thickness_of`: JSON by the schema, CSV equal
/// to it, and the row at the design thickness equal to the check's own numbers bit for bit.
#[test]
fn stack_sweep_varies_its_layer() {
    let j = json(&out(&[
        "check",
        PRIMER,
        "--sweep-thickness",
        "10um:10um:1",
        "--format",
        "json",
    ]));
    valid(coatcheck::report::SWEEP_SCHEMA, &j, "stack sweep");
    assert_eq!(j["thickness_of"], "rubber");
    let check = json(&out(&["check", PRIMER, "--format", "json"]));
    let row = &j["sweep"][0];
    assert_eq!(row["thickness_m"], check["thickness_m"]);
    assert_eq!(row["interfaces"].as_array().unwrap().len(), 2);
    for k in [
        "area_fraction",
        "mean_contact_pressure_pa",
        "sigma_rms_top_pa",
        "tau_peak_pa",
    ] {
        assert_eq!(row[k], check[k], "{k}");
    }
    for (a, b) in row["interfaces"]
        .as_array()
        .unwrap()
        .iter()
        .zip(check["interfaces"].as_array().unwrap())
    {
        for k in [
            "name",
            "depth_m",
            "sigma_rms_pa",
            "tau_rms_pa",
            "tau_peak_pa",
            "sigma_peak_pa",
        ] {
            assert_eq!(a[k], b[k], "{k}");
        }
    }
    let args = ["check", PRIMER, "--sweep-thickness", "2um:50um:4"];
    let j = json(&out(&[&args[..], &["--format", "json"]].concat()));
    valid(coatcheck::report::SWEEP_SCHEMA, &j, "stack sweep");
    let (head, rows) = parse_csv(&out(&[&args[..], &["--format", "csv"]].concat()).stdout);
    let items = j["sweep"].as_array().unwrap();
    assert_eq!(rows.len(), 4);
    let mut ds = Vec::new();
    for (row, item) in rows.iter().zip(items) {
        let mut want: BTreeMap<String, Value> = item
            .as_object()
            .unwrap()
            .iter()
            .filter(|(k, _)| !["checks", "interfaces"].contains(&k.as_str()))
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect();
        for (k, i) in item["interfaces"].as_array().unwrap().iter().enumerate() {
            for key in ["sigma_rms_pa", "tau_rms_pa", "tau_peak_pa", "sigma_peak_pa"] {
                want.insert(format!("interface{}_{key}", k + 1), i[key].clone());
            }
        }
        assert_eq!(head.len(), want.len());
        row_matches(&head, row, &want, "sweep row");
        // The primer stays: the interface below the rubber moves with it, the bottom one too.
        let depths: Vec<f64> = item["interfaces"]
            .as_array()
            .unwrap()
            .iter()
            .map(|i| i["depth_m"].as_f64().unwrap())
            .collect();
        let d = item["thickness_m"].as_f64().unwrap();
        assert_eq!(depths[0], d);
        assert!((depths[1] - d - 10e-6).abs() < 1e-18, "{depths:?}");
        ds.push(d);
    }
    assert!((ds[0] - 2e-6).abs() < 1e-20 && (ds[3] - 50e-6).abs() < 1e-19);
    let table = String::from_utf8(out(&args).stdout).unwrap();
    assert!(
        table.contains("layer 'rubber'") && table.contains("τ_peak primer"),
        "{table}"
    );
}

/// `--report` on a stack: the page lists every interface and every check with where it applies.
#[test]
fn stack_report_lists_every_interface() {
    let dir = tempfile::tempdir().unwrap();
    let html = dir.path().join("r.html");
    let o = run(&["check", PTFE, "--report", html.to_str().unwrap()]);
    assert!(o.status.code().is_some_and(|c| c <= 1));
    let page = std::fs::read_to_string(&html).unwrap();
    let j = json(&out(&["check", PTFE, "--format", "json"]));
    assert!(page.contains("Interfaces (Persson"), "no interface table");
    for i in j["interfaces"].as_array().unwrap() {
        assert!(page.contains(&format!("<td>{}</td>", i["name"].as_str().unwrap())));
    }
    for c in j["checks"].as_array().unwrap() {
        let name = format!(
            "{} at {}",
            c["name"].as_str().unwrap(),
            c["at"].as_str().unwrap()
        );
        assert!(page.contains(&name), "the page lacks {name}");
    }
    for want in [
        "layer &#39;skin&#39;",
        "layer &#39;lining&#39;",
        "Roughness power spectrum",
    ] {
        assert!(page.contains(want), "the page lacks {want}");
    }
}

fn paper_spectrum() -> Spectrum {
    Spectrum::self_affine(1.0, 1e5, 1e8, None)
        .unwrap()
        .scaled_to_rms_slope(1.0)
        .unwrap()
}

/// Rubber (the paper's, 1 MPa, ν = ½) `d` thick on an epoxy primer 10 µm on steel, with the
/// given bonds (rubber–primer, primer–steel) and yield strength.
fn rubber_on_primer(d: f64, bonds: (f64, f64), yield_strength: f64, pressure: f64) -> StackDesign {
    let layer = |name: &str, e: f64, nu: f64, t: f64, b: f64| StackLayer {
        name: name.into(),
        material: Elastic::new(e, nu).unwrap(),
        thickness: t,
        bond_strength: b,
    };
    StackDesign {
        layers: vec![
            layer("rubber", 1e6, 0.5, d, bonds.0),
            layer("primer", 3e9, 0.35, 10e-6, bonds.1),
        ],
        substrate: Elastic::new(200e9, 0.3).unwrap(),
        pressure,
        yield_strength: Some(yield_strength),
        friction: 0.0,
        criteria: Criteria {
            epsilon: 1e-6,
            checks: Checks::all(),
            ..Criteria::default()
        },
        thickness_of: 0,
    }
}

fn passes(s: &Spectrum, d: &StackDesign) -> bool {
    StackChecker::new(s, d.clone(), Settings::default())
        .unwrap()
        .stress_checks_pass()
        .unwrap()
}

/// The outcome of a stack that must fail, and its levers.
fn failing_with_levers(s: &Spectrum, base: &StackDesign) -> (StackOutcome, Vec<Lever>) {
    let outcome = StackChecker::new(s, base.clone(), Settings::default())
        .unwrap()
        .run()
        .unwrap();
    assert!(!outcome.pass);
    let all = stack_levers(s, base, Settings::default(), &outcome).unwrap();
    (outcome, all)
}

fn lever<'a>(all: &'a [Lever], name: &str) -> &'a Lever {
    all.iter().find(|l| l.name == name).expect(name)
}

/// A thin rubber skin on a primer with weak bonds fails bond-shear at both interfaces and
/// substrate-yield; each lever alone makes its stress checks pass, and a step past it fails.
#[test]
fn each_stack_lever_alone_makes_a_failing_stack_pass() {
    let s = paper_spectrum();
    let base = rubber_on_primer(0.5e-6, (0.5e6, 0.5e6), 250e6, 1e5);
    let (outcome, all) = failing_with_levers(&s, &base);
    let failing: Vec<String> = outcome
        .checks
        .iter()
        .filter(|c| !c.result.pass && c.result.kind.name() == "bond-shear")
        .map(|c| c.at.clone())
        .collect();
    assert!(!failing.is_empty(), "{:?}", outcome.checks);
    // Every failing interface's bond, raised alone to its lever, passes there; all raised
    // together (with the yield lever if any) pass every stress check, and a bond just below
    // its lever fails.
    let mut all_raised = base.clone();
    for l in all.iter().filter(|l| l.name == "bond_strength") {
        let at = l.at.as_deref().unwrap();
        assert!(failing.iter().any(|f| f == at));
        let k = base.layers.iter().position(|x| x.name == at).unwrap();
        all_raised.layers[k].bond_strength = l.value.unwrap() * 1.001;
    }
    assert_eq!(
        all.iter().filter(|l| l.name == "bond_strength").count(),
        failing.len()
    );
    if let Some(y) = all.iter().find(|l| l.name == "yield_strength") {
        all_raised.yield_strength = Some(y.value.unwrap() * 1.001);
    }
    assert!(passes(&s, &all_raised));
    for l in all.iter().filter(|l| l.name == "bond_strength") {
        let k = base
            .layers
            .iter()
            .position(|x| Some(x.name.as_str()) == l.at.as_deref())
            .unwrap();
        let mut below = all_raised.clone();
        below.layers[k].bond_strength = l.value.unwrap() * 0.999;
        assert!(!passes(&s, &below), "{l:?}");
    }
    let t = lever(&all, "thickness");
    assert_eq!(t.at.as_deref(), Some("rubber"));
    let thick = |d: f64| StackDesign {
        layers: {
            let mut l = base.layers.clone();
            l[0].thickness = d;
            l
        },
        ..base.clone()
    };
    let t = t.value.unwrap();
    assert!(passes(&s, &thick(t * 1.01)) && !passes(&s, &thick(t * 0.99)));
    let p = lever(&all, "pressure");
    if let Some(pv) = p.value {
        let at = |p: f64| StackDesign {
            pressure: p,
            ..base.clone()
        };
        assert!(passes(&s, &at(pv)));
        assert!(!passes(&s, &at(pv * (1.0 + 3.0 * REL_TOL))));
    }
    let r = lever(&all, "low_octave_rms");
    if let Some(w) = r.value {
        let k = (w / r.current).powi(2);
        assert!(passes(&crate::levers::octave_scaled(&s, k), &base));
        assert!(!passes(
            &crate::levers::octave_scaled(&s, k * (1.0 + 3.0 * REL_TOL)),
            &base
        ));
    }
}

/// A weak bond under the rubber alone: a lighter load passes, and a slightly heavier one
/// fails.
#[test]
fn a_lighter_load_alone_makes_a_weak_stack_bond_pass() {
    let s = paper_spectrum();
    let base = rubber_on_primer(5e-6, (0.4e6, 10e6), 1e12, 1e5);
    let (_, all) = failing_with_levers(&s, &base);
    let p = lever(&all, "pressure")
        .value
        .expect("a lighter load passes");
    assert!(p < base.pressure);
    let at = |p: f64| StackDesign {
        pressure: p,
        ..base.clone()
    };
    assert!(passes(&s, &at(p)));
    assert!(!passes(&s, &at(p * (1.0 + 3.0 * REL_TOL))));
    let b = lever(&all, "bond_strength");
    assert_eq!(b.at.as_deref(), Some("rubber"));
    let text = coatcheck::report::html::lever_text(b);
    assert!(text.contains("bond below 'rubber'"), "{text}");
}
