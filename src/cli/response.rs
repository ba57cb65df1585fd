//! `coatcheck response`: S(qd), f(qd), g(qd) for a film on a substrate (the paper's Fig. 14 as
//! numbers), and beside them the tangential-load kernels g_t, f_t, h
//! ([`coatcheck::layer::tangential`]); or S(q) and f_k(q), g_k(q) at every interface of a layer
//! stack (`--layer`, in [`super::response_stack`]).

use clap::{Args, ValueEnum};
use coatcheck::Error;
use coatcheck::layer::tangential::{TANGENTIAL_RTOL, TangentialResponse};
use coatcheck::layer::{Bilayer, Elastic, Response};
use coatcheck::prec::{KERNEL_RTOL, SMALLEST_SUBNORMAL};
use coatcheck::units::{Dim, parse_quantity};

#[derive(Clone, Copy, ValueEnum)]
pub enum Format {
    Table,
    Csv,
    Json,
}

#[derive(Args)]
pub struct ResponseArgs {
    /// Film: Young's modulus and Poisson ratio, e.g. `1MPa,0.5`.
    #[arg(long, required_unless_present = "layer", conflicts_with = "layer")]
    film: Option<String>,
    /// A layer of a stack, top first: Young's modulus, Poisson ratio and thickness, e.g.
    /// `1MPa,0.5,10um` (repeat for each layer, 1 to 10).
    #[arg(long, conflicts_with = "qd")]
    pub(super) layer: Vec<String>,
    /// Substrate: Young's modulus and Poisson ratio, e.g. `200GPa,0.3`.
    #[arg(long)]
    pub(super) substrate: String,
    /// q·d values: a list `0.1,1,10` or a log-spaced range `from:to:n`.
    #[arg(long, required_unless_present_any = ["q", "layer"], conflicts_with = "q")]
    qd: Option<String>,
    /// Wavenumbers q (1/m) for a stack: a list `1e5,1e6` or a log-spaced range `from:to:n`.
    #[arg(long, conflicts_with = "film")]
    pub(super) q: Option<String>,
    #[arg(long, value_enum, default_value = "table")]
    pub(super) format: Format,
}

pub(super) fn elastic(flag: &'static str, text: &str) -> Result<Elastic, Error> {
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() != 2 {
        return Err(Error::invalid(flag, text, "E,nu (e.g. 1MPa,0.5)"));
    }
    let e = parse_quantity(parts[0], Dim::Pressure)
        .map_err(|err| Error::invalid(flag, err, "a Young's modulus such as 1MPa"))?;
    let nu = parse_quantity(parts[1], Dim::Dimensionless)
        .map_err(|err| Error::invalid(flag, err, "a Poisson ratio in [0, 0.5]"))?;
    Elastic::new(e, nu)
}

/// The largest q·d: the kernels are exact to rounding up to it (S → 1, f and g decay as
/// e^(−qd) and are far below the smallest normal number beyond a few hundred).
const QD_MAX: f64 = 1e6;

/// The most points: a million rows of table, CSV or JSON (some 100 MB), computed in seconds.
const MAX_POINTS: usize = 1_000_000;

/// Parse `a,b,c` or `from:to:n` (n log-spaced points, 2 <= n <= 1e6), each q·d within
/// [0, 1e6].
pub fn parse_grid(flag: &'static str, text: &str) -> Result<Vec<f64>, Error> {
    parse_values(flag, text, QD_MAX, "a value from 0 to 1e6")
}

/// [`parse_grid`] with values within [0, max] (`range` says so in the error).
pub(super) fn parse_values(
    flag: &'static str,
    text: &str,
    max: f64,
    range: &'static str,
) -> Result<Vec<f64>, Error> {
    let num = |s: &str| -> Result<f64, Error> {
        let v: f64 = s
            .trim()
            .parse()
            .map_err(|_| Error::invalid(flag, s, "a number"))?;
        if (0.0..=max).contains(&v) {
            Ok(v)
        } else {
            Err(Error::invalid(flag, s, range))
        }
    };
    let parts: Vec<&str> = text.split(':').collect();
    match parts.as_slice() {
        [from, to, n] => {
            let (a, b) = (num(from)?, num(to)?);
            let n: usize = n
                .trim()
                .parse()
                .map_err(|_| Error::invalid(flag, n, "a whole number of points >= 2"))?;
            if !(2..=MAX_POINTS).contains(&n) || a <= 0.0 || b <= a {
                return Err(Error::invalid(
                    flag,
                    text,
                    "from:to:n with 0 < from < to and 2 <= n <= 1000000",
                ));
            }
            Ok((0..n)
                .map(|i| a * (b / a).powf(i as f64 / (n - 1) as f64))
                .collect())
        }
        [list] if list.split(',').count() <= MAX_POINTS => list.split(',').map(num).collect(),
        [_] => Err(Error::invalid(flag, text, "at most 1000000 values")),
        _ => Err(Error::invalid(
            flag,
            text,
            "a list a,b,c or a range from:to:n",
        )),
    }
}

/// The error estimate of a kernel value (absolute): relative [`KERNEL_RTOL`], plus the
/// smallest subnormal for a value below f64's normal range (f and g above q·d ≈ 700 round into
/// the subnormals, and to 0 beyond them).
fn err(v: f64) -> f64 {
    KERNEL_RTOL * v.abs() + flush(v)
}

/// The rounding of a value below the normal range (into the subnormals, or to 0), as the whole
/// smallest subnormal.
pub(super) fn flush(v: f64) -> f64 {
    if v.abs() < f64::MIN_POSITIVE {
        SMALLEST_SUBNORMAL
    } else {
        0.0
    }
}

/// The error estimates of g_t, f_t, h (absolute): relative [`TANGENTIAL_RTOL`], for g_t
/// absolute in units of e^{−qd}/100 where it is smaller than that (near its zero), plus the
/// flush below the normal range.
fn tangential_err(x: f64, t: &TangentialResponse) -> [f64; 3] {
    let floor = 0.01 * (-x).exp();
    [
        TANGENTIAL_RTOL * t.g_t.abs().max(floor) + flush(t.g_t),
        TANGENTIAL_RTOL * t.f_t.abs() + flush(t.f_t),
        TANGENTIAL_RTOL * t.h.abs() + flush(t.h),
    ]
}

pub fn run(args: ResponseArgs) -> Result<i32, Error> {
    let (Some(film), Some(qd)) = (&args.film, &args.qd) else {
        return super::response_stack::run(&args);
    };
    let pair = Bilayer::new(
        elastic("--film", film)?,
        elastic("--substrate", &args.substrate)?,
    );
    let qd = parse_grid("--qd", qd)?;
    let rows: Vec<(f64, Response, TangentialResponse)> = qd
        .iter()
        .map(|&x| (x, pair.response(x), pair.tangential(x)))
        .collect();
    let text = match args.format {
        Format::Table => {
            let mut t = coatcheck::report::table(&["q·d", "S", "f", "g", "g_t", "f_t", "h"]);
            for (x, r, tg) in &rows {
                t.add_row([
                    format!("{x:.4e}"),
                    format!("{:.10e}", r.s),
                    format!("{:.10e}", r.f),
                    format!("{:.10e}", r.g),
                    format!("{:.10e}", tg.g_t),
                    format!("{:.10e}", tg.f_t),
                    format!("{:.10e}", tg.h),
                ]);
            }
            let note = coatcheck::report::wrap(&format!(
                "error estimate: relative {KERNEL_RTOL:e} for each of S, f, g, plus 5e-324 \
                 below 2.2e-308 (the bound verified against a 100-digit solution over qd \
                 1e-8..1e4, E0/E1 1e-8..1e8, nu 0..0.5); relative {TANGENTIAL_RTOL:e} for g_t, \
                 f_t, h (for g_t near its zero absolute, {TANGENTIAL_RTOL:e} e^-qd/100)"
            ));
            format!("{t}\n{note}\n")
        }
        Format::Csv => csv(&rows),
        Format::Json => {
            // JSON shows NaN as null: the CSV of the same numbers is checked instead.
            coatcheck::report::finite_only(&csv(&rows))?;
            let v: Vec<serde_json::Value> = rows
                .iter()
                .map(|(x, r, tg)| {
                    let [gt_err, ft_err, h_err] = tangential_err(*x, tg);
                    serde_json::json!({
                        "qd": x, "S": r.s, "S_err": err(r.s), "f": r.f, "f_err": err(r.f),
                        "g": r.g, "g_err": err(r.g), "g_t": tg.g_t, "g_t_err": gt_err,
                        "f_t": tg.f_t, "f_t_err": ft_err, "h": tg.h, "h_err": h_err,
                    })
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

/// The kernels at the q·d values as CSV, with their error estimates.
fn csv(rows: &[(f64, Response, TangentialResponse)]) -> String {
    let mut text = String::from("qd,S,S_err,f,f_err,g,g_err,g_t,g_t_err,f_t,f_t_err,h,h_err\n");
    for (x, r, tg) in rows {
        let [gt_err, ft_err, h_err] = tangential_err(*x, tg);
        text += &format!(
            "{x:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e}\n",
            r.s,
            err(r.s),
            r.f,
            err(r.f),
            r.g,
            err(r.g),
            tg.g_t,
            gt_err,
            tg.f_t,
            ft_err,
            tg.h,
            h_err
        );
    }
    text
}
