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
use super::{Bilayer, QD_BULK};
use crate::cheb::{Interpolation, N, poly};
use crate::prec::TABLE_RTOL;
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

/// Piecewise-polynomial tables of the friction kernels' squares in y = ln(qd) for one pair.
#[derive(Debug, Clone)]
pub struct TangentialTable {
    layers: Bilayer,
    y0: f64,
    y1: f64,
    inv_width: f64,
    panels: Vec<[[f64; N]; 3]>,
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

impl TangentialTable {
    /// A table covering qd in [x_min, x_max], or `None` when the range is too wide or the
    /// kernels are not resolved to [`TABLE_RTOL`] by the finest panels.
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
        let count = (((y1 - y0) / width).ceil() as usize).max(1);
        let nodes = crate::cheb::nodes();
        let checks = [
            -1.0,
            1.0,
            0.5 * (nodes[0] + nodes[1]),
            0.5 * (nodes[N - 2] + nodes[N - 1]),
            0.5 * (nodes[N / 2 - 1] + nodes[N / 2]),
        ];
        let direct = (((X_DIRECT.ln() - y0) / width).floor().max(0.0) as usize).min(count);
        let mut panels = Vec::with_capacity(count);
        for p in 0..count {
            let centre = y0 + (p as f64 + 0.5) * width;
            let at = |t: f64| exact(&layers, centre + 0.5 * width * t, p < direct);
            let vals: [[f64; 3]; N] = std::array::from_fn(|j| at(nodes[j]));
            let coef: [[f64; N]; 3] =
                std::array::from_fn(|k| interp.coefficients(&std::array::from_fn(|j| vals[j][k])));
            for &t in &checks {
                let want = at(t);
                for k in 0..3 {
                    let scale = if p < direct {
                        want[k]
                    } else {
                        vals.iter().map(|v| v[k]).fold(want[k], f64::max)
                    };
                    if (poly(&coef[k], t) - want[k]).abs() > TABLE_RTOL * scale {
                        return None;
                    }
                }
            }
            panels.push(coef);
        }
        Some(Self {
            layers,
            y0,
            y1,
            inv_width: 1.0 / width,
            panels,
            far: far_lines(&layers),
            direct,
        })
    }

    /// The material pair tabulated.
    pub fn layers(&self) -> &Bilayer {
        &self.layers
    }

    /// The range of q·d tabulated (above its upper end, up to [`X_FAR`], nothing is needed).
    pub fn range(&self) -> (f64, f64) {
        (self.y0.exp(), self.y1.exp())
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

    /// The square `k` (0: f_t², 1: ((g_t + h)/2)² + (g_t − h)²/8, 2: (g_t − h)²/8) alone at
    /// x = qd with y = ln x: [`squares`](Self::squares)`(x, y)[k]` to the last bit (the same
    /// operations), for the sums that need one or two of the three.
    #[inline]
    pub fn square(&self, k: usize, x: f64, y: f64) -> f64 {
        if x > X_FAR {
            return self.squares(x, y)[k];
        }
        let s = ((y - self.y0) * self.inv_width).max(0.0);
        let p = (s as usize).min(self.panels.len() - 1);
        let t = 2.0 * (s - p as f64) - 1.0;
        let v = poly(&self.panels[p][k], t);
        if p < self.direct {
            return v;
        }
        v * exp_nonpositive(-2.0 * x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layer::Elastic;

    /// One square alone equals that entry of all three, to the last bit, in the direct panels,
    /// the scaled ones and the far field, for a soft film on steel and a stiff film on rubber.
    #[test]
    fn one_square_is_the_entry_of_all_three() {
        let e = |y: f64, nu: f64| Elastic::new(y, nu).unwrap();
        for layers in [
            Bilayer::new(e(1e6, 0.5), e(2e11, 0.3)),
            Bilayer::new(e(1e9, 0.3), e(1e6, 0.5)),
        ] {
            let t = TangentialTable::new(layers, 1e-6, 200.0).unwrap();
            for i in 0..=2000 {
                let x = 1e-6 * 10f64.powf(8.5 * f64::from(i) / 2000.0);
                let all = t.squares(x, x.ln());
                for (k, v) in all.iter().enumerate() {
                    assert_eq!(t.square(k, x, x.ln()).to_bits(), v.to_bits(), "{x} {k}");
                }
            }
        }
    }
}
