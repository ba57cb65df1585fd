//! Tabulated layer kernels for fast repeated evaluation.
//!
//! The contact integrals need S⁻², f² and g² at thousands of values of x = qd per thickness, and
//! the stable forms of [`Bilayer::response`] cost ~70 ns each. All three depend on x alone, so for
//! one material pair they are tabulated once in y = ln x: uniform panels of width [`WIDTH`] in y,
//! each a polynomial of degree [`DEGREE`](crate::cheb::DEGREE) through the Chebyshev points of
//! the panel ([`crate::cheb`]: stored as monomials in the panel's local variable t ∈ [−1, 1],
//! evaluated by Estrin's scheme). The tabulated
//! functions are K = S⁻², F = f² e^{2x} and Γ = g² e^{2x}: all smooth in y with no large dynamic
//! range across a panel (f and g decay like e^{−x}, which the table leaves to one `exp` per point);
//! panels below q·d = [`X_DIRECT`] hold f² and g² themselves and need no `exp`.
//!
//! Batches ([`KernelTable::k_many`], [`KernelTable::interface_many`]): one polynomial per run of
//! nodes in a panel, in loops without branches that the compiler vectorises, compiled twice (the
//! baseline, and for AVX2, chosen at run time); both give the single-point values to the last
//! bit.
//!
//! Accuracy is checked when the table is built, not assumed: every panel is compared with the
//! exact kernels at points between its interpolation nodes and at its ends; if any differs by
//! more than [`TABLE_RTOL`] of the panel's largest value the whole table is rebuilt with panels
//! half as wide, and after [`MAX_HALVINGS`] halvings the caller gets `None` and uses the exact
//! kernels.
//!
//! Far field. Above x = [`X_FAR`] = 40, t = e^{−2x} < 2e−35 drops out of every stable form in
//! f64 (its terms enter as t, x t, x² t relative to O(1) ones, all below 1e−31): S = 1 and f e^x,
//! g e^x are exactly linear in x (f e^x = (1+κ0)[2(1−ν0) + 2r(1−ν1) + x(1 + rκ1)] / ((1+rκ1)(κ0+r)),
//! and g likewise). The table takes the lines through the exact values at x = 40 and 80 and needs
//! no panels there; the test `far_field_is_linear` checks them against the exact kernels until f²
//! and g² underflow (q·d ≈ 350).

use super::{Bilayer, QD_BULK};
use crate::cheb::{Interpolation, N, poly};
use crate::prec::TABLE_RTOL;
use crate::simd::with_avx2;
use crate::special::exp_nonpositive;

/// Panel width in y = ln(qd) before any halving.
pub const WIDTH: f64 = 0.25;
/// How often the panel width may be halved when a panel misses [`TABLE_RTOL`].
pub const MAX_HALVINGS: u32 = 3;
/// Above this qd the kernels are S = 1 and f e^x, g e^x linear in x (module doc).
pub const X_FAR: f64 = 40.0;
/// The widest y-range a table may span (beyond it the exact kernels are cheaper than building).
pub const MAX_SPAN: f64 = 120.0;

/// Ascending quadrature nodes q (with u = ln q) at one film thickness d (with ln d): the batched
/// kernels are evaluated at x = q d, y = u + ln d.
#[derive(Debug, Clone, Copy)]
pub struct Nodes<'a> {
    pub q: &'a [f64],
    pub u: &'a [f64],
    pub d: f64,
    pub ln_d: f64,
}

/// S⁻², f² and g² at one x = qd.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Squared {
    /// S(qd)⁻².
    pub k: f64,
    /// f(qd)².
    pub f2: f64,
    /// g(qd)².
    pub g2: f64,
}

/// Piecewise-polynomial tables of S⁻², f² e^{2x}, g² e^{2x} in y = ln(qd) for one material pair.
#[derive(Debug, Clone)]
pub struct KernelTable {
    layers: Bilayer,
    y0: f64,
    y1: f64,
    inv_width: f64,
    k: Vec<[f64; N]>,
    f: Vec<[f64; N]>,
    g: Vec<[f64; N]>,
    /// f e^x and g e^x above [`X_FAR`]: intercepts and slopes.
    far: [[f64; 2]; 2],
    /// Panels [0, direct) lie below [`X_DIRECT`] and hold f², g² themselves.
    direct: usize,
}

/// Panels that end below this q·d tabulate f² and g² themselves, not times e^{2x}: e^{−2x} is
/// smooth in y there (it changes by less than a factor e^{−1.1} across a panel), and the
/// evaluation saves its `exp`. Their accuracy is checked relative to every value checked, not
/// to the panel's largest.
pub const X_DIRECT: f64 = 2.0;

/// f e^x and g e^x as lines a + b x above [`X_FAR`], through the exact values at 40 and 80.
fn far_lines(layers: &Bilayer) -> [[f64; 2]; 2] {
    let (xa, xb) = (X_FAR, 2.0 * X_FAR);
    let (ra, rb) = (layers.response(xa), layers.response(xb));
    let (ea, eb) = (xa.exp(), xb.exp());
    let line = |va: f64, vb: f64| {
        let slope = (vb - va) / (xb - xa);
        [va - slope * xa, slope]
    };
    [line(ra.f * ea, rb.f * eb), line(ra.g * ea, rb.g * eb)]
}

/// The exact values tabulated at y: S⁻², and f², g² themselves (`direct`) or times e^{2x}.
fn exact(layers: &Bilayer, y: f64, direct: bool) -> [f64; 3] {
    let x = y.exp();
    let r = layers.response(x);
    if direct {
        return [1.0 / (r.s * r.s), r.f * r.f, r.g * r.g];
    }
    // (f e^x)², not f² e^{2x}: near x = 700 the latter under- and overflows.
    let e = x.exp();
    [1.0 / (r.s * r.s), (r.f * e).powi(2), (r.g * e).powi(2)]
}

impl KernelTable {
    /// A table covering qd in [x_min, x_max] (the part above 700 needs none), or `None` when the
    /// range is too wide or the kernels are not resolved to [`TABLE_RTOL`] by the finest panels.
    pub fn new(layers: Bilayer, x_min: f64, x_max: f64) -> Option<Self> {
        let y1 = x_max.min(X_FAR).ln();
        let y0 = x_min.ln().min(y1 - WIDTH);
        if !(y0.is_finite() && y1.is_finite() && y1 - y0 <= MAX_SPAN) {
            return None;
        }
        let interp = Interpolation::new();
        (0..=MAX_HALVINGS)
            .find_map(|h| Self::build(layers, y0, y1, WIDTH / f64::from(1 << h), &interp))
    }

    fn build(
        layers: Bilayer,
        y0: f64,
        y1: f64,
        width: f64,
        interp: &Interpolation,
    ) -> Option<Self> {
        let panels = (((y1 - y0) / width).ceil() as usize).max(1);
        let nodes = crate::cheb::nodes();
        // Checks: the panel's ends and the midpoints between its outer nodes.
        let checks = [
            -1.0,
            1.0,
            0.5 * (nodes[0] + nodes[1]),
            0.5 * (nodes[N - 2] + nodes[N - 1]),
            0.5 * (nodes[N / 2 - 1] + nodes[N / 2]),
        ];
        let direct = (((X_DIRECT.ln() - y0) / width).floor().max(0.0) as usize).min(panels);
        let mut table = KernelTable {
            layers,
            y0,
            y1,
            inv_width: 1.0 / width,
            k: Vec::with_capacity(panels),
            f: Vec::with_capacity(panels),
            g: Vec::with_capacity(panels),
            far: far_lines(&layers),
            direct,
        };
        for p in 0..panels {
            let centre = y0 + (p as f64 + 0.5) * width;
            let at = |t: f64| exact(&layers, centre + 0.5 * width * t, p < direct);
            let vals: [[f64; 3]; N] = std::array::from_fn(|j| at(nodes[j]));
            let mut coef = [[0.0; N]; 3];
            for (q, c) in coef.iter_mut().enumerate() {
                *c = interp.coefficients(&std::array::from_fn(|j| vals[j][q]));
            }
            for &t in &checks {
                let want = at(t);
                for q in 0..3 {
                    let scale = if p < direct && q > 0 {
                        want[q].abs()
                    } else {
                        vals.iter()
                            .map(|v| v[q].abs())
                            .fold(want[q].abs(), f64::max)
                    };
                    if (poly(&coef[q], t) - want[q]).abs() > TABLE_RTOL * scale {
                        return None;
                    }
                }
            }
            table.k.push(coef[0]);
            table.f.push(coef[1]);
            table.g.push(coef[2]);
        }
        Some(table)
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

    /// Panel and local variable for y, clamped to the table (rounding at its ends).
    #[inline(always)]
    fn locate(&self, y: f64) -> (usize, f64) {
        let s = ((y - self.y0) * self.inv_width).max(0.0);
        let p = (s as usize).min(self.k.len() - 1);
        (p, 2.0 * (s - p as f64) - 1.0)
    }

    /// S⁻² at x = qd with y = ln x (x ≤ 700 must lie in the table's range).
    #[inline]
    pub fn k(&self, x: f64, y: f64) -> f64 {
        if x > X_FAR {
            return 1.0;
        }
        let (p, t) = self.locate(y);
        poly(&self.k[p], t)
    }

    /// S⁻², f², g² at x = qd with y = ln x.
    #[inline]
    pub fn squared(&self, x: f64, y: f64) -> Squared {
        let (f2, g2) = self.interface(x, y);
        Squared {
            k: self.k(x, y),
            f2,
            g2,
        }
    }

    /// For ascending nodes u (= ln q) at y = u + ln d: the panel p of the first and how many
    /// of them lie in p, with b = −(2p + 1) for the local variable t = 2s + b: the same t as
    /// [`locate`](Self::locate)'s 2(s − p) − 1 (s − p is exact, so both round the same real
    /// number once).
    #[inline(always)]
    fn run(&self, u: &[f64], ln_d: f64) -> (usize, usize, f64) {
        let (p, _) = self.locate(u[0] + ln_d);
        let len = if p + 1 == self.k.len() {
            u.len()
        } else {
            let next = (p + 1) as f64;
            u.partition_point(|&v| self.scaled(v + ln_d) < next).max(1)
        };
        (p, len, -2.0 * p as f64 - 1.0)
    }

    /// s = (y − y0)/width, clamped at 0, as in [`locate`](Self::locate).
    #[inline(always)]
    fn scaled(&self, y: f64) -> f64 {
        ((y - self.y0) * self.inv_width).max(0.0)
    }

    /// S⁻² at x = q d, y = u + ln d for ascending nodes, into `out`: the values of
    /// [`k`](Self::k) to the last bit, with one polynomial per run of nodes in a panel so that the
    /// loop over the run has no branches and is vectorised (AVX2 where the CPU has it:
    /// `crate::simd`).
    pub fn k_many(&self, at: Nodes, out: &mut [f64]) {
        with_avx2!(self.k_many_avx2(at, out), self.k_many_in(at, out))
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn k_many_avx2(&self, at: Nodes, out: &mut [f64]) {
        self.k_many_in(at, out);
    }

    #[inline(always)]
    fn k_many_in(&self, Nodes { q, u, d, ln_d }: Nodes, out: &mut [f64]) {
        let near = q.partition_point(|&q| q * d <= X_FAR);
        let mut j = 0;
        while j < near {
            let (p, len, b) = self.run(&u[j..near], ln_d);
            let c = &self.k[p];
            for (o, &v) in out[j..j + len].iter_mut().zip(&u[j..j + len]) {
                *o = poly(c, 2.0 * self.scaled(v + ln_d) + b);
            }
            j += len;
        }
        out[near..q.len()].fill(1.0);
    }

    /// f² and g² at x = q d, y = u + ln d for ascending nodes, into `f2` and `g2`: the values
    /// of [`interface`](Self::interface) to the last bit, run by run as in
    /// [`k_many`](Self::k_many), with the e^{−2x} factors formed first.
    pub fn interface_many(&self, at: Nodes, f2: &mut [f64], g2: &mut [f64]) {
        with_avx2!(
            self.interface_many_avx2(at, f2, g2),
            self.interface_many_in(at, f2, g2)
        )
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn interface_many_avx2(&self, at: Nodes, f2: &mut [f64], g2: &mut [f64]) {
        self.interface_many_in(at, f2, g2);
    }

    #[inline(always)]
    fn interface_many_in(&self, Nodes { q, u, d, ln_d }: Nodes, f2: &mut [f64], g2: &mut [f64]) {
        let near = q.partition_point(|&q| q * d <= X_FAR);
        // Nodes in direct panels first: no e^{−2x}.
        let direct = self.direct as f64;
        let split = u[..near].partition_point(|&v| self.scaled(v + ln_d) < direct);
        for (e, &q) in f2[split..near].iter_mut().zip(&q[split..near]) {
            *e = exp_nonpositive(-2.0 * (q * d));
        }
        let mut j = 0;
        while j < near {
            let (p, len, b) = self.run(&u[j..near], ln_d);
            let (cf, cg) = (&self.f[p], &self.g[p]);
            let range = j..j + len;
            let out = f2[range.clone()]
                .iter_mut()
                .zip(&mut g2[range.clone()])
                .zip(&u[range]);
            if p < self.direct {
                for ((fo, go), &v) in out {
                    let t = 2.0 * self.scaled(v + ln_d) + b;
                    (*fo, *go) = (poly(cf, t), poly(cg, t));
                }
            } else {
                for ((fo, go), &v) in out {
                    let t = 2.0 * self.scaled(v + ln_d) + b;
                    let e = *fo;
                    *fo = poly(cf, t) * e;
                    *go = poly(cg, t) * e;
                }
            }
            j += len;
        }
        for ((fo, go), &q) in f2[near..q.len()]
            .iter_mut()
            .zip(&mut g2[near..q.len()])
            .zip(&q[near..])
        {
            (*fo, *go) = self.interface(q * d, 0.0);
        }
    }

    /// f² and g² at x = qd with y = ln x (S⁻² not evaluated).
    #[inline(always)]
    pub fn interface(&self, x: f64, y: f64) -> (f64, f64) {
        if x > X_FAR {
            if x > QD_BULK {
                return (0.0, 0.0);
            }
            let e = (-x).exp();
            let [f, g] = self.far.map(|[a, b]| (a + b * x) * e);
            return (f * f, g * g);
        }
        let (p, t) = self.locate(y);
        let (f, g) = (poly(&self.f[p], t), poly(&self.g[p], t));
        if p < self.direct {
            return (f, g);
        }
        let e = exp_nonpositive(-2.0 * x);
        (f * e, g * e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layer::Elastic;

    /// The baseline build of the batched forms equals the dispatched one (AVX2 where the CPU has
    /// it) to the last bit: the tests of the public forms run only the dispatched path.
    #[test]
    fn baseline_batches_equal_dispatched() {
        let layers = Bilayer::new(
            Elastic::new(1e6, 0.5).expect("valid"),
            Elastic::new(2e11, 0.3).expect("valid"),
        );
        let table = KernelTable::new(layers, 1e-6, 1e4).expect("resolved");
        let d = 1e-5;
        let q: Vec<f64> = (0..2000).map(|i| 0.1 * 1.009f64.powi(i)).collect();
        let u: Vec<f64> = q.iter().map(|q| q.ln()).collect();
        let mut v = [(); 6].map(|_| vec![0.0; q.len()]);
        let [k, f, g, kb, fb, gb] = &mut v;
        let at = Nodes {
            q: &q,
            u: &u,
            d,
            ln_d: d.ln(),
        };
        table.k_many(at, k);
        table.k_many_in(at, kb);
        table.interface_many(at, f, g);
        table.interface_many_in(at, fb, gb);
        for (a, b) in [(&*k, &*kb), (&*f, &*fb), (&*g, &*gb)] {
            assert!(a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits()));
        }
    }
}
