//! Plausibility of height data: magnitudes that make sense in SI (for files that state no
//! units), and whether data used as one period of a periodic surface join up at their edges.
//!
//! Edge mismatch: a periodic surface continues across its edges, so the height step from the
//! last column (row, point) to the first is one more step like those inside. The ratio of the
//! rms of those wrap-around steps to the rms of the interior neighbour steps is then about 1;
//! a measurement cut from a larger surface has steps across the edges of the order of h_rms,
//! far larger than its neighbour steps. Above [`EDGE_MISMATCH_WARN`] the data are reported as
//! not periodic: the periodic FFT (no window) then sees a jump at every edge, which adds a
//! spurious q^−2 (scans) or q^−3 (maps, radially averaged) tail to the spectrum.

use super::{HeightMap, Profile};
use crate::error::Error;
use std::path::Path;

/// The ratio of wrap-around to interior rms height steps above which data used as periodic
/// are reported as not periodic.
pub const EDGE_MISMATCH_WARN: f64 = 3.0;

/// Heights read as SI (no unit stated) are accepted with an rms within this range, m: from
/// atomically smooth to the roughest machined or cast surfaces.
pub const H_RMS_SI: (f64, f64) = (1e-11, 1e-2);
/// Sample spacings read as SI are accepted within this range, m.
pub const SPACING_SI: (f64, f64) = (1e-11, 1.0);

fn rms(steps: impl Iterator<Item = f64>) -> f64 {
    let (mut s, mut n) = (0.0, 0usize);
    for d in steps {
        s += d * d;
        n += 1;
    }
    (s / n.max(1) as f64).sqrt()
}

/// Wrap-around over interior rms steps of a map, along both axes together.
pub fn edge_mismatch_map(m: &HeightMap) -> f64 {
    let at = |ix: usize, iy: usize| m.z[iy * m.nx + ix];
    let interior = rms((0..m.ny)
        .flat_map(|iy| (1..m.nx).map(move |ix| at(ix, iy) - at(ix - 1, iy)))
        .chain((1..m.ny).flat_map(|iy| (0..m.nx).map(move |ix| at(ix, iy) - at(ix, iy - 1)))));
    let wrap = rms((0..m.ny)
        .map(|iy| at(0, iy) - at(m.nx - 1, iy))
        .chain((0..m.nx).map(|ix| at(ix, 0) - at(ix, m.ny - 1))));
    wrap / interior
}

/// Wrap-around over interior rms steps of line scans.
pub fn edge_mismatch_profile(p: &Profile) -> f64 {
    let interior = rms(p
        .scans
        .iter()
        .flat_map(|s| s.windows(2).map(|w| w[1] - w[0])));
    let wrap = rms(p.scans.iter().map(|s| s[0] - s[s.len() - 1]));
    wrap / interior
}

/// The warning for data of `path` used as periodic whose edges do not join (ratio from
/// [`edge_mismatch_map`] or [`edge_mismatch_profile`]).
pub fn periodic_warning(path: &Path, ratio: f64) -> Option<String> {
    (ratio > EDGE_MISMATCH_WARN).then(|| {
        format!(
            "{}: used as one period of a periodic surface, but its edges do not join: the rms \
             height step across the edges is {ratio:.2} times the rms step between neighbours \
             (above {EDGE_MISMATCH_WARN}); the periodic spectrum sees a jump at every edge \
             (drop periodic, or give a periodic map)",
            path.display()
        )
    })
}

/// Heights of a file that states no units, read as SI: a finite, non-zero rms or spacing
/// outside [`H_RMS_SI`] and [`SPACING_SI`] is an error that suggests the unit flags.
pub fn check_si(path: &Path, h_rms: f64, spacing: f64) -> Result<(), Error> {
    // Flat or non-finite heights are left to the spectrum's own errors, which say so.
    let inside =
        |v: f64, (lo, hi): (f64, f64)| !(v.is_finite() && v > 0.0) || (lo..=hi).contains(&v);
    if inside(h_rms, H_RMS_SI) && inside(spacing, SPACING_SI) {
        return Ok(());
    }
    Err(Error::Value {
        origin: path.display().to_string(),
        msg: format!(
            "the file states no units, and read as metres its heights have h_rms = {h_rms:.3e} m \
             (plausible: {:e} to {:e} m) and its spacing is {spacing:.3e} m (plausible: {:e} to \
             {:e} m); give the units: --z-unit um (heights), --dx 0.5um or --pixel-size 1um \
             (spacing), or roughness.z_unit in a scene",
            H_RMS_SI.0, H_RMS_SI.1, SPACING_SI.0, SPACING_SI.1
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn map(f: impl Fn(f64, f64) -> f64) -> HeightMap {
        let n = 32;
        HeightMap {
            nx: n,
            ny: n,
            dx: 1e-6,
            dy: 1e-6,
            z: (0..n * n)
                .map(|i| f((i % n) as f64 / n as f64, (i / n) as f64 / n as f64))
                .collect(),
            periodic: true,
        }
    }

    #[test]
    fn periodic_maps_join_and_tilted_ones_do_not() {
        // One period of a cosine: the wrap-around step is one interior step, ratio ≈ 1.
        let periodic = map(|x, y| (2.0 * PI * x).cos() + (2.0 * PI * 3.0 * y).sin());
        let r = edge_mismatch_map(&periodic);
        assert!((0.5..1.5).contains(&r), "{r}");
        assert!(periodic_warning(Path::new("p"), r).is_none());
        // A tilt: every interior step is 1/32 of the height range, the wrap-around step all of it.
        let tilted = map(|x, _| x);
        let r = edge_mismatch_map(&tilted);
        assert!(r > 10.0, "{r}");
        let w = periodic_warning(Path::new("t.csv"), r).unwrap();
        assert!(w.contains("t.csv") && w.contains(&format!("{r:.2}")), "{w}");
    }

    #[test]
    fn si_plausibility_bounds() {
        assert!(check_si(Path::new("a"), 1e-6, 1e-6).is_ok());
        // Heights in nm read as m: h_rms 1 mm... 1 km.
        let e = check_si(Path::new("a.csv"), 500.0, 1e-6)
            .unwrap_err()
            .to_string();
        assert!(e.contains("a.csv") && e.contains("--z-unit"), "{e}");
        assert!(check_si(Path::new("a"), 1e-6, 5.0).is_err());
    }
}
