//! The data of the paper's figures, one function per figure, each returning its series.
//!
//! The paper's setting (Sec. III): "rubber" film E_R = 1 MPa, ν_R = 0.5 on "steel" E_S = 1e11 Pa,
//! ν_S = 0.5; rms slope ξ = 1; p0 = 0.1 MPa; film thickness d = 50 µm for Figs. 4, 5, 9, 10;
//! Gaussian spectra (eq. 5) with Q = 0.1 q0; self-affine (eq. 2) with H = 1, q1 = 1e8 1/m.
//! Figs. 6, 7 and 14 use q0 = 1e5 1/m (and d = 10 µm for Figs. 6 and 14); Fig. 12 keeps q0 = 1e5 1/m and
//! varies d. The Gent disc of Fig. 12 is eq. (9): E_eff/E_R ≈ 1 + (R/d)²/8.
//!
//! Equations used (through the engine): C(q) of eqs. (2) and (5), S(q) of eq. (7), G and P of
//! eqs. (B11)–(B12), the rms stresses of eqs. (B8)–(B10), f and g of eq. (B7), E_eff as in
//! notes.md, the distributions of notes.md ("Distributions") and the Gent disc, eq. (9).
//!
//! Every y value comes with its error estimate (kept in [`Series::err`]);
//! a computation that misses its tolerance is an error, not a silent number. `n` sets the number
//! of points per series (reduced resolution for tests). Values are SI; each [`Axis`] names the
//! unit the paper shows and the scale to it (applied only when writing, e.g. by the examples).

use crate::Error;
use crate::contact::{Engine, NormalStress, Request, tau_pdf};
use crate::layer::{Bilayer, Elastic, Stack};
use crate::prec::{Estimate, KERNEL_RTOL, Settings, Termination};
use crate::psd::Spectrum;
use crate::units::{self, Dim};

/// Rubber: E_R = 1 MPa, ν = 0.5.
pub const E_RUBBER: f64 = 1e6;
/// Steel as in the paper: E_S = 1e11 Pa, ν = 0.5.
pub const E_STEEL: f64 = 1e11;
/// Nominal pressure of the paper's calculations, Pa.
pub const P0: f64 = 1e5;
/// Film thickness of Figs. 4, 5, 9, 10, m.
pub const D_FIG4: f64 = 50e-6;
/// Upper cut-off of the self-affine spectra, 1/m.
pub const Q1: f64 = 1e8;
/// ν of a real rubber with bulk modulus 2 GPa (Fig. 5).
pub const NU_COMPRESSIBLE: f64 = 0.49985;

/// One curve: x, y and the absolute error estimate of each y.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub label: String,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub err: Vec<f64>,
}

/// One axis: what it shows, the display unit and whether it is logarithmic. Series values are
/// SI; the value shown is `si / scale` (`scale` = the SI value of one display unit).
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    pub label: &'static str,
    /// Display unit, e.g. "MPa", "1/m", "um"; empty for a pure number.
    pub unit: &'static str,
    pub scale: f64,
    pub log: bool,
}

impl Axis {
    /// An axis shown in `unit` of dimension `dim` (scale from [`units::unit_scale`]).
    fn new(label: &'static str, unit: &'static str, dim: Dim, log: bool) -> Axis {
        let scale = units::unit_scale(unit, dim).expect("a unit known to coatcheck::units");
        Axis {
            label,
            unit,
            scale,
            log,
        }
    }

    /// A pure number.
    fn number(label: &'static str, log: bool) -> Axis {
        Axis::new(label, "", Dim::Dimensionless, log)
    }

    /// "label [unit]", or the label alone for a pure number.
    pub fn title(&self) -> String {
        if self.unit.is_empty() {
            self.label.to_string()
        } else {
            format!("{} [{}]", self.label, self.unit)
        }
    }
}

/// A figure: its axes and its curves.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    pub name: &'static str,
    pub title: &'static str,
    pub x: Axis,
    pub y: Axis,
    pub series: Vec<Series>,
}

/// `n` points logarithmically spaced from a to b (inclusive).
pub fn log_space(a: f64, b: f64, n: usize) -> Vec<f64> {
    let n = n.max(2);
    (0..n)
        .map(|i| a * (b / a).powf(i as f64 / (n - 1) as f64))
        .collect()
}

fn checked(e: Estimate, what: &'static str) -> Result<Estimate, Error> {
    if e.status == Termination::ToleranceNotReached || !e.value.is_finite() {
        return Err(Error::invalid(
            what,
            format!("{} ± {}", e.value, e.err),
            "a converged value",
        ));
    }
    Ok(e)
}

fn series(
    label: &str,
    x: Vec<f64>,
    mut y: impl FnMut(f64) -> Result<Estimate, Error>,
) -> Result<Series, Error> {
    let ys = x.iter().map(|&x| y(x)).collect::<Result<Vec<_>, _>>()?;
    Ok(Series {
        label: label.to_string(),
        y: ys.iter().map(|e| e.value).collect(),
        err: ys.iter().map(|e| e.err).collect(),
        x,
    })
}

fn kernel(v: f64) -> Estimate {
    Estimate::new(v, KERNEL_RTOL * v.abs(), Termination::Converged)
}

/// Rubber film (Poisson ratio `nu`) on the paper's steel.
pub fn rubber_on_steel(nu: f64, d: f64) -> Result<Stack, Error> {
    Stack::new(
        Bilayer::new(Elastic::new(E_RUBBER, nu)?, Elastic::new(E_STEEL, 0.5)?),
        d,
    )
}

/// Self-affine H = 1 from q0 to 1e8 1/m, rms slope 1.
pub fn fractal(q0: f64) -> Result<Spectrum, Error> {
    Spectrum::self_affine(1.0, q0, Q1, None)?.scaled_to_rms_slope(1.0)
}

/// Gaussian band at q0 with Q = 0.1 q0, rms slope 1.
pub fn gaussian(q0: f64) -> Result<Spectrum, Error> {
    Spectrum::gaussian(q0, 0.1 * q0)?.scaled_to_rms_slope(1.0)
}

fn area(spectrum: &Spectrum, stack: &Stack, p0: f64) -> Result<Estimate, Error> {
    let c = Engine::new(spectrum, Settings::default()).evaluate(stack, p0, Request::default())?;
    checked(c.area_fraction, "A/A0")
}

fn e_eff(spectrum: &Spectrum, stack: &Stack) -> Result<Estimate, Error> {
    let request = Request {
        e_eff: true,
        ..Default::default()
    };
    let c = Engine::new(spectrum, Settings::default()).evaluate(stack, P0, request)?;
    checked(c.e_eff_over_e_film.expect("requested"), "E_eff/E_R")
}

/// Fig. 4: A/A0 against q0 (1e1 … 1e7 1/m) for the fractal and the Gaussian spectra, d = 50 µm,
/// with the homogeneous rubber and steel values as two flat reference lines.
pub fn fig04(n: usize) -> Result<Figure, Error> {
    let q0 = log_space(1e1, 1e7, n);
    let stack = rubber_on_steel(0.5, D_FIG4)?;
    let homogeneous = |e: f64| -> Result<Series, Error> {
        let s = Stack::new(
            Bilayer::new(Elastic::new(e, 0.5)?, Elastic::new(e, 0.5)?),
            1.0,
        )?;
        let label = if e == E_RUBBER { "rubber" } else { "steel" };
        series(label, q0.clone(), |q| area(&fractal(q)?, &s, P0))
    };
    Ok(Figure {
        name: "fig04",
        title: "Fig. 4: contact area against q0 (d = 50 um, p0 = 0.1 MPa)",
        x: Axis::new("q0", "1/m", Dim::Length(-1), true),
        y: Axis::number("A/A0", true),
        series: vec![
            series("fractal H = 1", q0.clone(), |q| {
                area(&fractal(q)?, &stack, P0)
            })?,
            series("Gaussian Q = 0.1 q0", q0.clone(), |q| {
                area(&gaussian(q)?, &stack, P0)
            })?,
            homogeneous(E_RUBBER)?,
            homogeneous(E_STEEL)?,
        ],
    })
}

/// Fig. 5: A/A0 against q0 (1e1 … 1e7 1/m, d = 50 µm, fractal) for ν_R = 0.5 and 0.49985.
pub fn fig05(n: usize) -> Result<Figure, Error> {
    let q0 = log_space(1e1, 1e7, n);
    let curve = |nu: f64, label: &str| {
        let stack = rubber_on_steel(nu, D_FIG4)?;
        series(label, q0.clone(), |q| area(&fractal(q)?, &stack, P0))
    };
    Ok(Figure {
        name: "fig05",
        title: "Fig. 5: contact area, incompressible and real rubber (d = 50 um)",
        x: Axis::new("q0", "1/m", Dim::Length(-1), true),
        y: Axis::number("A/A0", true),
        series: vec![
            curve(0.5, "nu = 0.5")?,
            curve(NU_COMPRESSIBLE, "nu = 0.49985")?,
        ],
    })
}

/// Stress range of Fig. 6, Pa: to 5 MPa, where the top distribution's tail is below 1e-7.
pub const FIG06_MAX_STRESS: f64 = 5e6;
/// Film thickness of Figs. 6 and 14, m.
pub const D_FIG6: f64 = 10e-6;

/// A density evaluated at `x` whose width parameter `w` carries an error: the value, and the
/// first-order error |∂pdf/∂w|·err(w) (central difference, step 1e-4 w: truncation ~1e-8 and
/// rounding ~1e-12 of the derivative) plus 16 ulps of rounding in the density itself.
fn density(x: f64, w: Estimate, pdf: impl Fn(f64, f64) -> f64) -> Estimate {
    let v = pdf(x, w.value);
    let h = 1e-4 * w.value;
    let dv_dw = (pdf(x, w.value + h) - pdf(x, w.value - h)) / (2.0 * h);
    Estimate::new(
        v,
        dv_dw.abs() * w.err + 16.0 * f64::EPSILON * v.abs(),
        w.status,
    )
}

/// Fig. 6: the distributions of the normal stress at the top surface (Persson's form with
/// G(q1), i.e. width √(2 G(q1))) and at the interface (same form, width σ_rms(d)), and of the
/// interface shear stress (half-normal, width τ_rms), all normalised on [0, ∞) (notes.md,
/// "Distributions"); fractal q0 = 1e5 1/m, d = 10 µm, p0 = 0.1 MPa; σ from 0 to 5 MPa.
pub fn fig06(n: usize) -> Result<Figure, Error> {
    let c = Engine::new(&fractal(1e5)?, Settings::default()).evaluate(
        &rubber_on_steel(0.5, D_FIG6)?,
        P0,
        Request {
            sigma_interface: true,
            tau_interface: true,
            ..Default::default()
        },
    )?;
    let g1 = checked(c.g1, "G(q1)")?;
    // 4G = 2 w²: w = √(2G), dw/dG = 1/(2w).
    let top = g1.map(|g| (2.0 * g).sqrt(), |g| 0.5 / (2.0 * g).sqrt());
    let interface = checked(c.sigma_rms_interface.expect("requested"), "sigma_rms(d)")?;
    let tau = checked(c.tau_rms_interface.expect("requested"), "tau_rms(d)")?;
    let x: Vec<f64> = (0..n.max(2))
        .map(|i| FIG06_MAX_STRESS * i as f64 / (n.max(2) - 1) as f64)
        .collect();
    let normal = |s: f64, w: f64| {
        NormalStress {
            p0: P0,
            sigma_rms: w,
        }
        .pdf(s)
    };
    Ok(Figure {
        name: "fig06",
        title: "Fig. 6: stress distributions (q0 = 1e5 1/m, d = 10 um, p0 = 0.1 MPa)",
        x: Axis::new("stress", "MPa", Dim::Pressure, false),
        y: Axis {
            label: "P",
            unit: "1/MPa",
            scale: 1.0 / units::unit_scale("MPa", Dim::Pressure).expect("a known unit"),
            log: false,
        },
        series: vec![
            series("sigma top (z = 0)", x.clone(), |s| {
                Ok(density(s, top, normal))
            })?,
            series("sigma interface (z = d)", x.clone(), |s| {
                Ok(density(s, interface, normal))
            })?,
            series("tau interface (z = d)", x, |t| {
                Ok(density(t, tau, |t, w| tau_pdf(w, t)))
            })?,
        ],
    })
}

/// Fig. 7: σ_rms at the top surface and of the interface normal and shear stress against d
/// (fractal, q0 = 1e5 1/m, p0 = 0.1 MPa), d from 0.1 µm to 1 mm. One engine serves every d.
pub fn fig07(n: usize) -> Result<Figure, Error> {
    let engine = Engine::new(&fractal(1e5)?, Settings::default());
    let d = log_space(1e-7, 1e-3, n);
    let contacts = d
        .iter()
        .map(|&d| engine.evaluate(&rubber_on_steel(0.5, d)?, P0, Request::all()))
        .collect::<Result<Vec<_>, _>>()?;
    let pick = |label: &str, f: &dyn Fn(&crate::contact::Contact) -> Option<Estimate>| {
        let mut i = 0;
        series(label, d.clone(), |_| {
            let c = &contacts[i];
            i += 1;
            checked(f(c).expect("requested"), "rms stress")
        })
    };
    Ok(Figure {
        name: "fig07",
        title: "Fig. 7: rms stresses against film thickness (q0 = 1e5 1/m, p0 = 0.1 MPa)",
        x: Axis::new("d", "um", Dim::Length(1), true),
        y: Axis::new("rms stress", "MPa", Dim::Pressure, true),
        series: vec![
            pick("sigma top (z = 0)", &|c| c.sigma_rms_top)?,
            pick("sigma interface (z = d)", &|c| c.sigma_rms_interface)?,
            pick("tau interface (z = d)", &|c| c.tau_rms_interface)?,
        ],
    })
}

/// Fig. 9: A/A0 against p0 (1e3 … 1e8 Pa) for the fractal surfaces with q0 = 1e4 and 3e3 1/m,
/// d = 50 µm.
pub fn fig09(n: usize) -> Result<Figure, Error> {
    let p0 = log_space(1e3, 1e8, n);
    let stack = rubber_on_steel(0.5, D_FIG4)?;
    let curve = |q0: f64, label: &str| {
        let engine = Engine::new(&fractal(q0)?, Settings::default());
        series(label, p0.clone(), |p| {
            checked(
                engine
                    .evaluate(&stack, p, Request::default())?
                    .area_fraction,
                "A/A0",
            )
        })
    };
    Ok(Figure {
        name: "fig09",
        title: "Fig. 9: contact area against nominal pressure (d = 50 um)",
        x: Axis::new("p0", "MPa", Dim::Pressure, true),
        y: Axis::number("A/A0", true),
        series: vec![curve(1e4, "q0 = 1e4 1/m")?, curve(3e3, "q0 = 3e3 1/m")?],
    })
}

/// Fig. 10: E_eff/E_R against q0 d for the fractal spectra (q0 varied at d = 50 µm).
pub fn fig10(n: usize) -> Result<Figure, Error> {
    let x = log_space(1e-4, 1e2, n);
    let stack = rubber_on_steel(0.5, D_FIG4)?;
    Ok(Figure {
        name: "fig10",
        title: "Fig. 10: effective modulus against q0 d (fractal, d = 50 um)",
        x: Axis::number("q0 d", true),
        y: Axis::number("E_eff / E_R", true),
        series: vec![series("fractal H = 1", x, |qd| {
            e_eff(&fractal(qd / D_FIG4)?, &stack)
        })?],
    })
}

/// Fig. 12: E_eff/E_R for the Gaussian spectrum (q0 = 1e5 1/m, d varied) against q0 d, and the
/// Gent disc, eq. (9), 1 + (R/d)²/8, against d/R.
pub fn fig12(n: usize) -> Result<Figure, Error> {
    let x = log_space(1e-3, 1e2, n);
    let q0 = 1e5;
    let engine = Engine::new(&gaussian(q0)?, Settings::default());
    let request = Request {
        e_eff: true,
        ..Default::default()
    };
    Ok(Figure {
        name: "fig12",
        title: "Fig. 12: effective modulus, Gaussian roughness and the Gent disc (eq. 9)",
        x: Axis::number("q0 d (Gaussian), d/R (disc)", true),
        y: Axis::number("E_eff / E_R", true),
        series: vec![
            series("Gaussian, q0 = 1e5 1/m", x.clone(), |qd| {
                let c = engine.evaluate(&rubber_on_steel(0.5, qd / q0)?, P0, request)?;
                checked(c.e_eff_over_e_film.expect("requested"), "E_eff/E_R")
            })?,
            series("Gent disc, eq. (9)", x, |dr| {
                Ok(Estimate::exact(1.0 + 0.125 / (dr * dr)))
            })?,
        ],
    })
}

/// Fig. 14: f(qd) and g(qd) against q for d = 10 µm, q from q0 = 1e5 to 1e8 1/m.
pub fn fig14(n: usize) -> Result<Figure, Error> {
    let d = D_FIG6;
    let layers = rubber_on_steel(0.5, d)?.layers;
    let q = log_space(1e5, 1e8, n);
    Ok(Figure {
        name: "fig14",
        title: "Fig. 14: interface stress kernels f and g (d = 10 um, rubber on steel)",
        x: Axis::new("q", "1/m", Dim::Length(-1), true),
        y: Axis::number("f, g", false),
        series: vec![
            series("f (normal)", q.clone(), |q| {
                Ok(kernel(layers.response(q * d).f))
            })?,
            series("g (shear)", q, |q| Ok(kernel(layers.response(q * d).g)))?,
        ],
    })
}

/// Bond shear strength marked on the sliding figure (the paper's epoxy), Pa.
pub const BOND_SLIDING_FIG: f64 = 10e6;

/// Not in the paper (which stops at static contact): the peak interface shear |τ| at exceedance
/// 1e-6 against d under sliding friction μ = 0, 0.5, 1 (vector rule, [`crate::tail`]; the
/// uncoupled approximation of [`crate::contact`]'s sliding module), Fig. 7's setting, with the
/// bond strength marked. One engine serves every d and μ.
pub fn sliding(n: usize) -> Result<Figure, Error> {
    let engine = Engine::new(&fractal(1e5)?, Settings::default());
    let d = log_space(1e-7, 1e-3, n);
    let mut series_all = Vec::new();
    for mu in [0.0, 0.5, 1.0] {
        let label = format!("mu = {mu}");
        series_all.push(series(&label, d.clone(), |d| {
            let (_, s) = engine.evaluate_sliding(
                &rubber_on_steel(0.5, d)?,
                P0,
                mu,
                Request {
                    tau_interface: true,
                    ..Request::default()
                },
            )?;
            let s = s.expect("shear requested");
            let v =
                crate::tail::ShearVector::new(s.mean.value, s.tau_x_rms.value, s.tau_y_rms.value)?;
            let mut peak = v.peak(crate::prec::DEFAULT_EPSILON)?;
            peak.err += s.tau_x_rms.rel_err().max(s.tau_y_rms.rel_err()) * peak.value;
            checked(peak, "peak interface shear")
        })?);
    }
    series_all.push(series("bond strength (epoxy)", d.clone(), |_| {
        Ok(Estimate::exact(BOND_SLIDING_FIG))
    })?);
    Ok(Figure {
        name: "sliding",
        title: "Sliding: peak interface shear |tau| (eps = 1e-6) against film thickness (q0 = 1e5 1/m, p0 = 0.1 MPa)",
        x: Axis::new("d", "um", Dim::Length(1), true),
        y: Axis::new("peak |tau|", "MPa", Dim::Pressure, true),
        series: series_all,
    })
}
