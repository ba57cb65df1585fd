//! Contact: G(q), P(q), A/A0 (eqs. B11, B12), rms stresses (B8–B10), E_eff (Fig. 10) and the
//! stress distributions of Appendix B.
//!
//! Conventions (notes.md): z = 0 is the film's top surface, z = d the film–substrate interface.
//! - G(q) = (π/4) E0*² ∫_{q_L}^{q} q'³ C S⁻² dq' (eq. B12, q_L the spectrum's lowest q),
//!   P(q) = erf(p0/(2√G)) (B11), A/A0 = P(q1).
//! - σ_rms(z)² = (π/2) E0*² ∫ q³ C S⁻² P F² dq = 2∫ P F² dG, F = 1 at z = 0, f at z = d; τ_rms² the
//!   same with g (B8–B10 with d²q = 2πq dq). At z = 0 this has a closed form in G(q1):
//!   σ_top² = 2[G1 erf(u) + (p0²/(2√π))(e^{−u²}/u − √π erfc u)], u = p0/(2√G1).
//! - E_eff*² = E0*² ∫q³C S⁻² dq / ∫q³C dq; reported as E_eff*/E0* ("E_eff/E_film").
//!
//! Quadrature. In u = ln q the integrand is W(u)·ψ(u), W = q⁴C. Panels run between the
//! spectrum's own knots (data points, q0, q_r, q1, and 2q_L for the low-octave share), split so
//! that none is wider than h = 1.25·rtol^{1/4} in ln q. On each panel W is replaced by the exact
//! power law through its end values (exact for tabulated and self-affine spectra; the smooth
//! remainder ρ = W/W_ref of a Gaussian band goes into ψ), and a two-node Gauss rule for that
//! exponential weight integrates ψ = ρ S⁻² (times P F² for the interface). Its error is
//! ψ⁗(ξ)·∫W(u−u1)²(u−u2)²du/24, estimated with the fourth divided difference of ψ over five
//! neighbouring nodes and a safety factor 2. Nodes and weights do not depend on d: an [`Engine`]
//! is built once per spectrum and serves every thickness. G at the interior nodes (for P) comes
//! from the same rule's partial integrals (exact for ψ linear on the panel).
//! The kernels S⁻², f², g² at the nodes come from a [`KernelTable`] of the material pair (built
//! once per engine and pair, checked against the exact forms to 2e−14 relative; the exact forms
//! when no table resolves them), two to four times cheaper than the stable forms themselves,
//! and evaluated at all nodes in batches (`KernelTable::k_many`, `interface_many`), as is P
//! (`special::erf_and_gauss_many`): the per-node loops have no branches and are vectorised.
//! Linear P: P decreases with q (G increases). From the first panel where x = p0/(2√G) ≤ 1 and
//! Taylor's remainder (3/4)|dP/dG|(G1 − G)²/G is below rtol/100 of A, P is taken as
//! A + |dP/dG|(G1)·(G1 − G) with that remainder added to its error (`linear_probability`): no
//! erf and no analytic derivatives there. For thin films, where G saturates near q_L, that is
//! most of the range (d = 1 µm on the benchmark PSD: 510 of the 761 panels before the cut; none
//! at 5 µm and above, where P still falls towards the cut).
//! Interface tail: above q·d = 20 f e^x and g e^x are linear in x to 1e−15 (the far field of
//! `layer::KernelTable`: the stable forms' e^{−2x} terms are below x²e^{−2x} < 2e−15 there), and
//! (a + bx)e^{−x} with a/b ≥ 0 decreases for x > 1: f² and g² decrease. The interface integrals
//! stop at the first panel whose first node has q·d ≥ 20 and F²(node)·∫W K du beyond it (a bound
//! on the rest, P ≤ 1) below tol = rtol/1000 times A·∫W K F² du before it (a lower bound on the
//! integral so far, since P ≥ P(G1) = A everywhere); that bound is added to their error estimate.
//! The cut adapts to the film and the spectrum: f, g and P are evaluated only where they matter.
//! If the estimate misses rtol, the evaluation is repeated on grids with panels halved, up to
//! [`MAX_REFINE`] times, and reports `ToleranceNotReached` if it still misses.

use crate::error::Error;
use crate::layer::{Bilayer, KernelTable, Nodes, Squared, Stack};
use crate::prec::{EPS, Estimate, KERNEL_RTOL, Settings, Termination};
use crate::psd::Spectrum;
use crate::quad::{self, ExpGauss2};
use crate::simd::with_avx2;
use crate::special::{erf_and_gauss, erf_and_gauss_many};
use libm::{erf, erfc};
use serde::Serialize;
use statrs::function::erf::erfc_inv;
use std::f64::consts::{FRAC_2_SQRT_PI, PI};
use std::sync::{Arc, Mutex, OnceLock};

/// How many times a grid may be refined (panels halved) when the error estimate misses rtol.
pub const MAX_REFINE: usize = 3;
/// Safety factor on the divided-difference error estimate.
const ERR_SAFETY: f64 = 2.0;

/// Which quantities to compute; only these are evaluated (the area alone never touches f, g).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct Request {
    /// σ_rms at the top surface (z = 0).
    pub sigma_top: bool,
    /// σ_rms of the interface normal stress (z = d).
    pub sigma_interface: bool,
    /// τ_rms of the interface shear stress (z = d).
    pub tau_interface: bool,
    /// E_eff / E0 (Fig. 10).
    pub e_eff: bool,
}

impl Request {
    pub fn all() -> Self {
        Self {
            sigma_top: true,
            sigma_interface: true,
            tau_interface: true,
            e_eff: true,
        }
    }

    fn interface(&self) -> bool {
        self.sigma_interface || self.tau_interface
    }
}

/// Results at one thickness; fields not requested are `None`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Contact {
    pub thickness: f64,
    pub pressure: f64,
    /// G(q1), Pa².
    pub g1: Estimate,
    /// A/A0 = P(q1).
    pub area_fraction: Estimate,
    pub sigma_rms_top: Option<Estimate>,
    pub sigma_rms_interface: Option<Estimate>,
    pub tau_rms_interface: Option<Estimate>,
    pub e_eff_over_e_film: Option<Estimate>,
    /// Share of G(q1) from the lowest octave [q_L, 2 q_L] of the spectrum (1 when the spectrum
    /// spans less than an octave).
    pub low_octave_share: f64,
    /// How many kernel evaluations the result took (all grids tried).
    pub kernel_evaluations: usize,
    /// How many of them evaluated the interface kernels f, g as well as S (0 unless an
    /// interface stress was requested).
    pub interface_kernel_evaluations: usize,
}

/// One quadrature grid: nodes in ascending q with d-independent weights.
struct Grid {
    q: Vec<f64>,
    u: Vec<f64>,
    /// Rule weight of node j (∫ W_ref ℓ_j du over its panel), ρ_j excluded.
    w: Vec<f64>,
    /// ρ_j = W(u_j)/W_ref(u_j).
    rho: Vec<f64>,
    /// Whether every ρ_j is 1 (piecewise power-law spectra).
    unit_rho: bool,
    /// W(u_j) = q_j⁴ C(q_j), for dG/du at the nodes.
    w_at: Vec<f64>,
    /// Per panel: d ln W_ref / du.
    beta: Vec<f64>,
    /// Per panel: error constant ∫ W_ref (u−u1)²(u−u2)² du / 24.
    err4: Vec<f64>,
    /// Per panel: partial-integral coefficients for G at its two nodes (from the panel's left end).
    partial: Vec<[[f64; 2]; 2]>,
    /// Per panel: the leading error term of those partial integrals per unit ψ'' (signed).
    partial_curv: Vec<[f64; 2]>,
    /// Per panel: 1/(u_2 − u_1), its two nodes' distance.
    inv_gap: Vec<f64>,
    /// Per panel: width in u and left end.
    width: Vec<f64>,
    left: Vec<f64>,
    /// Per panel: ln W at its left end when the spectrum is a piecewise power law (W is then
    /// e^{lw + β(u − left)} on the panel), else empty.
    lw_left: Vec<f64>,
    /// Number of panels below 2 q_L.
    low_octave_panels: usize,
    /// ∫W du and its error estimate (E_eff's denominator).
    bare: (f64, f64),
    /// 1/(u_{j+k} − u_j) for k = 1..4 (entry k − 1; n − k of them), for Newton's divided
    /// differences without a division ([`Grid::newton`]).
    inv_span: [Vec<f64>; 4],
}

/// The grid's knots: the spectrum's own, with 2 q_L inserted, and how many panels each knot
/// interval is split into for panels no wider than `h_max` in ln q. Grids of equal splits are
/// equal, whatever the h_max (engines of one spectrum share them: [`Engine::sibling`]).
struct Knots {
    q: Vec<f64>,
    q_oct: f64,
    splits: Vec<u32>,
}

impl Knots {
    /// Fails when the spectrum's knots collapse to one point (a support narrower than 1e-12
    /// relative: no panel) or W = q⁴C is not finite and positive at one of them (no power law
    /// through it).
    fn new(spectrum: &Spectrum, h_max: f64) -> Result<Knots, Error> {
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
        let w = |k: f64| k.powi(4) * spectrum.c(k);
        if let Some(&k) = knots.iter().find(|&&k| !(w(k).is_finite() && w(k) > 0.0)) {
            return Err(Error::Numerical {
                what: "contact quadrature",
                detail: format!("q⁴C(q) = {:e} at the spectrum's knot q = {k:e} 1/m", w(k)),
            });
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
    fn new(spectrum: &Spectrum, knots: &Knots) -> Grid {
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
    fn w_at_u(&self, spectrum: &Spectrum, u: f64) -> f64 {
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
    fn newton(&self, f: &[f64], lo: usize, hi: usize, out: &mut [Vec<f64>; 4]) {
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

    fn panels(&self) -> usize {
        self.err4.len()
    }

    /// Per-panel error estimates of Σ w f, f = ρψ: the Gauss error term with ψ⁗ from the fourth
    /// divided difference of f over five neighbouring nodes (`d4`: [`Grid::newton`]'s fourth
    /// level over all nodes).
    fn panel_errors(&self, d4: &[f64], out: &mut Vec<f64>) {
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
    fn sum_with_errors(&self, f: &[f64], errs: &[f64]) -> (f64, f64) {
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
    fn interface_sum(
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

/// Relative error of the n-point Gauss–Legendre rule on ∫ x^{-1/2} dx over a panel at ρ times
/// its width from the singular point, ≈ C_n (2ρ + 1)^{−2n}: C_n fitted to 30-digit evaluations for
/// n = 2..7 at ρ = 1..64 (within a factor 1.3 there). P(G(u)) behaves so near q_L.
fn graded_rule_error(n: usize, rho: f64) -> f64 {
    const C: [f64; GL_MAX + 1] = [0.0, 0.0, 0.024, 5.2e-3, 1.2e-3, 2.9e-4, 7.0e-5, 1.7e-5];
    C[n.min(GL_MAX)] * (2.0 * rho + 1.0).powi(-2 * n as i32)
}

/// The most Gauss–Legendre nodes on a graded panel.
const GL_MAX: usize = 7;

/// The per-panel share of rtol a graded-region panel's (or the first base panels') error may
/// take: their errors add up over panels whose integrals are each a small part of the total.
const GRADED_SHARE: f64 = 0.05;

/// How far the graded region reaches above q_L, in panel widths: where the two-node base rule's
/// error on the x^{-1/2} behaviour falls below [`SPAN_SHARE`]·rtol (at most 64 widths: 64 at
/// rtol 1e-8, 23 at 1e-6). The base panels' own estimate (P's derivatives by the chain rule,
/// with a safety factor) is more cautious than this model, and with the 20 times larger
/// [`GRADED_SHARE`] it exceeded rtol for σ_rms at the interface on the bundled measured PSD
/// (d = 20 µm), refining the whole grid.
fn graded_span(rtol: f64) -> f64 {
    (1..=64)
        .map(f64::from)
        .find(|&rho| graded_rule_error(2, rho) <= SPAN_SHARE * rtol)
        .unwrap_or(64.0)
}

/// The share of rtol the base rule's model error may take where it takes over from the graded
/// panels ([`graded_span`]).
const SPAN_SHARE: f64 = 0.0025;

/// Nodes of a graded panel at ρ times its width from q_L, over which the integrand also grows or
/// decays like e^{βu} with βw = `z` (W's power law plus the kernels'): the fewest (3 to [`GL_MAX`])
/// whose companion rule (one node fewer, the error estimate) meets [`GRADED_SHARE`]·rtol on
/// both. The m-point rule's relative error on e^{βu} is about (m!)⁴ z^{2m}/((2m+1)((2m)!)³)
/// (1/4320 z⁴ for m = 2).
fn graded_nodes(rho: f64, z: f64, rtol: f64) -> usize {
    let exp_error = |m: i32| {
        let fact = |k: i32| (1..=k).map(f64::from).product::<f64>();
        fact(m).powi(4) * z.abs().powi(2 * m) / (f64::from(2 * m + 1) * fact(2 * m).powi(3))
    };
    (3..=GL_MAX)
        .find(|&n| graded_rule_error(n - 1, rho) + exp_error(n as i32 - 1) <= GRADED_SHARE * rtol)
        .unwrap_or(GL_MAX)
}
/// Width (in ln q) of the innermost piece above q_L, done in closed form.
const INNER_WIDTH: f64 = 1e-11;

/// One n-point Gauss–Legendre panel of the graded region (n ≤ [`GL_MAX`]), with an (n−1)-point companion
/// rule for the error estimate. Weights include W = q⁴C at the node; `b`, `bc` integrate the
/// n-node interpolant of the G integrand from the panel's left end to each node. Only the first
/// n (n − 1) entries are used.
struct GlPanel {
    n: usize,
    q: [f64; GL_MAX],
    u: [f64; GL_MAX],
    w: [f64; GL_MAX],
    b: [[f64; GL_MAX]; GL_MAX],
    qc: [f64; GL_MAX - 1],
    uc: [f64; GL_MAX - 1],
    wc: [f64; GL_MAX - 1],
    bc: [[f64; GL_MAX]; GL_MAX - 1],
    /// Positions of the n nodes and of the n − 1 companion nodes among the panel's 2n − 1
    /// nodes in ascending order (how [`Graded::nodes`] holds them).
    at: [usize; GL_MAX],
    atc: [usize; GL_MAX - 1],
}

/// The interface quadrature near q_L, where P(G(u)) ∝ (u − u_L)^{-1/2} once G ≫ p0²: panels
/// shrinking towards q_L (each as wide as its distance to q_L, split at the spectrum's knots),
/// n-point Gauss–Legendre on each (n = 7 next to q_L at rtol 1e-8, fewer further out: [`graded_nodes`];
/// error: the difference to n − 1 points), and the innermost
/// [u_L, u_L + 1e-11] in closed form, ∫_0^{G} P dG being known exactly.
///
/// Within the first base panel (no knot there) the panels are linear in s = √(u − u_L) and
/// halve in s, not in u: the integrand W S⁻² F² P is then ∝ s·(u − u_L)^{-1/2}, bounded, and
/// still analytic but at s = 0, so a panel as wide as its distance from q_L in s converges as
/// fast as one so in u, and half as many of them span the same range (at d = 1 µm on the
/// 1000-point benchmark PSD, 679 nodes instead of 848 in the region).
///
/// Where G stays below (p0/2)²/36 the contact probability is erf(≥ 6) = 1 in f64 and the
/// integrand is smooth: the innermost panels up to there are replaced by one 6-point panel from
/// q_L (`merged`, chosen per evaluation from a bound on G). Where G stays below (p0/2)²/3 over the
/// whole region P varies slowly and the base grid starts at q_L (see `evaluate_on`).
struct Graded {
    panels: Vec<GlPanel>,
    /// Every panel's nodes and companion nodes (q, u), ascending, and where each panel's start.
    nodes: (Vec<f64>, Vec<f64>),
    offsets: Vec<usize>,
    /// First two-node panel of the base grid after the graded region.
    base_from: usize,
    q_l: f64,
    /// W(q_L) times the innermost piece's width.
    w_l: f64,
    /// W(q_L).
    w_at_l: f64,
    /// One panel over [u_L, right end of panel i] for each i whose end lies within the first
    /// base panel (no knot inside), and those ends' offsets from u_L.
    merged: Vec<(f64, GlPanel)>,
    /// γ with G(u_L + r) ≤ G'(u_L)·r·e^{γr} within the first base panel: |d ln W/du| there
    /// plus 8 ≥ |d ln S⁻²/du| (≤ 6: S⁻² is at most ∝ (qd)⁻⁶).
    growth: f64,
}

struct Near {
    g_raw: f64,
    g_raw_err: f64,
    sigma: (f64, f64),
    tau: (f64, f64),
    /// Kernel evaluations made.
    evaluations: usize,
}

/// Near-q_L sums before any panel: nothing.
const NEAR_NONE: Near = Near {
    g_raw: 0.0,
    g_raw_err: 0.0,
    sigma: (0.0, 0.0),
    tau: (0.0, 0.0),
    evaluations: 0,
};

/// The share of rtol (relative to A) by which P may differ from its linear model ("Linear P").
const FLAT_SHARE: f64 = 0.01;

/// Where G stays below (p0/2)² divided by this over the graded region, it is not used.
const GRADED_SKIP: f64 = 3.0;

/// ∫_{-1}^{y} ℓ_k(x) dx for the Lagrange basis on `nodes`, by the Gauss–Legendre rule (x, w)
/// with as many nodes (exact for the degree-(n−1) basis).
fn lagrange_integral(nodes: &[f64], (x, w): (&[f64], &[f64]), k: usize, y: f64) -> f64 {
    let half = 0.5 * (y + 1.0);
    x.iter()
        .zip(w)
        .map(|(&xi, &wi)| {
            let t = -1.0 + half * (xi + 1.0);
            let l: f64 = nodes
                .iter()
                .enumerate()
                .filter(|&(m, _)| m != k)
                .map(|(_, &xm)| (t - xm) / (nodes[k] - xm))
                .product();
            wi * l
        })
        .sum::<f64>()
        * half
}

impl Graded {
    fn new(spectrum: &Spectrum, grid: &Grid, h: f64, rtol: f64) -> Graded {
        let q_l = spectrum.q_low();
        let u0 = q_l.ln();
        let u_end = spectrum.support().1.ln();
        // The two-node rule takes over where panels are narrower than 1/64 of their distance to q_L.
        let first = grid.width.first().copied().unwrap_or(h).min(h);
        let base_from = (0..grid.panels())
            .find(|&p| grid.left[p] - u0 >= graded_span(rtol) * first.max(grid.width[p]))
            .unwrap_or(grid.panels());
        let span = if base_from < grid.panels() {
            grid.left[base_from] - u0
        } else {
            u_end - u0
        };
        // Offsets from u_L of the panel ends: halving steps down to the first base panel's end,
        // quartering steps (halving in s = √(u − u_L)) within it, plus every base-grid end
        // (knots).
        let first_end = grid.width.first().copied().unwrap_or(span).min(span);
        let mut ends = vec![];
        let mut delta = span;
        while delta > first_end {
            ends.push(delta);
            delta *= 0.5;
        }
        delta = first_end;
        while delta > INNER_WIDTH {
            ends.push(delta);
            delta *= 0.25;
        }
        ends.push(delta);
        ends.extend(
            grid.left[..base_from]
                .iter()
                .map(|&l| l - u0)
                .filter(|&o| o > delta && o < span),
        );
        ends.sort_by(f64::total_cmp);
        ends.dedup_by(|a, b| (*a - *b).abs() <= 1e-14 * b.abs());
        // Gauss–Legendre rules with 2..GL_MAX nodes, and the partial-integral matrices of the n-node
        // interpolant at the n nodes and at the n − 1 companion nodes.
        let rules: Vec<(Vec<f64>, Vec<f64>)> = (0..=GL_MAX).map(quad::gauss_legendre).collect();
        let partials = |n: usize, at: &[f64]| -> [[f64; GL_MAX]; GL_MAX] {
            let (x, w) = (&rules[n].0, &rules[n].1);
            std::array::from_fn(|j| {
                std::array::from_fn(|k| match (at.get(j), k < n) {
                    (Some(&y), true) => lagrange_integral(x, (x, w), k, y),
                    _ => 0.0,
                })
            })
        };
        let bn: Vec<[[f64; GL_MAX]; GL_MAX]> = (0..=GL_MAX)
            .map(|n| {
                if n < 2 {
                    [[0.0; GL_MAX]; GL_MAX]
                } else {
                    partials(n, &rules[n].0)
                }
            })
            .collect();
        let bcn: Vec<[[f64; GL_MAX]; GL_MAX]> = (0..=GL_MAX)
            .map(|n| {
                if n < 2 {
                    [[0.0; GL_MAX]; GL_MAX]
                } else {
                    partials(n, &rules[n - 1].0)
                }
            })
            .collect();
        let w_of = |q: f64| grid.w_at_u(spectrum, q.ln());
        // An n-node panel in x ∈ [−1, 1] with u − u_L = r(x) by `map` (x ↦ (r, dr/dx)): its
        // weights and partial-integral matrices carry dr/dx·W at the nodes.
        let mapped_panel = |map: &dyn Fn(f64) -> (f64, f64), n: usize| {
            let at = |x: f64| {
                let (r, jac) = map(x);
                let q = q_l * r.exp();
                (q, jac * w_of(q))
            };
            let (x, gw) = (&rules[n].0, &rules[n].1);
            let (xc, gwc) = (&rules[n - 1].0, &rules[n - 1].1);
            let main: [(f64, f64); GL_MAX] =
                std::array::from_fn(|k| x.get(k).map_or((q_l, 0.0), |&x| at(x)));
            let comp: [(f64, f64); GL_MAX - 1] =
                std::array::from_fn(|k| xc.get(k).map_or((q_l, 0.0), |&x| at(x)));
            let (q, wq) = (main.map(|m| m.0), main.map(|m| m.1));
            let (qc, wqc) = (comp.map(|m| m.0), comp.map(|m| m.1));
            // Merge the two ascending node sets.
            let (mut at, mut atc) = ([0; GL_MAX], [0; GL_MAX - 1]);
            let (mut i, mut k) = (0, 0);
            while i < n || k < n - 1 {
                if k == n - 1 || (i < n && q[i] <= qc[k]) {
                    at[i] = i + k;
                    i += 1;
                } else {
                    atc[k] = i + k;
                    k += 1;
                }
            }
            GlPanel {
                n,
                at,
                atc,
                q,
                u: q.map(f64::ln),
                w: std::array::from_fn(|k| gw.get(k).map_or(0.0, |g| g * wq[k])),
                b: std::array::from_fn(|j| std::array::from_fn(|k| bn[n][j][k] * wq[k])),
                qc,
                uc: qc.map(f64::ln),
                wc: std::array::from_fn(|k| gwc.get(k).map_or(0.0, |g| g * wqc[k])),
                bc: std::array::from_fn(|j| std::array::from_fn(|k| bcn[n][j][k] * wq[k])),
            }
        };
        // Linear in u over [a, b].
        let gl_panel = |a: f64, b: f64, n: usize| {
            let half = 0.5 * (b - a);
            mapped_panel(&|x| (a + half * (x + 1.0), half), n)
        };
        // Linear in s = √(u − u_L) over [√a, √b].
        let s_panel = |a: f64, b: f64, n: usize| {
            let (sa, half) = (a.sqrt(), 0.5 * (b.sqrt() - a.sqrt()));
            mapped_panel(
                &|x| {
                    let s = sa + half * (x + 1.0);
                    (s * s, 2.0 * s * half)
                },
                n,
            )
        };
        // The halving sequence's panels (ρ = 1, or more where a knot splits them) and the
        // knot-split panels further out: as many nodes as their distance from q_L needs.
        let panels: Vec<GlPanel> = ends
            .windows(2)
            .map(|p| {
                // W's log-slope on the panel's base-grid panel, plus 8 for the kernels.
                let base = grid
                    .left
                    .partition_point(|&l| l <= u0 + p[0])
                    .saturating_sub(1);
                let z = (grid.beta[base].abs() + 8.0) * (p[1] - p[0]);
                if p[1] <= first_end {
                    let (sa, sb) = (p[0].sqrt(), p[1].sqrt());
                    s_panel(p[0], p[1], graded_nodes(sa / (sb - sa), z, rtol))
                } else {
                    gl_panel(p[0], p[1], graded_nodes(p[0] / (p[1] - p[0]), z, rtol))
                }
            })
            .collect();
        let merged = ends[1..]
            .iter()
            .take_while(|&&r| r <= first_end)
            .map(|&r| (r, gl_panel(0.0, r, 6)))
            .collect();
        let w_at_l = w_of(q_l);
        let slope = (w_of(q_l * first_end.exp()) / w_at_l).ln() / first_end;
        let mut offsets = Vec::with_capacity(panels.len() + 1);
        let (mut nq, mut nu) = (vec![], vec![]);
        for panel in &panels {
            offsets.push(nq.len());
            for &(q, u) in &panel.sorted()[..2 * panel.n - 1] {
                nq.push(q);
                nu.push(u);
            }
        }
        offsets.push(nq.len());
        Graded {
            panels,
            nodes: (nq, nu),
            offsets,
            base_from,
            q_l,
            w_l: w_at_l * ends[0],
            w_at_l,
            merged,
            growth: slope.abs() + 8.0,
        }
    }

    /// The graded region's sums: the kernels at all its nodes in two batches (S⁻², then f² and
    /// g²) into `buf`, G at all of them panel by panel, P at all of them in one batch, then the
    /// panels' sums.
    fn integrate(
        &self,
        kernels: &Kernels,
        p0: f64,
        cg: f64,
        req: Request,
        buf: &mut [Vec<f64>; 6],
    ) -> Near {
        let (k0, f0, g0) = {
            let r = kernels.squared(self.q_l, self.q_l.ln());
            (r.k, r.f2, r.g2)
        };
        // The largest merged panel over which G ≤ a²/36 by the bound G'(u_L)·r·e^{γr}.
        let (a2, gp0) = (0.25 * p0 * p0, cg * self.w_at_l * k0);
        let merge = self
            .merged
            .iter()
            .rposition(|&(r, _)| gp0 * r * (self.growth * r).exp() <= a2 / 36.0);
        let (mut near, first) = match merge {
            Some(i) => {
                let mut near = Near {
                    evaluations: 1,
                    ..NEAR_NONE
                };
                let panel = &self.merged[i].1;
                let m = 2 * panel.n - 1;
                let mut v = [[0.0; 2 * GL_MAX - 1]; 6];
                for (j, &(q, u)) in panel.sorted()[..m].iter().enumerate() {
                    let r = kernels.squared(q, u);
                    (v[0][j], v[1][j], v[2][j]) = (r.k, r.f2, r.g2);
                }
                let [k, f2, g2, x, p, gauss] = &mut v;
                panel.arguments(k, &mut near, p0, cg, x);
                erf_and_gauss_many(&x[..m], &mut p[..m], &mut gauss[..m]);
                panel.sums(k, f2, g2, p, &mut near, req);
                (near, i + 1)
            }
            None => {
                // Innermost piece: G grows linearly from 0, F² is constant to 1e-10.
                let g_inner = self.w_l * k0;
                let j0 = top_variance_half(p0, cg * g_inner) / cg;
                let near = Near {
                    g_raw: g_inner,
                    g_raw_err: 1e-9 * g_inner,
                    sigma: (f0 * j0, 1e-9 * f0 * j0),
                    tau: (g0 * j0, 1e-9 * g0 * j0),
                    evaluations: 1,
                };
                (near, 0)
            }
        };
        let lo = self.offsets[first];
        let (q, u) = (&self.nodes.0[lo..], &self.nodes.1[lo..]);
        let m = q.len();
        let [k, f2, g2, x, p, gauss] = buf;
        kernels.k_many(q, u, sized(k, m, 0.0));
        kernels.interface_many(q, u, sized(f2, m, 0.0), sized(g2, m, 0.0));
        let range = |i: usize| self.offsets[i] - lo..self.offsets[i + 1] - lo;
        sized(x, m, 0.0);
        for (i, panel) in self.panels.iter().enumerate().skip(first) {
            let r = range(i);
            panel.arguments(&k[r.clone()], &mut near, p0, cg, &mut x[r]);
        }
        erf_and_gauss_many(x, sized(p, m, 0.0), sized(gauss, m, 0.0));
        for (i, panel) in self.panels.iter().enumerate().skip(first) {
            let r = range(i);
            panel.sums(
                &k[r.clone()],
                &f2[r.clone()],
                &g2[r.clone()],
                &p[r],
                &mut near,
                req,
            );
        }
        near
    }
}

impl GlPanel {
    /// The panel's 2n − 1 nodes (q, u) in ascending order (the rest of the array unused).
    fn sorted(&self) -> [(f64, f64); 2 * GL_MAX - 1] {
        let mut out = [(0.0, 0.0); 2 * GL_MAX - 1];
        for k in 0..self.n {
            out[self.at[k]] = (self.q[k], self.u[k]);
        }
        for k in 0..self.n - 1 {
            out[self.atc[k]] = (self.qc[k], self.uc[k]);
        }
        out
    }

    /// x = p0/(2√G) at the panel's 2n − 1 nodes (ascending, into `x`) from S⁻² there (`k`) and
    /// G before the panel (`near.g_raw`, raw: without the factor cg); then the panel's n-node
    /// integral of S⁻² added to G and its difference to the companion's to G's error.
    fn arguments(&self, k: &[f64], near: &mut Near, p0: f64, cg: f64, x: &mut [f64]) {
        let n = self.n;
        let k_n: [f64; GL_MAX] = std::array::from_fn(|i| if i < n { k[self.at[i]] } else { 0.0 });
        let at = |row: &[f64; GL_MAX]| {
            let partial: f64 = row.iter().zip(&k_n).take(n).map(|(b, k)| b * k).sum();
            probability_argument(p0, cg * (near.g_raw + partial))
        };
        for (row, &pos) in self.b.iter().zip(&self.at).take(n) {
            x[pos] = at(row);
        }
        for (row, &pos) in self.bc.iter().zip(&self.atc).take(n - 1) {
            x[pos] = at(row);
        }
        let g_n: f64 = (0..n).map(|i| self.w[i] * k_n[i]).sum();
        let g_c: f64 = (0..n - 1).map(|i| self.wc[i] * k[self.atc[i]]).sum();
        near.g_raw += g_n;
        near.g_raw_err += (g_n - g_c).abs();
        near.evaluations += 2 * n - 1;
    }

    /// The panel's σ and τ sums (n nodes; error: the difference to the companion's) added to
    /// `near`, from S⁻², f², g² and P at its 2n − 1 nodes (ascending).
    fn sums(&self, k: &[f64], f2: &[f64], g2: &[f64], p: &[f64], near: &mut Near, req: Request) {
        let n = self.n;
        let add = |acc: &mut (f64, f64), k2: &[f64]| {
            let term = |w: f64, j: usize| w * k[j] * p[j] * k2[j];
            let i_n: f64 = (0..n).map(|i| term(self.w[i], self.at[i])).sum();
            let i_c: f64 = (0..n - 1).map(|i| term(self.wc[i], self.atc[i])).sum();
            acc.0 += i_n;
            acc.1 += (i_n - i_c).abs() + 8.0 * EPS * i_n.abs();
        };
        if req.sigma_interface {
            add(&mut near.sigma, f2);
        }
        if req.tau_interface {
            add(&mut near.tau, g2);
        }
    }
}

/// The d-independent part of the contact integrals for one spectrum; serves every thickness.
pub struct Engine {
    spectrum: Spectrum,
    settings: Settings,
    grids: [OnceLock<Arc<Grid>>; MAX_REFINE + 1],
    graded: [OnceLock<Graded>; MAX_REFINE + 1],
    shared: Arc<Shared>,
}

/// What engines of one spectrum share ([`Engine::sibling`]).
#[derive(Default)]
struct Shared {
    /// Grids built so far, by their knot splits.
    grids: Mutex<Vec<(Vec<u32>, Arc<Grid>)>>,
    /// The kernel table of the last material pair evaluated (d-independent; rebuilt, wider, when
    /// a thickness needs q·d outside it).
    table: Mutex<Option<Arc<KernelTable>>>,
}

/// Where f² and g² are known to decrease, the lowest q·d at which the interface integrals are
/// cut (module doc).
const X_CUT: f64 = 20.0;

/// How many nodes' f², g² are evaluated at a time beyond q·d = X_CUT, while the cut is looked
/// for (at most this many are evaluated and not used).
const CUT_CHUNK: usize = 16;

/// How far (in ln(qd)) a rebuilt kernel table reaches beyond the range asked for, so that a
/// thickness scan does not rebuild it at every step.
const TABLE_MARGIN: f64 = 2.0;

/// The layer kernels at nodes q (with u = ln q) for one thickness: tabulated, or exact when no
/// table resolves them (`layer::KernelTable`).
enum Kernels<'a> {
    Table {
        table: &'a KernelTable,
        d: f64,
        ln_d: f64,
    },
    Exact {
        layers: &'a Bilayer,
        d: f64,
    },
}

impl Kernels<'_> {
    #[inline]
    fn k(&self, q: f64, u: f64) -> f64 {
        match *self {
            Kernels::Table { table, d, ln_d } => table.k(q * d, u + ln_d),
            Kernels::Exact { layers, d } => layers.s(q * d).powi(-2),
        }
    }

    /// f², g² at the node.
    #[inline]
    fn interface(&self, q: f64, u: f64) -> (f64, f64) {
        match *self {
            Kernels::Table { table, d, ln_d } => table.interface(q * d, u + ln_d),
            Kernels::Exact { layers, d } => {
                let r = layers.response(q * d);
                (r.f * r.f, r.g * r.g)
            }
        }
    }

    /// S⁻² at the ascending nodes (q, u), into `out`.
    fn k_many(&self, q: &[f64], u: &[f64], out: &mut [f64]) {
        match *self {
            Kernels::Table { table, d, ln_d } => table.k_many(Nodes { q, u, d, ln_d }, out),
            Kernels::Exact { .. } => {
                for ((o, &q), &u) in out.iter_mut().zip(q).zip(u) {
                    *o = self.k(q, u);
                }
            }
        }
    }

    /// f², g² at the ascending nodes (q, u), into `f2` and `g2`.
    fn interface_many(&self, q: &[f64], u: &[f64], f2: &mut [f64], g2: &mut [f64]) {
        match *self {
            Kernels::Table { table, d, ln_d } => {
                table.interface_many(Nodes { q, u, d, ln_d }, f2, g2)
            }
            Kernels::Exact { .. } => {
                for (((fo, go), &q), &u) in f2.iter_mut().zip(g2.iter_mut()).zip(q).zip(u) {
                    (*fo, *go) = self.interface(q, u);
                }
            }
        }
    }

    #[inline]
    fn squared(&self, q: f64, u: f64) -> Squared {
        match *self {
            Kernels::Table { table, d, ln_d } => table.squared(q * d, u + ln_d),
            Kernels::Exact { layers, d } => {
                let r = layers.response(q * d);
                Squared {
                    k: r.s.powi(-2),
                    f2: r.f * r.f,
                    g2: r.g * r.g,
                }
            }
        }
    }
}

/// Panel width (in ln q) for a relative tolerance: the two-node rule's relative error per panel
/// is about h⁴ ψ⁗/(4320 ψ), with |ψ⁗/ψ| up to ~6⁴ where S⁻² ∝ (qd)⁻⁶.
pub fn panel_width(rtol: f64) -> f64 {
    (1.25 * rtol.max(1e-14).powf(0.25)).min(0.5)
}

impl Engine {
    pub fn new(spectrum: &Spectrum, settings: Settings) -> Self {
        Self {
            spectrum: spectrum.clone(),
            settings,
            grids: Default::default(),
            graded: Default::default(),
            shared: Arc::default(),
        }
    }

    /// An engine for the same spectrum with other settings, sharing this one's grids (where its
    /// panel width splits the knot intervals alike, as on a spectrum with dense points) and
    /// kernel tables: a check's search engine at a looser rtol costs no second set-up.
    pub fn sibling(&self, settings: Settings) -> Self {
        Self {
            spectrum: self.spectrum.clone(),
            settings,
            grids: Default::default(),
            graded: Default::default(),
            shared: Arc::clone(&self.shared),
        }
    }

    /// Builds the kernel table for `layers` at every thickness in [d_min, d_max] now, so that
    /// evaluations there (in parallel, in any order) all use the same one: a table rebuilt
    /// wider has other panels, and kernel values that differ within its 2e-14 tolerance.
    pub fn prepare(&self, layers: &Bilayer, d_min: f64, d_max: f64) {
        if d_min > 0.0 && d_max.is_finite() {
            self.table_covering(layers, d_min, d_max);
        }
    }

    /// A kernel table for `stack` covering every node's q·d, from the cache or newly built.
    fn table_for(&self, stack: &Stack) -> Option<Arc<KernelTable>> {
        self.table_covering(&stack.layers, stack.thickness, stack.thickness)
    }

    /// A kernel table for `layers` covering every node's q·d for d in [d_min, d_max].
    fn table_covering(&self, layers: &Bilayer, d_min: f64, d_max: f64) -> Option<Arc<KernelTable>> {
        let (q_lo, q_hi) = (self.spectrum.q_low(), self.spectrum.support().1);
        let (x_min, x_max) = (q_lo * d_min, q_hi * d_max);
        let mut cache = self.shared.table.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(t) = cache
            .as_ref()
            .filter(|t| t.layers() == layers && t.covers(x_min, x_max))
        {
            return Some(Arc::clone(t));
        }
        let (mut lo, mut hi) = (x_min.ln() - TABLE_MARGIN, x_max.ln() + TABLE_MARGIN);
        if let Some(t) = cache.as_ref().filter(|t| t.layers() == layers) {
            let (a, b) = t.range();
            (lo, hi) = (lo.min(a.ln()), hi.max(b.ln()));
        }
        let table = Arc::new(KernelTable::new(*layers, lo.exp(), hi.exp())?);
        *cache = Some(Arc::clone(&table));
        Some(table)
    }

    pub fn spectrum(&self) -> &Spectrum {
        &self.spectrum
    }

    pub fn settings(&self) -> Settings {
        self.settings
    }

    fn grid(&self, level: usize) -> Result<&Grid, Error> {
        if let Some(g) = self.grids[level].get() {
            return Ok(g);
        }
        let knots = Knots::new(
            &self.spectrum,
            panel_width(self.settings.rtol) / (1 << level) as f64,
        )?;
        Ok(self.grids[level].get_or_init(|| {
            let mut grids = self.shared.grids.lock().unwrap_or_else(|e| e.into_inner());
            if let Some((_, g)) = grids.iter().find(|(s, _)| *s == knots.splits) {
                return Arc::clone(g);
            }
            let g = Arc::new(Grid::new(&self.spectrum, &knots));
            grids.push((knots.splits, Arc::clone(&g)));
            g
        }))
    }

    fn graded(&self, level: usize) -> Result<&Graded, Error> {
        let grid = self.grid(level)?;
        Ok(self.graded[level].get_or_init(|| {
            Graded::new(
                &self.spectrum,
                grid,
                panel_width(self.settings.rtol) / (1 << level) as f64,
                // Each level halves the base panels: their error falls 16-fold.
                self.settings.rtol / 16f64.powi(level as i32),
            )
        }))
    }

    /// Evaluate at one stack (thickness) and nominal pressure p0 (Pa).
    pub fn evaluate(&self, stack: &Stack, p0: f64, request: Request) -> Result<Contact, Error> {
        if !(p0.is_finite() && p0 > 0.0) {
            return Err(Error::invalid(
                "nominal pressure p0",
                p0,
                "a finite pressure > 0 in Pa",
            ));
        }
        let table = self.table_for(stack);
        let kernels = match table.as_deref() {
            Some(table) => Kernels::Table {
                table,
                d: stack.thickness,
                ln_d: stack.thickness.ln(),
            },
            None => Kernels::Exact {
                layers: &stack.layers,
                d: stack.thickness,
            },
        };
        let mut evaluations = 0;
        let mut interface = 0;
        let mut last = None;
        for level in 0..=MAX_REFINE {
            let grid = self.grid(level)?;
            let graded = match request.interface() {
                true => Some(self.graded(level)?),
                false => None,
            };
            evaluations += grid.q.len();
            let mut c = SCRATCH.with_borrow_mut(|s| {
                evaluate_on(
                    grid,
                    graded,
                    &kernels,
                    stack,
                    p0,
                    request,
                    evaluations,
                    self.settings.rtol,
                    s,
                )
            })?;
            interface += c.interface_kernel_evaluations;
            c.interface_kernel_evaluations = interface;
            evaluations = c.kernel_evaluations;
            add_rounding_floor(&mut c);
            let done = converged(&c, self.settings.rtol);
            last = Some(c);
            if done {
                break;
            }
        }
        let mut c = last.expect("at least one grid level");
        if !converged(&c, self.settings.rtol) {
            mark_not_reached(&mut c, self.settings.rtol);
        }
        Ok(c)
    }
}

fn all_estimates(c: &Contact) -> impl Iterator<Item = &Estimate> {
    [
        Some(&c.g1),
        Some(&c.area_fraction),
        c.sigma_rms_top.as_ref(),
        c.sigma_rms_interface.as_ref(),
        c.tau_rms_interface.as_ref(),
        c.e_eff_over_e_film.as_ref(),
    ]
    .into_iter()
    .flatten()
}

fn converged(c: &Contact, rtol: f64) -> bool {
    all_estimates(c).all(|e| e.err <= rtol * e.value.abs() || e.value == 0.0 && e.err == 0.0)
}

/// Relative error every contact result carries whatever the grid: the kernels' rounding
/// ([`KERNEL_RTOL`], entering through S⁻² and f², g², i.e. twice, and once more through the
/// σ–G relations) and the summation over some thousand nodes (64 ε). Without it the quadrature
/// estimate alone fell below the true error near rtol 1e-10 (`examples/accuracy.rs`).
pub const ROUNDING_FLOOR: f64 = 4.0 * KERNEL_RTOL + 64.0 * EPS;

fn add_rounding_floor(c: &mut Contact) {
    for e in estimates_mut(c) {
        e.err += ROUNDING_FLOOR * e.value.abs();
    }
}

fn estimates_mut(c: &mut Contact) -> impl Iterator<Item = &mut Estimate> {
    [
        Some(&mut c.g1),
        Some(&mut c.area_fraction),
        c.sigma_rms_top.as_mut(),
        c.sigma_rms_interface.as_mut(),
        c.tau_rms_interface.as_mut(),
        c.e_eff_over_e_film.as_mut(),
    ]
    .into_iter()
    .flatten()
}

fn mark_not_reached(c: &mut Contact, rtol: f64) {
    for e in estimates_mut(c) {
        // A NaN estimate is never reported as converged.
        if e.err.is_nan() || e.err > rtol * e.value.abs() {
            e.status = Termination::ToleranceNotReached;
        }
    }
}

/// Buffers of one evaluation, kept per thread between evaluations: allocating and freeing them
/// every time made the allocator return the memory to the system (brk) and fetch it again,
/// ~9 % of an evaluation's time.
#[derive(Default)]
struct Scratch {
    f2: Vec<f64>,
    g2: Vec<f64>,
    f: Vec<f64>,
    g_errs: Vec<f64>,
    p_node: Vec<f64>,
    g_node: Vec<f64>,
    dp_cum: Vec<f64>,
    dp_part: Vec<f64>,
    p_der: Vec<[f64; 5]>,
    smooth: Vec<f64>,
    /// Divided differences (`Grid::newton`) of ρK and of ρK F².
    f_dd: [Vec<f64>; 4],
    a_dd: [Vec<f64>; 4],
    /// x = p0/(2√G) and e^{−x²} (then |dP/dG|) at the nodes.
    x_node: Vec<f64>,
    gauss: Vec<f64>,
    /// S⁻², f², g², x, P and e^{−x²} at the graded region's nodes.
    near_buf: [Vec<f64>; 6],
}

thread_local! {
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::default();
}

/// `v` resized to `n` entries, keeping its allocation and its old values (new entries are
/// `x`): every buffer here is written before it is read, over the range that is read, so
/// clearing it first only cost a memset of every buffer per evaluation.
fn sized<T: Copy>(v: &mut Vec<T>, n: usize, x: T) -> &mut Vec<T> {
    v.resize(n, x);
    v
}

/// ln(a/b) for a, b > 0, for a growth rate that only scales an error estimate: 2 atanh(s) with
/// s = (a − b)/(a + b) by its series to s⁵ where |s| ≤ 1/2 (a/b in [1/3, 3]; relative error below
/// s⁶·3/7 ≤ 7e-3; across a panel's two nodes a/b is within a few percent of 1, and the error
/// below 1e-10), `ln` elsewhere.
#[inline]
fn ln_ratio(a: f64, b: f64) -> f64 {
    let s = (a - b) / (a + b);
    if s.abs() <= 0.5 {
        let s2 = s * s;
        2.0 * s * (1.0 + s2 * (1.0 / 3.0 + s2 * 0.2))
    } else {
        (a / b).ln()
    }
}

/// x = p0/(2√G), the argument of P = erf(x); ∞ at G = 0 (P = 1 there).
#[inline]
fn probability_argument(p0: f64, g: f64) -> f64 {
    if g > 0.0 {
        0.5 * p0 / g.sqrt()
    } else {
        f64::INFINITY
    }
}

/// |dP/dG| = (p0 / (2√π)) G^{-3/2} e^{-p0²/(4G)} = (4/(√π p0²)) x³ e^{−x²} at x = p0/(2√G),
/// from e^{−x²} (`gauss`); 0 at G = 0 (x = ∞).
#[inline]
fn probability_slope(p0: f64, x: f64, gauss: f64) -> f64 {
    if gauss > 0.0 {
        x * x * x * gauss * (2.0 * FRAC_2_SQRT_PI / (p0 * p0))
    } else {
        0.0
    }
}

/// P(G) = erf(p0 / (2√G)), with P(0) = 1.
fn contact_probability(p0: f64, g: f64) -> f64 {
    erf_and_gauss(probability_argument(p0, g)).0
}

/// P(G) and |dP/dG| ([`probability_slope`]); (1, 0) at G = 0.
fn probability_and_slope(p0: f64, g: f64) -> (f64, f64) {
    let x = probability_argument(p0, g);
    let (p, gauss) = erf_and_gauss(x);
    (p, probability_slope(p0, x, gauss))
}

/// P(G(u)) and its first four u-derivatives, for G' = `gp` at G = `g` growing locally like
/// e^{λu} (G'' = λG', G''' = λ²G', G'''' = λ³G'), by Faà di Bruno's formula with
/// P_k = d^k P/dG^k = −(a/√π) e^{−w} G^{−(2k+1)/2} Q_k(w), a = p0/2, w = a²/G,
/// Q1 = 1, Q2 = w − 3/2, Q3 = w² − 5w + 15/4, Q4 = w³ − 21w²/2 + 105w/4 − 105/8.
/// Given x = a/√G (∞ at G = 0) and 1/a² rather than G: w = x² and 1/G = x²/a² without a division.
/// `slope` is |dP/dG| = −P_1 at G ([`probability_slope`]), passed in to spare its `exp`.
fn probability_derivatives(x: f64, inv_a2: f64, slope: f64, gp: f64, lam: f64, p: f64) -> [f64; 5] {
    if slope == 0.0 {
        // G = 0 (x = ∞) or e^{−x²} = 0 in f64: every derivative carries that factor.
        return [p, 0.0, 0.0, 0.0, 0.0];
    }
    // w = a²/G = x², 1/G = x²/a².
    let w = x * x;
    let inv_g = w * inv_a2;
    let q1 = w - 1.5;
    let q2 = w * (w - 5.0) + 3.75;
    let q3 = w * (w * (w - 10.5) + 26.25) - 13.125;
    // P_k = −|P_1| G^{1−k} Q_k.
    let s0 = -slope;
    let s1 = s0 * inv_g;
    let s2 = s1 * inv_g;
    let pk = [s0, s1 * q1, s2 * q2, s2 * inv_g * q3];
    let (g1, g2) = (gp, gp * lam);
    let (g3, g4) = (g2 * lam, g2 * lam * lam);
    let g1sq = g1 * g1;
    [
        p,
        pk[0] * g1,
        pk[1] * g1sq + pk[0] * g2,
        pk[2] * g1sq * g1 + 3.0 * pk[1] * g1 * g2 + pk[0] * g3,
        pk[3] * g1sq * g1sq
            + 6.0 * pk[2] * g1sq * g2
            + pk[1] * (4.0 * g1 * g3 + 3.0 * g2 * g2)
            + pk[0] * g4,
    ]
}

/// σ_top² / 2 = ∫_0^{G1} erf(a/√G) dG with a = p0/2, in closed form.
fn top_variance_half(p0: f64, g1: f64) -> f64 {
    if g1 <= 0.0 {
        return 0.0;
    }
    let a = 0.5 * p0;
    let u = a / g1.sqrt();
    g1 * erf(u) + 2.0 * a * a / PI.sqrt() * ((-u * u).exp() / u - PI.sqrt() * erfc(u))
}

/// One evaluation on one grid, for the relative tolerance `rtol`. The interface integrals stop
/// where their tail's bound is below rtol/1000 of the rest (module doc, "Interface tail"), and
/// take P as linear in G where that is within [`FLAT_SHARE`]·rtol of A ("Linear P").
#[allow(clippy::too_many_arguments)]
fn evaluate_on(
    grid: &Grid,
    graded: Option<&Graded>,
    kernels: &Kernels,
    stack: &Stack,
    p0: f64,
    req: Request,
    evaluations: usize,
    rtol: f64,
    scratch: &mut Scratch,
) -> Result<Contact, Error> {
    let tol = 1e-3 * rtol;
    let layers = &stack.layers;
    let d = stack.thickness;
    let e0 = layers.film.e_star();
    let cg = 0.25 * PI * e0 * e0;
    let n = grid.q.len();
    let need_fg = req.interface();
    let Scratch {
        f2,
        g2,
        f,
        g_errs,
        p_node,
        g_node,
        dp_cum,
        dp_part,
        p_der,
        smooth,
        f_dd,
        a_dd,
        x_node,
        gauss,
        near_buf,
    } = scratch;
    // f = ρ S⁻² (S⁻² alone where ρ = 1 throughout).
    kernels.k_many(&grid.q, &grid.u, sized(f, n, 0.0));
    if let Some(j) = f.iter().position(|k| !k.is_finite()) {
        return Err(Error::Numerical {
            what: "layer response",
            detail: format!("S(qd) = 0 at qd = {:e}", grid.q[j] * d),
        });
    }
    if !grid.unit_rho {
        for (f, &r) in f.iter_mut().zip(&grid.rho) {
            *f *= r;
        }
    }
    grid.newton(f, 0, n, f_dd);
    grid.panel_errors(&f_dd[3], g_errs);
    let (g_sum, g_err) = grid.sum_with_errors(f, g_errs);
    let g1 = Estimate::new(cg * g_sum, cg * g_err, Termination::Converged);
    let area = g1.map(
        |g| contact_probability(p0, g),
        |g| probability_and_slope(p0, g).1,
    );

    // Low-octave share: G at 2 q_L over G1.
    let low: f64 = (0..2 * grid.low_octave_panels)
        .map(|j| grid.w[j] * f[j])
        .sum();
    let low_octave_share = if g_sum > 0.0 {
        (low / g_sum).min(1.0)
    } else {
        1.0
    };

    let sigma_rms_top = req.sigma_top.then(|| {
        let v = 2.0 * top_variance_half(p0, g1.value);
        // d(σ²)/dG1 = 2 erf(p0/(2√G1)) = 2 P.
        let dv = 2.0 * area.value * g1.err;
        sqrt_estimate(v, dv + 8.0 * EPS * v, g1.status)
    });

    let (mut sigma_rms_interface, mut tau_rms_interface) = (None, None);
    let (mut near_evaluations, mut n_fg, mut from_panel) = (0, 0, 0);
    if let Some(graded) = graded {
        // The start of the range, where P(G(u)) ∝ (u − u_L)^{-1/2}: graded panels, unless G stays
        // below (p0/2)²/GRADED_SKIP over their region (P flat there; the base grid's estimates
        // follow P's derivatives).
        let span_raw: f64 = (0..2 * graded.base_from).map(|j| grid.w[j] * f[j]).sum();
        let (near, from) = if 0.25 * p0 * p0 >= GRADED_SKIP * cg * span_raw {
            (NEAR_NONE, 0)
        } else {
            (
                graded.integrate(kernels, p0, cg, req, near_buf),
                graded.base_from,
            )
        };
        near_evaluations = near.evaluations;
        from_panel = from;
        // f², g² in ascending q from the first base node, until the first panel whose first node
        // has q·d ≥ X_CUT and whose tail bound, F²(node)·Σ_{j ≥ node} w_j f_j (P ≤ 1, F²
        // decreasing), is below tol times a lower bound of the integral before it for each F asked
        // for: the graded region's sum plus A·Σ_{from ≤ j < node} w_j f_j F²_j (P ≥ P(G1) = A at
        // every node). Σ_{j ≥ node} is g_sum less the running sum, plus both sums' rounding (all
        // terms are positive). Then four more nodes for the divided differences.
        // f², g² are evaluated in batches (`Kernels::interface_many`): below q·d = X_CUT in one,
        // then CUT_CHUNK nodes at a time while the cut is looked for.
        let rounding = 4.0 * EPS * n as f64 * g_sum;
        sized(f2, n, 0.0);
        sized(g2, n, 0.0);
        let mut to = grid.panels();
        let mut before = [near.sigma.0, near.tau.0];
        let mut running = if from > 0 { span_raw } else { 0.0 };
        let start = 2 * from;
        let checked = start + grid.q[start..].partition_point(|&q| q * d < X_CUT);
        let mut done = start;
        let evaluate = |to: usize, done: &mut usize, f2: &mut [f64], g2: &mut [f64]| {
            if to > *done {
                let r = *done..to;
                kernels.interface_many(
                    &grid.q[r.clone()],
                    &grid.u[r.clone()],
                    &mut f2[r.clone()],
                    &mut g2[r],
                );
                *done = to;
            }
        };
        evaluate(checked, &mut done, f2, g2);
        let r = start..checked;
        for (((&w, &fj), &f2j), &g2j) in grid.w[r.clone()]
            .iter()
            .zip(&f[r.clone()])
            .zip(&f2[r.clone()])
            .zip(&g2[r])
        {
            let wf = w * fj;
            running += wf;
            before[0] += area.value * wf * f2j;
            before[1] += area.value * wf * g2j;
        }
        for j in checked..n {
            if j == done {
                evaluate((j + CUT_CHUNK).min(n), &mut done, f2, g2);
            }
            let (fj, gj) = (f2[j], g2[j]);
            if j % 2 == 0 {
                let rest = (g_sum - running).max(0.0) + rounding;
                let small = |want: bool, fv: f64, b: f64| !want || fv * rest <= tol * b;
                if small(req.sigma_interface, fj, before[0])
                    && small(req.tau_interface, gj, before[1])
                {
                    to = j / 2;
                    break;
                }
            }
            let wf = grid.w[j] * f[j];
            running += wf;
            before[0] += area.value * wf * fj;
            before[1] += area.value * wf * gj;
        }
        evaluate((2 * to + 5).min(n), &mut done, f2, g2);
        n_fg = done;
        // Then the two-node panels. First G at every node (forward pass: running sum plus the
        // panel's partial integral), then, up to where P is flat, P and its slope at all of them
        // in one batch, and the error of P from the error of G. (Nodes and panels up to the cut.)
        sized(p_node, 2 * to, 0.0);
        sized(g_node, 2 * to, 0.0);
        sized(x_node, 2 * to, 0.0);
        sized(gauss, 2 * to, 0.0);
        // |dP/dG| times the cumulative G error, and dP/dG times the signed partial-integral error
        // (first the G errors alone).
        sized(dp_cum, 2 * to, 0.0);
        sized(dp_part, 2 * to, 0.0);
        // P and its first four u-derivatives at each panel's first node, for the error terms.
        sized(p_der, to, [0.0; 5]);
        let mut g_left = near.g_raw;
        let mut g_left_err = near.g_raw_err;
        for (p, g_err) in g_errs.iter().enumerate().take(to).skip(from) {
            let (j0, j1) = (2 * p, 2 * p + 1);
            let start = j0.saturating_sub(1).min(n.saturating_sub(3));
            let psi2 = if n >= 3 { 2.0 * f_dd[1][start] } else { 0.0 };
            for (jj, j) in [j0, j1].into_iter().enumerate() {
                g_node[j] =
                    cg * (g_left + grid.partial[p][jj][0] * f[j0] + grid.partial[p][jj][1] * f[j1]);
                dp_cum[j] = cg * g_left_err;
                dp_part[j] = cg * psi2 * grid.partial_curv[p][jj];
            }
            g_left += grid.w[j0] * f[j0] + grid.w[j1] * f[j1];
            g_left_err += g_err;
        }
        // From panel `flat` on, P is linear in G (module doc, "Linear P").
        let (flat, linear) = linear_probability(
            p0,
            g1,
            area.value,
            FLAT_SHARE * rtol,
            (from, to),
            g_node,
            dp_cum,
            dp_part,
        );
        let nodes = 2 * from..2 * flat;
        for (x, &g) in x_node[nodes.clone()].iter_mut().zip(&g_node[nodes.clone()]) {
            *x = probability_argument(p0, g);
        }
        erf_and_gauss_many(
            &x_node[nodes.clone()],
            &mut p_node[nodes.clone()],
            &mut gauss[nodes.clone()],
        );
        // The slopes |dP/dG| (into `gauss`), and the errors of P.
        for j in nodes {
            let slope = probability_slope(p0, x_node[j], gauss[j]);
            gauss[j] = slope;
            dp_cum[j] *= slope;
            dp_part[j] *= slope;
        }
        if let Some((s1, remainder)) = linear {
            // P = A + s₁(G1 − G) there, its error from G's as above, plus the model's.
            for j in 2 * flat..2 * to {
                p_node[j] = area.value + s1 * (g1.value - g_node[j]);
                dp_cum[j] = s1 * dp_cum[j] + remainder;
                dp_part[j] *= s1;
            }
        }
        let inv_a2 = 4.0 / (p0 * p0);
        let s1 = linear.map_or(0.0, |l| l.0);
        for (p, der) in p_der.iter_mut().enumerate().take(to).skip(from) {
            let (j0, j1) = (2 * p, 2 * p + 1);
            // G' = cg W K ρ at the node, growing locally like e^{λu}: λ = d ln W/du + d ln(Kρ)/du
            // across the panel's two nodes.
            let gp = cg * grid.w_at[j0] * f[j0];
            let lam = grid.beta[p] + ln_ratio(f[j1], f[j0]) * grid.inv_gap[p];
            *der = if p < flat {
                probability_derivatives(x_node[j0], inv_a2, gauss[j0], gp, lam, p_node[j0])
            } else {
                // P' = −s₁G', G^{(k)} = λ^{k−1}G'.
                let d1 = -s1 * gp;
                [
                    p_node[j0],
                    d1,
                    d1 * lam,
                    d1 * lam * lam,
                    d1 * lam * lam * lam,
                ]
            };
        }
        // Beyond the last panel P ≤ 1 and F² ≤ its value at the first node left out (f², g²
        // decrease for q·d ≥ X_CUT), so the tail is at most F²(that node)·Σ w ρ K.
        let tail_weight: f64 = (2 * to..n).map(|j| grid.w[j] * f[j]).sum();
        // ρ K F² at the nodes the sums and their divided differences use.
        let used = (2 * to + 5).min(n);
        let mut base = |k2: &[f64], a: &mut Vec<f64>, acc: (f64, f64)| {
            sized(a, used, 0.0);
            let r = 2 * from..used;
            for ((a, &fj), &k2) in a[r.clone()].iter_mut().zip(&f[r.clone()]).zip(&k2[r]) {
                *a = fj * k2;
            }
            let (v, e) = grid.interface_sum(a, a_dd, p_node, dp_cum, dp_part, p_der, from, to);
            let tail = k2.get(2 * to).map_or(0.0, |&k2c| k2c * tail_weight);
            (acc.0 + v, acc.1 + e + tail)
        };
        let (mut sig, mut tau) = (near.sigma, near.tau);
        for (want, k2, acc) in [
            (req.sigma_interface, &f2, &mut sig),
            (req.tau_interface, &g2, &mut tau),
        ] {
            if want {
                *acc = base(k2, smooth, *acc);
            }
        }
        if req.sigma_interface {
            sigma_rms_interface = Some(sqrt_estimate(
                2.0 * cg * sig.0,
                2.0 * cg * sig.1,
                Termination::Converged,
            ));
        }
        if req.tau_interface {
            tau_rms_interface = Some(sqrt_estimate(
                2.0 * cg * tau.0,
                2.0 * cg * tau.1,
                Termination::Converged,
            ));
        }
    }

    let e_eff_over_e_film = req.e_eff.then(|| {
        let (bare, bare_err) = grid.bare;
        let ratio = g_sum / bare;
        let ratio_err = g_err / bare + ratio * bare_err / bare;
        sqrt_estimate(ratio, ratio_err, Termination::Converged)
    });

    Ok(Contact {
        thickness: d,
        pressure: p0,
        g1,
        area_fraction: area,
        sigma_rms_top,
        sigma_rms_interface,
        tau_rms_interface,
        e_eff_over_e_film,
        low_octave_share,
        kernel_evaluations: evaluations + near_evaluations,
        // Here: this grid's nodes that evaluated f, g (the caller adds up the grids tried).
        interface_kernel_evaluations: if need_fg {
            n_fg - 2 * from_panel + near_evaluations
        } else {
            0
        },
    })
}

/// Where P is linear in G (module doc, "Linear P"): the first panel p in [from, to) at whose
/// first node x = p0/(2√G) ≤ 1 and the remainder bound (3/4)|dP/dG|(G_p)·(G1 − G_p + e)²/G_p
/// is at most `share`·A, e the errors of G1 and G_p (`g_node`: G at the nodes; `dp_cum`,
/// `dp_part`: G's cumulative and within-panel errors there, before they are turned into P's).
/// Beyond p, P(G) = A + s₁(G1 − G) (s₁ = |dP/dG| at G1) within that bound: Taylor's remainder
/// ½|P''|(G1 − G)², with P'' = −|P'|(x² − 3/2)/G, |x² − 3/2| ≤ 3/2 for x ≤ 1, and |P'| and 1/G
/// decreasing with G. Returns p (`to` if there is none) and, if there is one, (s₁, the bound).
/// Found by bisection (the bound decreases with p but for the slowly growing errors; the panel
/// found is checked).
#[allow(clippy::too_many_arguments)]
fn linear_probability(
    p0: f64,
    g1: Estimate,
    area: f64,
    share: f64,
    (from, to): (usize, usize),
    g_node: &[f64],
    dp_cum: &[f64],
    dp_part: &[f64],
) -> (usize, Option<(f64, f64)>) {
    let bound = |p: usize| {
        let j = 2 * p;
        let g = g_node[j];
        if probability_argument(p0, g) > 1.0 {
            return None;
        }
        let slope = probability_and_slope(p0, g).1;
        let errors = g1.err + dp_cum[j] + ERR_SAFETY * dp_part[j].abs();
        let span = (g1.value - g).max(0.0) + errors;
        let remainder = 0.75 * slope * span * span / g;
        (remainder <= share * area).then_some(remainder)
    };
    let (mut lo, mut hi) = (from, to);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if bound(mid).is_some() {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    match (lo < to).then(|| bound(lo)).flatten() {
        Some(remainder) => (lo, Some((probability_and_slope(p0, g1.value).1, remainder))),
        None => (to, None),
    }
}

/// √v with the error of v propagated (d√v = dv / (2√v)), bounded by √dv near v = 0.
fn sqrt_estimate(v: f64, dv: f64, status: Termination) -> Estimate {
    let s = v.max(0.0).sqrt();
    let err = if s > 0.0 {
        (dv / (2.0 * s)).min(dv.sqrt())
    } else {
        dv.sqrt()
    };
    Estimate::new(s, err + 4.0 * EPS * s, status)
}

// ---------------------------------------------------------------------------------------------
// Distributions (notes.md, "Distributions and peak values").

/// Interface shear: Gaussian, zero mean, rms τ_rms; P(|τ| > level) = erfc(level/(√2 τ_rms)).
pub fn tau_exceedance(tau_rms: f64, level: f64) -> f64 {
    if tau_rms <= 0.0 {
        if level < 0.0 { 1.0 } else { 0.0 }
    } else {
        erfc(level / (std::f64::consts::SQRT_2 * tau_rms))
    }
}

/// The shear level exceeded on a fraction ε of the interface: √2 τ_rms erfc⁻¹(ε).
/// statrs' erfc⁻¹ is good to ~1e-11; two Newton steps on erfc bring it to rounding.
pub fn tau_peak(tau_rms: f64, epsilon: f64) -> f64 {
    let mut x = erfc_inv(epsilon);
    for _ in 0..2 {
        let slope = -2.0 / PI.sqrt() * (-x * x).exp();
        if slope == 0.0 {
            break;
        }
        x -= (erfc(x) - epsilon) / slope;
    }
    std::f64::consts::SQRT_2 * tau_rms * x
}

/// Half-normal density of |τ| (normalised on [0, ∞)).
pub fn tau_pdf(tau_rms: f64, tau: f64) -> f64 {
    let s = tau_rms;
    (2.0 / PI).sqrt() / s * (-0.5 * (tau / s).powi(2)).exp()
}

/// Normal stress: Persson's form centred at p0 with width σ_rms (4G → 2σ_rms²), restricted
/// to σ ≥ 0 and normalised there. At the top surface σ_rms² = 2G(q1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalStress {
    pub p0: f64,
    pub sigma_rms: f64,
}

impl NormalStress {
    fn scaled(&self, s: f64) -> (f64, f64, f64) {
        let k = std::f64::consts::SQRT_2 * self.sigma_rms;
        ((s - self.p0) / k, (s + self.p0) / k, self.p0 / k)
    }

    /// Density on σ ≥ 0: [e^{−(σ−p0)²/2σ²} − e^{−(σ+p0)²/2σ²}] / (√(2π) σ_rms erf(p0/(√2 σ_rms))).
    pub fn pdf(&self, s: f64) -> f64 {
        if s < 0.0 {
            return 0.0;
        }
        let (a, b, delta) = self.scaled(s);
        // e^{−a²} − e^{−b²} = e^{−a²}(1 − e^{−(b²−a²)}), b² − a² = 4 δ s/(√2 σ_rms) ≥ 0.
        let diff = (-a * a).exp() * -(-(b * b - a * a)).exp_m1();
        diff / ((2.0 * PI).sqrt() * self.sigma_rms * erf(delta))
    }

    /// Fraction of the area where the stress exceeds `level`.
    pub fn exceedance(&self, level: f64) -> f64 {
        if level <= 0.0 {
            return 1.0;
        }
        let (a, b, delta) = self.scaled(level);
        if delta < 1e-6 {
            // p0 ≪ σ_rms: the ratio tends to e^{−c²}, c = level/(√2σ_rms), with relative
            // corrections O(δ² c²).
            let c = 0.5 * (a + b);
            return (-c * c).exp();
        }
        ((erfc(a) - erfc(b)) / (2.0 * erf(delta))).clamp(0.0, 1.0)
    }

    /// The level exceeded on a fraction ε of the area, by bisection on the monotone tail to a
    /// relative width of 1e-13.
    pub fn peak(&self, epsilon: f64) -> Estimate {
        let mut lo = 0.0;
        let mut hi = self.p0 + self.sigma_rms;
        while self.exceedance(hi) > epsilon {
            lo = hi;
            hi *= 2.0;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if self.exceedance(mid) > epsilon {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo <= 1e-13 * hi {
                break;
            }
        }
        Estimate::new(
            0.5 * (lo + hi),
            (hi - lo) + 1e-12 * hi,
            Termination::Converged,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::psd::Tabulated;

    /// The growth rate's ln(a/b): within 7e-3 relative of `ln` for a/b in [1/3, 3], within
    /// 1e-10 for a/b within 2 % of 1 (as across a panel's two nodes), `ln` itself beyond.
    #[test]
    fn ln_ratio_is_ln_where_it_matters() {
        for i in 0..=4000 {
            let r = (-1.2 + 2.4 * f64::from(i) / 4000.0).exp();
            let (got, want) = (ln_ratio(r, 1.0), r.ln());
            let s = (r - 1.0) / (r + 1.0);
            let tol = if (r - 1.0).abs() <= 0.02 {
                1e-10
            } else if s.abs() <= 0.5 {
                7e-3
            } else {
                4.0 * EPS
            };
            assert!(
                (got - want).abs() <= tol * want.abs() + 1e-300,
                "ln({r}) = {want}, got {got}"
            );
        }
    }

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
    /// P linear in G: wherever `linear_probability` takes P as A + s₁(G1 − G), libm's
    /// erf(p0/(2√G)) is within its remainder bound, and the bound within the share asked for;
    /// the panel before the one it returns fails its condition (it is the first). G at the
    /// panels' first nodes approaches G1 geometrically from G1/4 for contact areas A from 1e-6
    /// to 0.6 (x at G1 from 1e-6 to 0.6), with and without G errors.
    #[test]
    fn linear_probability_bounds_p() {
        let p0: f64 = 1e5;
        for x1 in [1e-6, 1e-3, 0.1, 0.477, 0.6] {
            let g1 = (0.5 * p0 / x1).powi(2);
            let area = erf(x1);
            for (g_err, share) in [(0.0, 1e-10), (1e-13 * g1, 1e-10), (0.0, 1e-14)] {
                let panels = 400;
                let mut g_node = vec![0.0; 2 * panels];
                for p in 0..panels {
                    // 1 − G/G1 from 3/4 down to 1e-12 geometrically.
                    let t = p as f64 / (panels - 1) as f64;
                    let gap = 0.75f64.ln() * (1.0 - t) + 1e-12f64.ln() * t;
                    g_node[2 * p] = g1 * (1.0 - gap.exp());
                    g_node[2 * p + 1] = g_node[2 * p];
                }
                let cum = vec![g_err; 2 * panels];
                let part = vec![0.0; 2 * panels];
                let est = Estimate::new(g1, g_err, Termination::Converged);
                let (flat, linear) =
                    linear_probability(p0, est, area, share, (0, panels), &g_node, &cum, &part);
                let Some((s1, remainder)) = linear else {
                    panic!("x1 = {x1}: no linear region");
                };
                assert!(remainder <= share * area);
                assert!(flat > 0, "x1 = {x1}: linear from the first panel");
                let x_prev = 0.5 * p0 / g_node[2 * (flat - 1)].sqrt();
                let prev = probability_and_slope(p0, g_node[2 * (flat - 1)]).1
                    * (g1 - g_node[2 * (flat - 1)] + 2.0 * g_err).powi(2)
                    * 0.75
                    / g_node[2 * (flat - 1)];
                assert!(
                    x_prev > 1.0 || prev > share * area,
                    "x1 = {x1}: not the first"
                );
                for &g in &g_node[2 * flat..] {
                    let exact = erf(0.5 * p0 / g.sqrt());
                    let model = area + s1 * (g1 - g);
                    assert!(
                        (exact - model).abs() <= remainder + 4.0 * EPS * area,
                        "x1 = {x1}, G/G1 = {}: {exact} vs {model}, bound {remainder}",
                        g / g1
                    );
                }
            }
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
