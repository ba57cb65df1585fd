//! Tabulated friction kernels for the contact integrals under sliding (`contact::sliding`): the
//! squares f_t², ((g_t + h)/2)² + (g_t − h)²/8 and (g_t − h)²/8 of the tangential kernels
//! ([`crate::layer::tangential`]) for one material pair, as [`super::KernelTable`] tabulates
//! S⁻², f², g²: panels of width [`WIDTH`] in y = ln(qd) (halved up to [`MAX_HALVINGS`] times),
//! each a polynomial of degree [`DEGREE`](crate::cheb::DEGREE) through its Chebyshev points;
//! the squares themselves on panels below q·d = [`X_DIRECT`], times e^{2x} above; above
//! [`X_FAR`] the lines a + b x through the exact f_t e^x, h e^x and (g_t − h) e^x at x = 40 and
//! 80 (t = e^{−2x} drops out of every stable form there), squared and times e^{−2x}.
//!
//! All three squares are positive at every q·d > 0 (f_t > 0; g_t − h < 0, and the second is
//! at least the third), so they are tabulated to a relative tolerance even where g_t changes
//! sign; g_t − h comes from its stable form ([`Bilayer::shear_undecayed`]), not from the
//! difference of g_t and h. As for the static table, accuracy is checked when the table is
//! built: at every panel's ends and between its outer and middle nodes, the interpolant must be
//! within [`TABLE_RTOL`] of the exact value, relative to the panel's largest (to each value on
//! the panels below [`X_DIRECT`]); otherwise the panels are halved, and after
//! [`MAX_HALVINGS`] halvings there is no table and the caller uses the exact kernels.

use super::table::{MAX_HALVINGS, MAX_SPAN, WIDTH, X_DIRECT, X_FAR};
use super::{Bilayer, Nodes, QD_BULK};
use crate::cheb::{Interpolation, N, poly};
use crate::prec::TABLE_RTOL;
use crate::simd::with_avx2;
use crate::special::exp_nonpositive;

/// f_t², ((g_t + h)/2)² + (g_t − h)²/8 and (g_t − h)²/8 from f_t, h and g_t − h (all scaled
/// alike).
#[inline]
pub fn friction_squares(f_t: f64, h: f64, diff: f64) -> [f64; 3] {
    let half_sum = h + 0.5 * diff;
    let across = 0.125 * diff * diff;
    [f_t * f_t, half_sum * half_sum + across, across]
}

/// The three squares at x = qd times e^{2x}, from the exact stable forms.
pub fn undecayed_squares(layers: &Bilayer, x: f64) -> [f64; 3] {
    let s = layers.shear_undecayed(x);
    friction_squares(s.f_t, s.h, s.diff)
}

/// The exact values tabulated at y: the squares themselves (`direct`) or times e^{2x}.
fn exact(layers: &Bilayer, y: f64, direct: bool) -> [f64; 3] {
    let x = y.exp();
    let v = undecayed_squares(layers, x);
    if direct {
        let e = (-2.0 * x).exp();
        return v.map(|v| v * e);
    }
    v
}

/// Panel j (from 0) down from ln [`X_FAR`] at `width`, on [ln X_FAR − (j + 1)·width,
/// ln X_FAR − j·width]: each square's interpolant through its Chebyshev points, or `None` when
/// one misses the exact value at a check point by more than [`TABLE_RTOL`] relative to the
/// panel's largest value (to each value where the panel lies below [`X_DIRECT`] and holds the
/// squares themselves).
fn panel(layers: &Bilayer, j: usize, width: f64, interp: &Interpolation) -> Option<[[f64; N]; 3]> {
    let centre = X_FAR.ln() - (j as f64 + 0.5) * width;
    let direct = j >= first_direct(width);
    let nodes = crate::cheb::nodes();
    let at = |t: f64| exact(layers, centre + 0.5 * width * t, direct);
    let vals: [[f64; 3]; N] = std::array::from_fn(|j| at(nodes[j]));
    let coef: [[f64; N]; 3] =
        std::array::from_fn(|i| interp.coefficients(&std::array::from_fn(|j| vals[j][i])));
    for t in check_points() {
        let want = at(t);
        for i in 0..3 {
            let scale = if direct {
                want[i]
            } else {
                vals.iter().map(|v| v[i]).fold(want[i], f64::max)
            };
            if (poly(&coef[i], t) - want[i]).abs() > TABLE_RTOL * scale {
                return None;
            }
        }
    }
    Some(coef)
}

/// Piecewise-polynomial tables of the friction kernels' squares in y = ln(qd) for one pair.
/// The panels lie on a grid counted down from y = ln [`X_FAR`] (panel k from the top spans
/// [ln X_FAR − (k + 1)·width, ln X_FAR − k·width], k from 0), so a table built over a narrow range and
/// extended later ([`Self::extended`]) keeps its panels and equals, to the last bit, one built
/// over the wider range at once.
#[derive(Debug, Clone)]
pub struct TangentialTable {
    layers: Bilayer,
    y0: f64,
    y1: f64,
    width: f64,
    inv_width: f64,
    /// Panels bottom-up: panels[p] is panel `top + panels.len() − 1 − p` from the top.
    panels: Vec<[[f64; N]; 3]>,
    /// The table's upper end, counted in panels down from ln [`X_FAR`].
    top: usize,
    /// f_t e^x, h e^x and (g_t − h) e^x above [`X_FAR`]: intercepts and slopes.
    far: [[f64; 2]; 3],
    /// Panels [0, direct) lie below [`X_DIRECT`] and hold the squares themselves.
    direct: usize,
}

/// The lines through the exact f_t e^x, h e^x, (g_t − h) e^x at x = 40 and 80.
fn far_lines(layers: &Bilayer) -> [[f64; 2]; 3] {
    let (xa, xb) = (X_FAR, 2.0 * X_FAR);
    let (a, b) = (layers.shear_undecayed(xa), layers.shear_undecayed(xb));
    let line = |va: f64, vb: f64| {
        let slope = (vb - va) / (xb - xa);
        [va - slope * xa, slope]
    };
    [line(a.f_t, b.f_t), line(a.h, b.h), line(a.diff, b.diff)]
}

/// The first panel from the top (at `width`) that lies below [`X_DIRECT`] ([`panel`]).
fn first_direct(width: f64) -> usize {
    ((X_FAR.ln() - X_DIRECT.ln()) / width).ceil() as usize
}

/// The panels from the top (at `width`, [`panel`]) that cover qd in [x_min, x_max]: the first
/// and one past the last, at least one; `None` beyond [`MAX_SPAN`].
fn panels_covering(x_min: f64, x_max: f64, width: f64) -> Option<(usize, usize)> {
    let top = X_FAR.ln();
    let (hi, lo) = (x_max.min(X_FAR).ln(), x_min.ln());
    if !(hi.is_finite() && lo.is_finite() && hi - lo <= MAX_SPAN) {
        return None;
    }
    let first = ((top - hi) / width).floor() as usize;
    let last = (((top - lo) / width).ceil() as usize).max(first + 1);
    Some((first, last))
}

/// The checks of a panel's interpolant: its ends and the midpoints between its outer nodes
/// and between its middle ones, in the local variable t.
fn check_points() -> [f64; 5] {
    let nodes = crate::cheb::nodes();
    [
        -1.0,
        1.0,
        0.5 * (nodes[0] + nodes[1]),
        0.5 * (nodes[N - 2] + nodes[N - 1]),
        0.5 * (nodes[N / 2 - 1] + nodes[N / 2]),
    ]
}

impl TangentialTable {
    /// A table covering qd in [x_min, x_max], or `None` when the range is too wide or the
    /// kernels are not resolved to [`TABLE_RTOL`] by the finest panels.
    pub fn new(layers: Bilayer, x_min: f64, x_max: f64) -> Option<Self> {
        let interp = Interpolation::new();
        (0..=MAX_HALVINGS).find_map(|h| {
            let width = WIDTH / f64::from(1 << h);
            let (first, last) = panels_covering(x_min, x_max, width)?;
            let panels = (first..last)
                .rev()
                .map(|k| panel(&layers, k, width, &interp))
                .collect::<Option<Vec<_>>>()?;
            Some(Self::with_panels(layers, width, first, panels))
        })
    }

    /// This table extended to cover qd in [x_min, x_max] as well: its panels kept, the
    /// missing ones built at its width (a table at another width where they are not resolved
    /// there, [`Self::new`] over the union). `None` as for [`Self::new`].
    pub fn extended(&self, x_min: f64, x_max: f64) -> Option<Self> {
        let (lo, hi) = self.range();
        let (x_min, x_max) = (x_min.min(lo), x_max.max(hi));
        let interp = Interpolation::new();
        let (first, last) = panels_covering(x_min, x_max, self.width)?;
        let (first, last) = (first.min(self.top), last.max(self.top + self.panels.len()));
        let built = |ks: std::ops::Range<usize>| {
            ks.rev()
                .map(|k| panel(&self.layers, k, self.width, &interp))
                .collect::<Option<Vec<_>>>()
        };
        let below = built(self.top + self.panels.len()..last);
        let above = built(first..self.top);
        match (below, above) {
            (Some(mut panels), Some(above)) => {
                panels.extend_from_slice(&self.panels);
                panels.extend(above);
                Some(Self::with_panels(self.layers, self.width, first, panels))
            }
            _ => Self::new(self.layers, x_min, x_max),
        }
    }

    /// The table of `panels` (bottom-up) at `width`, the uppermost `first` panels below the
    /// grid's top.
    fn with_panels(layers: Bilayer, width: f64, first: usize, panels: Vec<[[f64; N]; 3]>) -> Self {
        let top = X_FAR.ln();
        let last = first + panels.len();
        let direct = last.saturating_sub(first_direct(width)).min(panels.len());
        Self {
            layers,
            y0: top - last as f64 * width,
            y1: top - first as f64 * width,
            width,
            inv_width: 1.0 / width,
            panels,
            top: first,
            far: far_lines(&layers),
            direct,
        }
    }

    /// The material pair tabulated.
    pub fn layers(&self) -> &Bilayer {
        &self.layers
    }

    /// The range of q·d tabulated (above its upper end, up to [`X_FAR`], nothing is needed).
    pub fn range(&self) -> (f64, f64) {
        (self.y0.exp(), self.y1.exp())
    }

    /// Whether the table covers qd in [x_min, x_max] (anything above [`X_FAR`] is covered).
    pub fn covers(&self, x_min: f64, x_max: f64) -> bool {
        x_min.ln() >= self.y0 && x_max.min(X_FAR).ln() <= self.y1
    }

    /// f_t², ((g_t + h)/2)² + (g_t − h)²/8 and (g_t − h)²/8 at x = qd with y = ln x (x must
    /// lie in the table's range or above it).
    #[inline]
    pub fn squares(&self, x: f64, y: f64) -> [f64; 3] {
        if x > X_FAR {
            if x > QD_BULK {
                return [0.0; 3];
            }
            let e = (-x).exp();
            let [f_t, h, diff] = self.far.map(|[a, b]| (a + b * x) * e);
            return friction_squares(f_t, h, diff);
        }
        let s = ((y - self.y0) * self.inv_width).max(0.0);
        let p = (s as usize).min(self.panels.len() - 1);
        let t = 2.0 * (s - p as f64) - 1.0;
        let c = &self.panels[p];
        let v = [poly(&c[0], t), poly(&c[1], t), poly(&c[2], t)];
        if p < self.direct {
            return v;
        }
        let e = exp_nonpositive(-2.0 * x);
        v.map(|v| v * e)
    }

    /// s = (y − y0)/width, clamped at 0, and the panel p of y with the local variable
    /// t = 2(s − p) − 1, as [`squares`](Self::squares) forms them.
    #[inline(always)]
    fn scaled(&self, y: f64) -> f64 {
        ((y - self.y0) * self.inv_width).max(0.0)
    }

    /// For ascending nodes u (= ln q) at y = u + ln d: the panel p of the first and how many of
    /// them lie in p, with b = −(2p + 1) for t = 2s + b (the same t as 2(s − p) − 1: s − p is
    /// exact, so both round the same real number once), as [`super::KernelTable`]'s batches.
    #[inline(always)]
    fn run(&self, u: &[f64], ln_d: f64) -> (usize, usize, f64) {
        let p = (self.scaled(u[0] + ln_d) as usize).min(self.panels.len() - 1);
        let len = if p + 1 == self.panels.len() {
            u.len()
        } else {
            let next = (p + 1) as f64;
            u.partition_point(|&v| self.scaled(v + ln_d) < next).max(1)
        };
        (p, len, -2.0 * p as f64 - 1.0)
    }

    /// The contact integrals' slots under sliding at x = q d, y = u + ln d for ascending nodes:
    /// `f2[j] += half_mu2·f_t²` (σ's kernel f² + μ²f_t²/2 from f²) and, with `friction`, the
    /// squares ((g_t + h)/2)² + (g_t − h)²/8 and (g_t − h)²/8 into its two slices. The values
    /// of [`squares`](Self::squares) to the last bit, with one panel's polynomials per run of
    /// nodes in loops without branches and e^{−2x} formed once per node for all three (AVX2
    /// where the CPU has it: `crate::simd`).
    pub fn slots_many(
        &self,
        at: Nodes,
        half_mu2: f64,
        f2: &mut [f64],
        friction: Option<[&mut [f64]; 2]>,
    ) {
        with_avx2!(
            self.slots_many_avx2(at, half_mu2, f2, friction),
            self.slots_many_in(at, half_mu2, f2, friction)
        )
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn slots_many_avx2(
        &self,
        at: Nodes,
        half_mu2: f64,
        f2: &mut [f64],
        friction: Option<[&mut [f64]; 2]>,
    ) {
        self.slots_many_in(at, half_mu2, f2, friction);
    }

    #[inline(always)]
    fn slots_many_in(
        &self,
        Nodes { q, u, d, ln_d }: Nodes,
        half_mu2: f64,
        f2: &mut [f64],
        mut friction: Option<[&mut [f64]; 2]>,
    ) {
        let near = q.partition_point(|&q| q * d <= X_FAR);
        let mut j = 0;
        while j < near {
            let (p, len, b) = self.run(&u[j..near], ln_d);
            let c = &self.panels[p];
            let r = j..j + len;
            let (q, u) = (&q[r.clone()], &u[r.clone()]);
            let direct = p < self.direct;
            let t = |v: f64| 2.0 * self.scaled(v + ln_d) + b;
            let e = |q: f64| exp_nonpositive(-2.0 * (q * d));
            match friction.as_mut() {
                Some([along, across]) => {
                    let out = f2[r.clone()]
                        .iter_mut()
                        .zip(&mut along[r.clone()])
                        .zip(&mut across[r])
                        .zip(q.iter().zip(u));
                    if direct {
                        for (((fo, ao), co), (_, &v)) in out {
                            let t = t(v);
                            *fo += half_mu2 * poly(&c[0], t);
                            (*ao, *co) = (poly(&c[1], t), poly(&c[2], t));
                        }
                    } else {
                        for (((fo, ao), co), (&q, &v)) in out {
                            let (t, e) = (t(v), e(q));
                            *fo += half_mu2 * (poly(&c[0], t) * e);
                            (*ao, *co) = (poly(&c[1], t) * e, poly(&c[2], t) * e);
                        }
                    }
                }
                None => {
                    let out = f2[r].iter_mut().zip(q.iter().zip(u));
                    if direct {
                        for (fo, (_, &v)) in out {
                            *fo += half_mu2 * poly(&c[0], t(v));
                        }
                    } else {
                        for (fo, (&q, &v)) in out {
                            *fo += half_mu2 * (poly(&c[0], t(v)) * e(q));
                        }
                    }
                }
            }
            j += len;
        }
        for (k, &q) in q.iter().enumerate().skip(near) {
            let [f_t2, along, across] = self.squares(q * d, 0.0);
            f2[k] += half_mu2 * f_t2;
            if let Some([a, c]) = friction.as_mut() {
                (a[k], c[k]) = (along, across);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layer::Elastic;

    /// A table built over a narrow range and extended (below, above, both) equals the one
    /// built over the union at once, to the last bit at every x, with the same range; it
    /// covers what it was asked for, and a table that already covers a range is unchanged by
    /// extending it there.
    #[test]
    fn extended_tables_equal_tables_built_at_once() {
        let e = |y: f64, nu: f64| Elastic::new(y, nu).unwrap();
        for layers in [
            Bilayer::new(e(1e6, 0.5), e(2e11, 0.3)),
            Bilayer::new(e(1e9, 0.3), e(1e6, 0.5)),
        ] {
            let narrow = TangentialTable::new(layers, 0.3, 5.0).unwrap();
            for (lo, hi) in [(1e-3, 5.0), (0.3, 200.0), (2e-4, 60.0), (0.5, 4.0)] {
                let grown = narrow.extended(lo, hi).unwrap();
                let (lo, hi) = (lo.min(0.3), hi.max(5.0));
                let once = TangentialTable::new(layers, lo, hi).unwrap();
                assert!(grown.covers(lo, hi) && once.covers(lo, hi));
                assert_eq!(grown.range(), once.range());
                assert_eq!(grown.direct, once.direct);
                for i in 0..=4000 {
                    let x = 1e-4 * 10f64.powf(6.0 * f64::from(i) / 4000.0);
                    if x < lo || x > hi.max(X_FAR) {
                        continue;
                    }
                    let (a, b) = (grown.squares(x, x.ln()), once.squares(x, x.ln()));
                    assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits), "x = {x}");
                }
            }
        }
    }

    /// The batched slots equal [`TangentialTable::squares`] at every node to the last bit (the
    /// σ slot as f² + (μ²/2)·f_t² formed in that order), with and without the friction slots, in
    /// the dispatched build (AVX2 where the CPU has it) and the baseline, over direct panels,
    /// scaled ones and the far field, for a soft film on steel and a stiff film on rubber.
    #[test]
    fn batched_slots_equal_the_squares() {
        let e = |y: f64, nu: f64| Elastic::new(y, nu).unwrap();
        for layers in [
            Bilayer::new(e(1e6, 0.5), e(2e11, 0.3)),
            Bilayer::new(e(1e9, 0.3), e(1e6, 0.5)),
        ] {
            let t = TangentialTable::new(layers, 1e-6, 200.0).unwrap();
            let d = 1e-5;
            let q: Vec<f64> = (0..2000)
                .map(|i| 0.1 * 10f64.powf(8.5 * f64::from(i) / 2000.0))
                .collect();
            let u: Vec<f64> = q.iter().map(|q| q.ln()).collect();
            let at = Nodes {
                q: &q,
                u: &u,
                d,
                ln_d: d.ln(),
            };
            let f2: Vec<f64> = (0..q.len()).map(|i| 1e-3 * f64::from(i as u32)).collect();
            let half_mu2 = 0.5 * 0.7 * 0.7;
            let mut got = [(); 7].map(|_| f2.clone());
            let [fa, along, across, fb, along_b, across_b, fc] = &mut got;
            t.slots_many(at, half_mu2, fa, Some([along, across]));
            t.slots_many_in(at, half_mu2, fb, Some([along_b, across_b]));
            t.slots_many(at, half_mu2, fc, None);
            for (j, (&q, &u)) in q.iter().zip(&u).enumerate() {
                let [f_t2, a, c] = t.squares(q * d, u + d.ln());
                let want = [f2[j] + half_mu2 * f_t2, a, c];
                // got: the three slots twice (dispatched, baseline), then σ's alone.
                for (k, slot) in got.iter().enumerate() {
                    let w = want[k % 3];
                    assert_eq!(slot[j].to_bits(), w.to_bits(), "x = {} slot {k}", q * d);
                }
            }
        }
    }
}
