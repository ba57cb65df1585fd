//! Boundary-element contact (`coatcheck::bem`): closed forms (Westergaard, Hertz/JGH, the
//! kernel's linear full-contact solution), the published κ ≈ 2 of half-space BEM studies with
//! grid refinement, and the layered kernel's limits (rigid base, identical materials).

use coatcheck::bem::{self, BemSettings, Surface};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::Termination;
use coatcheck::topography::synth::{Amplitude, SynthSpec, self_affine_map};
use std::f64::consts::PI;

const E_STAR: f64 = 1e6;

fn half_space(q: f64) -> f64 {
    2.0 / (q * E_STAR)
}

fn tight() -> BemSettings {
    BemSettings {
        gap_tol: 1e-10,
        max_iter: 2000,
        ..BemSettings::default()
    }
}

fn rubber_on_steel() -> Bilayer {
    Bilayer::new(
        Elastic::new(1e6, 0.5).unwrap(),
        Elastic::new(1e11, 0.3).unwrap(),
    )
}

/// A sum of cosine modes `(amplitude, kx, ky)` (integer wave numbers on an n × n grid of side l).
fn modes(n: usize, l: f64, m: &[(f64, i64, i64)]) -> Surface {
    let mut h = vec![0.0; n * n];
    for iy in 0..n {
        for ix in 0..n {
            h[iy * n + ix] = m
                .iter()
                .map(|&(a, kx, ky)| {
                    a * (2.0 * PI * (kx as f64 * ix as f64 + ky as f64 * iy as f64) / n as f64)
                        .cos()
                })
                .sum();
        }
    }
    Surface::new(h, n, n, l / n as f64, l / n as f64).unwrap()
}

fn line_sinusoid(n: usize, l: f64, a: f64) -> Surface {
    let h = (0..n)
        .map(|i| a * (2.0 * PI * i as f64 / n as f64).cos())
        .collect();
    Surface::new(h, n, 1, l / n as f64, l / n as f64).unwrap()
}

#[test]
fn sinusoid_full_contact_pressure_is_the_kernels_prediction() {
    // Above Westergaard's p* = π E* a/λ the contact is complete and p = p0 + a/K(q)·cos(qx).
    let (n, l, a) = (256, 1e-3, 1e-6);
    let s = line_sinusoid(n, l, a);
    let q = 2.0 * PI / l;
    let p_star = a / half_space(q);
    assert!((p_star - PI * E_STAR * a / l).abs() < 1e-12 * p_star);
    for ratio in [1.01, 1.5, 4.0] {
        let p0 = ratio * p_star;
        let sol = bem::solve_with_compliance(&s, half_space, p0, &tight()).unwrap();
        assert_eq!(sol.convergence.status, Termination::Converged);
        assert_eq!(sol.area_fraction.value, 1.0);
        for (i, p) in sol.pressure.iter().enumerate() {
            let want = p0 + p_star * (2.0 * PI * i as f64 / n as f64).cos();
            assert!(
                (p - want).abs() < 1e-9 * p_star,
                "p0/p* {ratio}, x {i}: {p} vs {want}"
            );
        }
        assert!(sol.convergence.load_error < 1e-14);
    }
}

#[test]
fn sinusoid_contact_width_matches_westergaard() {
    // Westergaard: the contact half-width a_c obeys sin²(π a_c/λ) = p0/p*, and inside it
    // p(x) = 2 p0 cos(πx/λ) √(sin²(πa_c/λ) − sin²(πx/λ)) / sin²(πa_c/λ).
    // Pixel counting resolves the width to a pixel at each edge; the pressure away from the
    // edges (≥ 3 pixels) to 2e-3 of its peak on 1024 pixels.
    let (n, l, a) = (1024, 1e-3, 1e-6);
    let s = line_sinusoid(n, l, a);
    let p_star = PI * E_STAR * a / l;
    for ratio in [0.01, 0.05, 0.1, 0.3, 0.6, 0.9, 0.99] {
        let p0 = ratio * p_star;
        let sol = bem::solve_with_compliance(&s, half_space, p0, &tight()).unwrap();
        assert_eq!(sol.convergence.status, Termination::Converged);
        let width = n as f64 * 2.0 / PI * ratio.sqrt().asin();
        let counted = sol.area_fraction.value * n as f64;
        assert!(
            (counted - width).abs() <= 2.0,
            "p0/p* {ratio}: {counted} pixels vs {width}"
        );
        let sa2 = ratio;
        let p_peak = 2.0 * p0 / sa2.sqrt();
        for (i, p) in sol.pressure.iter().enumerate() {
            let x = if i <= n / 2 {
                i as f64
            } else {
                i as f64 - n as f64
            };
            if x.abs() < width / 2.0 - 3.0 {
                let sx = (PI * x / n as f64).sin();
                let want = 2.0 * p0 / sa2 * (PI * x / n as f64).cos() * (sa2 - sx * sx).sqrt();
                assert!((p - want).abs() < 2e-3 * p_peak, "p0/p* {ratio}, x {x}");
            }
        }
    }
}

#[test]
fn single_wavelength_2d_surface_small_load_is_hertzian() {
    // Johnson, Greenwood & Higginson (1985): h = Δ cos(kx) cos(ky) has p* = √2 π E* Δ/λ; at
    // small p0/p* each of the two peaks per period carries F = p0 λ²/2 as a Hertz contact with
    // R = 1/(Δ k²): a³ = 3FR/(4E*), A/A0 = 2πa²/λ², p_max = 3F/(2πa²).
    let (n, l, delta) = (256, 1e-3, 1e-6);
    let h_modes = [(delta / 2.0, 1, 1), (delta / 2.0, 1, -1)];
    let s = modes(n, l, &h_modes);
    let k = 2.0 * PI / l;
    let p_star = 2f64.sqrt() * PI * E_STAR * delta / l;
    let mut last_pmax_err = f64::INFINITY;
    for ratio in [0.02, 0.01, 0.005, 0.002] {
        let p0 = ratio * p_star;
        let sol = bem::solve_with_compliance(&s, half_space, p0, &BemSettings::default()).unwrap();
        assert_eq!(sol.convergence.status, Termination::Converged);
        let f = p0 * l * l / 2.0;
        let r = 1.0 / (delta * k * k);
        let a = (3.0 * f * r / (4.0 * E_STAR)).cbrt();
        let area = 2.0 * PI * a * a / (l * l);
        let p_max = 3.0 * f / (2.0 * PI * a * a);
        let got = sol.area_fraction.value;
        let (area_err, pmax_err) = (got / area - 1.0, sol.contact_pressure.max / p_max - 1.0);
        // The peak pressure is smooth and converges to Hertz as the load falls (the periodic
        // neighbours' correction grows with p0/p*: 0.3 % at 0.002, 1.3 % at 0.02); the
        // pixel-counted area carries about half a pixel of rim on a radius of 11–24 pixels.
        assert!(
            pmax_err.abs() < 1.5e-2,
            "p0/p* {ratio}: p_max off Hertz by {pmax_err}"
        );
        assert!(
            pmax_err.abs() < last_pmax_err,
            "p0/p* {ratio}: not converging to Hertz"
        );
        last_pmax_err = pmax_err.abs();
        assert!(
            area_err.abs() < 6e-2,
            "p0/p* {ratio}: A/A0 off Hertz by {area_err}"
        );
    }
}

/// A self-affine surface (H = 0.8, no roll-off, q from the fundamental to 16 of it) sampled on
/// n × n pixels; every grid carries the same band-limited surface (the n = 256 map subsampled),
/// so refining the grid only refines the discretisation.
fn self_affine(n: usize) -> Surface {
    let fine = 256;
    let l = 1e-3;
    let q_l = 2.0 * PI / l;
    let map = self_affine_map(&SynthSpec {
        n: fine,
        dx: l / fine as f64,
        hurst: 0.8,
        q0: q_l,
        q1: 16.0 * q_l,
        amplitude: Amplitude::RmsSlope(0.1),
        seed: 11,
    })
    .unwrap();
    let step = fine / n;
    let mut h = Vec::with_capacity(n * n);
    for iy in 0..n {
        for ix in 0..n {
            h.push(map.z[iy * step * fine + ix * step]);
        }
    }
    Surface::new(h, n, n, l / n as f64, l / n as f64).unwrap()
}

#[test]
fn self_affine_small_load_area_is_linear_with_kappa_near_2() {
    // Half-space BEM studies of self-affine surfaces (Hyun et al. 2004; Campañá & Müser 2007;
    // Prodanov et al. 2014) find A/A0 = κ p0/(E* ξ) at small load with κ ≈ 2 (1.9–2.2
    // depending on H and resolution); Persson's theory gives √(8/π) ≈ 1.6. The spectral
    // discretisation over-counts the contact rim, so κ falls as the grid is refined: the
    // changes must shrink and the finest grid must sit in the published range.
    let loads = [0.01, 0.02];
    let mut kappa = Vec::new();
    for n in [64, 128, 256] {
        let s = self_affine(n);
        let xi = s.rms_slope();
        assert!(
            (xi - 0.1).abs() < 1e-12,
            "subsampling keeps the band-limited surface"
        );
        let row: Vec<f64> = loads
            .iter()
            .map(|&load| {
                let sol = bem::solve_with_compliance(
                    &s,
                    half_space,
                    load * E_STAR * xi,
                    &BemSettings::default(),
                )
                .unwrap();
                assert_eq!(sol.convergence.status, Termination::Converged);
                sol.area_fraction.value / load
            })
            .collect();
        kappa.push(row);
    }
    for j in 0..loads.len() {
        let (k64, k128, k256) = (kappa[0][j], kappa[1][j], kappa[2][j]);
        assert!(
            (k256 - k128).abs() < (k128 - k64).abs(),
            "load {}: {kappa:?}",
            loads[j]
        );
        assert!(
            (k256 - k128).abs() < 0.05 * k256,
            "load {}: {kappa:?}",
            loads[j]
        );
        assert!(
            (1.9..=2.2).contains(&k256),
            "load {}: kappa {k256}",
            loads[j]
        );
    }
    // Linear at small load: the two loads give the same κ within 5 %.
    assert!((kappa[2][0] / kappa[2][1] - 1.0).abs() < 0.05, "{kappa:?}");
}

/// Rigid-base closed form of eq. (7) (m = −1/κ, n = −κ, κ = 3 − 4ν; a classic result written
/// independently of `layer`): S = (κ sinh 2x − 2x) / (κ cosh 2x + (1 + κ²)/2 + 2x²).
fn s_rigid_base(nu: f64, x: f64) -> f64 {
    let k = 3.0 - 4.0 * nu;
    (k * (2.0 * x).sinh() - 2.0 * x) / (k * (2.0 * x).cosh() + 0.5 * (1.0 + k * k) + 2.0 * x * x)
}

#[test]
fn layered_full_contact_pressure_is_the_kernels_linear_prediction() {
    let (n, l) = (64, 1e-3);
    let d = 0.3 * l / (2.0 * PI); // q_L d = 0.3
    let layers = rubber_on_steel();
    let stack = Stack::new(layers, d).unwrap();
    let e0 = layers.film.e_star();
    let m = [(1e-6, 1, 0), (4e-7, 2, 3), (2e-7, 5, -4)];
    let s = modes(n, l, &m);
    // p = p0 + Σ a q E0*/(2 S(qd)) cos(q·x): the mode amplitudes of the pressure.
    let amps: Vec<f64> = m
        .iter()
        .map(|&(a, kx, ky)| {
            let q = 2.0 * PI / l * (kx as f64).hypot(ky as f64);
            a * q * e0 / (2.0 * layers.s(q * d))
        })
        .collect();
    let scale: f64 = amps.iter().sum();
    let p0 = 1.5 * scale;
    let sol = bem::solve(&s, &stack, p0, &tight()).unwrap();
    assert_eq!(sol.convergence.status, Termination::Converged);
    assert_eq!(sol.area_fraction.value, 1.0);
    for iy in 0..n {
        for ix in 0..n {
            let want = p0
                + m.iter()
                    .zip(&amps)
                    .map(|(&(_, kx, ky), p)| {
                        p * (2.0 * PI * (kx as f64 * ix as f64 + ky as f64 * iy as f64) / n as f64)
                            .cos()
                    })
                    .sum::<f64>();
            let got = sol.pressure[iy * n + ix];
            assert!(
                (got - want).abs() < 1e-9 * scale,
                "({ix}, {iy}): {got} vs {want}"
            );
        }
    }
}

#[test]
fn interface_fields_of_one_mode_match_the_tabulated_kernels() {
    // Rubber (1 MPa, ν 0.5) on steel (1e11 Pa, ν 0.5): S, f, g at qd = 0.1, 1, 10 from
    // notes.md (an independent 100-digit evaluation). A single oblique mode p = p0 + A cos(q·x)
    // gives σ_n(d) = p0 + f A cos(q·x) and τ = −g A sin(q·x) q̂.
    let table = [
        (0.1, 6.6488081104e-4, 0.99508591419, 0.098526500004),
        (1.0, 0.24059022762, 0.80396367594, 0.45638307583),
        (10.0, 0.99999908899, 9.9878763764e-4, 9.0798876490e-4),
    ];
    let layers = Bilayer::new(
        Elastic::new(1e6, 0.5).unwrap(),
        Elastic::new(1e11, 0.5).unwrap(),
    );
    let e0 = layers.film.e_star();
    let (n, l, a, kx, ky) = (32, 1e-3, 1e-7, 3i64, -2i64);
    let s = modes(n, l, &[(a, kx, ky)]);
    let qx = 2.0 * PI / l * kx as f64;
    let qy = 2.0 * PI / l * ky as f64;
    let q = qx.hypot(qy);
    for (qd, s_ref, f_ref, g_ref) in table {
        let stack = Stack::new(layers, qd / q).unwrap();
        let amp = a * q * e0 / (2.0 * s_ref);
        let p0 = 2.0 * amp;
        let sol = bem::solve(&s, &stack, p0, &tight()).unwrap();
        let fields = bem::interface_fields(&sol, &stack).unwrap();
        for iy in 0..n {
            for ix in 0..n {
                let i = iy * n + ix;
                let th = 2.0 * PI * (kx as f64 * ix as f64 + ky as f64 * iy as f64) / n as f64;
                let tol = 1e-8 * amp;
                assert!(
                    (sol.pressure[i] - p0 - amp * th.cos()).abs() < tol,
                    "qd {qd}: p"
                );
                assert!(
                    (fields.normal[i] - p0 - f_ref * amp * th.cos()).abs() < tol,
                    "qd {qd}"
                );
                let tau = -g_ref * amp * th.sin();
                assert!(
                    (fields.shear_x[i] - tau * qx / q).abs() < tol,
                    "qd {qd}: tau_x"
                );
                assert!(
                    (fields.shear_y[i] - tau * qy / q).abs() < tol,
                    "qd {qd}: tau_y"
                );
            }
        }
        // rms of the fluctuations: f A/√2 (normal), g A/√2 (|τ|).
        let rel = |x: f64, y: f64| (x - y).abs() / y;
        assert!(rel(fields.normal_stats.rms_dev, f_ref * amp / 2f64.sqrt()) < 1e-8);
        assert!(rel(fields.shear_stats.rms, g_ref * amp / 2f64.sqrt()) < 1e-8);
        assert!(rel(fields.normal_stats.mean, p0) < 1e-12);
        assert!(rel(fields.shear_stats.max, g_ref * amp) < 1e-8);
    }
}

#[test]
fn rigid_base_limit_matches_the_closed_form_kernel() {
    // A substrate 1e14 times stiffer than the film, against the rigid-base kernel in closed
    // form, at partial contact on a self-affine surface with q_L d = 0.5 (film ν = 0.45).
    let s = self_affine(64);
    let film = Elastic::new(1e6, 0.45).unwrap();
    let layers = Bilayer::new(film, Elastic::new(1e20, 0.3).unwrap());
    let d = 0.5 / s.q_low();
    let stack = Stack::new(layers, d).unwrap();
    let e0 = film.e_star();
    let p0 = 0.1 * e0 * s.rms_slope();
    let sol = bem::solve(&s, &stack, p0, &tight()).unwrap();
    let rigid = bem::solve_with_compliance(
        &s,
        |q| 2.0 * s_rigid_base(0.45, q * d) / (q * e0),
        p0,
        &tight(),
    )
    .unwrap();
    assert_eq!(sol.convergence.status, Termination::Converged);
    assert!(sol.area_fraction.value > 0.05 && sol.area_fraction.value < 0.9);
    assert_eq!(sol.area_fraction.value, rigid.area_fraction.value);
    let p_max = rigid.contact_pressure.max;
    for (a, b) in sol.pressure.iter().zip(&rigid.pressure) {
        assert!((a - b).abs() < 1e-7 * p_max, "{a} vs {b}");
    }
}

#[test]
fn identical_materials_are_the_half_space() {
    // Film = substrate: S = 1, f = (1 + qd) e^{−qd}, g = qd e^{−qd} (notes.md).
    let s = self_affine(64);
    let rubber = Elastic::new(1e6, 0.5).unwrap();
    let e0 = rubber.e_star();
    let d = 2.0 / s.q_low();
    let stack = Stack::new(Bilayer::new(rubber, rubber), d).unwrap();
    let p0 = 0.02 * e0 * s.rms_slope();
    let sol = bem::solve(&s, &stack, p0, &tight()).unwrap();
    let bulk = bem::solve_with_compliance(&s, |q| 2.0 / (q * e0), p0, &tight()).unwrap();
    assert_eq!(sol.area_fraction.value, bulk.area_fraction.value);
    let p_max = bulk.contact_pressure.max;
    for (a, b) in sol.pressure.iter().zip(&bulk.pressure) {
        assert!((a - b).abs() < 1e-9 * p_max);
    }
    let layered = bem::interface_fields(&sol, &stack).unwrap();
    let closed = bem::interface_fields_with(&bulk, |q| {
        let x = q * d;
        ((1.0 + x) * (-x).exp(), x * (-x).exp())
    })
    .unwrap();
    let scale = layered.shear_stats.max.max(layered.normal_stats.max);
    for i in 0..s.len() {
        assert!((layered.normal[i] - closed.normal[i]).abs() < 1e-9 * scale);
        assert!((layered.shear_x[i] - closed.shear_x[i]).abs() < 1e-9 * scale);
        assert!((layered.shear_y[i] - closed.shear_y[i]).abs() < 1e-9 * scale);
    }
    assert!(layered.shear_stats.rms > 0.0);
}

fn verify(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_coatcheck"))
        .arg("verify")
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn cli_verify_reports_json_writes_fields_and_maps_exit_codes() {
    let dir = std::env::temp_dir().join(format!("coatcheck-bem-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A 16 x 8 map of one sinusoid along x, heights in µm, pixel size from the flag.
    let map = dir.join("map.csv");
    let (nx, ny, a_um, pixel) = (16usize, 8usize, 0.1, 1e-6);
    let mut text = String::from("# a sinusoid\n");
    for _ in 0..ny {
        let row: Vec<String> = (0..nx)
            .map(|i| format!("{}", a_um * (2.0 * PI * i as f64 / nx as f64).cos()))
            .collect();
        text.push_str(&row.join(","));
        text.push('\n');
    }
    std::fs::write(&map, text).unwrap();
    let fields = dir.join("fields.csv");
    let base = [
        map.to_str().unwrap(),
        "--film",
        "1MPa,0.5",
        "--substrate",
        "1MPa,0.5",
        "--thickness",
        "2um",
        "--pixel-size",
        "1um",
        "--height-unit",
        "um",
    ];
    // Full contact: p* = π E* a/λ (E* = 4/3 MPa for ν = 0.5); at p0 = 2p* the exact rms of
    // p − p0 is p*/√2.
    let e_star = 1e6 / 0.75;
    let p_star = PI * e_star * a_um * 1e-6 / (nx as f64 * pixel);
    let p0 = format!("{}", 2.0 * p_star);
    let mut args = base.to_vec();
    args.extend(["--pressure", &p0, "--format", "json", "--fields"]);
    args.push(fields.to_str().unwrap());
    let out = verify(&args);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["area_fraction"].as_f64(), Some(1.0));
    assert_eq!(v["solver"]["status"].as_str(), Some("converged"));
    let rms = v["sigma_rms_top_pa"].as_f64().unwrap();
    assert!((rms / (p_star / 2f64.sqrt()) - 1.0).abs() < 1e-8, "{rms}");
    let written = std::fs::read_to_string(&fields).unwrap();
    assert_eq!(written.lines().count(), 1 + nx * ny);
    assert!(written.starts_with("x_m,y_m,height_m,pressure_pa"));

    // A bond strength below the interface shear: exit 1; far above: exit 0.
    for (bond, code) in [("1Pa", 1), ("1GPa", 0)] {
        let mut args = base.to_vec();
        args.extend(["--pressure", &p0, "--bond-strength", bond]);
        assert_eq!(verify(&args).status.code(), Some(code), "bond {bond}");
    }

    // Bad input: exit 2, one line naming the file and line, no fields file.
    let bad = dir.join("bad.csv");
    std::fs::write(&bad, "0,1,2\n0,1\n").unwrap();
    let bad_fields = dir.join("bad-fields.csv");
    let mut args = base.to_vec();
    args[0] = bad.to_str().unwrap();
    args.extend([
        "--pressure",
        "1kPa",
        "--fields",
        bad_fields.to_str().unwrap(),
    ]);
    let out = verify(&args);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad.csv:2"), "{err}");
    assert!(!bad_fields.exists());
    let mut args = base.to_vec();
    args[2] = "1MPa";
    args.extend(["--pressure", "1kPa"]);
    let out = verify(&args);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--film"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn converges_to_an_admissible_solution_across_thickness_and_load() {
    // Thin films make the kernel stiff at long wavelengths (ill-conditioned); the solution
    // must still satisfy p ≥ 0, mean p0, gap ≥ −tol off contact and rms gap ≤ tol in contact.
    let s = self_affine(64);
    let layers = rubber_on_steel();
    let e0 = layers.film.e_star();
    for qld in [0.05, 0.5, 5.0] {
        let stack = Stack::new(layers, qld / s.q_low()).unwrap();
        for load in [0.003, 0.03, 0.3] {
            let p0 = load * e0 * s.rms_slope();
            let sol = bem::solve(&s, &stack, p0, &BemSettings::default()).unwrap();
            let c = sol.convergence;
            assert_eq!(c.status, Termination::Converged, "qLd {qld}, load {load}");
            assert!(c.load_error < 1e-12);
            let mean = sol.pressure.iter().sum::<f64>() / s.len() as f64;
            assert!((mean / p0 - 1.0).abs() < 1e-12);
            for (p, g) in sol.pressure.iter().zip(&sol.gap) {
                assert!(
                    *p >= 0.0 && (*p > 0.0 || *g >= -c.tolerance),
                    "qLd {qld}, load {load}: p {p}, g {g}, tol {}",
                    c.tolerance
                );
            }
            let in_contact: Vec<f64> = sol
                .pressure
                .iter()
                .zip(&sol.gap)
                .filter(|(p, _)| **p > 0.0)
                .map(|(_, g)| g * g)
                .collect();
            let rms = (in_contact.iter().sum::<f64>() / in_contact.len() as f64).sqrt();
            assert!(rms <= c.tolerance, "qLd {qld}, load {load}");
        }
    }
}

#[test]
fn coarse_to_fine_start_converges_to_the_cold_solution() {
    // A 512² cold solve starts from the solution on the 256² map; started from the full
    // contact instead (a uniform warm start), it must reach the same solution to the solver
    // tolerance, in more iterations.
    let n = 512;
    let l = 1e-3;
    let q_l = 2.0 * PI / l;
    let map = self_affine_map(&SynthSpec {
        n,
        dx: l / n as f64,
        hurst: 0.8,
        q0: q_l,
        q1: 64.0 * q_l,
        amplitude: Amplitude::RmsSlope(0.1),
        seed: 1,
    })
    .unwrap();
    let s = Surface::from_height_map(&map).unwrap();
    let layers = rubber_on_steel();
    let stack = Stack::new(layers, 1.0 / s.q_low()).unwrap();
    let p0 = 0.035 * layers.film.e_star() * 0.1;
    let settings = BemSettings::default();
    let fast = bem::solve(&s, &stack, p0, &settings).unwrap();
    let cold = bem::solve_from(&s, &stack, p0, &settings, &vec![p0; s.len()]).unwrap();
    let (cf, cc) = (fast.convergence, cold.convergence);
    assert_eq!(cf.status, Termination::Converged);
    assert_eq!(cc.status, Termination::Converged);
    assert!(
        cf.iterations < cc.iterations,
        "{} vs {}",
        cf.iterations,
        cc.iterations
    );
    let tol = cf.tolerance;
    let mut differ = 0;
    let pairs = fast.pressure.iter().zip(&fast.gap);
    for (i, ((pf, gf), (pc, gc))) in pairs.zip(cold.pressure.iter().zip(&cold.gap)).enumerate() {
        if (*pf > 0.0) != (*pc > 0.0) {
            differ += 1;
            // In contact in one and not in the other: a pixel at the edge of the contact,
            // within the tolerance of touching in both.
            let gap = if *pf > 0.0 { gc } else { gf };
            assert!(
                gap.abs() <= 10.0 * tol,
                "pixel {i}: gap {gap:e}, tol {tol:e}"
            );
        }
    }
    let a = fast.area_fraction;
    let area_diff = (a.value - cold.area_fraction.value).abs();
    eprintln!(
        "iterations {} vs {}, {differ} pixels differ, A/A0 {} vs {} (err {:e})",
        cf.iterations, cc.iterations, a.value, cold.area_fraction.value, a.err
    );
    assert!(area_diff <= a.err + cold.area_fraction.err, "{area_diff:e}");
    let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt();
    let dp: Vec<f64> = fast
        .pressure
        .iter()
        .zip(&cold.pressure)
        .map(|(a, b)| a - b)
        .collect();
    eprintln!("rms pressure difference / p0 {:e}", rms(&dp) / p0);
}

#[test]
fn preconditioned_solution_meets_the_contact_conditions_with_an_independent_influence_matrix() {
    // The solver's own gap comes from its FFT convolution; here the displacement of the returned
    // pressure is recomputed by direct sums: the periodic influence function
    // G(x) = (1/N) Σ_{q ≠ 0} K(q) cos(q·x), then u = Σ_j p_j G(x − x_j). The contact conditions
    // must hold with it to the solver tolerance: rms gap on the contact set and largest
    // penetration off it both ≤ tol, p ≥ 0 with mean p0.
    let n = 64;
    let s = self_affine(n);
    let (l, _) = s.lengths();
    let layers = rubber_on_steel();
    let e0 = layers.film.e_star();
    for qld in [0.1, 1.0] {
        let d = qld / s.q_low();
        let stack = Stack::new(layers, d).unwrap();
        let compliance = |q: f64| 2.0 * layers.s(q * d) / (q * e0);
        let p0 = 0.03 * e0 * s.rms_slope();
        let sol = bem::solve(&s, &stack, p0, &BemSettings::default()).unwrap();
        let c = sol.convergence;
        assert_eq!(c.status, Termination::Converged);
        let nn = n * n;
        let wrap = |k: usize| {
            if k <= n / 2 {
                k as f64
            } else {
                k as f64 - n as f64
            }
        };
        let mut green = vec![0.0; nn];
        for ky in 0..n {
            for kx in 0..n {
                if kx == 0 && ky == 0 {
                    continue;
                }
                let kq = compliance(2.0 * PI / l * wrap(kx).hypot(wrap(ky))) / nn as f64;
                for (i, gi) in green.iter_mut().enumerate() {
                    let phase = (kx * (i % n) + ky * (i / n)) % n;
                    *gi += kq * (2.0 * PI * phase as f64 / n as f64).cos();
                }
            }
        }
        let mut u = vec![0.0; nn];
        for (j, pj) in sol.pressure.iter().enumerate().filter(|(_, p)| **p > 0.0) {
            let (xj, yj) = (j % n, j / n);
            for (i, ui) in u.iter_mut().enumerate() {
                let (x, y) = ((i % n + n - xj) % n, (i / n + n - yj) % n);
                *ui += pj * green[y * n + x];
            }
        }
        let mean_h = s.mean();
        let contact: Vec<usize> = (0..nn).filter(|&i| sol.pressure[i] > 0.0).collect();
        let gbar = contact
            .iter()
            .map(|&i| u[i] - (s.heights[i] - mean_h))
            .sum::<f64>()
            / contact.len() as f64;
        let gap = |i: usize| u[i] - (s.heights[i] - mean_h) - gbar;
        let rms =
            (contact.iter().map(|&i| gap(i).powi(2)).sum::<f64>() / contact.len() as f64).sqrt();
        let pen = (0..nn)
            .filter(|&i| sol.pressure[i] == 0.0)
            .map(|i| -gap(i))
            .fold(0.0f64, f64::max);
        let tol = c.tolerance;
        eprintln!(
            "qLd {qld}: {} iterations, rms gap {:e} tol, penetration {:e} tol",
            c.iterations,
            rms / tol,
            pen / tol
        );
        assert!(
            rms <= 1.001 * tol,
            "qLd {qld}: rms gap {rms:e}, tol {tol:e}"
        );
        assert!(
            pen <= 1.001 * tol,
            "qLd {qld}: penetration {pen:e}, tol {tol:e}"
        );
        assert!(sol.pressure.iter().all(|p| *p >= 0.0));
        let mean = sol.pressure.iter().sum::<f64>() / nn as f64;
        assert!((mean / p0 - 1.0).abs() < 1e-12);
    }
}
