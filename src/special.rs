//! erf(x) and e^{−x²} together, for the contact probability P = erf(p0/(2√G)) (eq. B11) and its
//! slope dP/dG at every quadrature node of a contact evaluation (`contact`). libm's erf (musl's:
//! above x = 1.25 two `exp`s and a rational function) and a separate `exp` for e^{−x²} took about
//! a fifth of an evaluation; here one `exp` at most.
//!
//! - x < [`SERIES_X`] = 1/4: both are ten-term Taylor series in t = x²,
//!   erf(x) = (2/√π) x Σ (−t)ⁿ/(n!(2n+1)), e^{−t} = Σ (−t)ⁿ/n! (the next terms are below 2.5e−19
//!   relative), evaluated by Estrin's scheme.
//! - [`SERIES_X`] ≤ x < [`TABLE_END`] = 6.25: e^{−x²} = e^{−h}(1 − l) with x² = h + l split exactly
//!   (Dekker's product), e^{−h} by [`exp_nonpositive`], and erfc(x) = e^{−x²} R(x), where
//!   R = e^{x²} erfc(x) is smooth and slowly varying
//!   (R → 1/(x√π)): degree-13 Chebyshev interpolants ([`crate::cheb`]) on panels 1/2 wide, built
//!   once from libm's erfc and e^{−x²} as above at the Chebyshev points (erfc to 3.4e−15
//!   relative, measured).
//!   Then erf = 1 − erfc: erfc ≤ 0.73 and erf ≥ 0.27 there, so no digits cancel.
//! - x ≥ [`TABLE_END`]: erf = 1 in f64 (erfc(6.25) = 1e−18), e^{−x²} as in the table's range.
//!
//! [`erf_and_gauss_many`] gives the same values for many x at once, in branch-free loops.
//!
//! Accuracy: within 3 ulp of libm's erf and exp over the series range and 1e−14 relative over
//! the table (tested on dense grids): far below the contact integrals' rounding floor
//! (`contact::ROUNDING_FLOOR`, 8e−13).

use crate::cheb::{Interpolation, N, nodes, poly};
use crate::simd::with_avx2;
use libm::erfc;
use std::sync::OnceLock;

/// Below this x the Taylor series are used.
pub const SERIES_X: f64 = 0.25;
/// Width of the table's panels in x.
const WIDTH: f64 = 0.5;
/// Number of table panels: [`SERIES_X`] to [`TABLE_END`].
const PANELS: usize = 12;
/// The table's upper end; above it erf = 1 in f64.
pub const TABLE_END: f64 = SERIES_X + WIDTH * PANELS as f64;

/// e^{−x²} to rounding for x ≥ 0: x² split exactly into h + l by Dekker's product (x in halves
/// of 26 bits by Veltkamp's split; no `fma`, which without the target feature is a call),
/// e^{−l} = 1 − l to O(l²) ≈ 1e−29, e^{−h} by [`exp_nonpositive`] (0 beyond h = 745).
#[inline(always)]
fn gauss(x: f64) -> f64 {
    let h = x * x;
    let c = 134_217_729.0 * x;
    let hi = c - (c - x);
    let lo = x - hi;
    let l = ((hi * hi - h) + 2.0 * hi * lo) + lo * lo;
    if h > 745.0 {
        0.0
    } else {
        exp_nonpositive(-h) * (1.0 - l)
    }
}

/// The Chebyshev interpolants of R(x) = e^{x²} erfc(x), one per panel.
fn table() -> &'static [[f64; N]; PANELS] {
    static TABLE: OnceLock<[[f64; N]; PANELS]> = OnceLock::new();
    TABLE.get_or_init(|| {
        let interp = Interpolation::new();
        let t = nodes();
        std::array::from_fn(|p| {
            let centre = SERIES_X + WIDTH * (p as f64 + 0.5);
            interp.coefficients(&std::array::from_fn(|j| {
                let x = centre + 0.5 * WIDTH * t[j];
                erfc(x) / gauss(x)
            }))
        })
    })
}

/// Which branch of [`erf_and_gauss`] serves x: the series, a table panel, or erf = 1.
#[derive(Clone, Copy, PartialEq)]
enum Branch {
    Series,
    Table(usize),
    One,
}

#[inline(always)]
fn branch(x: f64) -> Branch {
    if x < SERIES_X {
        Branch::Series
    } else if x < TABLE_END {
        Branch::Table((((x - SERIES_X) * (1.0 / WIDTH)) as usize).min(PANELS - 1))
    } else {
        Branch::One
    }
}

/// The table branch at x in panel p.
#[inline(always)]
fn tabulated(x: f64, p: usize, c: &[f64; N]) -> (f64, f64) {
    let s = (x - SERIES_X) * (1.0 / WIDTH);
    let g = gauss(x);
    (1.0 - g * poly(c, 2.0 * (s - p as f64) - 1.0), g)
}

/// erf(x) and e^{−x²} for x ≥ 0 (module doc).
#[inline]
pub fn erf_and_gauss(x: f64) -> (f64, f64) {
    match branch(x) {
        Branch::Series => series(x),
        Branch::Table(p) => tabulated(x, p, &table()[p]),
        Branch::One => (1.0, gauss(x)),
    }
}

/// [`erf_and_gauss`] at every x ≥ 0 of `x`, into `erf` and `gauss`, to the last bit: run by run
/// of consecutive points served by one branch (one table panel), so that the loop over a run
/// has no branches and is vectorised. Fastest when x is monotone, as at a contact evaluation's
/// nodes (G increases with q, x = p0/(2√G) decreases). AVX2 where the CPU has it (`crate::simd`).
pub fn erf_and_gauss_many(x: &[f64], erf: &mut [f64], gauss_out: &mut [f64]) {
    with_avx2!(
        erf_and_gauss_many_avx2(x, erf, gauss_out),
        erf_and_gauss_many_in(x, erf, gauss_out)
    )
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn erf_and_gauss_many_avx2(x: &[f64], erf: &mut [f64], gauss_out: &mut [f64]) {
    erf_and_gauss_many_in(x, erf, gauss_out);
}

#[inline(always)]
fn erf_and_gauss_many_in(x: &[f64], erf: &mut [f64], gauss_out: &mut [f64]) {
    let mut j = 0;
    while j < x.len() {
        let b = branch(x[j]);
        let len = x[j..]
            .iter()
            .position(|&v| branch(v) != b)
            .unwrap_or(x.len() - j);
        let r = j..j + len;
        let out = erf[r.clone()].iter_mut().zip(&mut gauss_out[r.clone()]);
        match b {
            Branch::Series => {
                for ((e, g), &v) in out.zip(&x[r]) {
                    (*e, *g) = series(v);
                }
            }
            Branch::Table(p) => {
                let c = &table()[p];
                for ((e, g), &v) in out.zip(&x[r]) {
                    (*e, *g) = tabulated(v, p, c);
                }
            }
            Branch::One => {
                for ((e, g), &v) in out.zip(&x[r]) {
                    (*e, *g) = (1.0, gauss(v));
                }
            }
        }
        j += len;
    }
}

/// The series branch (x < [`SERIES_X`]).
#[inline(always)]
fn series(x: f64) -> (f64, f64) {
    const E: [f64; 10] = [
        1.0,
        -1.0 / 3.0,
        1.0 / 10.0,
        -1.0 / 42.0,
        1.0 / 216.0,
        -1.0 / 1320.0,
        1.0 / 9360.0,
        -1.0 / 75600.0,
        1.0 / 685440.0,
        -1.0 / 6894720.0,
    ];
    const G: [f64; 10] = [
        1.0,
        -1.0,
        1.0 / 2.0,
        -1.0 / 6.0,
        1.0 / 24.0,
        -1.0 / 120.0,
        1.0 / 720.0,
        -1.0 / 5040.0,
        1.0 / 40320.0,
        -1.0 / 362880.0,
    ];
    let t = x * x;
    let t2 = t * t;
    let t4 = t2 * t2;
    let t8 = t4 * t4;
    let estrin = |c: &[f64; 10]| {
        let p = |i: usize| c[i] + c[i + 1] * t;
        (p(0) + t2 * p(2)) + t4 * (p(4) + t2 * p(6)) + t8 * p(8)
    };
    (
        std::f64::consts::FRAC_2_SQRT_PI * x * estrin(&E),
        estrin(&G),
    )
}

/// e^z for z in [−708, 0] without a branch or a call, so that a loop over many z is
/// vectorised (the layer kernels' e^{−2qd} at every node, `layer::KernelTable`): z = n ln 2 + r
/// with n = round(z/ln 2) (by adding 1.5·2⁵², which leaves n in the low bits), r = z − n ln 2 in
/// two parts (ln 2's high part has 11 trailing zero bits, so n·LN2_HI is exact), |r| ≤ ln 2 / 2,
/// e^r by its Taylor polynomial of degree 13 (the next term is below 1.3e−17 relative) in
/// Estrin's scheme, and 2ⁿ from its bits. Within 2 ulp of libm's exp (tested).
#[inline(always)]
pub fn exp_nonpositive(z: f64) -> f64 {
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    const LN2_HI: f64 = 0.693_147_180_369_123_8;
    const LN2_LO: f64 = 1.908_214_929_270_587_7e-10;
    const C: [f64; 14] = [
        1.0,
        1.0,
        1.0 / 2.0,
        1.0 / 6.0,
        1.0 / 24.0,
        1.0 / 120.0,
        1.0 / 720.0,
        1.0 / 5040.0,
        1.0 / 40_320.0,
        1.0 / 362_880.0,
        1.0 / 3_628_800.0,
        1.0 / 39_916_800.0,
        1.0 / 479_001_600.0,
        1.0 / 6_227_020_800.0,
    ];
    let shifted = z * std::f64::consts::LOG2_E + SHIFT;
    let n = shifted - SHIFT;
    let r = (z - n * LN2_HI) - n * LN2_LO;
    let bits = shifted.to_bits().wrapping_sub(SHIFT.to_bits());
    let scale = f64::from_bits(bits.wrapping_add(1023) << 52);
    poly(&C, r) * scale
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prec::EPS;
    use libm::erf;

    fn check(x: f64, erf_tol: f64, gauss_tol: f64) {
        let (e, g) = erf_and_gauss(x);
        let (e_ref, g_ref) = (erf(x), (-x * x).exp());
        assert!(
            (e - e_ref).abs() <= erf_tol * e_ref,
            "erf({x}): {e} vs libm {e_ref} ({:.1e})",
            (e / e_ref - 1.0).abs()
        );
        // libm's exp(−x²) itself carries fl(x²)'s rounding, up to 36 ulp relative near x = 6.
        let g_tol = gauss_tol + EPS * (x * x);
        assert!(
            (g - g_ref).abs() <= g_tol * g_ref,
            "exp(-{x}²): {g} vs libm {g_ref} ({:.1e})",
            (g / g_ref - 1.0).abs()
        );
    }

    /// The series against libm's erf and exp (each within 1 ulp) on 20001 points of [0, 1/4]
    /// and just below the switch: within 3 ulp relative.
    #[test]
    fn series_matches_libm() {
        let xs = (0..20_000)
            .map(|i| SERIES_X * f64::from(i) / 20_000.0)
            .chain((1..=50).map(|k| SERIES_X * (1.0 - f64::from(k) * EPS)));
        for x in xs {
            check(x, 3.0 * EPS, 3.0 * EPS);
        }
    }

    /// The table against libm on 200001 points of [1/4, 6.25] (between and on the panel ends),
    /// and beyond it: erf within 1e-14 relative (7.3e-15 measured, at x = 1/4 where erfc is
    /// largest), e^{−x²} within 3 ulp plus fl(x²)'s rounding in libm's own value.
    #[test]
    fn table_matches_libm() {
        let xs = (0..=200_000)
            .map(|i| SERIES_X + (TABLE_END - SERIES_X) * f64::from(i) / 200_000.0)
            .chain((0..=PANELS).map(|p| SERIES_X + WIDTH * p as f64))
            .chain([6.5, 7.0, 10.0, 26.0]);
        for x in xs {
            check(x, 1e-14, 3.0 * EPS);
        }
    }

    /// The branch-free exp against libm's (within 1 ulp) on 400001 points of [−708, 0] and
    /// near the rounding points of n = z/ln 2: within 2 ulp.
    #[test]
    fn exp_nonpositive_matches_libm() {
        let ln2 = std::f64::consts::LN_2;
        let zs = (0..=400_000)
            .map(|i| -708.0 * f64::from(i) / 400_000.0)
            .chain((0..1000).flat_map(|k| {
                let m = (f64::from(k) + 0.5) * ln2;
                [-m, -m * (1.0 + 4.0 * EPS), -m * (1.0 - 4.0 * EPS)]
            }));
        for z in zs {
            let (v, want) = (exp_nonpositive(z), z.exp());
            assert!(
                (v - want).abs() <= 2.0 * EPS * want,
                "exp({z}): {v} vs libm {want} ({:.1e})",
                (v / want - 1.0).abs()
            );
        }
    }

    /// The batched form gives the single-point values to the last bit: on points descending
    /// through every branch and panel (as at a contact evaluation's nodes), in a scrambled order,
    /// at the branch ends, 0 and ∞.
    #[test]
    fn batched_equals_single_points() {
        let mut xs: Vec<f64> = (0..3000)
            .map(|i| 30.0 * (1.0 - f64::from(i) / 3000.0).powi(3))
            .chain((0..=PANELS).map(|p| SERIES_X + WIDTH * p as f64))
            .chain([0.0, f64::INFINITY, 1e300, TABLE_END * (1.0 - EPS)])
            .collect();
        let n = xs.len();
        let scrambled: Vec<f64> = (0..n).map(|i| xs[(i * 7919) % n]).collect();
        xs.extend(scrambled);
        let (mut e, mut g) = (vec![0.0; xs.len()], vec![0.0; xs.len()]);
        erf_and_gauss_many(&xs, &mut e, &mut g);
        for (i, &x) in xs.iter().enumerate() {
            let (e1, g1) = erf_and_gauss(x);
            assert_eq!(e[i].to_bits(), e1.to_bits(), "erf({x})");
            assert_eq!(g[i].to_bits(), g1.to_bits(), "exp(-{x}²)");
        }
        assert_eq!(erf_and_gauss(f64::INFINITY), (1.0, 0.0));
        // The baseline build of the loop equals the dispatched one (AVX2 where available).
        let (mut eb, mut gb) = (vec![0.0; xs.len()], vec![0.0; xs.len()]);
        erf_and_gauss_many_in(&xs, &mut eb, &mut gb);
        assert!(e.iter().zip(&eb).all(|(a, b)| a.to_bits() == b.to_bits()));
        assert!(g.iter().zip(&gb).all(|(a, b)| a.to_bits() == b.to_bits()));
    }

    /// The interpolant of R = e^{x²} erfc(x) itself: e^{−x²}R against libm's erfc within 5e-15
    /// relative (3.4e-15 measured) over the table, where erf = 1 − erfc alone would hide erfc's
    /// error near x = 6.
    #[test]
    fn complement_matches_erfc() {
        for i in 0..=5000 {
            let x = SERIES_X + (TABLE_END - SERIES_X) * f64::from(i) / 5000.0;
            let (_, g) = erf_and_gauss(x);
            let s = (x - SERIES_X) / WIDTH;
            let p = (s as usize).min(PANELS - 1);
            let c = g * poly(&table()[p], 2.0 * (s - p as f64) - 1.0);
            let want = erfc(x);
            assert!((c / want - 1.0).abs() <= 5e-15, "erfc({x}): {c} vs {want}");
        }
    }
}
