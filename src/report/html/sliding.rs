//! The interface shear plots under the vector rule (sliding friction, or the rule asked for;
//! notes.md, "Sliding friction"): the exceedance P(|τ| > t) and the density of |τ| for the
//! vector τ = (μp0 + X, Y), X and Y independent zero-mean Gaussians with the rms of the shear's
//! x and y fluctuations ([`crate::tail::ShearVector`], computed by integration over the angle),
//! with ε, the peak, the limit and the bond strength marked.

use super::{POINTS, Plot, axis, curve, exceedance_plot, levels, marker};
use crate::Error;
use crate::contact::SlidingShear;
use crate::figures::Figure;
use crate::report::mpa;
use crate::report::plot::{Extras, Legend, svg};
use crate::tail::ShearVector;

/// The exceedance and the density of |τ| for the shear vector `s`, with ε, the peak `peak`, the
/// check's `limit` (bond strength / safety factor) and the bond strength `bond` marked.
pub(super) fn shear_plots(
    s: &SlidingShear,
    eps: f64,
    peak: f64,
    limit: Option<f64>,
    bond: f64,
) -> Result<Vec<Plot>, Error> {
    let v = ShearVector::new(s.mean.value, s.tau_x_rms.value, s.tau_y_rms.value)?;
    let rms = s.tau_x_rms.value.hypot(s.tau_y_rms.value);
    let label = "Persson, vector (mu p0 + X, Y)";
    let numbers = format!(
        "mean mu p0 = {} MPa, rms of X and Y {} and {} MPa",
        mpa(s.mean.value),
        mpa(s.tau_x_rms.value),
        mpa(s.tau_y_rms.value)
    );
    let t = levels(rms, peak, limit.map(|l| l.max(bond)));
    let p = t.iter().map(|&t| v.exceedance(t).value).collect();
    // Three vertical labels close together on a log axis overlap: the bond strength is marked
    // here only when there is no limit, and on the density plot always.
    let markers = vec![
        marker(eps, false, format!("epsilon = {}", super::sig(eps))),
        marker(peak, true, format!("tau_peak {} MPa", mpa(peak))),
        match limit {
            Some(l) => marker(l, true, format!("limit {} MPa", mpa(l))),
            None => marker(bond, true, format!("bond strength {} MPa", mpa(bond))),
        },
    ];
    let exceedance = exceedance_plot(
        "Interface shear: fraction of the interface where |tau| exceeds t",
        "shear level t",
        "P(|tau| > t)",
        curve(label, t, p),
        markers,
        &format!(
            "Under sliding the interface shear is the vector (mu p0 + X, Y) ({numbers}): the \
             mean friction passes the film, X and Y are the pressure- and friction-driven \
             fluctuations. The level exceeded on a fraction epsilon of the interface is the peak \
             shear; it is compared with the bond strength over the safety factor."
        ),
    )?;
    let hi = 1.2 * peak.max(limit.unwrap_or(0.0)).max(bond);
    let x: Vec<f64> = (0..=4 * POINTS)
        .map(|i| hi * i as f64 / (4 * POINTS) as f64)
        .collect();
    let f = x.iter().map(|&t| v.density(t)).collect();
    let mut markers = vec![marker(peak, true, format!("tau_peak {} MPa", mpa(peak)))];
    if let Some(l) = limit.filter(|&l| l != bond) {
        markers.push(marker(l, true, format!("limit {} MPa", mpa(l))));
    }
    markers.push(marker(
        bond,
        true,
        format!("bond strength {} MPa", mpa(bond)),
    ));
    let fig = Figure {
        name: "shear-density",
        title: "Interface shear under sliding: probability density of |tau|",
        x: axis("shear |tau|", "MPa", 1e6, false),
        y: axis("density", "1/MPa", 1e-6, false),
        series: vec![curve(label, x, f)],
    };
    let extras = Extras {
        markers,
        legend: Legend::MiddleRight,
        ..Extras::default()
    };
    let density = Plot {
        caption: format!(
            "The density of |tau| over the interface (its integral is 1; {numbers}), with the \
             peak, the limit and the bond strength. Its mode sits near the mean friction mu p0 \
             when the fluctuations are small against it."
        ),
        svg: svg(&fig, &extras)?,
    };
    Ok(vec![exceedance, density])
}
