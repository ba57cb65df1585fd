//! The low-octave warning quotes the exact/Persson ratios that the tool's own exact solver
//! measured (`coatcheck::check::regime`, committed as `src/check/regime.csv`): the figures in
//! the warning of a check without `--verify` are the table's, interpolated at the design's
//! q_L·d, and the table is what its generator (`examples/regime_table.rs`,
//! `coatcheck::verify::regime`) computes.

use crate::common::{json, run};
use coatcheck::bem::BemSettings;
use coatcheck::check::regime::{at, rows};
use coatcheck::topography::io::{MapOptions, read_height_map};
use coatcheck::verify::regime::row;
use std::path::Path;

/// The number after `before` in `text` (up to the next character that is not part of it).
fn number_after(text: &str, before: &str) -> f64 {
    let i = text
        .find(before)
        .unwrap_or_else(|| panic!("'{before}' in {text}"))
        + before.len();
    let end = text[i..]
        .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == 'e'))
        .map_or(text.len(), |j| i + j);
    text[i..end].parse().unwrap()
}

/// `check` on the bundled map's scene (2 µm rubber, q_L·d = 0.196, inside the table) warns
/// with the table's ratios at its q_L·d: each figure equals the interpolated value to the
/// rounding of the printed q_L·d and figures (four significant digits: within 0.5 %).
#[test]
fn the_warning_quotes_the_tables_ratios_at_the_designs_q_low_d() {
    let o = run(&["check", "examples/height-map-film.toml", "--format", "json"]);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{o:?}");
    let j = json(&o);
    let w = j["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|w| w.as_str())
        .find(|w| w.contains("lowest octave"))
        .expect("the low-octave warning")
        .to_string();
    let q = number_after(&w, "the exact solver at q_L d = ");
    assert!((q - 0.1963).abs() < 1e-4, "{w}");
    let (r, inside) = at(rows(), q);
    assert!(inside);
    for (what, want) in [
        ("found A/A0 ", r.area_ratio),
        ("tau peak ", r.tau_peak_ratio),
        ("sigma peak ", r.sigma_peak_ratio),
    ] {
        let got = number_after(&w, what);
        assert!(
            (got - want).abs() <= 5e-3 * want,
            "{what}: warning {got}, table {want} ({w})"
        );
    }
    assert!(w.contains("src/check/regime.csv"), "{w}");
    // Between the rows at 0.1 and 0.2, as the table interpolates.
    let t = rows();
    let (lo, hi) = (
        t.iter().find(|r| r.q_low_d == 0.1).unwrap(),
        t.iter().find(|r| r.q_low_d == 0.2).unwrap(),
    );
    let (a, b) = (
        lo.area_ratio.min(hi.area_ratio),
        lo.area_ratio.max(hi.area_ratio),
    );
    assert!((a..=b).contains(&r.area_ratio), "{r:?} {lo:?} {hi:?}");
}

/// Two rows of the committed table, recomputed by the generator, agree with it to 1e-6
/// relative (the table holds nine significant digits; parallel sums may round differently).
#[test]
fn the_table_is_reproducible_from_its_generator() {
    let opts = MapOptions {
        periodic: Some(true),
        ..MapOptions::default()
    };
    let map = read_height_map(Path::new("examples/data/height-map.csv"), &opts).unwrap();
    for q in [0.1, 0.5] {
        let table = rows().iter().find(|r| r.q_low_d == q).unwrap();
        let again = row(&map, q, &BemSettings::default()).unwrap();
        for (what, a, b) in [
            ("A/A0", again.area_ratio, table.area_ratio),
            ("tau peak", again.tau_peak_ratio, table.tau_peak_ratio),
            ("sigma peak", again.sigma_peak_ratio, table.sigma_peak_ratio),
        ] {
            assert!(
                (a - b).abs() <= 1e-6 * b,
                "q_L d = {q}, {what}: {a} vs table {b}"
            );
        }
    }
}
