//! The periodic solver's element-wise work, fused into as few passes over memory as possible.
//!
//! On a large grid every field is bigger than the cache, so each pass over a field costs a
//! stream from main memory; the conjugate-gradient iteration of [`super::solve_from_dyn`] is
//! bound by those streams, not by arithmetic. Its element-wise steps are therefore done row by
//! row inside the passes that already read or write the fields: the gap's statistics where the
//! displacement is formed (the inverse row pass of its convolution, or the incremental update),
//! the masked gap in the forward row pass of the preconditioner's convolution and its products
//! in that convolution's inverse row pass (`precond`), the new direction in the forward row pass
//! of its own convolution, and the step's denominator in that convolution's inverse row pass.
//!
//! Conventions: `graw = u − h` is stored; the gap is g = graw − ḡ with ḡ the mean of graw on the
//! contact set (`contact[i]` ⇔ p_i > 0), applied where g is read. Sums are formed per grid row
//! and combined in row order, so they do not depend on the thread count. The statistics about ḡ
//! are combined from per-row means with the pairwise formula of Chan, Golub & LeVeque (Am. Stat.
//! 37, 1983, 242–247): Σ (x − x̄)² = Σ_rows [Σ_row (x − x̄_row)² + n_row (x̄_row − x̄)²], whose
//! terms are all non-negative, so no large nearly equal numbers are subtracted.

use super::fft::{Fft2, Real};
use super::{Changes, SPARSE_MAX};
use rayon::prelude::*;
use rustfft::num_complex::Complex;

/// Per-row gap statistics, see [`gap_row`].
pub(super) type GapRow = [f64; 7];

/// One row's gap statistics from its `graw = u − h`, contact flags and previous direction
/// `t`: [n, Σ graw, Σ (graw − m)², Σ (graw − m) t, Σ t, Σ (graw − m)] over the row's contact
/// points (m their computed mean graw, 0 if there are none; the last sum is m's rounding error
/// times −n, kept so that the combination is exact for the m used) and the smallest graw off
/// contact (+∞ if none). The row is in
/// cache, so its second loop costs no memory traffic.
pub(super) fn gap_row(graw: &[f64], contact: &[bool], t: &[f64]) -> GapRow {
    let (mut n, mut s, mut sum_t, mut low) = (0.0, 0.0, 0.0, f64::INFINITY);
    for ((g, c), ti) in graw.iter().zip(contact).zip(t) {
        if *c {
            n += 1.0;
            s += g;
            sum_t += ti;
        } else {
            low = low.min(*g);
        }
    }
    let m = if n > 0.0 { s / n } else { 0.0 };
    let (mut m2, mut gt, mut e) = (0.0, 0.0, 0.0);
    for ((g, c), ti) in graw.iter().zip(contact).zip(t) {
        if *c {
            let d = g - m;
            m2 += d * d;
            gt += d * ti;
            e += d;
        }
    }
    [n, s, m2, gt, sum_t, low, e]
}

/// The gap's statistics over the grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct GapSums {
    /// Contact points (at least 1).
    pub n_c: f64,
    /// ḡ: the mean of graw on the contact set.
    pub gbar: f64,
    /// Σ_c g².
    pub g2: f64,
    /// Largest penetration −g off the contact set (≥ 0).
    pub pen: f64,
    /// Σ_c g·t with the previous direction t.
    pub gt: f64,
}

impl GapSums {
    /// Combine the rows' [`gap_row`] statistics (in row order).
    pub(super) fn of(rows: &[GapRow]) -> Self {
        let (mut n_c, mut s, mut low) = (0.0, 0.0, f64::INFINITY);
        for row in rows {
            n_c += row[0];
            s += row[1];
            low = low.min(row[5]);
        }
        let n_c = f64::max(n_c, 1.0);
        let gbar = s / n_c;
        let (mut g2, mut gt) = (0.0, 0.0);
        for row in rows.iter().filter(|row| row[0] > 0.0) {
            let d = row[1] / row[0] - gbar;
            g2 += row[2] + (2.0 * row[6] + row[0] * d) * d;
            gt += row[3] + d * row[4];
        }
        Self {
            n_c,
            gbar,
            g2,
            pen: f64::max(gbar - low, 0.0),
            gt,
        }
    }
}

/// t ← (v − v̄) + β t on the row's contact points (0 elsewhere): v is the preconditioned gap z
/// with its contact-set mean v̄ = z̄ in the solver (and graw with ḡ, i.e. the gap, unpreconditioned);
/// returns [Σ t].
pub(super) fn direction_row(
    t: &mut [f64],
    v: &[f64],
    contact: &[bool],
    vbar: f64,
    beta: f64,
) -> [f64; 1] {
    let mut sum_t = 0.0;
    for ((ti, vi), c) in t.iter_mut().zip(v).zip(contact) {
        if *c {
            *ti = (vi - vbar) + beta * *ti;
            sum_t += *ti;
        } else {
            *ti = 0.0;
        }
    }
    [sum_t]
}

/// The row's part of the step's denominator Σ_c r (t − t̄) (see [`super::step_denominator`]).
pub(super) fn denominator_row(r: &[f64], t: &[f64], contact: &[bool], tbar: f64) -> [f64; 1] {
    let mut den = 0.0;
    for ((ri, ti), c) in r.iter().zip(t).zip(contact) {
        if *c {
            den += ri * (ti - tbar);
        }
    }
    [den]
}

/// p ← ps·p − step·t on the contact set, projected to p ≥ 0, with penetrating points
/// (g = graw − ḡ < 0) re-admitted at −readmit·g, and `contact` (if given) set to p > 0; returns
/// Σ p, the number of points clamped or re-admitted and, if there are at most [`SPARSE_MAX`],
/// those points with their change beyond the linear update ps·p − step·t (t is 0 off the
/// contact set), in index order.
pub(super) fn project(
    p: &mut [f64],
    contact: Option<&mut [bool]>,
    (ps, step, readmit): (f64, f64, f64),
    t: &[f64],
    graw: &[f64],
    gbar: f64,
) -> (f64, usize, Option<Changes>) {
    const CHUNK: usize = super::PAR_CHUNK;
    let flags: Vec<Option<&mut [bool]>> = match contact {
        Some(c) => c.chunks_mut(CHUNK).map(Some).collect(),
        None => (0..p.len().div_ceil(CHUNK)).map(|_| None).collect(),
    };
    let parts: Vec<(f64, Changes, bool, usize)> = p
        .par_chunks_mut(CHUNK)
        .zip(flags)
        .enumerate()
        .map(|(c, (pc, mut fc))| {
            let o = c * CHUNK;
            let (mut total, mut changes, mut many, mut moved) = (0.0, Vec::new(), false, 0);
            for (k, (pi, (ti, gr))) in pc.iter_mut().zip(t[o..].iter().zip(&graw[o..])).enumerate()
            {
                *pi *= ps;
                let linear = *pi - step * ti;
                let mut changed = false;
                if *pi > 0.0 {
                    if linear <= 0.0 {
                        changed = true;
                        *pi = 0.0;
                    } else {
                        *pi = linear;
                    }
                }
                let gi = gr - gbar;
                if *pi == 0.0 && gi < 0.0 {
                    *pi = -readmit * gi;
                    changed = true;
                }
                if changed {
                    moved += 1;
                    if !many {
                        changes.push((o + k, *pi - linear));
                        many = changes.len() > SPARSE_MAX;
                    }
                }
                if let Some(fc) = fc.as_deref_mut() {
                    fc[k] = *pi > 0.0;
                }
                total += *pi;
            }
            (total, changes, many, moved)
        })
        .collect();
    let total = parts.iter().map(|part| part.0).sum();
    let moved = parts.iter().map(|part| part.3).sum();
    let count: usize = parts.iter().map(|part| part.1.len()).sum();
    let changes = (count <= SPARSE_MAX && !parts.iter().any(|part| part.2))
        .then(|| parts.into_iter().flat_map(|part| part.1).collect());
    (total, moved, changes)
}

/// The incremental displacement update in terms of graw = u − h: u ← scale·(u − step·r +
/// Σ_j δ_j G_j) for the point changes (j, δ_j) (see [`super::Field`]); returns the rows'
/// [`gap_row`] statistics of the new graw.
pub(super) fn update(
    field: &super::Field,
    graw: &mut [f64],
    (h, r, t): (&[f64], &[f64], &[f64]),
    contact: &[bool],
    (step, scale): (f64, f64),
    changes: &[(usize, f64)],
) -> Vec<GapRow> {
    let nx = field.nx;
    graw.par_chunks_mut(nx)
        .enumerate()
        .map(|(y, row)| {
            let o = y * nx;
            let hrow = &h[o..o + nx];
            for ((gi, hi), ri) in row.iter_mut().zip(hrow).zip(&r[o..o + nx]) {
                *gi = (*gi + hi) - step * ri;
            }
            field.add_columns(y, row, changes);
            for (gi, hi) in row.iter_mut().zip(hrow) {
                *gi = scale * *gi - hi;
            }
            gap_row(row, &contact[o..o + nx], &t[o..o + nx])
        })
        .collect()
}

/// A fresh displacement: graw = K(ps·p) − h by FFT (`multiply` applies K), with the rows'
/// gap statistics (contact set and previous direction t) formed in its inverse row pass.
pub(super) fn fresh<T: Real, M>(
    plan: &mut Fft2<T>,
    (p, ps): (&[f64], f64),
    graw: &mut [f64],
    multiply: M,
    (h, contact, t): (&[f64], &[bool], &[f64]),
) -> GapSums
where
    M: Fn(usize, &mut [Complex<T>]) + Sync,
{
    let nx = plan.nx();
    let rows = plan.filter_scaled_then(p, ps, graw, multiply, |y, _, row| {
        let o = y * nx;
        for (gi, hi) in row.iter_mut().zip(&h[o..o + nx]) {
            *gi -= hi;
        }
        gap_row(row, &contact[o..o + nx], &t[o..o + nx])
    });
    GapSums::of(&rows)
}

/// The new direction t ← (z − z̄) + β t (on the contact set of `n_c` points, 0 elsewhere; z the
/// preconditioned gap) formed in the forward row pass of r = K t, and the step's denominator
/// Σ_c r (t − t̄) in its inverse row pass.
pub(super) fn conjugate<T: Real, M>(
    plan: &mut Fft2<T>,
    (t, r): (&mut [f64], &mut [f64]),
    multiply: M,
    (z, zbar, contact): (&[f64], f64, &[bool]),
    n_c: f64,
    beta: f64,
) -> f64
where
    M: Fn(usize, &mut [Complex<T>]) + Sync,
{
    let nx = plan.nx();
    let (_, den_rows) = plan.filter_rows(
        t,
        |y, trow| {
            let o = y * nx;
            direction_row(trow, &z[o..o + nx], &contact[o..o + nx], zbar, beta)
        },
        r,
        multiply,
        |[sum_t]| {
            let tbar = sum_t / n_c;
            move |y, trow, rrow| denominator_row(rrow, trow, &contact[y * nx..(y + 1) * nx], tbar)
        },
    );
    den_rows.iter().map(|d| d[0]).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bem::{direction, measure_gap, step_denominator};

    /// A test grid: graw with a large offset (the rigid approach) over small gaps, a contact
    /// set of about two thirds of the points, a previous direction and a response field.
    fn fields(nx: usize, ny: usize) -> (Vec<f64>, Vec<bool>, Vec<f64>, Vec<f64>) {
        let n = nx * ny;
        let v = |i: usize, m: usize| ((i * 7919) % m) as f64 / m as f64 - 0.5;
        let graw = (0..n).map(|i| 3.0e2 + 1e-3 * v(i, 101)).collect();
        let contact = (0..n).map(|i| (i * 104_729) % 3 != 0).collect();
        let t = (0..n).map(|i| v(i + 5, 97)).collect();
        let r = (0..n).map(|i| v(i + 11, 89) + 0.25).collect();
        (graw, contact, t, r)
    }

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    #[test]
    fn fused_passes_match_the_unfused_ones() {
        let (nx, ny) = (37, 23);
        let (graw, contact, t, r) = fields(nx, ny);
        let p: Vec<f64> = contact.iter().map(|&c| if c { 1.0 } else { 0.0 }).collect();
        let rows: Vec<GapRow> = (0..ny)
            .map(|y| {
                let o = y * nx;
                gap_row(&graw[o..o + nx], &contact[o..o + nx], &t[o..o + nx])
            })
            .collect();
        let sums = GapSums::of(&rows);
        // Unfused: g = u − h − ḡ with u = graw, h = 0, then the direction from it.
        let mut g = vec![0.0; nx * ny];
        let (g2, pen, n_c) = measure_gap(&mut g, &graw, &vec![0.0; nx * ny], &p);
        assert_eq!(sums.n_c, n_c);
        // Both sums see the gaps (≈ 3e-4) through graw's rounding (≈ 6e-14 at 300): agreement
        // to 1e-12 relative is that condition, not the summation.
        assert!(rel(sums.g2, g2) < 1e-12, "{} vs {g2}", sums.g2);
        // ḡ itself may differ by an ulp of the offset with the order of summation.
        let ulp = f64::EPSILON * graw[0];
        assert!((sums.pen - pen).abs() <= 2.0 * ulp, "{} vs {pen}", sums.pen);
        // The direction and what follows, unfused, from the same ḡ.
        for (gi, gr) in g.iter_mut().zip(&graw) {
            *gi = gr - sums.gbar;
        }
        let beta = 0.7;
        let mut t_unfused = t.clone();
        let (num, sum_t) = direction(&mut t_unfused, &g, &p, beta);
        let num_fused = sums.g2 + beta * sums.gt;
        assert!(rel(num_fused, num) < 1e-12, "{num_fused} vs {num}");
        let mut t_fused = t.clone();
        let mut sum_t_fused = 0.0;
        for y in 0..ny {
            let o = y * nx;
            let [s] = direction_row(
                &mut t_fused[o..o + nx],
                &graw[o..o + nx],
                &contact[o..o + nx],
                sums.gbar,
                beta,
            );
            sum_t_fused += s;
        }
        // Σ t cancels (terms ≈ 0.3, sum ≈ 5e-5): compared with the sum of |t|.
        let abs_t: f64 = t_unfused.iter().map(|v| v.abs()).sum();
        assert!(
            (sum_t_fused - sum_t).abs() < 1e-14 * abs_t,
            "{sum_t_fused} vs {sum_t}"
        );
        assert_eq!(t_fused, t_unfused);
        let tbar = sum_t / n_c;
        let den = step_denominator("test", &r, &t_unfused, &p, tbar, 1).unwrap();
        let den_fused: f64 = (0..ny)
            .map(|y| {
                let o = y * nx;
                let row = o..o + nx;
                denominator_row(
                    &r[row.clone()],
                    &t_unfused[row.clone()],
                    &contact[row],
                    tbar,
                )[0]
            })
            .sum();
        assert!(rel(den_fused, den) < 1e-13, "{den_fused} vs {den}");
        // The projection with the gap as graw − ḡ and the contact flags written.
        let step = 0.9;
        let mut p_unfused = p.clone();
        let (total, changes) =
            crate::bem::project(&mut p_unfused, 1.3, &t_unfused, &g, step, 0.6 * step);
        let mut p_fused = p.clone();
        let mut flags = vec![false; nx * ny];
        let (total_fused, moved, changes_fused) = project(
            &mut p_fused,
            Some(&mut flags),
            (1.3, step, 0.6 * step),
            &t_unfused,
            &graw,
            sums.gbar,
        );
        assert!(rel(total_fused, total) < 1e-13, "{total_fused} vs {total}");
        assert_eq!(changes_fused.is_some(), changes.is_some());
        // Moved: clamped (in contact, the linear update ≤ 0) or re-admitted (out, penetrating).
        let expect_moved = (0..nx * ny)
            .filter(|&i| {
                (p[i] > 0.0 && 1.3 * p[i] - step * t_unfused[i] <= 0.0)
                    || (p[i] == 0.0 && g[i] < 0.0)
            })
            .count();
        assert!(expect_moved > 0);
        assert_eq!(moved, expect_moved);
        for ((a, b), c) in p_fused.iter().zip(&p_unfused).zip(&flags) {
            assert!((a - b).abs() <= 1e-15 * b.abs().max(1.0), "{a} vs {b}");
            assert_eq!(*c, *a > 0.0);
        }
    }

    #[test]
    fn gap_sums_keep_small_gaps_under_a_large_offset() {
        // Two rows of 16 points, all in contact: 128 ± e and 128 + 2e ± e with e = 2^-20, all
        // exact in binary. ḡ = 128 + e, the gaps are 0 or ∓2e and Σ g² = 64 e² exactly, which
        // Σ graw² − n ḡ² (terms of 2^14 against a difference of 2^-34) would lose entirely.
        let (nx, e) = (16, 2f64.powi(-20));
        let graw: Vec<f64> = (0..2 * nx)
            .map(|i| 128.0 + if i < nx { 0.0 } else { 2.0 * e } + if i % 2 == 0 { e } else { -e })
            .collect();
        let contact = vec![true; 2 * nx];
        let t = vec![1.0; 2 * nx];
        let rows = [
            gap_row(&graw[..nx], &contact[..nx], &t[..nx]),
            gap_row(&graw[nx..], &contact[nx..], &t[nx..]),
        ];
        let sums = GapSums::of(&rows);
        assert_eq!(sums.gbar, 128.0 + e);
        assert_eq!(sums.g2, 64.0 * e * e);
        // Σ g·t with t = 1 is Σ g = 0.
        assert_eq!(sums.gt, 0.0);
        assert_eq!(sums.pen, 0.0);
    }
}
