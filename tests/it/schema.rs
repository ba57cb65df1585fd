//! The JSON Schemas shipped in `src/report/schema/` checked against real output of every command
//! that writes JSON, with a small validator for the part of JSON Schema (2020-12) they use:
//! `type`, `properties`, `required`, `additionalProperties: false`, `items`, `enum`, `const`,
//! `minimum`, `anyOf`, `$ref` to `#/$defs/…`. (The `jsonschema` crate would pull in an HTTP
//! client and a regex engine for this.) The validator itself is tested on small cases, including
//! ones it must reject.

use serde_json::{Value, json};

fn type_matches(t: &str, v: &Value) -> bool {
    match t {
        "object" => v.is_object(),
        "array" => v.is_array(),
        "string" => v.is_string(),
        "number" => v.is_number(),
        "integer" => v.as_f64().is_some_and(|x| x.fract() == 0.0),
        "boolean" => v.is_boolean(),
        "null" => v.is_null(),
        _ => false,
    }
}

/// Errors of `v` against `schema` (resolving `$ref` in `root`), each with its JSON path.
pub fn validate(root: &Value, schema: &Value, v: &Value, path: &str, errors: &mut Vec<String>) {
    if let Some(r) = schema.get("$ref").and_then(Value::as_str) {
        let name = r
            .strip_prefix("#/$defs/")
            .expect("only #/$defs/ references");
        let target = &root["$defs"][name];
        assert!(!target.is_null(), "unknown $ref {r}");
        return validate(root, target, v, path, errors);
    }
    if let Some(t) = schema.get("type") {
        let ok = match t {
            Value::String(t) => type_matches(t, v),
            Value::Array(ts) => ts.iter().any(|t| type_matches(t.as_str().unwrap_or(""), v)),
            _ => false,
        };
        if !ok {
            errors.push(format!("{path}: expected type {t}, got {v}"));
            return;
        }
    }
    if let Some(options) = schema.get("enum").and_then(Value::as_array)
        && !options.contains(v)
    {
        errors.push(format!("{path}: {v} not one of {options:?}"));
    }
    if let Some(c) = schema.get("const")
        && c != v
    {
        errors.push(format!("{path}: {v} is not {c}"));
    }
    if let (Some(min), Some(x)) = (schema.get("minimum").and_then(Value::as_f64), v.as_f64())
        && x < min
    {
        errors.push(format!("{path}: {x} below the minimum {min}"));
    }
    if let Some(options) = schema.get("anyOf").and_then(Value::as_array) {
        let any = options.iter().any(|s| {
            let mut e = Vec::new();
            validate(root, s, v, path, &mut e);
            e.is_empty()
        });
        if !any {
            errors.push(format!("{path}: matches none of anyOf"));
        }
    }
    if let Some(obj) = v.as_object() {
        let props = schema.get("properties").and_then(Value::as_object);
        for key in schema
            .get("required")
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
        {
            let key = key.as_str().expect("required names");
            if !obj.contains_key(key) {
                errors.push(format!("{path}: missing required key '{key}'"));
            }
        }
        for (k, x) in obj {
            match props.and_then(|p| p.get(k)) {
                Some(s) => validate(root, s, x, &format!("{path}.{k}"), errors),
                None if schema.get("additionalProperties") == Some(&Value::Bool(false)) => {
                    errors.push(format!("{path}: key '{k}' is not in the schema"));
                }
                None => {}
            }
        }
    }
    if let (Some(items), Some(arr)) = (schema.get("items"), v.as_array()) {
        for (i, x) in arr.iter().enumerate() {
            validate(root, items, x, &format!("{path}[{i}]"), errors);
        }
    }
}

pub fn errors(schema: &Value, v: &Value) -> Vec<String> {
    let mut e = Vec::new();
    validate(schema, schema, v, "$", &mut e);
    e
}

#[test]
fn the_validator_accepts_and_rejects_what_it_should() {
    let schema = json!({
        "$defs": { "pos": { "type": "number", "minimum": 0 } },
        "type": "object",
        "required": ["a", "b"],
        "additionalProperties": false,
        "properties": {
            "a": { "$ref": "#/$defs/pos" },
            "b": { "type": "array", "items": { "enum": ["x", "y"] } },
            "c": { "anyOf": [{ "type": "null" }, { "type": "string" }] },
            "v": { "const": 1 }
        }
    });
    assert!(errors(&schema, &json!({"a": 1.5, "b": ["x"], "c": null, "v": 1})).is_empty());
    for (bad, why) in [
        (json!({"b": []}), "missing required key 'a'"),
        (json!({"a": -1, "b": []}), "below the minimum"),
        (json!({"a": 1, "b": ["z"]}), "not one of"),
        (
            json!({"a": 1, "b": [], "d": 0}),
            "key 'd' is not in the schema",
        ),
        (json!({"a": 1, "b": [], "c": 3}), "matches none of anyOf"),
        (json!({"a": "1", "b": []}), "expected type"),
        (json!({"a": 1, "b": [], "v": 2}), "is not 1"),
    ] {
        let e = errors(&schema, &bad);
        assert!(e.iter().any(|m| m.contains(why)), "{bad}: {e:?}");
    }
}

/// `check --format json` of every kind of scene (model, measured PSD, failing, several
/// roughness files, `--verify`, flags only, one check, layer stacks, sliding friction, the
/// vector rule) against the shipped schema.
#[test]
fn check_json_follows_its_schema() {
    let schema: Value = serde_json::from_str(coatcheck::report::CHECK_SCHEMA).unwrap();
    for args in [
        &["check", "examples/paper-rubber-on-steel.toml"][..],
        &["check", "examples/measured-rolloff.toml"],
        &["check", "examples/waviness-thin-film.toml"],
        &["check", "examples/specs/lining-two-scans.toml"],
        &["check", "examples/height-map-film.toml", "--verify"],
        &[
            "check",
            "examples/paper-rubber-on-steel.toml",
            "--checks",
            "bond-shear",
        ],
        &["check", "examples/specs/paper-film-too-thin.toml"],
        &["check", "examples/rubber-epoxy-primer-steel.toml"],
        &["check", "examples/ptfe-rubber-steel.toml"],
        &["check", "examples/ptfe-rubber-steel-sliding.toml"],
        &[
            "check",
            "examples/rubber-epoxy-primer-steel.toml",
            "--shear-tail",
            "vector",
        ],
        &[
            "check",
            "examples/paper-rubber-on-steel.toml",
            "--friction",
            "0.5",
        ],
        &[
            "check",
            "examples/height-map-film.toml",
            "--shear-tail",
            "vector",
        ],
    ] {
        let mut argv = args.to_vec();
        argv.extend(["--format", "json"]);
        let o = crate::common::run(&argv);
        assert!(o.status.code().is_some_and(|c| c < 2), "{argv:?}: {o:?}");
        let v = crate::common::json(&o);
        let e = errors(&schema, &v);
        assert!(e.is_empty(), "{argv:?}:\n{}", e.join("\n"));
    }
}

/// `materials --format json` follows its schema; every bundled file is an entry with its source,
/// in SI, and the numbers are the library's own.
#[test]
fn materials_json_lists_every_file_with_its_source() {
    let o = crate::common::run(&["materials", "--format", "json"]);
    assert_eq!(o.status.code(), Some(0));
    let v = crate::common::json(&o);
    let schema: Value = serde_json::from_str(coatcheck::report::MATERIALS_SCHEMA).unwrap();
    let e = errors(&schema, &v);
    assert!(e.is_empty(), "{}", e.join("\n"));
    assert_eq!(v["schema_version"], 1);
    let (mats, bonds) = (
        v["materials"].as_array().unwrap(),
        v["bonds"].as_array().unwrap(),
    );
    let files = std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/materials"))
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "toml")
        })
        .count();
    assert_eq!(mats.len() + bonds.len(), files);
    let lib = coatcheck::material::Library::builtin().unwrap();
    for m in mats {
        let name = m["name"].as_str().unwrap();
        let want = lib.material(name).unwrap();
        assert_eq!(m["youngs_modulus_pa"].as_f64(), Some(want.elastic.youngs));
        assert_eq!(m["poisson_ratio"].as_f64(), Some(want.elastic.poisson));
        assert_eq!(m["yield_strength_pa"].as_f64(), want.yield_strength);
        assert!(!m["source"].as_str().unwrap().is_empty(), "{name}");
    }
    for b in bonds {
        let want = lib.bond(b["name"].as_str().unwrap()).unwrap();
        assert_eq!(b["shear_strength_pa"].as_f64(), Some(want.shear_strength));
        assert!(!b["source"].as_str().unwrap().is_empty());
    }
}

/// Every schema shipped in `src/report/schema/` is exported by the library (and so exercised
/// against real output: check and materials above, batch, sweep, verify, psd and response in
/// tests/it/formats.rs),
/// and each is a draft 2020-12 object with an `$id` naming its file.
#[test]
fn every_shipped_schema_is_exported_and_well_formed() {
    use coatcheck::report::{
        BATCH_SCHEMA, CHECK_SCHEMA, MATERIALS_SCHEMA, PSD_SCHEMA, RESPONSE_SCHEMA, SWEEP_SCHEMA,
        VERIFY_SCHEMA,
    };
    let exported = [
        ("check", CHECK_SCHEMA),
        ("batch", BATCH_SCHEMA),
        ("verify", VERIFY_SCHEMA),
        ("psd", PSD_SCHEMA),
        ("response", RESPONSE_SCHEMA),
        ("sweep", SWEEP_SCHEMA),
        ("materials", MATERIALS_SCHEMA),
    ];
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/src/report/schema");
    let mut files: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    let mut want: Vec<String> = exported
        .iter()
        .map(|(n, _)| format!("{n}.schema.json"))
        .collect();
    want.sort();
    assert_eq!(files, want);
    for (name, text) in exported {
        let s: Value = serde_json::from_str(text).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(s["$schema"], "https://json-schema.org/draft/2020-12/schema");
        assert_eq!(s["$id"], format!("coatcheck/{name}.schema.json"));
        assert!(
            s["title"].as_str().is_some_and(|t| t.contains(name)),
            "{name}"
        );
    }
}
