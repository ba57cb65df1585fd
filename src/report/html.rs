//! The qualification report as one self-contained HTML page: verdict and governing check first,
//! then the checks, what to change when one fails, the inputs with their sources, the plots
//! (inline SVG from [`crate::report::plot`]), the warnings and the uncertainty. No script, no network,
//! no font files: the page prints as it shows. Batches: a summary table, then a section per
//! scene.
//!
//! Plots (SI inside, shown in the units of the tables):
//! - the spectrum C(q) with the band used and the lowest octave [q_L, 2 q_L] shaded;
//! - the interface shear and normal-stress exceedance P(|τ| > t), P(σ > s) (notes.md,
//!   "Distributions"), with ε and the limits marked;
//! - under the vector rule (sliding friction) the shear's exceedance and density for the vector
//!   (μp0 + X, Y), with the bond strength marked (`html/sliding.rs`);
//! - utilisation (value/limit) of each stress check against thickness, with the limit 1, d_min and
//!   the design thickness marked.

use crate::Error;
use crate::batch::SceneRun;
use crate::check::levers::{Lever, SPAN};
use crate::check::{CheckKind, Checker, Outcome, log_space};
use crate::contact::{NormalStress, tau_exceedance};
use crate::figures::{Axis, Figure, Series};
use crate::pipeline::{Judged, Verdict};
use crate::psd::Spectrum;
use crate::report::plot::{Band, Extras, Legend, Marker, svg};

mod exact;
mod sliding;

/// Points per plotted curve.
const POINTS: usize = 121;

/// A figure ready for the page: caption and SVG text.
#[derive(Debug, Clone, PartialEq)]
pub struct Plot {
    pub caption: String,
    pub svg: String,
}

/// What one scene's section shows. Rows are (label, value) pairs already formatted for people.
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    /// The scene's name (its file, or "scene").
    pub title: String,
    pub pass: bool,
    /// "governing check: … (utilisation …)" or the error of a scene that could not be judged.
    pub headline: String,
    /// Check rows: check, value, limit, utilisation, margin, result.
    pub checks: Vec<[String; 6]>,
    /// What alone would make each failing check pass.
    pub levers: Vec<String>,
    pub inputs: Vec<(String, String)>,
    pub results: Vec<(String, String)>,
    /// A layer stack's interfaces, top first: the layer above, depth, σ_rms, τ_rms, τ_peak,
    /// σ_peak, P(|τ| > bond) (empty for a film).
    pub interfaces: Vec<[String; 7]>,
    /// Persson against exact rows (quantity, Persson, exact), when the exact check ran.
    pub exact: Vec<[String; 3]>,
    pub plots: Vec<Plot>,
    pub warnings: Vec<String>,
    pub uncertainty: Vec<String>,
}

/// Who made the page and how.
#[derive(Debug, Clone, PartialEq)]
pub struct Meta {
    pub version: String,
    /// UTC date, YYYY-MM-DD.
    pub date: String,
    pub command_line: String,
}

/// Today's UTC date (YYYY-MM-DD) from the system clock (civil date from days since 1970).
pub fn utc_date() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    civil_date(secs / 86_400)
}

/// The proleptic Gregorian date of day `days` after 1970-01-01.
fn civil_date(days: u64) -> String {
    let z = days as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y:04}-{m:02}-{d:02}")
}

/// Text made safe for HTML element content and attribute values.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

fn axis(label: &'static str, unit: &'static str, scale: f64, log: bool) -> Axis {
    Axis {
        label,
        unit,
        scale,
        log,
    }
}

fn curve(label: &str, x: Vec<f64>, y: Vec<f64>) -> Series {
    let err = vec![0.0; x.len()];
    Series {
        label: label.to_string(),
        x,
        y,
        err,
    }
}

fn marker(at: f64, vertical: bool, label: String) -> Marker {
    Marker {
        at,
        vertical,
        label,
    }
}

/// The spectrum C(q) with the band used and the lowest octave shaded.
pub fn spectrum_plot(spectrum: &Spectrum) -> Result<Plot, Error> {
    let (lo, hi) = spectrum.support();
    let q = log_space(lo, hi, POINTS);
    let c = q.iter().map(|&q| spectrum.c(q)).collect();
    let fig = Figure {
        name: "psd",
        title: "Roughness power spectrum",
        x: axis("wavenumber q", "1/m", 1.0, true),
        y: axis("C(q)", "µm^4", 1e-24, true),
        series: vec![curve("C(q)", q, c)],
    };
    let extras = Extras {
        log_decades: f64::INFINITY,
        bands: vec![
            Band {
                from: lo,
                to: hi,
                label: "band used".into(),
            },
            Band {
                from: lo,
                to: (2.0 * lo).min(hi),
                label: "lowest octave".into(),
            },
        ],
        ..Extras::default()
    };
    Ok(Plot {
        caption: format!(
            "Power spectrum used, q = {} to {} 1/m; the lowest octave [q_L, 2 q_L] carries the \
             contact of a thin film.",
            sig(lo),
            sig(hi)
        ),
        svg: svg(&fig, &extras)?,
    })
}

/// Exceedance curves of the interface shear and normal stress, with ε and the limits marked;
/// under the vector rule the shear's are the vector's (`html/sliding.rs`), with its density.
pub fn stress_plots(checker: &Checker, outcome: &Outcome) -> Result<Vec<Plot>, Error> {
    let design = checker.design();
    let eps = design.criteria.epsilon;
    let ev = &outcome.evaluation;
    let c = &ev.contact;
    let mut plots = Vec::new();
    let limit_of = |kind| {
        outcome
            .checks
            .iter()
            .find(|ch| ch.kind == kind)
            .and_then(|ch| ch.limit)
    };
    if let (Some(s), Some(peak)) = (&ev.sliding, ev.tau_peak) {
        let limit = limit_of(CheckKind::BondShear);
        plots.extend(sliding::shear_plots(
            s,
            eps,
            peak.value,
            limit,
            design.bond_strength,
        )?);
    } else if let (Some(rms), Some(peak)) = (c.tau_rms_interface, ev.tau_peak) {
        let limit = limit_of(CheckKind::BondShear);
        let t = levels(rms.value, peak.value, limit);
        let p = t.iter().map(|&t| tau_exceedance(rms.value, t)).collect();
        let mut markers = vec![
            marker(eps, false, format!("epsilon = {}", sig(eps))),
            marker(
                peak.value,
                true,
                format!("tau_peak {} MPa", mpa(peak.value)),
            ),
        ];
        if let Some(l) = limit {
            markers.push(marker(l, true, format!("limit {} MPa", mpa(l))));
        }
        plots.push(exceedance_plot(
            "Interface shear: fraction of the interface where |tau| exceeds t",
            "shear level t",
            "P(|tau| > t)",
            curve("Persson, half-normal", t, p),
            markers,
            "The level exceeded on a fraction epsilon of the interface is the peak shear; \
             it is compared with the bond strength over the safety factor.",
        )?);
    }
    if let (Some(rms), Some(peak)) = (c.sigma_rms_interface, ev.sigma_peak_interface) {
        let dist = NormalStress {
            p0: design.pressure,
            sigma_rms: rms.value,
        };
        let limit = limit_of(CheckKind::SubstrateYield);
        let s = levels(rms.value, peak.value, limit);
        let p = s.iter().map(|&s| dist.exceedance(s)).collect();
        let mut markers = vec![
            marker(eps, false, format!("epsilon = {}", sig(eps))),
            marker(
                peak.value,
                true,
                format!("sigma_peak {} MPa", mpa(peak.value)),
            ),
        ];
        if let Some(l) = limit {
            markers.push(marker(l, true, format!("limit {} MPa", mpa(l))));
        }
        plots.push(exceedance_plot(
            "Interface normal stress: fraction where sigma exceeds s",
            "normal stress s",
            "P(sigma > s)",
            curve("Persson", s, p),
            markers,
            "The substrate-yield check takes the larger of this peak and the mean pressure in \
             real contact.",
        )?);
    }
    Ok(plots)
}

/// Stress levels for an exceedance curve: log-spaced from a tenth of the rms to beyond both the
/// peak and the limit.
fn levels(rms: f64, peak: f64, limit: Option<f64>) -> Vec<f64> {
    let hi = 1.5 * peak.max(limit.unwrap_or(0.0));
    log_space(0.1 * rms.min(peak), hi, POINTS)
}

fn exceedance_plot(
    title: &'static str,
    x: &'static str,
    y: &'static str,
    series: Series,
    markers: Vec<Marker>,
    caption: &str,
) -> Result<Plot, Error> {
    let fig = Figure {
        name: "exceedance",
        title,
        x: axis(x, "MPa", 1e6, true),
        y: axis(y, "", 1.0, true),
        series: vec![series],
    };
    let extras = Extras {
        markers,
        legend: Legend::LowerLeft,
        ..Extras::default()
    };
    Ok(Plot {
        caption: caption.to_string(),
        svg: svg(&fig, &extras)?,
    })
}

/// Utilisation of each enabled stress check against thickness, with the limit, d_min and the
/// design thickness marked.
pub fn utilisation_plot(checker: &Checker, outcome: &Outcome) -> Result<Option<Plot>, Error> {
    let d = outcome.thickness;
    let d_min = outcome
        .min_thickness
        .as_ref()
        .and_then(|m| m.thickness.map(|e| e.value));
    let (scan_lo, scan_hi) = checker.scan_range();
    let lo = (d.min(d_min.unwrap_or(d)) / 30.0).max(scan_lo);
    let hi = (d.max(d_min.unwrap_or(d)) * 30.0)
        .min(scan_hi)
        .max(lo * 10.0);
    let ds = log_space(lo, hi, 61);
    let evals = checker.sweep(&ds)?;
    let mut series = Vec::new();
    for kind in [CheckKind::BondShear, CheckKind::SubstrateYield] {
        let (x, y): (Vec<f64>, Vec<f64>) = ds
            .iter()
            .zip(&evals)
            .filter_map(|(&d, ev)| {
                let ch = ev.checks.iter().find(|c| c.kind == kind)?;
                Some((d, ch.value.value / ch.limit?))
            })
            .unzip();
        if !x.is_empty() {
            series.push(curve(kind.name(), x, y));
        }
    }
    if series.is_empty() {
        return Ok(None);
    }
    let mut markers = vec![
        marker(1.0, false, "limit (utilisation 1)".into()),
        marker(d, true, format!("design {} µm", um(d))),
    ];
    if let Some(m) = d_min {
        markers.push(marker(m, true, format!("d_min {} µm", um(m))));
    }
    let fig = Figure {
        name: "utilisation",
        title: "Utilisation (value / limit) against film thickness",
        x: axis("film thickness d", "µm", 1e-6, true),
        y: axis("utilisation", "", 1.0, true),
        series,
    };
    let extras = Extras {
        markers,
        legend: Legend::LowerLeft,
        ..Extras::default()
    };
    Ok(Some(Plot {
        caption: "Above 1 a check fails. d_min is the smallest thickness above which every \
                  check passes at every thickness."
            .into(),
        svg: svg(&fig, &extras)?,
    }))
}

/// The section of one judged scene: its checks with utilisation, what would make a failing
/// design pass, inputs with sources, results, Persson against exact, plots, warnings and the
/// uncertainty. The spectrum and checker are rebuilt from the scene (a few milliseconds).
pub fn section(title: &str, j: &Judged) -> Result<Section, Error> {
    let scene = &j.scene;
    let outcome = match &j.outcome {
        Verdict::Film(o) => o,
        Verdict::Stack(o) => return super::html_stack::section(title, j, o),
    };
    let (spectrum, _) = scene.roughness.spectrum()?;
    let checker = Checker::new(&spectrum, scene.design(), scene.settings)?;
    let checks = super::check::check_rows(outcome);
    let headline = match outcome
        .governing
        .and_then(|g| outcome.checks.iter().find(|c| c.kind == g))
    {
        Some(c) => format!(
            "governing check: {}{}",
            c.kind.name(),
            c.margin
                .map(|m| format!(" (utilisation {:.1} %)", 100.0 * (1.0 - m)))
                .unwrap_or_default()
        ),
        None => "no check enabled".into(),
    };
    let headline = match &j.robust {
        Some(r) => format!(
            "{headline}; robust (worst corner of the materials' ranges): {}",
            if r.pass { "PASS" } else { "FAIL" }
        ),
        None => headline,
    };
    let levers = j.levers.iter().map(lever_text).collect();
    let mut inputs = super::check::scene_rows(scene);
    for (what, source) in [
        (&scene.film.name, &scene.film.source),
        (&scene.substrate.name, &scene.substrate.source),
        (&scene.bond.name, &scene.bond.source),
    ] {
        inputs.push((format!("source of {what}"), source.clone()));
    }
    let results = super::check::result_rows(outcome)
        .into_iter()
        .map(|[k, v, e]| {
            let shown = if e.is_empty() {
                v
            } else {
                format!("{v} ± {e}")
            };
            (k, shown)
        })
        .collect();
    let mut plots = vec![spectrum_plot(&spectrum)?];
    plots.extend(stress_plots(&checker, outcome)?);
    plots.extend(utilisation_plot(&checker, outcome)?);
    let mut exact = Vec::new();
    let c = &outcome.evaluation.contact;
    let (lo, _) = spectrum.support();
    let mut uncertainty = vec![
        format!(
            "Numerical: each result above carries its estimated numerical error (relative              tolerance {}).",
            sig(scene.settings.rtol)
        ),
        format!(
            "Model: {} of the contact stress variance comes from the lowest octave of the \
             spectrum (q_L d = {}). Above 0.5 a few long waves carry the contact, Persson's \
             contact area is too small and his contact pressures are conservative{}; run \
             --verify to solve the contact exactly.",
            sig(c.low_octave_share),
            sig(lo * outcome.thickness),
            if c.low_octave_share > crate::check::LOW_OCTAVE_WARN {
                crate::check::regime::sentence(lo * outcome.thickness)
            } else {
                String::new()
            }
        ),
        "Materials: the moduli and strengths are the library's values (sources above); their          spread is not propagated."
            .into(),
    ];
    if let Some(r) = &j.robust {
        uncertainty.pop();
        uncertainty.extend(super::robust::sentences(r, &scene.design(), outcome));
    }
    if let Some(e) = &j.exact {
        exact = exact::rows(e, outcome);
        uncertainty.extend(exact::sentences(e, outcome));
    }
    Ok(Section {
        title: title.to_string(),
        pass: j.pass(),
        headline,
        checks,
        levers,
        inputs,
        results,
        interfaces: Vec::new(),
        exact,
        plots,
        warnings: j.warnings.clone(),
        uncertainty,
    })
}

/// The page of a run: one section per scene (a scene that could not be judged gets a section
/// with its error).
pub fn page(runs: &[SceneRun], meta: &Meta) -> Result<String, Error> {
    let sections = runs
        .iter()
        .map(|run| {
            let title = run.file.display().to_string();
            match &run.result {
                Ok(j) => section(&title, j),
                Err(e) => Ok(Section {
                    title,
                    pass: false,
                    headline: format!("could not be judged: {e}"),
                    checks: Vec::new(),
                    levers: Vec::new(),
                    inputs: Vec::new(),
                    results: Vec::new(),
                    interfaces: Vec::new(),
                    exact: Vec::new(),
                    plots: Vec::new(),
                    warnings: Vec::new(),
                    uncertainty: Vec::new(),
                }),
            }
        })
        .collect::<Result<Vec<_>, Error>>()?;
    Ok(document(&sections, meta))
}

/// "film thickness >= 12.3 µm (now 5 µm)", in the units people read.
pub fn lever_text(lever: &Lever) -> String {
    let (scale, unit, what) = match lever.name {
        "thickness" => (1e-6, "µm", "film thickness"),
        "bond_strength" => (1e6, "MPa", "bond shear strength"),
        "yield_strength" => (1e6, "MPa", "substrate yield strength"),
        "pressure" => (1e6, "MPa", "nominal pressure"),
        _ => (
            1e-6,
            "µm",
            "rms height of the lowest octave of the roughness",
        ),
    };
    let what = match (&lever.at, lever.name) {
        (Some(at), "thickness") => format!("thickness of layer '{at}'"),
        (Some(at), "bond_strength") => format!("shear strength of the bond below '{at}'"),
        _ => what.to_string(),
    };
    let show = |v: f64| super::sig(v / scale, 4);
    match lever.value {
        Some(v) => format!(
            "{what} {} {} {unit} (now {} {unit})",
            lever.relation,
            show(v),
            show(lever.current)
        ),
        None => format!(
            "{what}: no value down to {} of the present one passes",
            super::sig(SPAN, 1)
        ),
    }
}

/// A number to four significant digits.
fn sig(x: f64) -> String {
    crate::report::sig(x, 4)
}

fn mpa(pa: f64) -> String {
    sig(pa / 1e6)
}

fn um(m: f64) -> String {
    sig(m / 1e-6)
}

const STYLE: &str = "body{font-family:sans-serif;max-width:60rem;margin:1.5rem auto;\
padding:0 1rem;color:#111;line-height:1.4}h1{font-size:1.5rem}h2{font-size:1.25rem;\
border-bottom:1px solid #999;margin-top:2rem}h3{font-size:1.05rem}table{border-collapse:\
collapse;margin:.5rem 0}td,th{border:1px solid #bbb;padding:.2rem .5rem;text-align:left;\
vertical-align:top}th{background:#eee}.verdict{font-size:1.3rem;font-weight:bold;padding:\
.4rem .8rem;display:inline-block;border-radius:.3rem}.pass{background:#d6f0d6;color:#0a5a0a}\
.fail{background:#f7d4d4;color:#8a0b0b}figure{margin:1rem 0;page-break-inside:avoid}\
figure svg{max-width:100%;height:auto}figcaption{font-size:.9rem;color:#333}.meta{font-size:\
.85rem;color:#444}ul.warn li{color:#7a4a00}@media print{h2{page-break-before:auto}}";

fn rows_table(head: &[&str], rows: impl Iterator<Item = Vec<String>>) -> String {
    let mut t = String::from("<table><tr>");
    for h in head {
        t += &format!("<th>{}</th>", escape(h));
    }
    t += "</tr>";
    for row in rows {
        t += "<tr>";
        for cell in row {
            t += &format!("<td>{}</td>", escape(&cell));
        }
        t += "</tr>";
    }
    t + "</table>\n"
}

fn list(class: &str, items: &[String]) -> String {
    let mut s = format!("<ul class=\"{class}\">");
    for i in items {
        s += &format!("<li>{}</li>", escape(i));
    }
    s + "</ul>\n"
}

fn verdict(pass: bool) -> String {
    let (class, text) = if pass {
        ("pass", "PASS")
    } else {
        ("fail", "FAIL")
    };
    format!("<span class=\"verdict {class}\">{text}</span>")
}

fn section_html(s: &Section, level: u8) -> String {
    let h = |n: u8, text: &str| format!("<h{n}>{}</h{n}>\n", escape(text));
    let mut out = format!(
        "{}<p>{} {}</p>\n",
        h(level, &s.title),
        verdict(s.pass),
        escape(&s.headline)
    );
    if !s.checks.is_empty() {
        out += &h(level + 1, "Checks");
        out += &rows_table(
            &["check", "value", "limit", "utilisation", "margin", "result"],
            s.checks.iter().map(|r| r.to_vec()),
        );
    }
    if !s.levers.is_empty() {
        out += &h(level + 1, "What alone would make it pass");
        out += &list("levers", &s.levers);
    }
    if !s.warnings.is_empty() {
        out += &h(level + 1, "Warnings");
        out += &list("warn", &s.warnings);
    }
    if !s.inputs.is_empty() {
        out += &h(level + 1, "Inputs");
        out += &rows_table(
            &["input", "value"],
            s.inputs.iter().map(|(k, v)| vec![k.clone(), v.clone()]),
        );
    }
    if !s.results.is_empty() {
        out += &h(level + 1, "Results (Persson's theory)");
        out += &rows_table(
            &["quantity", "value ± numerical error"],
            s.results.iter().map(|(k, v)| vec![k.clone(), v.clone()]),
        );
    }
    if !s.interfaces.is_empty() {
        out += &h(level + 1, "Interfaces (Persson's theory)");
        out += &rows_table(
            &[
                "interface below",
                "depth [µm]",
                "σ_rms [MPa]",
                "τ_rms [MPa]",
                "τ_peak [MPa]",
                "σ_peak [MPa]",
                "P(|τ| > bond)",
            ],
            s.interfaces.iter().map(|r| r.to_vec()),
        );
    }
    if !s.exact.is_empty() {
        out += &h(level + 1, "Persson against the exact solution");
        out += &rows_table(
            &["quantity", "Persson", "exact (boundary elements)"],
            s.exact.iter().map(|r| r.to_vec()),
        );
    }
    for p in &s.plots {
        out += &format!(
            "<figure>{}<figcaption>{}</figcaption></figure>\n",
            p.svg,
            escape(&p.caption)
        );
    }
    if !s.uncertainty.is_empty() {
        out += &h(level + 1, "How far to trust these numbers");
        out += &list("uncertainty", &s.uncertainty);
    }
    out
}

/// The whole page: one section, or a batch summary (scene, verdict, headline) and a section
/// per scene.
pub fn document(sections: &[Section], meta: &Meta) -> String {
    let all_pass = sections.iter().all(|s| s.pass);
    let mut body = String::new();
    if let [one] = sections {
        body += "<h1>coatcheck qualification report</h1>\n";
        body += &section_html(one, 2);
    } else {
        body += &format!(
            "<h1>coatcheck qualification report: {} scenes</h1>\n<p>{} {} of {} pass</p>\n",
            sections.len(),
            verdict(all_pass),
            sections.iter().filter(|s| s.pass).count(),
            sections.len()
        );
        body += &rows_table(
            &["scene", "verdict", "governing"],
            sections.iter().map(|s| {
                vec![
                    s.title.clone(),
                    if s.pass { "PASS" } else { "FAIL" }.into(),
                    s.headline.clone(),
                ]
            }),
        );
        for s in sections {
            body += &section_html(s, 2);
        }
    }
    let meta = format!(
        "<p class=\"meta\">coatcheck {} · {} · <code>{}</code></p>\n",
        escape(&meta.version),
        escape(&meta.date),
        escape(&meta.command_line)
    );
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>coatcheck report</title><style>{STYLE}</style></head><body>\n{meta}{body}\
         </body></html>\n"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn civil_dates_match_known_days() {
        assert_eq!(civil_date(0), "1970-01-01");
        assert_eq!(civil_date(59), "1970-03-01");
        assert_eq!(civil_date(11_016), "2000-02-29");
        assert_eq!(civil_date(20_417), "2025-11-25");
        assert_eq!(civil_date(20_782), "2026-11-25");
    }

    #[test]
    fn escape_covers_markup() {
        assert_eq!(
            escape("a<b>&\"c'"),
            "a&lt;b&gt;&amp;&quot;c&#39;".to_string()
        );
    }

    fn section(pass: bool) -> Section {
        Section {
            title: "scene <1>".into(),
            pass,
            headline: "governing check: bond-shear".into(),
            checks: vec![[
                "bond-shear".into(),
                "3 MPa".into(),
                "10 MPa".into(),
                "30 %".into(),
                "+70 %".into(),
                "pass".into(),
            ]],
            levers: vec![],
            inputs: vec![("film".into(), "NBR".into())],
            results: vec![],
            interfaces: vec![],
            exact: vec![],
            plots: vec![],
            warnings: vec!["thin".into()],
            uncertainty: vec![],
        }
    }

    #[test]
    fn document_is_self_contained_and_escaped() {
        let meta = Meta {
            version: "0.1.0".into(),
            date: "2026-11-25".into(),
            command_line: "coatcheck check a.toml --report r.html".into(),
        };
        let one = document(&[section(true)], &meta);
        assert!(one.starts_with("<!DOCTYPE html>"));
        assert!(one.contains("scene &lt;1&gt;") && !one.contains("scene <1>"));
        assert!(one.contains("PASS") && one.contains("bond-shear"));
        for external in ["http://", "https://", "<script", "<link", "@import"] {
            assert!(!one.contains(external), "{external}");
        }
        let two = document(&[section(true), section(false)], &meta);
        assert!(two.contains("2 scenes") && two.contains("1 of 2 pass"));
        assert!(two.contains("verdict fail"));
    }
}
