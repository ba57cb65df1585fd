//! `coatcheck response --layer E,nu,d [--layer …] --substrate E,nu --q …`: S(q) and, at every
//! interface k (top first), f_k(q) and g_k(q) of a layer stack ([`coatcheck::layer::stack`]),
//! then at every interface the tangential-load kernels g_t,k, f_t,k, h_k.

use super::response::{Format, ResponseArgs, elastic, flush, parse_values};
use coatcheck::Error;
use coatcheck::layer::stack::{InterfaceShear, Layer, STACK_RTOL, Stack, StackResponse};
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

/// The error estimates of g_t,k, f_t,k, h_k (absolute): as [`err`], with g_t,k's taken
/// relative to max(|g_t,k|, h_k/100) (absolute near its zeros, the bound the tests verify).
fn tangential_err(t: &InterfaceShear) -> [f64; 3] {
    [
        STACK_RTOL * t.g_t.abs().max(0.01 * t.h) + flush(t.g_t),
        err(t.f_t),
        err(t.h),
    ]
}

/// Column names: q, S, then f1, g1, f2, g2, …, then g_t1, f_t1, h1, g_t2, ….
fn columns(n: usize) -> Vec<String> {
    let mut c = vec!["q".to_string(), "S".to_string()];
    for k in 1..=n {
        c.push(format!("f{k}"));
        c.push(format!("g{k}"));
    }
    for k in 1..=n {
        c.extend([format!("g_t{k}"), format!("f_t{k}"), format!("h{k}")]);
    }
    c
}

/// S, f1, g1, f2, g2, …, g_t1, f_t1, h1, … of one row, each with its error estimate.
fn values(r: &StackResponse, t: &[InterfaceShear]) -> Vec<(f64, f64)> {
    let normal = std::iter::once(r.s)
        .chain(r.interfaces.iter().flat_map(|&(f, g)| [f, g]))
        .map(|v| (v, err(v)));
    let tangential = t.iter().flat_map(|t| {
        let e = tangential_err(t);
        [(t.g_t, e[0]), (t.f_t, e[1]), (t.h, e[2])]
    });
    normal.chain(tangential).collect()
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
    let rows: Vec<(f64, Vec<(f64, f64)>)> = qs
        .iter()
        .map(|&q| (q, values(&stack.response(q), &stack.tangential(q))))
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
                    .chain(v.iter().map(|(x, _)| format!("{x:.10e}")));
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
                 1e-8..1e8, nu 0..0.5), and for g_t,k, f_t,k, h_k (for g_t,k near its zeros \
                 absolute, {STACK_RTOL:e} h_k/100)\n",
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
                for (x, e) in v {
                    text += &format!(",{x:e},{e:e}");
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
                    for (n, (x, e)) in names[1..].iter().zip(v) {
                        row.insert(n.clone(), (*x).into());
                        row.insert(format!("{n}_err"), (*e).into());
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
