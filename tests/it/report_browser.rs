//! The HTML report as a person sees it: rendered by headless Chromium (Debian's `chromium`)
//! into a PNG, which must not be blank, and the page's SVG plots must carry their titles, axis
//! titles and tick labels. Without Chromium the test says so and passes, unless
//! `COATCHECK_REQUIRE_CHROMIUM` is set (CI sets it, and installs Chromium).

use crate::common::run;
use std::path::{Path, PathBuf};
use std::process::Command;

fn chromium() -> Option<&'static str> {
    ["chromium", "chromium-browser", "google-chrome"]
        .into_iter()
        .find(|b| {
            Command::new(b)
                .arg("--version")
                .output()
                .is_ok_and(|o| o.status.success())
        })
}

/// Screenshot `html` into `png` at the given width and height (px).
fn screenshot(browser: &str, html: &Path, png: &Path, size: (u32, u32)) {
    let profile = tempfile::tempdir().unwrap();
    let out = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .arg(format!("--window-size={},{}", size.0, size.1))
        .arg(format!("--screenshot={}", png.display()))
        .arg(format!("file://{}", html.display()))
        .output()
        .unwrap();
    assert!(
        png.exists(),
        "no screenshot: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Share of pixels that differ from the most common colour (the background).
fn ink(png: &Path) -> f64 {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(png).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let bpp = info.color_type.samples();
    let pixels: Vec<&[u8]> = buf[..info.buffer_size()].chunks(bpp).collect();
    let mut counts = std::collections::HashMap::new();
    for p in &pixels {
        *counts.entry(p.to_vec()).or_insert(0usize) += 1;
    }
    let background = counts.values().max().copied().unwrap_or(0);
    1.0 - background as f64 / pixels.len() as f64
}

/// Chromium, or `None` when it is missing and not required (`COATCHECK_REQUIRE_CHROMIUM`).
fn required_chromium() -> Option<&'static str> {
    let browser = chromium();
    if browser.is_none() {
        assert!(
            std::env::var_os("COATCHECK_REQUIRE_CHROMIUM").is_none(),
            "Chromium is required here (COATCHECK_REQUIRE_CHROMIUM) but not found"
        );
        eprintln!("skipped: no Chromium on this machine");
    }
    browser
}

/// `check SCENE --report` into a temporary directory, the exit code one of `codes`: the
/// directory and the page.
fn report_page(scene: &str, codes: &[i32]) -> (tempfile::TempDir, PathBuf, String) {
    let dir = tempfile::tempdir().unwrap();
    let html = dir.path().join("report.html");
    let o = run(&["check", scene, "--report", html.to_str().unwrap()]);
    assert!(
        o.status.code().is_some_and(|c| codes.contains(&c)),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let page = std::fs::read_to_string(&html).unwrap();
    (dir, html, page)
}

/// The page rendered at `size` (px) is not blank.
fn renders_with_ink(browser: &str, dir: &Path, html: &Path, size: (u32, u32)) {
    let png = dir.join("report.png");
    screenshot(browser, html, &png, size);
    let share = ink(&png);
    assert!(share > 0.02, "the screenshot is almost blank ({share})");
}

#[test]
fn the_report_renders_with_its_plots_axes_and_labels() {
    let Some(browser) = required_chromium() else {
        return;
    };
    let (dir, html, page) = report_page("examples/paper-rubber-on-steel.toml", &[0]);
    for want in [
        "PASS",
        "Roughness power spectrum",
        "wavenumber q [1/m]",
        "C(q) [µm^4]",
        "Interface shear",
        "P(|tau| &gt; t)",
        "Utilisation (value / limit) against film thickness",
        "film thickness d [µm]",
        "d_min",
        "epsilon",
        "paper-rubber",
    ] {
        assert!(page.contains(want), "the page lacks '{want}'");
    }
    assert_eq!(page.matches("<svg").count(), 4, "four plots");
    for network in ["src=\"http", "href=\"http", "<script", "url(http"] {
        assert!(!page.contains(network), "the page loads {network}");
    }
    renders_with_ink(browser, dir.path(), &html, (1000, 4000));
}

/// A layer stack's report renders too: its interface table (every interface by name) and its
/// checks with their places are on the page, and the screenshot is not blank.
#[test]
fn a_stack_report_renders_with_its_interfaces() {
    let Some(browser) = required_chromium() else {
        return;
    };
    let (dir, html, page) = report_page("examples/rubber-epoxy-primer-steel.toml", &[0, 1]);
    for want in [
        "Interfaces (Persson",
        "τ_peak [MPa]",
        "<td>rubber</td>",
        "<td>primer</td>",
        "bond-shear at rubber",
        "bond-shear at primer",
        "substrate-yield at substrate",
        "Roughness power spectrum",
    ] {
        assert!(page.contains(want), "the page lacks '{want}'");
    }
    renders_with_ink(browser, dir.path(), &html, (1000, 3000));
}

/// `check SCENE --verify --report` with `extra` flags: the directory and the page.
fn verified_report_page(scene: &str, extra: &[&str]) -> (tempfile::TempDir, PathBuf, String) {
    let dir = tempfile::tempdir().unwrap();
    let html = dir.path().join("report.html");
    let mut args = vec![
        "check",
        scene,
        "--verify",
        "--report",
        html.to_str().unwrap(),
    ];
    args.extend(extra);
    let o = run(&args);
    assert!(
        matches!(o.status.code(), Some(0 | 1)),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let page = std::fs::read_to_string(&html).unwrap();
    (dir, html, page)
}

/// With `--verify` the report sets the exact d_min with its error (bracket and grid) beside
/// Persson's, every exact number with its grid error; for a scene given by a spectrum also the
/// realisations' spread and the share of the slope variance their grid cannot hold. Both pages
/// render (not blank).
#[test]
fn a_verified_report_shows_the_exact_d_min_and_the_realisation_spread() {
    let (dir, html, page) = verified_report_page("examples/height-map-film.toml", &[]);
    for want in [
        "Persson against the exact solution",
        "minimum thickness d_min",
        "(bracket ± ",
        ", grid ± ",
        "half and a quarter of the",
        "the exact solver at q_L d = ",
    ] {
        assert!(page.contains(want), "the map's page lacks '{want}'");
    }
    assert!(!page.contains("spread ±"), "a map has no realisations");
    let browser = required_chromium();
    if let Some(b) = browser {
        renders_with_ink(b, dir.path(), &html, (1000, 5000));
    }
    let (dir, html, page) = verified_report_page(
        "examples/waviness-thin-film.toml",
        &["--realisations", "2", "--realisation-grid", "32"],
    );
    for want in [
        "minimum thickness d_min",
        "spread ± ",
        "2 random-phase realisations",
        "32 x 32 grid",
        "of its slope variance lies above it",
    ] {
        assert!(page.contains(want), "the spectrum's page lacks '{want}'");
    }
    if let Some(b) = browser {
        renders_with_ink(b, dir.path(), &html, (1000, 5000));
    }
}

/// A stack's report with `--robust`: the robust verdict in the headline and the ranges, each
/// check at its worst corner and the d_min range among the uncertainty are on the page, and the
/// page renders (not blank).
#[test]
fn a_stack_report_renders_its_robust_section() {
    let dir = tempfile::tempdir().unwrap();
    let html = dir.path().join("report.html");
    let o = run(&[
        "check",
        "examples/rubber-epoxy-primer-steel.toml",
        "--robust",
        "--report",
        html.to_str().unwrap(),
    ]);
    assert!(
        matches!(o.status.code(), Some(0 | 1)),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let page = std::fs::read_to_string(&html).unwrap();
    for want in [
        "robust (worst corner of the materials&#39; ranges): ",
        "Materials: judged at the worst corner of the ranges layer[2].youngs_modulus 3.000 GPa \
         (2.400 GPa to 4.000 GPa)",
        "Utilisation of each check at its own worst corner: bond-shear at rubber ",
        "bond-shear at primer ",
        "d_min of layer &#39;rubber&#39; over the corners of the ranges: ",
    ] {
        assert!(page.contains(want), "the page lacks '{want}'");
    }
    let Some(browser) = required_chromium() else {
        return;
    };
    renders_with_ink(browser, dir.path(), &html, (1000, 3000));
}
