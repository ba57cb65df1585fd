//! The d-independent quadrature grid of the contact integrals, its error model and its sums.
//!
//! In u = ln q the integrand is W(u)·ψ(u), W = q⁴C. Panels run between the spectrum's own knots
//! (data points, q0, q_r, q1, and 2q_L for the low-octave share), split so that none is wider
//! than h = 1.25·rtol^{1/4} in ln q ([`super::panel_width`]). On each panel W is replaced by the
//! exact power law through its end values (exact for tabulated and self-affine spectra; the
//! smooth remainder ρ = W/W_ref of a Gaussian band goes into ψ), and a two-node Gauss rule for
//! that exponential weight ([`ExpGauss2`]) integrates ψ = ρ S⁻² (times P F² for the interface).
//! Its error is ψ⁗(ξ)·∫W(u−u1)²(u−u2)²du/24, estimated with the fourth divided difference of ψ
//! over five neighbouring nodes and a safety factor 2 (at the grid's edges, where the window
//! cannot be centred on the panel, grown by the difference's growth towards the edge). Nodes and
//! weights do not depend on d. G at the interior nodes (for P) comes from the same rule's partial
//! integrals (exact for ψ linear on the panel).

use super::{ERR_SAFETY, sized};
use crate::error::Error;
use crate::prec::EPS;
use crate::psd::Spectrum;
use crate::quad::ExpGauss2;
use crate::simd::with_avx2;

/// One quadrature grid: nodes in ascending q with d-independent weights.
pub(super) struct Grid {
    pub(super) q: Vec<f64>,
    pub(super) u: Vec<f64>,
    /// Rule weight of node j (∫ W_ref ℓ_j du over its panel), ρ_j excluded.
    pub(super) w: Vec<f64>,
    /// ρ_j = W(u_j)/W_ref(u_j).
    pub(super) rho: Vec<f64>,
    /// Whether every ρ_j is 1 (piecewise power-law spectra).
    pub(super) unit_rho: bool,
    /// W(u_j) = q_j⁴ C(q_j), for dG/du at the nodes.
    pub(super) w_at: Vec<f64>,
    /// Per panel: d ln W_ref / du.
    pub(super) beta: Vec<f64>,
    /// Per panel: error constant ∫ W_ref (u−u1)²(u−u2)² du / 24.
    pub(super) err4: Vec<f64>,
    /// Per panel: partial-integral coefficients for G at its two nodes (from the panel's left end).
    pub(super) partial: Vec<[[f64; 2]; 2]>,
    /// Per panel: the leading error term of those partial integrals per unit ψ'' (signed).
    pub(super) partial_curv: Vec<[f64; 2]>,
    /// Per panel: 1/(u_2 − u_1), its two nodes' distance.
    pub(super) inv_gap: Vec<f64>,
    /// Per panel: width in u and left end.
    pub(super) width: Vec<f64>,
    pub(super) left: Vec<f64>,
    /// Per panel: ln W at its left end when the spectrum is a piecewise power law (W is then
    /// e^{lw + β(u − left)} on the panel), else empty.
    pub(super) lw_left: Vec<f64>,
    /// Number of panels below 2 q_L.
    pub(super) low_octave_panels: usize,
    /// ∫W du and its error estimate (E_eff's denominator).
    pub(super) bare: (f64, f64),
    /// 1/(u_{j+k} − u_j) for k = 1..4 (entry k − 1; n − k of them), for Newton's divided
    /// differences without a division ([`Grid::newton`]).
    pub(super) inv_span: [Vec<f64>; 4],
}

/// The grid's knots: the spectrum's own, with 2 q_L inserted, and how many panels each knot
/// interval is split into for panels no wider than `h_max` in ln q. Grids of equal splits are
/// equal, whatever the h_max (engines of one spectrum share them: [`Engine::sibling`]).
pub(super) struct Knots {
    pub(super) q: Vec<f64>,
    pub(super) q_oct: f64,
    pub(super) splits: Vec<u32>,
}

impl Knots {
    /// Fails when the spectrum's knots collapse to one point (a support narrower than 1e-12
    /// relative: no panel).
    pub(super) fn new(spectrum: &Spectrum, h_max: f64) -> Result<Knots, Error> {
        // Knots within rounding of their successor (e.g. a Gaussian band's last stepped knot
        // landing 1 ulp below the support's end) would make a panel of width ~1e-16 whose error
        // estimate is 0·∞ = NaN; keep the later one.
        let all = spectrum.knots();
        let mut knots: Vec<f64> = all
            .windows(2)
            .filter(|w| w[1] > w[0] * (1.0 + 1e-12))
            .map(|w| w[0])
            .collect();
        let (&lo, &hi) = all.first().zip(all.last()).ok_or(Error::Numerical {
            what: "contact quadrature",
            detail: "the spectrum has no knots".into(),
        })?;
        knots.push(hi);
        if knots.len() < 2 {
            return Err(Error::invalid(
                "spectrum's wavenumber range for the contact integrals",
                format!("{lo:e}..{hi:e} 1/m"),
                "q_max/q_min − 1 > 1e-12",
            ));
        }
        let q_l = knots[0];
        let mut q_oct = 2.0 * q_l;
        // A spectrum knot within rounding of 2 q_L (e.g. a Gaussian band whose knot grid starts
        // at q_L + 0.5 Q with q_L = 0.5 Q) is taken as the octave's end: inserting 2 q_L beside
        // it would make a panel of width ~1e-16 whose error estimate is 0·∞ = NaN.
        let at = knots.partition_point(|&k| k < q_oct);
        let near = |k: f64| (k / q_oct - 1.0).abs() <= 1e-12;
        if let Some(&k) = [at.checked_sub(1), Some(at)]
            .into_iter()
            .flatten()
            .filter_map(|i| knots.get(i))
            .find(|&&k| near(k))
        {
            q_oct = k;
        } else if q_oct < *knots.last().unwrap() {
            knots.insert(at, q_oct);
        }
        let splits = knots
            .windows(2)
            .map(|w| ((w[1].ln() - w[0].ln()) / h_max).ceil().max(1.0) as u32)
            .collect();
        Ok(Knots {
            q: knots,
            q_oct,
            splits,
        })
    }
}

impl Grid {
    pub(super) fn new(spectrum: &Spectrum, knots: &Knots) -> Grid {
        let Knots {
            q: knots,
            q_oct,
            splits,
        } = knots;
        let q_oct = *q_oct;
        let panels: usize = splits.iter().map(|&n| n as usize).sum();
        let nodes = 2 * panels;
        let mut g = Grid {
            q: Vec::with_capacity(nodes),
            u: Vec::with_capacity(nodes),
            w: Vec::with_capacity(nodes),
            rho: Vec::with_capacity(nodes),
            unit_rho: false,
            w_at: Vec::with_capacity(nodes),
            beta: Vec::with_capacity(panels),
            err4: Vec::with_capacity(panels),
            partial: Vec::with_capacity(panels),
            partial_curv: Vec::with_capacity(panels),
            inv_gap: Vec::with_capacity(panels),
            width: Vec::with_capacity(panels),
            left: Vec::with_capacity(panels),
            lw_left: Vec::with_capacity(panels),
            low_octave_panels: 0,
            bare: (0.0, 0.0),
            inv_span: Default::default(),
        };
        let ln_w = |u: f64| 4.0 * u + spectrum.c(u.exp()).ln();
        // Between knots of a piecewise power law, ln W is linear in u and W_ref = W (ρ = 1).
        let power_law = spectrum.is_piecewise_power_law();
        let ln_knots: Vec<f64> = knots.iter().map(|k| k.ln()).collect();
        let lw_knots: Vec<f64> = knots
            .iter()
            .zip(&ln_knots)
            .map(|(&k, &u)| 4.0 * u + spectrum.c(k).ln())
            .collect();
        let (mut ends, mut lw) = (vec![], vec![]);
        for (i, uu) in ln_knots.windows(2).enumerate() {
            let (ua, ub) = (uu[0], uu[1]);
            let (lwa, lwb) = (lw_knots[i], lw_knots[i + 1]);
            let n = splits[i] as usize;
            let h = (ub - ua) / n as f64;
            // Ends of sub-panels: exact knots at both ends, interior points equally spaced.
            ends.clear();
            ends.extend((0..=n).map(|i| if i == n { ub } else { ua + i as f64 * h }));
            lw.clear();
            lw.extend(ends.iter().enumerate().map(|(i, &u)| match i {
                0 => lwa,
                i if i == n => lwb,
                _ if power_law => lwa + (lwb - lwa) * (u - ua) / (ub - ua),
                _ => ln_w(u),
            }));
            for i in 0..n {
                let (a, b) = (ends[i], ends[i + 1]);
                let width = b - a;
                let (lwa, lwb) = (lw[i], lw[i + 1]);
                // Orient so that the weight decays from s = 0: z = −|Δ ln W|.
                let flip = lwb > lwa;
                let (lw_max, z) = if flip {
                    (lwb, lwa - lwb)
                } else {
                    (lwa, lwb - lwa)
                };
                let rule = ExpGauss2::new(z);
                let scale = lw_max.exp() * width;
                // Node positions in u, ascending.
                let mut nodes = [0usize, 1];
                let pos = |s: f64| if flip { b - s * width } else { a + s * width };
                if flip {
                    nodes = [1, 0];
                }
                for &k in &nodes {
                    let u = pos(rule.s[k]);
                    let q = u.exp();
                    let w_ref = lw_max + z * rule.s[k];
                    g.q.push(q);
                    g.u.push(u);
                    g.w.push(rule.w[k] * scale);
                    if power_law {
                        g.rho.push(1.0);
                        g.w_at.push(w_ref.exp());
                    } else {
                        let lw_u = ln_w(u);
                        g.rho.push((lw_u - w_ref).exp());
                        g.w_at.push(lw_u.exp());
                    }
                }
                // partial[j][k]: G from the panel's left end to ascending node j, per ascending node k.
                let mut partial = [[0.0; 2]; 2];
                for (jj, &j) in nodes.iter().enumerate() {
                    for (kk, &k) in nodes.iter().enumerate() {
                        let from_s0 = rule.partial[j][k] * scale;
                        partial[jj][kk] = if flip {
                            rule.w[k] * scale - from_s0
                        } else {
                            from_s0
                        };
                    }
                }
                g.beta.push((lwb - lwa) / width);
                g.partial.push(partial);
                // ∫ from the left end = −∫ from the right end when flipped (the full-panel integral
                // of (s − s1)(s − s2) vanishes by orthogonality); (u − u1)(u − u2) = Δ²(s − s1)(s − s2).
                let c = |k: usize| 0.5 * rule.curv[k] * scale * width * width;
                g.partial_curv.push(if flip {
                    [-c(nodes[0]), -c(nodes[1])]
                } else {
                    [c(nodes[0]), c(nodes[1])]
                });
                let (u1, u2) = (g.u[g.u.len() - 2], g.u[g.u.len() - 1]);
                g.inv_gap.push(1.0 / (u2 - u1));
                g.err4.push(rule.err4 * scale * width.powi(4));
                g.width.push(width);
                g.left.push(a);
                if power_law {
                    g.lw_left.push(lwa);
                }
                if b <= q_oct.ln() + 1e-12 {
                    g.low_octave_panels += 1;
                }
            }
        }
        g.inv_span = std::array::from_fn(|i| {
            let k = i + 1;
            g.u.iter()
                .zip(g.u.iter().skip(k))
                .map(|(a, b)| 1.0 / (b - a))
                .collect()
        });
        g.bare = g.bare_integral();
        g.unit_rho = g.rho.iter().all(|&r| r == 1.0);
        g
    }

    /// W = q⁴C at q = e^u: from the panel's power law when there is one, else from the spectrum.
    pub(super) fn w_at_u(&self, spectrum: &Spectrum, u: f64) -> f64 {
        if self.lw_left.is_empty() {
            let q = u.exp();
            return q.powi(4) * spectrum.c(q);
        }
        let p = self.left.partition_point(|&l| l <= u).saturating_sub(1);
        (self.lw_left[p] + self.beta[p] * (u - self.left[p])).exp()
    }

    /// Newton's divided differences of `f` over the nodes lo..hi: `out[k − 1][j]` =
    /// f[u_j, …, u_{j+k}] for k = 1..4 and lo ≤ j < hi − k (each `out[k − 1]` made hi long;
    /// other entries are left as they were). Each level is one loop over consecutive nodes, with
    /// the grid's reciprocal spans for the divisions: vectorised, with AVX2 where the CPU has it
    /// (`crate::simd`; the same values to the last bit).
    pub(super) fn newton(&self, f: &[f64], lo: usize, hi: usize, out: &mut [Vec<f64>; 4]) {
        with_avx2!(
            self.newton_avx2(f, lo, hi, out),
            self.newton_in(f, lo, hi, out)
        )
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn newton_avx2(&self, f: &[f64], lo: usize, hi: usize, out: &mut [Vec<f64>; 4]) {
        self.newton_in(f, lo, hi, out);
    }

    #[inline(always)]
    fn newton_in(&self, f: &[f64], lo: usize, hi: usize, out: &mut [Vec<f64>; 4]) {
        for k in 1..=4 {
            let end = hi.saturating_sub(k).max(lo);
            let (done, todo) = out.split_at_mut(k - 1);
            let prev: &[f64] = if k == 1 { f } else { &done[k - 2] };
            let cur = sized(&mut todo[0], hi, 0.0);
            for ((c, &inv), (a, b)) in cur[lo..end]
                .iter_mut()
                .zip(&self.inv_span[k - 1][lo..end])
                .zip(prev[lo..end].iter().zip(&prev[lo + 1..end + 1]))
            {
                *c = (b - a) * inv;
            }
        }
    }

    pub(super) fn panels(&self) -> usize {
        self.err4.len()
    }

    /// Per-panel error estimates of Σ w f, f = ρψ: the Gauss error term with ψ⁗ from the fourth
    /// divided difference of f over five neighbouring nodes (`d4`: [`Grid::newton`]'s fourth
    /// level over all nodes).
    pub(super) fn panel_errors(&self, d4: &[f64], out: &mut Vec<f64>) {
        let (n, panels) = (self.q.len(), self.panels());
        let out = sized(out, panels, 0.0);
        if n < 5 {
            out.fill(0.0);
            return;
        }
        // Panel p's window starts at node 2p − 2, clamped to [0, n − 5]: panel 0 and the last
        // panel (2p − 2 > n − 5) apart, the windows of panels 1.. are d4[0], d4[2], ….
        let inner = ((n - 3) / 2 + 1).min(panels).max(1);
        let err = |e: f64, d: f64| ERR_SAFETY * e * (24.0 * d).abs();
        // Panel 0's window lies two nodes right of where it would be centred, the last panels'
        // up to one node left: where the fourth difference grows towards that edge by a ratio r
        // per node, ψ⁗ on the panel is about r^shift times the window's (`edge_growth`).
        let (first, last) = if n >= 6 {
            (edge_growth(d4[0], d4[1]), edge_growth(d4[n - 5], d4[n - 6]))
        } else {
            (1.0, 1.0)
        };
        out[0] = err(self.err4[0], d4[0]) * edge_factor(first, 2);
        for ((o, &e), &d) in out[1..inner]
            .iter_mut()
            .zip(&self.err4[1..inner])
            .zip(d4.iter().step_by(2))
        {
            *o = err(e, d);
        }
        for (p, (o, &e)) in out.iter_mut().zip(&self.err4).enumerate().skip(inner) {
            *o = err(e, d4[n - 5]) * edge_factor(last, (2 * p + 3).saturating_sub(n) as i32);
        }
    }

    /// Σ_j w_j f_j over all panels for f = ρψ, with the panel error estimates already made and
    /// the summation's rounding ([`sum4`] for both sums). Every term is positive (Gauss weights
    /// for a positive weight function, ρ and S⁻² positive), so the sum is also Σ|w_j f_j|.
    pub(super) fn sum_with_errors(&self, f: &[f64], errs: &[f64]) -> (f64, f64) {
        let (w, f) = (&self.w[..], &f[..self.w.len()]);
        let sum = sum4(w.len(), |j| w[j] * f[j]);
        let err = sum4(errs.len(), |p| errs[p]);
        (sum, err + 8.0 * EPS * sum * (self.q.len() as f64).sqrt())
    }

    /// ∫W du (Σ_j w_j ρ_j) with its error estimate, for E_eff.
    fn bare_integral(&self) -> (f64, f64) {
        let (mut errs, mut dd) = (vec![], Default::default());
        self.newton(&self.rho, 0, self.q.len(), &mut dd);
        self.panel_errors(&dd[3], &mut errs);
        self.sum_with_errors(&self.rho, &errs)
    }

    /// Σ w ρ K F² P over the panels [from, to) with its error estimate, from `a` = ρ K F² at the
    /// nodes (up to two panels and a node past `to`) and P at them.
    ///
    /// The Gauss error term: P = P(G(u)) has kinks in its second derivative at the spectrum's
    /// knots (G'' jumps there) and so cannot be differenced across panels. The smooth factor `a`
    /// is differenced (divided differences over five nodes); P's u-derivatives at each panel's
    /// first node (`p_der`, from [`probability_derivatives`]) come from the chain rule with the
    /// analytic G-derivatives of erf(a/√G); Leibniz's rule gives (aP)⁗ and the error term
    /// err4·|(aP)⁗|, with the safety factor. Then P's own error from G's: `dp_cum` (the
    /// cumulative G error times |dP/dG|) and `dp_part` (the partial integral's curvature term
    /// times dP/dG, signed), weighted by w·a.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn interface_sum(
        &self,
        a: &[f64],
        dd: &mut [Vec<f64>; 4],
        p_node: &[f64],
        dp_cum: &[f64],
        dp_part: &[f64],
        p_der: &[[f64; 5]],
        from: usize,
        to: usize,
    ) -> (f64, f64) {
        let n = self.q.len();
        let lo = 2 * from;
        let differenced = n >= lo + 5;
        if differenced {
            self.newton(a, lo, a.len(), dd);
        }
        let (mut v, mut gauss, mut dp) = (0.0, 0.0, 0.0);
        for (p, pd) in p_der.iter().enumerate().take(to).skip(from) {
            let (j0, j1) = (2 * p, 2 * p + 1);
            let (wa0, wa1) = (self.w[j0] * a[j0], self.w[j1] * a[j1]);
            v += wa0 * p_node[j0] + wa1 * p_node[j1];
            dp += wa0 * dp_cum[j0]
                + wa1 * dp_cum[j1]
                + ERR_SAFETY * (wa0 * dp_part[j0] + wa1 * dp_part[j1]).abs();
            if differenced {
                let start = j0.saturating_sub(2).max(lo).min(n - 5);
                // a[u_s..u_{s+k}] ≈ a^(k)/k!.
                let d4 = 24.0 * dd[3][start] * pd[0]
                    + 4.0 * 6.0 * dd[2][start] * pd[1]
                    + 6.0 * 2.0 * dd[1][start] * pd[2]
                    + 4.0 * dd[0][start] * pd[3]
                    + a[j0] * pd[4];
                gauss += ERR_SAFETY * self.err4[p] * d4.abs();
            }
        }
        (v, gauss + dp)
    }
}

/// |a/b|, the growth per node of the fourth difference towards an edge of the grid (from the
/// window `b` next to the edge's `a`); 1 where it does not grow or either is 0.
fn edge_growth(a: f64, b: f64) -> f64 {
    let r = (a / b).abs();
    if r.is_finite() && r > 1.0 { r } else { 1.0 }
}

/// How much an edge panel's estimate grows for a window `shift` nodes off its centre, given the
/// growth `r` per node towards the edge: r^shift, beyond what [`ERR_SAFETY`] covers already. 1
/// while r^shift ≤ ERR_SAFETY: the divided difference is then a local derivative within that
/// factor. Beyond it (a kernel changing by more than a factor ERR_SAFETY over a node spacing,
/// as S⁻² near q_L at q·d ≈ 10 on wide panels) it is the function's value at the window's edge
/// over the node spacings, not ψ⁗ on the panel.
fn edge_factor(r: f64, shift: i32) -> f64 {
    (r.powi(shift) / ERR_SAFETY).max(1.0)
}

/// Σ_{j < n} term(j) in four running sums (term j into sum j mod 4), added pairwise at the end:
/// four chains of additions that overlap instead of one.
#[inline(always)]
fn sum4(n: usize, term: impl Fn(usize) -> f64) -> f64 {
    let mut s = [0.0; 4];
    let full = n - n % 4;
    for j in (0..full).step_by(4) {
        for (k, s) in s.iter_mut().enumerate() {
            *s += term(j + k);
        }
    }
    for (s, j) in s.iter_mut().zip(full..n) {
        *s += term(j);
    }
    (s[0] + s[1]) + (s[2] + s[3])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::psd::Tabulated;

    /// W from the grid's panel power laws equals q⁴C(q) from the spectrum, inside knot intervals
    /// split by the panel width or not.
    #[test]
    fn panel_power_law_is_the_spectrum() {
        let q: Vec<f64> = (0..40).map(|i| 1e4 * 1.3f64.powi(i)).collect();
        let c: Vec<f64> = q
            .iter()
            .enumerate()
            .map(|(i, &q)| q.powf(-3.6) * (1.0 + 0.5 * (i as f64).sin()))
            .collect();
        let spectrum = Spectrum::Tabulated(Tabulated::new(q.clone(), c).unwrap());
        let grid = Grid::new(&spectrum, &Knots::new(&spectrum, 0.1).unwrap());
        let (u0, u1) = (q[0].ln(), q[39].ln());
        for i in 0..=1000 {
            let u = u0 + (u1 - u0) * i as f64 / 1000.0;
            let want = u.exp().powi(4) * spectrum.c(u.exp());
            let got = grid.w_at_u(&spectrum, u);
            assert!((got / want - 1.0).abs() < 1e-12, "u = {u}: {got} vs {want}");
        }
    }

    /// The baseline build of the divided differences equals the dispatched one (AVX2 where the
    /// CPU has it) to the last bit, over a whole grid and over a part of it.
    #[test]
    fn newton_baseline_equals_dispatched() {
        let q: Vec<f64> = (0..300).map(|i| 1e4 * 1.05f64.powi(i)).collect();
        let c: Vec<f64> = q.iter().map(|&q| q.powf(-3.6)).collect();
        let spectrum = Spectrum::Tabulated(Tabulated::new(q, c).unwrap());
        let grid = Grid::new(&spectrum, &Knots::new(&spectrum, 0.02).unwrap());
        let n = grid.q.len();
        let f: Vec<f64> = grid.u.iter().map(|u| (3.0 * u).sin() * u.exp()).collect();
        for (lo, hi) in [(0, n), (17, n - 3)] {
            let (mut a, mut b): ([Vec<f64>; 4], [Vec<f64>; 4]) = Default::default();
            grid.newton(&f, lo, hi, &mut a);
            grid.newton_in(&f, lo, hi, &mut b);
            for k in 0..4 {
                assert_eq!(a[k].len(), hi);
                assert!(
                    a[k].iter()
                        .zip(&b[k])
                        .all(|(x, y)| x.to_bits() == y.to_bits())
                );
            }
        }
    }

    /// The per-panel errors and the sums: each panel's fourth difference taken from the window
    /// starting at node 2p − 2 clamped to [0, n − 5], as written out here; the sum and the summed
    /// errors equal straight sums within rounding.
    #[test]
    fn panel_errors_take_each_panels_window() {
        for knots in [3, 4, 9, 40] {
            let q: Vec<f64> = (0..knots).map(|i| 1e4 * 1.3f64.powi(i)).collect();
            let c: Vec<f64> = q.iter().map(|&q| q.powf(-3.2)).collect();
            let spectrum = Spectrum::Tabulated(Tabulated::new(q, c).unwrap());
            let grid = Grid::new(&spectrum, &Knots::new(&spectrum, 0.1).unwrap());
            let n = grid.q.len();
            let d4: Vec<f64> = (0..n)
                .map(|j| (j as f64 + 1.0) * if j % 3 == 0 { -1.0 } else { 1.0 })
                .collect();
            let mut errs = vec![];
            grid.panel_errors(&d4, &mut errs);
            assert_eq!(errs.len(), grid.panels());
            for (p, &e) in errs.iter().enumerate() {
                let start = (2 * p).saturating_sub(2).min(n - 5);
                let want = ERR_SAFETY * grid.err4[p] * (24.0 * d4[start]).abs();
                assert_eq!(e.to_bits(), want.to_bits(), "n = {n}, panel {p}");
            }
            let f: Vec<f64> = grid.u.iter().map(|u| (0.3 * u).exp()).collect();
            let (sum, err) = grid.sum_with_errors(&f, &errs);
            let want: f64 = grid.w.iter().zip(&f).map(|(w, f)| w * f).sum();
            let want_err: f64 = errs.iter().sum();
            assert!((sum - want).abs() <= 1e-14 * want, "n = {n}");
            // Plus the summation's rounding, 8ε√n Σ|w f|.
            let rounding = 8.0 * EPS * (n as f64).sqrt() * want;
            assert!((err - want_err - rounding).abs() <= 1e-14 * (want_err + rounding));
        }
    }
}
