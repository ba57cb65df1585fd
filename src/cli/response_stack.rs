//! `coatcheck response --layer E,nu,d [--layer …] --substrate E,nu --q …`: S(q) and, at every
//! interface k (top first), f_k(q) and g_k(q) of a layer stack ([`coatcheck::layer::stack`]).

use super::response::{Format, ResponseArgs, elastic, flush, parse_values};
use coatcheck::Error;
use coatcheck::layer::stack::{Layer, STACK_RTOL, Stack, StackResponse};
use coatcheck::units::{Dim, parse_quantity};
use comfy_table::{Table, presets::UTF8_FULL};

/// The largest q (1/m): beyond q·z ≈ 745 the interface kernels underflow and S is 1, so any
/// larger q only repeats those values; 1e15 1/m is far beyond any roughness spectrum.
const Q_MAX: f64 = 1e15;

/// One `--layer E,nu,d`.
pub(super) fn layer(text: &str) -> Result<Layer, Error> {
    let parts: Vec<&str> = text.split(',').collect();
    let [e, nu, d] = parts.as_slice() else {
        return Err(Error::invalid(
            "--layer",
            text,
            "E,nu,d (e.g. 1MPa,0.5,10um)",
        ));
    };
    let material = elastic("--layer", &format!("{e},{nu}"))?;
    let thickness = parse_quantity(d, Dim::Length(1))
        .map_err(|err| Error::invalid("--layer", err, "a thickness such as 10um"))?;
    Ok(Layer {
        material,
        thickness,
    })
}

/// The error estimate of a kernel value (absolute): relative [`STACK_RTOL`], plus the smallest
/// subnormal for a value below f64's normal range (f_k and g_k round into the subnormals above
/// q·z_k ≈ 700, and to 0 beyond them), as for the film's kernels.
fn err(v: f64) -> f64 {
    STACK_RTOL * v.abs() + flush(v)
}

/// Column names: q, S, then f1, g1, f2, g2, ….
fn columns(n: usize) -> Vec<String> {
    let mut c = vec!["q".to_string(), "S".to_string()];
    for k in 1..=n {
        c.push(format!("f{k}"));
        c.push(format!("g{k}"));
    }
    c
}

/// S, f1, g1, f2, g2, … of one row.
fn values(r: &StackResponse) -> Vec<f64> {
    std::iter::once(r.s)
        .chain(r.interfaces.iter().flat_map(|&(f, g)| [f, g]))
        .collect()
}

pub fn run(args: &ResponseArgs) -> Result<i32, Error> {
    let layers = args
        .layer
        .iter()
        .map(|l| layer(l))
        .collect::<Result<Vec<_>, _>>()?;
    let stack = Stack::new(layers, elastic("--substrate", &args.substrate)?)?;
    let Some(q_text) = args.q.as_deref() else {
        return Err(Error::invalid("--q", "missing", "--q Q1,Q2,… with --layer"));
    };
    let qs = parse_values("--q", q_text, Q_MAX, "a wavenumber from 0 to 1e15 1/m")?;
    let rows: Vec<(f64, Vec<f64>)> = qs
        .iter()
        .map(|&q| (q, values(&stack.response(q))))
        .collect();
    let names = columns(stack.layers().len());
    let text = match args.format {
        Format::Table => {
            let mut t = Table::new();
            let mut header = names.clone();
            header[0] = "q (1/m)".into();
            t.load_preset(UTF8_FULL).set_header(header);
            for (q, v) in &rows {
                let cells = std::iter::once(format!("{q:.4e}"))
                    .chain(v.iter().map(|x| format!("{x:.10e}")));
                t.add_row(cells.collect::<Vec<_>>());
            }
            let depths: Vec<String> = stack
                .depths()
                .iter()
                .enumerate()
                .map(|(k, z)| format!("z{} = {z:e} m", k + 1))
                .collect();
            format!(
                "{t}\ninterfaces (below layer k): {}\nerror estimate: relative {STACK_RTOL:e} \
                 for each of S, f_k, g_k where |value| >= 1e-30 (the bound verified against a \
                 120-digit solution for 1 to 10 layers, q·z 1e-8..1e4, neighbour modulus ratios \
                 1e-8..1e8, nu 0..0.5)\n",
                depths.join(", ")
            )
        }
        Format::Csv => {
            let mut text = names[0].clone();
            for n in &names[1..] {
                text += &format!(",{n},{n}_err");
            }
            text.push('\n');
            for (q, v) in &rows {
                text += &format!("{q:e}");
                for x in v {
                    text += &format!(",{x:e},{:e}", err(*x));
                }
                text.push('\n');
            }
            text
        }
        Format::Json => {
            let v: Vec<serde_json::Value> = rows
                .iter()
                .map(|(q, v)| {
                    let mut row = serde_json::Map::new();
                    row.insert("q".into(), (*q).into());
                    for (n, x) in names[1..].iter().zip(v) {
                        row.insert(n.clone(), (*x).into());
                        row.insert(format!("{n}_err"), err(*x).into());
                    }
                    serde_json::Value::Object(row)
                })
                .collect();
            format!(
                "{}\n",
                serde_json::to_string_pretty(&v).expect("plain numbers serialise")
            )
        }
    };
    coatcheck::report::stdout(&text)?;
    Ok(0)
}
