//! Free boundaries (`coatcheck::bem::free`, `--boundary`): Hertz on a half-space with grid
//! refinement, a periodic map tiled 3 × 3 against the periodic solver on one tile, a peer
//! free-boundary half-space solver (ContactMechanics) on a cropped map, and the choice of the
//! boundary by the periodicity test.

use coatcheck::bem::free::{Solid, solve_free};
use coatcheck::bem::{self, BemSettings, Boundary, Surface};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::Termination;
use std::f64::consts::PI;

fn tight() -> BemSettings {
    BemSettings {
        gap_tol: 1e-10,
        max_iter: 5000,
        ..BemSettings::default()
    }
}

/// A paraboloid of radius `r` centred on the middle pixel of an odd n × n grid of pixel dx.
fn paraboloid(n: usize, dx: f64, r: f64) -> Surface {
    let c = (n / 2) as f64;
    let h = (0..n * n)
        .map(|i| {
            let (x, y) = (((i % n) as f64 - c) * dx, ((i / n) as f64 - c) * dx);
            -(x * x + y * y) / (2.0 * r)
        })
        .collect();
    Surface::new(h, n, n, dx, dx).unwrap()
}

/// Hertz: a = (3FR/(4E*))^(1/3), p_max = 3F/(2πa²). The contact radius from the pixel count,
/// √(A/π), and the centre pixel's pressure, on grids with a/dx = 8, 16, 32 (the window 4a wide).
/// Measured errors: radius 2.9 %, 0.54 %, 0.50 % (a pixel count: of order dx/a, not monotone
/// beyond); centre pressure 1.1e-3, 2.5e-4, 4.9e-5 (second order). Asserted: both below the
/// coarsest's, the pressure's decreasing, and at a/dx = 32 within 0.6 % and 1e-4.
#[test]
fn hertz_on_a_half_space_converges_with_refinement() {
    let (e_star, r) = (1e6, 1e-3);
    let a_hertz: f64 = 1e-4;
    let force = 4.0 * e_star * a_hertz.powi(3) / (3.0 * r);
    let p_max = 3.0 * force / (2.0 * PI * a_hertz * a_hertz);
    let mut errors = Vec::new();
    for per_a in [8usize, 16, 32] {
        let n = 4 * per_a + 1;
        let dx = a_hertz / per_a as f64;
        let s = paraboloid(n, dx, r);
        let window = (n as f64 * dx).powi(2);
        let sol = solve_free(
            &s,
            &Solid::HalfSpace { e_star },
            force / window,
            &tight(),
            None,
        )
        .unwrap();
        assert_eq!(sol.convergence.status, Termination::Converged);
        assert_eq!(sol.boundary, Boundary::Free);
        let contact = sol.pressure.iter().filter(|&&p| p > 0.0).count() as f64;
        let a = (contact * dx * dx / PI).sqrt();
        let p_c = sol.pressure[(n / 2) * n + n / 2];
        let total: f64 = sol.pressure.iter().sum::<f64>() * dx * dx;
        assert!((total - force).abs() < 1e-12 * force);
        let e = ((a / a_hertz - 1.0).abs(), (p_c / p_max - 1.0).abs());
        eprintln!(
            "a/dx = {per_a}: radius error {:.3e}, centre pressure error {:.3e}",
            e.0, e.1
        );
        errors.push(e);
    }
    assert!(errors[2].0 < errors[0].0 && errors[2].1 < errors[1].1 && errors[1].1 < errors[0].1);
    assert!(errors[2].0 < 6e-3 && errors[2].1 < 1e-4, "{errors:?}");
}

/// A periodic map (a few modes with integer wavenumbers on a 32² tile of 1 µm pixels) tiled
/// 3 × 3 and 5 × 5 and solved with free boundaries, against the periodic solver on one tile, for
/// a film on a hard substrate (its response is local, on the scale of d, so the edges' influence
/// on the central tile dies out). Measured: the central tile's mean pressure approaches p0 (at
/// 5 × 5 within 1.1 %, 0.27 %, 0.18 % for d = 4, 1, 0.3 µm, each below the 3 × 3 value); its
/// A/A0 equals the periodic one to the pixel for d = 1 and 0.3 µm and within 0.5 % (4 of 1024
/// pixels) for d = 4 µm = L/8; the pressure fields differ by 1–3.5 % of p0 rms, a difference
/// that does not shrink with more tiles (the two discretisations differ: pixel-constant
/// pressure with collocation here, trigonometric polynomials in the periodic solver).
#[test]
fn tiled_periodic_map_matches_the_periodic_solver_in_the_central_tile() {
    let (n, dx) = (32usize, 1e-6);
    let m = [(2e-7, 1, 2), (1.5e-7, 3, -1), (1e-7, 4, 5), (0.6e-7, -7, 3)];
    let tile: Vec<f64> = (0..n * n)
        .map(|i| {
            let (x, y) = ((i % n) as f64, (i / n) as f64);
            m.iter()
                .map(|&(a, kx, ky)| {
                    a * (2.0 * PI * (kx as f64 * x + ky as f64 * y) / n as f64).cos()
                })
                .sum()
        })
        .collect();
    let tiled = |k: usize| -> Surface {
        let h = (0..k * n * k * n)
            .map(|i| {
                let (x, y) = (i % (k * n), i / (k * n));
                tile[(y % n) * n + x % n]
            })
            .collect();
        Surface::new(h, k * n, k * n, dx, dx).unwrap()
    };
    let layers = Bilayer::new(
        Elastic::new(2e6, 0.4).unwrap(),
        Elastic::new(2e11, 0.3).unwrap(),
    );
    let p0 = 0.2e6;
    let area = |p: &[f64]| p.iter().filter(|&&v| v > 0.0).count() as f64 / p.len() as f64;
    let free = BemSettings {
        boundary: Boundary::Free,
        ..tight()
    };
    for (d, area_tol, mean_tol) in [
        (4e-6, 5e-3, 1.1e-2),
        (1e-6, 0.0, 2.7e-3),
        (3e-7, 0.0, 1.8e-3),
    ] {
        let stack = Stack::new(layers, d).unwrap();
        let one = Surface::new(tile.clone(), n, n, dx, dx).unwrap();
        let periodic = bem::solve(&one, &stack, p0, &tight()).unwrap();
        let mut means = Vec::new();
        for k in [3usize, 5] {
            let sol = bem::solve(&tiled(k), &stack, p0, &free).unwrap();
            assert_eq!(sol.convergence.status, Termination::Converged);
            let o = (k / 2) * n;
            let centre: Vec<f64> = (0..n * n)
                .map(|i| sol.pressure[(o + i / n) * k * n + o + i % n])
                .collect();
            let rms = (centre
                .iter()
                .zip(&periodic.pressure)
                .map(|(a, b)| (a - b) * (a - b))
                .sum::<f64>()
                / (n * n) as f64)
                .sqrt();
            let mean = centre.iter().sum::<f64>() / (n * n) as f64 / p0 - 1.0;
            let (a, a_per) = (area(&centre), area(&periodic.pressure));
            eprintln!(
                "d = {d:e}, {k} x {k}: A/A0 {a} (periodic {a_per}), rms dp / p0 {:.3e}, \
                 mean p / p0 - 1 {mean:.3e}",
                rms / p0
            );
            assert!(
                (a / a_per - 1.0).abs() <= area_tol,
                "d = {d:e}, {k}: {a} vs {a_per}"
            );
            assert!(rms < 0.035 * p0, "d = {d:e}, {k}: {rms:e}");
            means.push(mean.abs());
        }
        assert!(
            means[1] < means[0] && means[1] <= mean_tol,
            "d = {d:e}: {means:?}"
        );
    }
}

/// The example map's heights (128 × 128, 0.5 µm pixels), rows = y.
fn example_map() -> coatcheck::topography::HeightMap {
    use coatcheck::topography::io::{MapOptions, read_height_map};
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/data/height-map.csv");
    read_height_map(path.as_ref(), &MapOptions::default()).unwrap()
}

/// Rows `row0..row0 + n`, columns `col0..col0 + n` of the example map.
fn crop(row0: usize, col0: usize, n: usize) -> Surface {
    let m = example_map();
    let h = (0..n * n)
        .map(|i| m.z[(row0 + i / n) * m.nx + col0 + i % n])
        .collect();
    Surface::new(h, n, n, m.dx, m.dy).unwrap()
}

/// Against ContactMechanics' FreeFFTElasticHalfSpace on the 96² crop of the example map that
/// `tests/data/free_peer_ref.py` solved (`tests/data/free_peer_ref.csv`): A/A0 within 0.5 %.
#[test]
fn half_space_matches_the_peer_free_boundary_solver_on_a_cropped_map() {
    let text = include_str!("../data/free_peer_ref.csv");
    let s = crop(16, 24, 96);
    let e_star = 1e6 / (1.0 - 0.25);
    let mut rows = 0;
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let (p0, peer) = (v[0], v[1]);
        let sol = solve_free(&s, &Solid::HalfSpace { e_star }, p0, &tight(), None).unwrap();
        assert_eq!(sol.convergence.status, Termination::Converged);
        let a = sol.area_fraction.value;
        eprintln!("p0 = {p0}: A/A0 {a} vs peer {peer}: {:.3e}", a / peer - 1.0);
        assert!((a / peer - 1.0).abs() < 5e-3, "p0 = {p0}: {a} vs {peer}");
        rows += 1;
    }
    assert_eq!(rows, 2);
}

/// A map written as a plain CSV matrix (m) in a temporary directory.
fn write_map(dir: &std::path::Path, name: &str, s: &Surface) -> String {
    let text: String = s
        .heights
        .chunks(s.nx)
        .map(|row| {
            let cells: Vec<String> = row.iter().map(|h| format!("{h:e}")).collect();
            cells.join(",") + "\n"
        })
        .collect();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// `verify`'s JSON `boundary` for the map at `path` (0.5 µm pixels) with `extra` flags.
fn verify_boundary(path: &str, extra: &[&str]) -> serde_json::Value {
    let mut args = vec![
        "verify",
        path,
        "--film",
        "2MPa,0.5",
        "--substrate",
        "200GPa,0.3",
        "--thickness",
        "5um",
        "--pressure",
        "0.1MPa",
        "--pixel-size",
        "0.5um",
        "--format",
        "json",
    ];
    args.extend_from_slice(extra);
    let o = crate::common::run(&args);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    crate::common::json(&o)["boundary"].clone()
}

/// The default follows the periodicity test: the example map sampled at every fourth pixel (a
/// periodic 32² map) is solved periodic, a 40² crop of it free; an explicit `--boundary`
/// overrides the test, and the test's figure is reported either way.
#[test]
fn default_boundary_follows_the_periodicity_test() {
    let dir = tempfile::tempdir().unwrap();
    let m = example_map();
    let coarse: Vec<f64> = (0..32 * 32)
        .map(|i| m.z[(4 * (i / 32)) * m.nx + 4 * (i % 32)])
        .collect();
    let periodic = write_map(
        dir.path(),
        "periodic.csv",
        &Surface::new(coarse, 32, 32, 2e-6, 2e-6).unwrap(),
    );
    let cropped = write_map(dir.path(), "crop.csv", &crop(30, 50, 40));
    let b = verify_boundary(&periodic, &[]);
    assert_eq!(
        (b["kind"].as_str(), b["choice"].as_str()),
        (Some("periodic"), Some("auto"))
    );
    assert!(b["edge_mismatch"].as_f64().unwrap() < 3.0, "{b}");
    let b = verify_boundary(&cropped, &[]);
    assert_eq!(
        (b["kind"].as_str(), b["choice"].as_str()),
        (Some("free"), Some("auto"))
    );
    assert!(b["edge_mismatch"].as_f64().unwrap() > 3.0, "{b}");
    let b = verify_boundary(&cropped, &["--boundary", "periodic"]);
    assert_eq!(
        (b["kind"].as_str(), b["choice"].as_str()),
        (Some("periodic"), Some("periodic"))
    );
    let b = verify_boundary(&periodic, &["--boundary", "free"]);
    assert_eq!(
        (b["kind"].as_str(), b["choice"].as_str()),
        (Some("free"), Some("free"))
    );
}

/// A bad `--boundary` is refused with exit code 2, naming the value and the accepted ones, on
/// `verify` and on `check --verify`; on `check` it needs `--verify`.
#[test]
fn bad_boundary_values_exit_2() {
    let cases: [&[&str]; 3] = [
        &[
            "verify",
            "examples/data/height-map.csv",
            "--film",
            "2MPa,0.5",
            "--substrate",
            "200GPa,0.3",
            "--thickness",
            "5um",
            "--pressure",
            "0.1MPa",
            "--boundary",
            "sideways",
        ],
        &[
            "check",
            "examples/height-map-film.toml",
            "--verify",
            "--boundary",
            "Free!",
        ],
        &[
            "check",
            "examples/height-map-film.toml",
            "--boundary",
            "free",
        ],
    ];
    for (k, args) in cases.iter().enumerate() {
        let o = crate::common::run(args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains("--boundary"), "{err}");
        if k < 2 {
            assert!(
                err.contains(args[args.len() - 1]) && err.contains("auto, periodic, free"),
                "{err}"
            );
        } else {
            assert!(err.contains("--verify"), "{err}");
        }
    }
}
