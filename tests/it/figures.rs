//! The paper's figures at reduced resolution (`coatcheck::figures`), checked against the
//! statements the paper (and notes.md) makes about each: limits and trends in the text.

use coatcheck::figures::{self, Figure, Series};
use statrs::function::erf::erf;

// The examples' CSV/SVG writer; `run` (their `main`) is not used here.
#[allow(dead_code)]
#[path = "../../examples/common/plot.rs"]
mod plot;

fn series<'a>(f: &'a Figure, label_start: &str) -> &'a Series {
    f.series
        .iter()
        .find(|s| s.label.starts_with(label_start))
        .unwrap_or_else(|| panic!("{}: no series {label_start}", f.name))
}

fn points(s: &Series) -> impl Iterator<Item = (f64, f64)> + '_ {
    s.x.iter().copied().zip(s.y.iter().copied())
}

fn assert_finite(f: &Figure) {
    for s in &f.series {
        assert!(s.x.len() == s.y.len() && s.y.len() == s.err.len() && !s.y.is_empty());
        for (&y, &e) in s.y.iter().zip(&s.err) {
            assert!(
                y.is_finite() && e.is_finite() && e <= 1e-6 * y.abs().max(1e-300),
                "{} {}: {y} ± {e}",
                f.name,
                s.label
            );
        }
    }
}

/// Homogeneous solid, ξ = 1: A/A0 = erf(√2 p0/E*) (notes.md).
fn homogeneous_area(e: f64) -> f64 {
    erf(2f64.sqrt() * figures::P0 / (e / 0.75))
}

/// Fig. 4: rubber limit for q0 d ≳ 2 (fractal) and ≳ 5 (Gaussian); for the Gaussian the steel
/// limit is reached for q0 d ≲ 0.005, for the fractal only for extremely small q0 d (not at
/// q0 d = 5e-4, the left end of the plot).
#[test]
fn fig04_limits() {
    let f = figures::fig04(13).unwrap();
    assert_finite(&f);
    let rubber = homogeneous_area(figures::E_RUBBER);
    let steel = homogeneous_area(figures::E_STEEL);
    // "≳": within 2.5 % (fractal, 2.1 % below at q0 d = 2) and 1 % (Gaussian, 0.6 % at 5).
    let stack = figures::rubber_on_steel(0.5, figures::D_FIG4).unwrap();
    let area_at = |s: coatcheck::psd::Spectrum| {
        coatcheck::contact::Engine::new(&s, Default::default())
            .evaluate(&stack, figures::P0, Default::default())
            .unwrap()
            .area_fraction
            .value
    };
    let q0 = |qd: f64| qd / figures::D_FIG4;
    let fractal_at_2 = area_at(figures::fractal(q0(2.0)).unwrap()) / rubber;
    let gaussian_at_5 = area_at(figures::gaussian(q0(5.0)).unwrap()) / rubber;
    eprintln!(
        "fig04 A/A_rubber: fractal at q0 d = 2 {fractal_at_2:.5}, Gaussian at 5 {gaussian_at_5:.5}"
    );
    assert!((fractal_at_2 - 1.0).abs() < 0.025 && (gaussian_at_5 - 1.0).abs() < 0.01);
    for (label, from, tol) in [("fractal", 2.0, 0.025), ("Gaussian", 5.0, 0.01)] {
        for (q0, a) in points(series(&f, label)) {
            let qd = q0 * figures::D_FIG4;
            eprintln!(
                "fig04 {label} q0d {qd:.3e} A {a:.6e} A/A_rubber {:.4} A/A_steel {:.4}",
                a / rubber,
                a / steel
            );
            if qd >= from {
                assert!((a / rubber - 1.0).abs() < tol, "{label} q0 d {qd}: {a}");
            }
            if label == "Gaussian" && qd <= 0.005 * (1.0 + 1e-9) {
                assert!((a / steel - 1.0).abs() < 0.02, "{label} q0 d {qd}: {a}");
            }
        }
    }
    for (_, a) in points(series(&f, "rubber")) {
        assert!((a / rubber - 1.0).abs() < 1e-12);
    }
    for (_, a) in points(series(&f, "steel")) {
        assert!((a / steel - 1.0).abs() < 1e-12);
    }
    let fractal = series(&f, "fractal");
    assert!(
        fractal.y[0] > 2.0 * steel,
        "steel limit reached at q0 d = 5e-4"
    );
    // Increasing in q0 up to the estimates (flat at the rubber limit).
    assert!(
        fractal
            .y
            .windows(2)
            .zip(fractal.err.windows(2))
            .all(|(w, e)| w[1] >= w[0] - e[0] - e[1])
    );
}

/// Fig. 5: ν = 0.49985 agrees with ν = 0.5 within 1 % for q0 d ≥ 0.3; for q0 d ≈ 0.01–0.03 the
/// slightly compressible film gives a clearly larger area (notes.md: 50–70 %).
#[test]
fn fig05_compressibility() {
    let f = figures::fig05(25).unwrap();
    assert_finite(&f);
    let (a, b) = (series(&f, "nu = 0.5"), series(&f, "nu = 0.49985"));
    let mut compared = (0, 0);
    for ((q0, inc), comp) in points(a).zip(&b.y) {
        let qd = q0 * figures::D_FIG4;
        let r = comp / inc;
        eprintln!("fig05 q0d {qd:.3e} ratio {r:.4}");
        if qd >= 0.3 {
            assert!((r - 1.0).abs() < 0.01, "q0 d {qd}: ratio {r}");
            compared.0 += 1;
        }
        if (0.01..=0.03).contains(&qd) {
            assert!(r > 1.4, "q0 d {qd}: ratio {r}");
            compared.1 += 1;
        }
    }
    assert!(compared.0 >= 10 && compared.1 >= 2, "{compared:?}");
}

/// ∫ y dx over a uniform grid with an odd number of points (Simpson's rule).
fn simpson(x: &[f64], y: &[f64]) -> f64 {
    assert!(x.len() % 2 == 1);
    let h = x[1] - x[0];
    let inner: f64 = y[1..y.len() - 1]
        .iter()
        .enumerate()
        .map(|(i, v)| if i % 2 == 0 { 4.0 * v } else { 2.0 * v })
        .sum();
    h / 3.0 * (y[0] + inner + y[y.len() - 1])
}

/// Fig. 6 (Sec. III and App. B): every distribution is normalised on [0, ∞); the normal stress
/// vanishes at σ = 0 (Persson's boundary condition); the top one is Persson's, whose mean over
/// the contact area is p0/(A/A0) (force balance; A/A0 ≈ 0.0927, notes.md); the interface normal
/// stress has a similar form with a smaller width; the shear stress is Gaussian centred at 0 with
/// τ_rms ≈ 0.133 MPa (notes.md), so P(0) = √(2/π)/τ_rms and ⟨τ²⟩ = τ_rms².
/// Also Fig. 6 against Fig. 7 by two independent routes: the top distribution's variance over the
/// whole nominal area (σ = 0 out of contact), A/A0·⟨σ²⟩_contact − p0², equals σ_rms(top)² of
/// eq. (B10). (Persson's P solves ∂P/∂G = ∂²P/∂σ² with P(0) = 0, so d⟨σ²⟩/dG = 2 P(q), and
/// (B10) at z = 0 is 2∫P dG.)
#[test]
fn fig06_distributions() {
    let f = figures::fig06(401).unwrap();
    let (top, sn, tau) = (
        series(&f, "sigma top"),
        series(&f, "sigma interface"),
        series(&f, "tau interface"),
    );
    let moment = |s: &Series, k: i32| {
        let y: Vec<f64> = points(s).map(|(x, y)| x.powi(k) * y).collect();
        simpson(&s.x, &y)
    };
    for s in [top, sn, tau] {
        let peak = s.y.iter().cloned().fold(0.0, f64::max);
        for (&y, &e) in s.y.iter().zip(&s.err) {
            assert!(y >= 0.0 && e.is_finite() && e <= 1e-6 * peak, "{}", s.label);
        }
        // Tails beyond 5 MPa are below 1e-7 (top), far below for the others.
        let norm = moment(s, 0);
        assert!((norm - 1.0).abs() < 1e-6, "{}: norm {norm}", s.label);
    }
    assert!(top.y[0] == 0.0 && sn.y[0] == 0.0);
    let c = coatcheck::contact::Engine::new(&figures::fractal(1e5).unwrap(), Default::default())
        .evaluate(
            &figures::rubber_on_steel(0.5, figures::D_FIG6).unwrap(),
            figures::P0,
            coatcheck::contact::Request {
                sigma_top: true,
                ..Default::default()
            },
        )
        .unwrap();
    let area = c.area_fraction.value;
    let sigma_top = c.sigma_rms_top.unwrap().value;
    let full_area_var = area * moment(top, 2) - figures::P0.powi(2);
    eprintln!(
        "fig06 full-area rms of the top distribution {:.7e}, sigma_rms top (B10) {sigma_top:.7e}",
        full_area_var.sqrt()
    );
    assert!((full_area_var / sigma_top.powi(2) - 1.0).abs() < 1e-5);
    assert!((area - 0.0927).abs() < 5e-4, "A/A0 {area}");
    let mean_top = moment(top, 1);
    assert!(
        (mean_top * area / figures::P0 - 1.0).abs() < 1e-5,
        "mean top {mean_top}, p0/A {}",
        figures::P0 / area
    );
    let var = |s: &Series| moment(s, 2) - moment(s, 1).powi(2);
    let tau_rms = (2.0 / std::f64::consts::PI).sqrt() / tau.y[0];
    eprintln!(
        "fig06 A {area:.5} norms {:.9} {:.9} {:.9} mean top {mean_top:.6e} p0/A {:.6e} \
         sd top {:.4e} sd interface {:.4e} tau_rms {tau_rms:.4e}",
        moment(top, 0),
        moment(sn, 0),
        moment(tau, 0),
        figures::P0 / area,
        var(top).sqrt(),
        var(sn).sqrt()
    );
    assert!(var(sn) < 0.1 * var(top), "{} {}", var(sn), var(top));
    assert!((tau_rms / 0.133e6 - 1.0).abs() < 4e-3, "tau_rms {tau_rms}");
    assert!((moment(tau, 2) / tau_rms.powi(2) - 1.0).abs() < 1e-6);
    assert!(tau.y.windows(2).all(|w| w[1] <= w[0]));
}

/// Fig. 7: interface stresses vanish for q0 d ≫ 1, where the normal and shear fluctuations become
/// the same; for q0 d ≲ 1/2 the interface normal stress is close to the top one, and with
/// decreasing thickness the shear rises more slowly than the normal stress; top σ_rms constant for
/// q0 d ≳ 2; at q0 d ≈ 5 (the paper's typical coating) the shear is strongly reduced from its
/// value at q0 d = 1; at d = 10 µm the notes' values.
#[test]
fn fig07_trends() {
    let f = figures::fig07(13).unwrap();
    assert_finite(&f);
    let top = series(&f, "sigma top");
    let sn = series(&f, "sigma interface");
    let tau = series(&f, "tau interface");
    let top_thick = *top.y.last().unwrap();
    for (i, &d) in top.x.iter().enumerate() {
        let qd = 1e5 * d;
        let (t, s, u) = (top.y[i], sn.y[i], tau.y[i]);
        eprintln!("fig07 q0d {qd:.3e} top {t:.4e} if {s:.4e} tau {u:.4e}");
        if qd >= 50.0 {
            assert!(s < 1e-15 * t && u < 1e-15 * t, "q0 d {qd}");
        }
        if qd <= 0.5 {
            assert!(s > 0.75 * t, "q0 d {qd}: {s} against top {t}");
        }
        if qd >= 2.0 {
            assert!((t / top_thick - 1.0).abs() < 0.02, "q0 d {qd}: top {t}");
        }
        if qd >= 20.0 {
            assert!((s / u - 1.0).abs() < 0.05, "q0 d {qd}: {s} against {u}");
        }
    }
    // Log-slopes against d between neighbouring points, where q0 d ≤ 1/2.
    let slope = |s: &Series, i: usize| (s.y[i + 1] / s.y[i]).ln() / (s.x[i + 1] / s.x[i]).ln();
    let mut compared = 0;
    for i in 0..top.x.len() - 1 {
        if 1e5 * top.x[i + 1] <= 0.5 {
            assert!(slope(sn, i) < slope(tau, i) - 0.3, "d {}", top.x[i]);
            compared += 1;
        }
    }
    assert!(compared >= 3);
    let at = |qd: f64| {
        top.x
            .iter()
            .position(|&d| (1e5 * d / qd - 1.0).abs() < 0.1)
            .unwrap()
    };
    assert!(tau.y[at(4.64)] < 0.1 * tau.y[at(1.0)]);
    let at_10um = top
        .x
        .iter()
        .position(|&d| (d / 1e-5 - 1.0).abs() < 1e-9)
        .unwrap();
    for (s, want) in [(top, 0.357e6), (sn, 0.222e6), (tau, 0.133e6)] {
        assert!((s.y[at_10um] / want - 1.0).abs() < 2e-3, "{}", s.label);
    }
}

/// Fig. 9: A/A0 linear in p0 at low load.
#[test]
fn fig09_linear_at_low_load() {
    let f = figures::fig09(11).unwrap();
    assert_finite(&f);
    for s in &f.series {
        let slope0 = s.y[0] / s.x[0];
        for (p, a) in points(s) {
            eprintln!(
                "fig09 {} p0 {p:.3e} A {a:.4e} A/p0 ratio {:.5}",
                s.label,
                a / p / slope0
            );
            if p <= 1e5 {
                assert!((a / p / slope0 - 1.0).abs() < 0.01, "{} p0 {p}", s.label);
            }
        }
        assert!(s.y.windows(2).all(|w| w[1] >= w[0]));
    }
}

/// Fig. 10: E_eff/E_R runs from E_S/E_R (q0 d → 0) down to 1 (q0 d → ∞).
#[test]
fn fig10_limits() {
    let f = figures::fig10(13).unwrap();
    assert_finite(&f);
    let s = &f.series[0];
    for (qd, e) in points(s) {
        eprintln!("fig10 q0d {qd:.3e} E_eff/E_R {e:.5e}");
    }
    assert!(s.y.windows(2).all(|w| w[1] <= w[0]));
    let ratio = figures::E_STEEL / figures::E_RUBBER;
    assert!(s.y[0] > 0.5 * ratio && s.y[0] <= ratio * (1.0 + 1e-9));
    assert!((s.y.last().unwrap() - 1.0).abs() < 1e-2);
}

/// Fig. 12: for decreasing thickness the Gaussian E_eff rises faster than the Gent disc's
/// 1 + (R/d)²/8 before saturating at E_S/E_R.
#[test]
fn fig12_gaussian_stiffens_faster_than_gent() {
    let f = figures::fig12(21).unwrap();
    assert_finite(&f);
    let g = series(&f, "Gaussian");
    let disc = series(&f, "Gent");
    let slope = |s: &Series, i: usize| (s.y[i + 1] / s.y[i]).ln() / (s.x[i + 1] / s.x[i]).ln();
    for i in 0..g.x.len() - 1 {
        eprintln!(
            "fig12 x {:.3e} gauss {:.4e} slope {:.3} gent {:.4e} slope {:.3}",
            g.x[i],
            g.y[i],
            slope(g, i),
            disc.y[i],
            slope(disc, i)
        );
    }
    // Where both rise steeply (0.03 ≤ x ≤ 0.3), the Gaussian log-slope is steeper.
    let mut compared = 0;
    for i in 0..g.x.len() - 1 {
        if g.x[i] >= 0.03 && g.x[i + 1] <= 0.3 {
            assert!(slope(g, i) < slope(disc, i) - 0.3, "x {}", g.x[i]);
            compared += 1;
        }
    }
    assert!(compared >= 3);
    // Saturation at E_S/E_R for small q0 d (both ν = 0.5, so E* ratio = E ratio).
    let saturated = figures::E_STEEL / figures::E_RUBBER;
    for (qd, e) in points(g) {
        assert!(e <= saturated * (1.0 + 1e-9));
        if qd <= 3.2e-3 {
            assert!(e > 0.99 * saturated, "q0 d {qd}: {e}");
        }
    }
}

/// Fig. 14: f and g nonzero only for small q (q d ≲ a few); notes.md values at q d = 1 and 10.
#[test]
fn fig14_only_small_q() {
    let f = figures::fig14(31).unwrap();
    assert_finite(&f);
    let (fs, gs) = (series(&f, "f"), series(&f, "g"));
    assert!((fs.y[0] - 0.80396367594).abs() < 1e-10 && (gs.y[0] - 0.45638307583).abs() < 1e-10);
    for (i, &q) in fs.x.iter().enumerate() {
        if q * 10e-6 >= 10.0 {
            assert!(fs.y[i] < 1e-3 && gs.y[i].abs() < 1e-3, "q {q}");
        }
    }
}

/// The examples' writer: the CSV holds every point in the axes' display units (d in µm, stress
/// in MPa) under a header naming them; the SVG has the axis titles, tick labels and legend; only
/// the two files are left in the output directory (the temporary files were renamed).
#[test]
fn figure_files() {
    use plotters::style::{BLUE, GREEN, RED};
    let fig = figures::fig07(5).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    let [csv_path, svg_path] =
        plot::write(&fig, &dir, &[RED, BLUE, GREEN], plot::Legend::UpperRight).unwrap();
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["fig07.csv", "fig07.svg"]);
    let mut r = csv::Reader::from_path(&csv_path).unwrap();
    assert_eq!(
        r.headers().unwrap(),
        vec![
            "series",
            "d [um]",
            "rms stress [MPa]",
            "rms stress [MPa] error"
        ]
    );
    let rows: Vec<csv::StringRecord> = r.records().map(|r| r.unwrap()).collect();
    assert_eq!(rows.len(), 15);
    let num = |s: &str| s.parse::<f64>().unwrap();
    for (row, (s, i)) in rows
        .iter()
        .zip(fig.series.iter().flat_map(|s| (0..5).map(move |i| (s, i))))
    {
        assert_eq!(&row[0], s.label);
        assert!((num(&row[1]) * 1e-6 / s.x[i] - 1.0).abs() < 1e-15);
        assert!((num(&row[2]) * 1e6 / s.y[i] - 1.0).abs() < 1e-15);
        assert!((num(&row[3]) * 1e6 / s.err[i] - 1.0).abs() < 1e-15);
    }
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    let texts: Vec<&str> = svg
        .split("</text>")
        .filter_map(|t| t.rsplit_once('>').map(|(_, text)| text.trim()))
        .collect();
    for text in [
        "d [um]",
        "rms stress [MPa]",
        "sigma top (z = 0)",
        "tau interface (z = d)",
        "1e-1",
        "1e3",
    ] {
        assert!(
            texts.contains(&text),
            "{text} missing from the SVG: {texts:?}"
        );
    }
}

/// The sliding figure (not in the paper): at μ = 0 the vector rule is the Rayleigh tail
/// τ_rms √(ln 1/ε) of Fig. 7's τ_rms; the peaks rise with μ at every d; at d = 1 mm the
/// fluctuation is screened and the peak is μ p0; the bond line is flat at 10 MPa.
#[test]
fn sliding_figure_limits() {
    let f = figures::sliding(5).unwrap();
    let tau = figures::fig07(5).unwrap();
    let tau = &tau.series[2];
    let k = (1e6f64).ln().sqrt();
    for (i, &d) in f.series[0].x.iter().enumerate() {
        let rayleigh = tau.y[i] * k;
        assert!(
            ((f.series[0].y[i] - rayleigh) / rayleigh).abs() < 1e-9,
            "d = {d}: {} vs {rayleigh}",
            f.series[0].y[i]
        );
        assert!(f.series[1].y[i] > f.series[0].y[i] && f.series[2].y[i] > f.series[1].y[i]);
        assert_eq!(f.series[3].y[i], figures::BOND_SLIDING_FIG);
    }
    let last = f.series[0].x.len() - 1;
    for (s, mu) in [(1, 0.5), (2, 1.0)] {
        let want = mu * figures::P0;
        assert!(((f.series[s].y[last] - want) / want).abs() < 1e-9);
    }
}
