//! `coatcheck verify MAP.csv`: the exact contact of a rigid flat with the film on the measured
//! height map (FFT boundary elements, `coatcheck::bem`) beside Persson's estimate from the same
//! map's power spectrum, and the interface stresses at z = d.
//!
//! Prints a side-by-side table (Persson, exact, exact/Persson) or one JSON object; optionally
//! writes the fields (`--fields out.csv`, atomically). Exit codes: 0 done (and no pixel's |τ|
//! above `--bond-strength`), 1 the bond strength is exceeded somewhere, 2 bad input or a solve
//! that did not converge (nothing is written then).

use coatcheck::Error;
use coatcheck::bem::{self, BemSettings, BemSolution, FieldStats, InterfaceFields, Surface};
use coatcheck::contact::{Contact, Engine, Request, tau_exceedance, tau_peak};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::{Estimate, Settings, Termination};
use coatcheck::psd::Spectrum;
use coatcheck::report::write_with;
use coatcheck::topography::io::{MapOptions, read_height_map};
use coatcheck::topography::spectrum::{PsdOptions, map_psd};
use coatcheck::units::{Dim, parse_quantity};
use coatcheck::verify::Verification;
use comfy_table::Table;
use serde_json::{Value, json};
use std::io::Write;
use std::path::{Path, PathBuf};

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum FormatArg {
    Table,
    Json,
}

/// Exact contact on a height map (treated as one period of a periodic surface), beside
/// Persson's estimate from its spectrum.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Exit codes: 0 done, 1 |tau| exceeds --bond-strength somewhere, \
                        2 bad input or a solve that did not converge."
)]
pub struct VerifyArgs {
    /// Height map: CSV matrix of heights (rows = y, columns = x), in m unless --height-unit
    /// or the file's `# coatcheck height map: ...` comment says otherwise.
    pub map: PathBuf,
    /// Film: Young's modulus and Poisson ratio, e.g. `1MPa,0.5`.
    #[arg(long)]
    pub film: String,
    /// Substrate: Young's modulus and Poisson ratio, e.g. `200GPa,0.3`.
    #[arg(long)]
    pub substrate: String,
    /// Film thickness, e.g. `50um`.
    #[arg(long)]
    pub thickness: String,
    /// Nominal pressure p0, e.g. `0.1MPa`.
    #[arg(long)]
    pub pressure: String,
    /// Pixel size (x, and y unless --pixel-size-y); overrides the file's metadata.
    #[arg(long)]
    pub pixel_size: Option<String>,
    /// Pixel size along y (between rows), if different from x.
    #[arg(long)]
    pub pixel_size_y: Option<String>,
    /// Unit of the heights (m, um, nm).
    #[arg(long)]
    pub height_unit: Option<String>,
    /// Interface bond strength in shear: reports the area fraction where |τ| exceeds it.
    #[arg(long)]
    pub bond_strength: Option<String>,
    /// Write the fields (x, y, height, pressure, gap, interface σ_n, τ_x, τ_y, |τ|) as CSV.
    #[arg(long)]
    pub fields: Option<PathBuf>,
    #[arg(long, value_enum, default_value = "table")]
    pub format: FormatArg,
    /// Solver tolerance: rms gap in contact and largest penetration, relative to h_rms.
    #[arg(long, default_value_t = BemSettings::default().gap_tol)]
    pub gap_tol: f64,
    /// Solver iteration limit.
    #[arg(long, default_value_t = BemSettings::default().max_iter)]
    pub max_iter: usize,
    /// Relative tolerance of Persson's contact integrals (default 1e-8).
    #[arg(long)]
    pub rtol: Option<String>,
}

fn quantity(flag: &'static str, s: &str, dim: Dim, expected: &'static str) -> Result<f64, Error> {
    parse_quantity(s, dim).map_err(|e| Error::invalid(flag, format!("'{s}' ({e})"), expected))
}

fn material(flag: &'static str, s: &str) -> Result<Elastic, Error> {
    const EXPECTED: &str = "E,nu with E a pressure (e.g. 1MPa,0.5)";
    let (e, nu) = s
        .split_once(',')
        .ok_or_else(|| Error::invalid(flag, format!("'{s}'"), EXPECTED))?;
    let e = quantity(flag, e, Dim::Pressure, EXPECTED)?;
    let nu = quantity(flag, nu, Dim::Dimensionless, EXPECTED)?;
    Elastic::new(e, nu)
}

/// One line of the side-by-side table.
struct Row {
    name: String,
    unit: &'static str,
    persson: Option<Estimate>,
    exact: f64,
}

impl Row {
    fn new(
        name: impl Into<String>,
        unit: &'static str,
        persson: Option<Estimate>,
        exact: f64,
    ) -> Self {
        Self {
            name: name.into(),
            unit,
            persson,
            exact,
        }
    }

    fn ratio(&self) -> Option<f64> {
        self.persson
            .filter(|p| p.value != 0.0)
            .map(|p| self.exact / p.value)
    }
}

fn stats_json(s: &FieldStats) -> Value {
    json!({
        "mean": s.mean,
        "rms": s.rms,
        "rms_dev": s.rms_dev,
        "max": s.max,
        "quantiles": s.quantiles.iter().map(|q| json!({"p": q.prob, "value": q.value})).collect::<Vec<_>>(),
    })
}

/// Persson's estimate on the map's own spectrum (periodic, no window, all wavelengths down to
/// the Nyquist limit, as the boundary elements see them).
fn persson(
    map: &coatcheck::topography::HeightMap,
    stack: &Stack,
    p0: f64,
    settings: Settings,
) -> Result<Contact, Error> {
    let psd = map_psd(
        map,
        &PsdOptions {
            cutoff_pixels: 2.0,
            ..PsdOptions::default()
        },
    )?;
    let engine = Engine::new(&Spectrum::Tabulated(psd.c2d), settings);
    engine.evaluate(stack, p0, Request::all())
}

/// Run `coatcheck verify`; returns the exit code or an error (exit code 2).
pub fn run(a: VerifyArgs) -> Result<i32, Error> {
    let film = material("--film", &a.film)?;
    let substrate = material("--substrate", &a.substrate)?;
    let d = quantity(
        "--thickness",
        &a.thickness,
        Dim::Length(1),
        "a length (e.g. 50um)",
    )?;
    let p0 = quantity(
        "--pressure",
        &a.pressure,
        Dim::Pressure,
        "a pressure (e.g. 0.1MPa)",
    )?;
    let bond = a
        .bond_strength
        .as_deref()
        .map(|s| {
            quantity(
                "--bond-strength",
                s,
                Dim::Pressure,
                "a pressure (e.g. 10MPa)",
            )
        })
        .transpose()?;
    let length = |flag, s: &Option<String>| {
        s.as_deref()
            .map(|s| quantity(flag, s, Dim::Length(1), "a length (e.g. 0.5um)"))
            .transpose()
    };
    let opts = MapOptions {
        dx: length("--pixel-size", &a.pixel_size)?,
        dy: length("--pixel-size-y", &a.pixel_size_y)?,
        z_unit: a.height_unit.clone(),
        periodic: Some(true),
    };
    let map = read_height_map(&a.map, &opts)?;
    let stack = Stack::new(Bilayer::new(film, substrate), d)?;
    let surface = Surface::from_height_map(&map)?;
    let settings = BemSettings {
        gap_tol: a.gap_tol,
        max_iter: a.max_iter,
    };
    let started = std::time::Instant::now();
    let sol = bem::solve(&surface, &stack, p0, &settings)?;
    let fields = bem::interface_fields(&sol, &stack)?;
    let seconds = started.elapsed().as_secs_f64();
    let rtol = a
        .rtol
        .as_deref()
        .map(|s| {
            quantity(
                "--rtol",
                s,
                Dim::Dimensionless,
                "a relative tolerance such as 1e-8",
            )
            .and_then(|r| {
                if r > 0.0 && r < 1.0 {
                    Ok(r)
                } else {
                    Err(Error::invalid("--rtol", s, "0 < rtol < 1"))
                }
            })
        })
        .transpose()?
        .unwrap_or(coatcheck::prec::DEFAULT_RTOL);
    let theory = persson(&map, &stack, p0, Settings { rtol })?;
    let converged = sol.convergence.status == Termination::Converged;
    if converged && let Some(path) = &a.fields {
        write_fields(path, &surface, &sol, &fields)?;
    }
    let above = bond.map(|b| fields.shear_fraction_above(b));
    let rows = rows(&sol, &fields, &theory, bond, above);
    let xi = surface.rms_slope();
    match a.format {
        FormatArg::Table => {
            coatcheck::report::stdout(&table(&a, &surface, &stack, p0, xi, &sol, seconds, &rows))?
        }
        FormatArg::Json => {
            let v = json!({
                "map": a.map.display().to_string(),
                "nx": surface.nx, "ny": surface.ny, "dx_m": surface.dx, "dy_m": surface.dy,
                "h_rms_m": sol.h_rms, "rms_slope": xi, "q_low_per_m": surface.q_low(),
                "q_low_d": surface.q_low() * d,
                "thickness_m": d, "pressure_pa": p0,
                "solver": {
                    "iterations": sol.convergence.iterations,
                    "restarts": sol.convergence.restarts,
                    "gap_rms_in_contact_m": sol.convergence.gap_rms_in_contact,
                    "max_penetration_m": sol.convergence.max_penetration,
                    "tolerance_m": sol.convergence.tolerance,
                    "load_error": sol.convergence.load_error,
                    "status": sol.convergence.status,
                    "seconds": seconds,
                },
                "area_fraction": sol.area_fraction.value,
                "area_fraction_err": sol.area_fraction.err,
                "persson_area_fraction": theory.area_fraction.value,
                "persson_area_fraction_err": theory.area_fraction.err,
                "sigma_rms_top_pa": sol.sigma_rms_top,
                "contact_pressure": stats_json(&sol.contact_pressure),
                "interface_normal": stats_json(&fields.normal_stats),
                "interface_shear_abs": stats_json(&fields.shear_stats),
                "bond_strength_pa": bond,
                "shear_fraction_above_bond": above,
                "comparison": rows.iter().map(|r| json!({
                    "quantity": r.name, "unit": r.unit,
                    "persson": r.persson.map(|p| p.value),
                    "persson_err": r.persson.map(|p| p.err),
                    "exact": r.exact, "ratio": r.ratio(),
                })).collect::<Vec<_>>(),
            });
            coatcheck::report::stdout(&format!(
                "{}\n",
                serde_json::to_string_pretty(&v).expect("a JSON value serialises")
            ))?;
        }
    }
    if !converged {
        eprintln!(
            "coatcheck: {}: the contact solve did not converge in {} iterations \
             (rms gap in contact {:.3e} m, penetration {:.3e} m, tolerance {:.3e} m); \
             raise --max-iter or --gap-tol",
            a.map.display(),
            sol.convergence.iterations,
            sol.convergence.gap_rms_in_contact,
            sol.convergence.max_penetration,
            sol.convergence.tolerance
        );
        return Ok(2);
    }
    Ok(if above.is_some_and(|f| f > 0.0) { 1 } else { 0 })
}

fn rows(
    sol: &BemSolution,
    fields: &InterfaceFields,
    theory: &Contact,
    bond: Option<f64>,
    above: Option<f64>,
) -> Vec<Row> {
    let tau_rms = theory.tau_rms_interface;
    let area = theory.area_fraction;
    let mut rows = vec![
        Row::new("A/A0", "", Some(area), sol.area_fraction.value),
        Row::new(
            "sigma_rms top",
            "Pa",
            theory.sigma_rms_top,
            sol.sigma_rms_top,
        ),
        Row::new(
            "sigma_rms interface",
            "Pa",
            theory.sigma_rms_interface,
            fields.normal_stats.rms_dev,
        ),
        Row::new("tau_rms interface", "Pa", tau_rms, fields.shear_stats.rms),
        Row::new(
            "contact pressure mean",
            "Pa",
            Some(area.map(|a| sol.p0 / a, |a| sol.p0 / (a * a))),
            sol.contact_pressure.mean,
        ),
    ];
    for q in &sol.contact_pressure.quantiles {
        rows.push(Row::new(
            format!("contact pressure q{}", q.prob),
            "Pa",
            None,
            q.value,
        ));
    }
    rows.push(Row::new(
        "contact pressure max",
        "Pa",
        None,
        sol.contact_pressure.max,
    ));
    for q in &fields.normal_stats.quantiles {
        rows.push(Row::new(
            format!("interface sigma_n q{}", q.prob),
            "Pa",
            None,
            q.value,
        ));
    }
    rows.push(Row::new(
        "interface sigma_n max",
        "Pa",
        None,
        fields.normal_stats.max,
    ));
    for q in &fields.shear_stats.quantiles {
        // Persson: |τ| half-normal with rms τ_rms, so the quantile at P is τ_peak(ε = 1 − P).
        let k = tau_peak(1.0, 1.0 - q.prob);
        let p = tau_rms.map(|t| t.map(|t| k * t, |_| k));
        rows.push(Row::new(
            format!("interface |tau| q{}", q.prob),
            "Pa",
            p,
            q.value,
        ));
    }
    rows.push(Row::new(
        "interface |tau| max",
        "Pa",
        None,
        fields.shear_stats.max,
    ));
    if let (Some(b), Some(f)) = (bond, above) {
        rows.push(Row::new(
            "area fraction |tau| > bond",
            "",
            tau_rms.map(|t| Estimate {
                value: tau_exceedance(t.value, b),
                err: (tau_exceedance(t.value + t.err, b) - tau_exceedance(t.value, b)).abs(),
                status: t.status,
            }),
            f,
        ));
    }
    rows
}

#[allow(clippy::too_many_arguments)]
fn table(
    a: &VerifyArgs,
    s: &Surface,
    stack: &Stack,
    p0: f64,
    xi: f64,
    sol: &BemSolution,
    seconds: f64,
    rows: &[Row],
) -> String {
    let mut scene = Table::new();
    scene.set_header(vec!["scene", "value"]);
    let l = stack.layers;
    scene.add_row(vec![
        "height map".into(),
        format!(
            "{} ({} x {}, pixel {:.4e} x {:.4e} m)",
            a.map.display(),
            s.nx,
            s.ny,
            s.dx,
            s.dy
        ),
    ]);
    scene.add_row(vec![
        "h_rms, rms slope".into(),
        format!("{:.4e} m, {:.4}", sol.h_rms, xi),
    ]);
    scene.add_row(vec![
        "film".into(),
        format!("E = {:.4e} Pa, nu = {}", l.film.youngs, l.film.poisson),
    ]);
    scene.add_row(vec![
        "substrate".into(),
        format!(
            "E = {:.4e} Pa, nu = {}",
            l.substrate.youngs, l.substrate.poisson
        ),
    ]);
    scene.add_row(vec![
        "thickness d, q_L d".into(),
        format!(
            "{:.4e} m, {:.4}",
            stack.thickness,
            s.q_low() * stack.thickness
        ),
    ]);
    scene.add_row(vec!["pressure p0".into(), format!("{p0:.4e} Pa")]);
    let c = &sol.convergence;
    scene.add_row(vec![
        "solver".into(),
        format!(
            "{:?} after {} iterations in {seconds:.2} s (rms gap in contact {:.2e} m, \
             penetration {:.2e} m, tolerance {:.2e} m)",
            c.status, c.iterations, c.gap_rms_in_contact, c.max_penetration, c.tolerance
        ),
    ]);
    let mut t = Table::new();
    t.set_header(vec![
        "quantity",
        "unit",
        "Persson",
        "Persson err",
        "exact (BEM)",
        "exact/Persson",
    ]);
    let num = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.4e}"));
    for r in rows {
        t.add_row(vec![
            r.name.clone(),
            r.unit.to_string(),
            num(r.persson.map(|p| p.value)),
            r.persson.map_or("-".into(), |p| format!("{:.1e}", p.err)),
            format!("{:.4e}", r.exact),
            r.ratio().map_or("-".into(), |v| format!("{v:.3}")),
        ]);
    }
    format!(
        "{scene}\n{t}\nA/A0 counts pixels in contact (±{:.1e} from the solver tolerance); refine the map to see \
         the discretisation error. Quantiles: contact pressure over the contact area, interface \
         stresses over the whole interface.\n",
        sol.area_fraction.err
    )
}

fn write_fields(
    path: &Path,
    s: &Surface,
    sol: &BemSolution,
    f: &InterfaceFields,
) -> Result<(), Error> {
    write_with(path, |w: &mut dyn Write| {
        writeln!(
            w,
            "x_m,y_m,height_m,pressure_pa,gap_m,sigma_n_interface_pa,tau_x_pa,tau_y_pa,tau_abs_pa"
        )?;
        for iy in 0..s.ny {
            for ix in 0..s.nx {
                let i = iy * s.nx + ix;
                writeln!(
                    w,
                    "{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e}",
                    ix as f64 * s.dx,
                    iy as f64 * s.dy,
                    s.heights[i],
                    sol.pressure[i],
                    sol.gap[i],
                    f.normal[i],
                    f.shear_x[i],
                    f.shear_y[i],
                    f.shear_magnitude(i)
                )?;
            }
        }
        Ok(())
    })
}

/// The map behind `check --verify`: the scene's height file, which must be a height map.
pub fn scene_map(scene: &coatcheck::scene::Scene) -> Result<(PathBuf, Surface), Error> {
    use coatcheck::scene::RoughnessSource;
    use coatcheck::topography::io::{HeightKind, sniff};
    let origin = || {
        scene
            .file
            .as_ref()
            .map_or("--verify".to_string(), |p| p.display().to_string())
    };
    let RoughnessSource::Profile { path } = &scene.roughness.source else {
        return Err(Error::Value {
            origin: origin(),
            msg: "--verify solves the contact on the measured surface: give the roughness as a \
                  height map (roughness.profile or --profile), not as a spectrum or a model"
                .into(),
        });
    };
    if sniff(path)? == Some(HeightKind::Lines) {
        return Err(Error::Input {
            path: path.clone(),
            line: 1,
            msg: "--verify needs a height map (a matrix of heights), not line scans".into(),
        });
    }
    let opts = MapOptions {
        periodic: Some(true),
        ..MapOptions::default()
    };
    let map = read_height_map(path, &opts)?;
    Ok((path.clone(), Surface::from_height_map(&map)?))
}

/// Persson's value and the exact one, for the side-by-side rows of `check --verify`.
fn check_rows(
    ev: &coatcheck::check::Evaluation,
    v: &Verification,
) -> Vec<(&'static str, &'static str, Option<Estimate>, Estimate)> {
    let c = &ev.contact;
    let mut rows = vec![
        (
            "A/A0",
            "area_fraction",
            Some(c.area_fraction),
            v.area_fraction,
        ),
        (
            "mean contact pressure",
            "mean_contact_pressure_pa",
            Some(ev.mean_contact_pressure),
            v.mean_contact_pressure,
        ),
        (
            "sigma_rms top",
            "sigma_rms_top_pa",
            c.sigma_rms_top,
            v.sigma_rms_top,
        ),
        (
            "sigma_rms interface",
            "sigma_rms_interface_pa",
            c.sigma_rms_interface,
            v.sigma_rms_interface,
        ),
        (
            "tau_rms interface",
            "tau_rms_interface_pa",
            c.tau_rms_interface,
            v.tau_rms_interface,
        ),
        ("tau_peak", "tau_peak_pa", ev.tau_peak, v.tau_peak.value),
        (
            "sigma_peak interface",
            "sigma_peak_interface_pa",
            ev.sigma_peak_interface,
            v.sigma_peak_interface.value,
        ),
    ];
    rows.push((
        "P(|tau| > bond strength)",
        "bond_exceedance",
        ev.bond_exceedance.map(|p| Estimate {
            value: p,
            err: 0.0,
            status: Termination::Converged,
        }),
        v.bond_exceedance,
    ));
    rows
}

/// The `check --verify` section as tables (MPa, 4 significant digits, like the check's report).
pub fn check_table(map: &Path, ev: &coatcheck::check::Evaluation, v: &Verification) -> String {
    use coatcheck::report::sig;
    use comfy_table::presets::UTF8_FULL_CONDENSED;
    let mut out = format!(
        "exact check on the height map {} ({} x {} pixels, q_L d = {}; boundary elements, {} \
         iterations; error = difference to the same map at half resolution)\n",
        map.display(),
        v.nx,
        v.ny,
        sig(v.q_low_d, 3),
        v.convergence.iterations
    );
    let show = |key: &str, x: f64| match key.strip_suffix("_pa") {
        Some(_) => format!("{} MPa", sig(x * 1e-6, 4)),
        None => sig(x, 4),
    };
    let mut t = Table::new();
    t.load_preset(UTF8_FULL_CONDENSED);
    t.set_header(vec![
        "quantity",
        "Persson",
        "exact (BEM)",
        "error estimate",
        "exact/Persson",
    ]);
    for (name, key, p, e) in check_rows(ev, v) {
        let ratio = p
            .filter(|p| p.value != 0.0)
            .map_or("-".into(), |p| sig(e.value / p.value, 3));
        t.add_row(vec![
            name.to_string(),
            p.map_or("-".into(), |p| show(key, p.value)),
            show(key, e.value),
            show(key, e.err),
            ratio,
        ]);
    }
    out += &format!("{t}\n");
    let mut c = Table::new();
    c.load_preset(UTF8_FULL_CONDENSED);
    c.set_header(vec!["check (exact)", "value", "limit", "margin", "result"]);
    for ch in &v.checks {
        let mut result = if ch.pass { "PASS" } else { "FAIL" }.to_string();
        if !ch.resolved {
            result += " (map maximum: epsilon < 1/pixels)";
        }
        c.add_row(vec![
            ch.kind.name().to_string(),
            show("_pa", ch.value.value),
            format!("<= {}", show("_pa", ch.limit)),
            format!("{:+.1} %", 100.0 * ch.margin),
            result,
        ]);
    }
    out += &format!("{c}\n");
    out += &format!(
        "exact verdict: {}; with --verify the design passes only if both Persson's and the exact \
         checks pass (min-thickness is judged by Persson's theory only)\n",
        if v.pass { "PASS" } else { "FAIL" }
    );
    out
}

/// The `check --verify` section as a JSON value.
pub fn check_json(map: &Path, ev: &coatcheck::check::Evaluation, v: &Verification) -> Value {
    let mut m = serde_json::Map::new();
    m.insert("map".into(), json!(map.display().to_string()));
    m.insert("nx".into(), json!(v.nx));
    m.insert("ny".into(), json!(v.ny));
    m.insert("q_low_d".into(), json!(v.q_low_d));
    for (_, key, p, e) in check_rows(ev, v) {
        m.insert(key.into(), json!(e.value));
        m.insert(format!("{key}_err"), json!(e.err));
        m.insert(format!("persson_{key}"), json!(p.map(|p| p.value)));
    }
    m.insert("peaks_resolved".into(), json!(v.tau_peak.resolved));
    m.insert(
        "checks".into(),
        json!(
            v.checks
                .iter()
                .map(|c| json!({
                    "name": c.kind.name(), "value": c.value.value, "value_err": c.value.err,
                    "limit": c.limit, "margin": c.margin, "pass": c.pass, "resolved": c.resolved,
                }))
                .collect::<Vec<_>>()
        ),
    );
    m.insert("solver".into(), json!(v.convergence));
    m.insert("seconds".into(), json!(v.seconds));
    m.insert(
        "verdict".into(),
        json!(if v.pass { "pass" } else { "fail" }),
    );
    Value::Object(m)
}

/// The `check --verify` section as CSV rows (`verify:<key>,value,err,unit`), no header.
pub fn check_csv(ev: &coatcheck::check::Evaluation, v: &Verification) -> String {
    let mut out = String::new();
    for (_, key, _, e) in check_rows(ev, v) {
        let (key, unit) = key.strip_suffix("_pa").map_or((key, "1"), |k| (k, "Pa"));
        out += &format!("verify:{key},{:e},{:e},{unit}\n", e.value, e.err);
    }
    for c in &v.checks {
        let name = c.kind.name();
        out += &format!(
            "verify:check:{name},{:e},{:e},Pa\n",
            c.value.value, c.value.err
        );
        out += &format!("verify:limit:{name},{:e},,Pa\n", c.limit);
        out += &format!("verify:pass:{name},{},,\n", u8::from(c.pass));
    }
    out += &format!(
        "verify:verdict,{},,\n",
        if v.pass { "pass" } else { "fail" }
    );
    out
}
