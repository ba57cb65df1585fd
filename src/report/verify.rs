//! Output of `coatcheck verify` (the side-by-side table of Persson's estimate and the exact
//! contact, its JSON object, the fields as CSV) and of the exact section of `check --verify`
//! (tables in MPa with 4 significant digits like the check's report, JSON, CSV rows).

use super::{margin_cell, modulus, mpa, sig, table, um, utilisation_cell, wrap};
use crate::bem::{BemSolution, Convergence, FieldStats, InterfaceFields, Surface};
use crate::check::Evaluation;
use crate::error::Error;
use crate::layer::Stack;
use crate::verify::{Comparison, Verification, check_rows};
use serde_json::{Value, json};
use std::io::Write;
use std::path::Path;

/// What `coatcheck verify` was asked: the map file, the layered solid and the load.
pub struct VerifyInputs<'a> {
    pub map: &'a Path,
    pub stack: &'a Stack,
    pub p0: f64,
    pub bond: Option<f64>,
}

pub(super) fn stats_json(s: &FieldStats) -> Value {
    json!({
        "mean": s.mean,
        "rms": s.rms,
        "rms_dev": s.rms_dev,
        "max": s.max,
        "quantiles": s.quantiles.iter().map(|q| json!({"p": q.prob, "value": q.value})).collect::<Vec<_>>(),
    })
}

/// `coatcheck verify`'s tables: the scene, then Persson beside the exact contact.
pub fn verify_table(i: &VerifyInputs, c: &Comparison) -> String {
    let (s, sol, stack, p0) = (&c.surface, &c.solution, i.stack, i.p0);
    let (xi, seconds, rows) = (s.rms_slope(), c.seconds, &c.rows);
    let mut scene = table(&["scene", "value"]);
    let l = stack.layers;
    scene.add_row(vec![
        "height map".into(),
        format!(
            "{} ({} x {}, pixel {} x {} µm)",
            i.map.display(),
            s.nx,
            s.ny,
            um(s.dx),
            um(s.dy)
        ),
    ]);
    scene.add_row(vec![
        "h_rms, rms slope".into(),
        format!("{} µm, {}", um(sol.h_rms), sig(xi, 4)),
    ]);
    scene.add_row(vec![
        "film".into(),
        format!("E = {}, nu = {}", modulus(l.film.youngs), l.film.poisson),
    ]);
    scene.add_row(vec![
        "substrate".into(),
        format!(
            "E = {}, nu = {}",
            modulus(l.substrate.youngs),
            l.substrate.poisson
        ),
    ]);
    scene.add_row(vec![
        "thickness d, q_L d".into(),
        format!(
            "{} µm, {}",
            um(stack.thickness),
            sig(s.q_low() * stack.thickness, 4)
        ),
    ]);
    scene.add_row(vec!["pressure p0".into(), format!("{} MPa", mpa(p0))]);
    let c = &sol.convergence;
    scene.add_row(vec![
        "solver".into(),
        format!(
            "{:?} after {} iterations in {seconds:.2} s (rms gap in contact {:.2e} µm, \
             penetration {:.2e} µm, tolerance {:.2e} µm)",
            c.status,
            c.iterations,
            c.gap_rms_in_contact * 1e6,
            c.max_penetration * 1e6,
            c.tolerance * 1e6
        ),
    ]);
    let mut t = table(&[
        "quantity",
        "unit",
        "Persson",
        "Persson err",
        "exact (BEM)",
        "exact/Persson",
    ]);
    // Stresses in MPa like every table; the rest as they are.
    let scale = |unit: &str| if unit == "Pa" { 1e-6 } else { 1.0 };
    for r in rows {
        let k = scale(r.unit);
        t.add_row(vec![
            r.name.clone(),
            if r.unit == "Pa" { "MPa" } else { r.unit }.to_string(),
            r.persson.map_or("-".into(), |p| sig(p.value * k, 4)),
            r.persson.map_or("-".into(), |p| sig(p.err * k, 2)),
            sig(r.exact * k, 4),
            r.ratio().map_or("-".into(), |v| sig(v, 3)),
        ]);
    }
    format!(
        "{scene}\n{t}\n{}\n",
        wrap(&format!(
            "A/A0 counts pixels in contact (±{:.1e} from the solver tolerance); refine the map to \
             see the discretisation error. Quantiles: contact pressure over the contact area, \
             interface stresses over the whole interface.",
            sol.area_fraction.err
        ))
    )
}

/// The boundary-element solver's convergence (lengths in m), as `verify` and `check --verify`
/// write it.
pub(super) fn solver_json(c: &Convergence, seconds: f64) -> Value {
    json!({
        "iterations": c.iterations,
        "restarts": c.restarts,
        "gap_rms_in_contact_m": c.gap_rms_in_contact,
        "max_penetration_m": c.max_penetration,
        "tolerance_m": c.tolerance,
        "load_error": c.load_error,
        "status": c.status,
        "seconds": seconds,
    })
}

/// `coatcheck verify`'s JSON object.
pub fn verify_json(i: &VerifyInputs, c: &Comparison) -> Value {
    let (surface, sol, fields, theory) = (&c.surface, &c.solution, &c.fields, &c.persson);
    let (d, p0, bond, above, rows) = (i.stack.thickness, i.p0, i.bond, c.above_bond, &c.rows);
    let (xi, seconds) = (surface.rms_slope(), c.seconds);
    json!({
        "schema_version": super::SCHEMA_VERSION,
        "coatcheck_version": env!("CARGO_PKG_VERSION"),
        "map": i.map.display().to_string(),
        "nx": surface.nx, "ny": surface.ny, "dx_m": surface.dx, "dy_m": surface.dy,
        "h_rms_m": sol.h_rms, "rms_slope": xi, "q_low_per_m": surface.q_low(),
        "q_low_d": surface.q_low() * d,
        "thickness_m": d, "pressure_pa": p0,
        "solver": solver_json(&sol.convergence, seconds),
        "area_fraction": sol.area_fraction.value,
        "area_fraction_err": sol.area_fraction.err,
        "persson_area_fraction": theory.area_fraction.value,
        "persson_area_fraction_err": theory.area_fraction.err,
        "sigma_rms_top_pa": sol.sigma_rms_top,
        "contact_pressure_pa": stats_json(&sol.contact_pressure),
        "interface_normal_pa": stats_json(&fields.normal_stats),
        "interface_shear_abs_pa": stats_json(&fields.shear_stats),
        "bond_strength_pa": bond,
        "shear_fraction_above_bond": above,
        "comparison": rows.iter().map(|r| json!({
            "quantity": r.name, "unit": r.unit,
            "persson": r.persson.map(|p| p.value),
            "persson_err": r.persson.map(|p| p.err),
            "exact": r.exact, "ratio": r.ratio(),
        })).collect::<Vec<_>>(),
    })
}

/// The fields of a solve as CSV: x, y, height, pressure, gap, interface σ_n, τ_x, τ_y, |τ|.
pub fn write_fields(
    path: &Path,
    s: &Surface,
    sol: &BemSolution,
    f: &InterfaceFields,
) -> Result<(), Error> {
    super::write_with(path, |w: &mut dyn Write| {
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

/// The `check --verify` section as tables (MPa, 4 significant digits, like the check's report).
pub fn check_table(map: &Path, ev: &Evaluation, v: &Verification) -> String {
    let mut out = wrap(&format!(
        "exact check on the height map {} ({} x {} pixels, q_L d = {}; boundary elements, {} \
         iterations; error = difference to the same map at half resolution)",
        map.display(),
        v.nx,
        v.ny,
        sig(v.q_low_d, 3),
        v.convergence.iterations
    ));
    out.push('\n');
    let show = |key: &str, x: f64| match key.strip_suffix("_pa") {
        Some(_) => format!("{} MPa", sig(x * 1e-6, 4)),
        None => sig(x, 4),
    };
    let mut t = table(&[
        "quantity",
        "Persson",
        "exact (BEM)",
        "error estimate",
        "exact/Persson",
    ]);
    for r in check_rows(ev, v) {
        let (name, key, p, e) = (r.name, r.key, r.persson, r.exact);
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
    let mut c = table(&[
        "check (exact)",
        "value",
        "limit",
        "utilisation",
        "margin",
        "result",
    ]);
    for ch in &v.checks {
        let mut result = if ch.pass { "PASS" } else { "FAIL" }.to_string();
        if !ch.resolved {
            result += " (map maximum: epsilon < 1/pixels)";
        }
        c.add_row(vec![
            ch.kind.name().to_string(),
            show("_pa", ch.value.value),
            format!("<= {}", show("_pa", ch.limit)),
            utilisation_cell(Some(ch.margin)),
            margin_cell(Some(ch.margin)),
            result,
        ]);
    }
    out += &format!("{c}\n");
    out += &wrap(&format!(
        "exact verdict: {}; with --verify the design passes only if both Persson's and the exact \
         checks pass (min-thickness is judged by Persson's theory only)",
        if v.pass { "PASS" } else { "FAIL" }
    ));
    out.push('\n');
    out
}

/// The `check --verify` section as a JSON value.
pub fn check_json(map: &Path, ev: &Evaluation, v: &Verification) -> Value {
    let mut m = serde_json::Map::new();
    m.insert("map".into(), json!(map.display().to_string()));
    m.insert("nx".into(), json!(v.nx));
    m.insert("ny".into(), json!(v.ny));
    m.insert("q_low_d".into(), json!(v.q_low_d));
    for r in check_rows(ev, v) {
        let (key, p, e) = (r.key, r.persson, r.exact);
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
                    "unit": "Pa", "limit": c.limit, "utilisation": 1.0 - c.margin,
                    "margin": c.margin, "pass": c.pass, "resolved": c.resolved,
                }))
                .collect::<Vec<_>>()
        ),
    );
    m.insert("solver".into(), solver_json(&v.convergence, v.seconds));
    m.insert(
        "verdict".into(),
        json!(if v.pass { "pass" } else { "fail" }),
    );
    Value::Object(m)
}
