//! The interface integrals near q_L ([`Graded`]), where P(G(u)) ∝ (u − u_L)^{-1/2} once
//! G ≫ p0²: graded Gauss–Legendre panels with companion rules for their errors, and the
//! innermost piece in closed form (∫_0^G P dG, eq. B11 integrated; see
//! [`super::probability::top_variance_half`]).

use super::grid::Grid;
use super::kernels::Kernels;
use super::probability::{probability_argument, top_variance_half};
use super::{Request, sized};
use crate::prec::EPS;
use crate::psd::Spectrum;
use crate::quad;
use crate::special::erf_and_gauss_many;

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
/// rtol 1e-8, 23 at 1e-6). The share is far below [`GRADED_SHARE`]: the base panels' own
/// estimate (P's derivatives by the chain rule, with a safety factor) is more cautious than this
/// model, and must stay within rtol there.
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
/// fast as one so in u, and half as many of them span the same range.
///
/// Where G stays below (p0/2)²/36 the contact probability is erf(≥ 6) = 1 in f64 and the
/// integrand is smooth: the innermost panels up to there are replaced by one 6-point panel from
/// q_L (`merged`, chosen per evaluation from a bound on G). Where G stays below (p0/2)²/3 over the
/// whole region P varies slowly and the base grid starts at q_L (`super::evaluate`).
pub(super) struct Graded {
    panels: Vec<GlPanel>,
    /// Every panel's nodes and companion nodes (q, u), ascending, and where each panel's start.
    nodes: (Vec<f64>, Vec<f64>),
    offsets: Vec<usize>,
    /// First two-node panel of the base grid after the graded region.
    pub(super) base_from: usize,
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

/// The graded region's sums: G (raw, without the factor cg) and its error, σ and τ sums with
/// their errors.
pub(super) struct Near {
    pub(super) g_raw: f64,
    pub(super) g_raw_err: f64,
    pub(super) sigma: (f64, f64),
    pub(super) tau: (f64, f64),
    /// The friction slots' sums with their errors (along x, along y), when asked for.
    pub(super) friction: [(f64, f64); 2],
    /// Kernel evaluations made.
    pub(super) evaluations: usize,
}

/// Near-q_L sums before any panel: nothing.
pub(super) const NEAR_NONE: Near = Near {
    g_raw: 0.0,
    g_raw_err: 0.0,
    sigma: (0.0, 0.0),
    tau: (0.0, 0.0),
    friction: [(0.0, 0.0); 2],
    evaluations: 0,
};

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

/// Gauss–Legendre rules with 2..=[`GL_MAX`] nodes, and for each n the partial-integral matrices
/// of the n-node interpolant at its n nodes (`at_nodes`) and at the n − 1 companion nodes
/// (`at_companions`): row j integrates the basis from the panel's left end to node j.
struct Rules {
    rules: Vec<(Vec<f64>, Vec<f64>)>,
    at_nodes: Vec<[[f64; GL_MAX]; GL_MAX]>,
    at_companions: Vec<[[f64; GL_MAX]; GL_MAX]>,
}

impl Rules {
    fn new() -> Rules {
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
        let table = |points: usize| -> Vec<[[f64; GL_MAX]; GL_MAX]> {
            (0..=GL_MAX)
                .map(|n| {
                    if n < 2 {
                        [[0.0; GL_MAX]; GL_MAX]
                    } else {
                        partials(n, &rules[n + points - 1].0)
                    }
                })
                .collect()
        };
        let (at_nodes, at_companions) = (table(1), table(0));
        Rules {
            rules,
            at_nodes,
            at_companions,
        }
    }

    /// An n-node panel in x ∈ [−1, 1] with u − u_L = r(x) by `map` (x ↦ (r, dr/dx)): its
    /// weights and partial-integral matrices carry dr/dx·W at the nodes (`w_of`: W at q).
    fn panel(
        &self,
        q_l: f64,
        w_of: &dyn Fn(f64) -> f64,
        map: &dyn Fn(f64) -> (f64, f64),
        n: usize,
    ) -> GlPanel {
        let at = |x: f64| {
            let (r, jac) = map(x);
            let q = q_l * r.exp();
            (q, jac * w_of(q))
        };
        let (x, gw) = (&self.rules[n].0, &self.rules[n].1);
        let (xc, gwc) = (&self.rules[n - 1].0, &self.rules[n - 1].1);
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
        let (bn, bcn) = (&self.at_nodes[n], &self.at_companions[n]);
        GlPanel {
            n,
            at,
            atc,
            q,
            u: q.map(f64::ln),
            w: std::array::from_fn(|k| gw.get(k).map_or(0.0, |g| g * wq[k])),
            b: std::array::from_fn(|j| std::array::from_fn(|k| bn[j][k] * wq[k])),
            qc,
            uc: qc.map(f64::ln),
            wc: std::array::from_fn(|k| gwc.get(k).map_or(0.0, |g| g * wqc[k])),
            bc: std::array::from_fn(|j| std::array::from_fn(|k| bcn[j][k] * wq[k])),
        }
    }

    /// A panel linear in u − u_L over [a, b].
    fn linear(&self, q_l: f64, w_of: &dyn Fn(f64) -> f64, (a, b): (f64, f64), n: usize) -> GlPanel {
        let half = 0.5 * (b - a);
        self.panel(q_l, w_of, &|x| (a + half * (x + 1.0), half), n)
    }

    /// A panel linear in s = √(u − u_L) over [√a, √b].
    fn root(&self, q_l: f64, w_of: &dyn Fn(f64) -> f64, (a, b): (f64, f64), n: usize) -> GlPanel {
        let (sa, half) = (a.sqrt(), 0.5 * (b.sqrt() - a.sqrt()));
        let map = |x: f64| {
            let s = sa + half * (x + 1.0);
            (s * s, 2.0 * s * half)
        };
        self.panel(q_l, w_of, &map, n)
    }
}

/// The graded region's extent: the first base panel it hands over to, and its width above u_L
/// (the two-node rule takes over where panels are narrower than 1/[`graded_span`] of their
/// distance to q_L).
fn region(grid: &Grid, u0: f64, u_end: f64, h: f64, rtol: f64) -> (usize, f64) {
    let first = grid.width.first().copied().unwrap_or(h).min(h);
    let base_from = (0..grid.panels())
        .find(|&p| grid.left[p] - u0 >= graded_span(rtol) * first.max(grid.width[p]))
        .unwrap_or(grid.panels());
    let span = if base_from < grid.panels() {
        grid.left[base_from] - u0
    } else {
        u_end - u0
    };
    (base_from, span)
}

/// Offsets from u_L of the graded panels' ends, ascending: halving steps from `span` down to
/// `first_end` (the first base panel's end), quartering steps (halving in s = √(u − u_L)) within
/// it down to [`INNER_WIDTH`], plus every base-grid panel end (knots) below `span`.
fn panel_ends(grid: &Grid, u0: f64, base_from: usize, span: f64, first_end: f64) -> Vec<f64> {
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
    ends
}

impl Graded {
    pub(super) fn new(spectrum: &Spectrum, grid: &Grid, h: f64, rtol: f64) -> Graded {
        let q_l = spectrum.q_low();
        let u0 = q_l.ln();
        let (base_from, span) = region(grid, u0, spectrum.support().1.ln(), h, rtol);
        let first_end = grid.width.first().copied().unwrap_or(span).min(span);
        let ends = panel_ends(grid, u0, base_from, span, first_end);
        let rules = Rules::new();
        let w_of = |q: f64| grid.w_at_u(spectrum, q.ln());
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
                    let n = graded_nodes(sa / (sb - sa), z, rtol);
                    rules.root(q_l, &w_of, (p[0], p[1]), n)
                } else {
                    let n = graded_nodes(p[0] / (p[1] - p[0]), z, rtol);
                    rules.linear(q_l, &w_of, (p[0], p[1]), n)
                }
            })
            .collect();
        let merged = ends[1..]
            .iter()
            .take_while(|&&r| r <= first_end)
            .map(|&r| (r, rules.linear(q_l, &w_of, (0.0, r), 6)))
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

    /// The graded region's sums: the kernels at all its nodes in two batches (S⁻², then the
    /// interface slots) into `s`'s buffers, G at all of them panel by panel, P at all of them in
    /// one batch, then the panels' sums; the friction slots' too with `friction`. S⁻², G and P
    /// beyond the innermost piece are taken from `s` where an earlier call formed them since
    /// [`GradedScratch::forget`] (the same region, S⁻², p0 and cg).
    pub(super) fn integrate(
        &self,
        kernels: &Kernels,
        p0: f64,
        cg: f64,
        req: Request,
        friction: bool,
        s: &mut GradedScratch,
    ) -> Near {
        let (r0, fr0) = kernels.squared(self.q_l, self.q_l.ln());
        // The largest merged panel over which G ≤ a²/36 by the bound G'(u_L)·r·e^{γr}.
        let (a2, gp0) = (0.25 * p0 * p0, cg * self.w_at_l * r0.k);
        let merge = self
            .merged
            .iter()
            .rposition(|&(r, _)| gp0 * r * (self.growth * r).exp() <= a2 / 36.0);
        let slots = Slots { req, friction };
        let (mut near, first) = match merge {
            Some(i) => {
                let mut near = Near {
                    evaluations: 1,
                    ..NEAR_NONE
                };
                let panel = &self.merged[i].1;
                let m = 2 * panel.n - 1;
                let mut v = [[0.0; 2 * GL_MAX - 1]; 8];
                for (j, &(q, u)) in panel.sorted()[..m].iter().enumerate() {
                    let (r, fr) = kernels.squared(q, u);
                    (v[0][j], v[1][j], v[2][j]) = (r.k, r.f2, r.g2);
                    (v[6][j], v[7][j]) = (fr[0], fr[1]);
                }
                let [k, f2, g2, x, p, gauss, fx, fy] = &mut v;
                panel.arguments(k, &mut near, p0, cg, x);
                erf_and_gauss_many(&x[..m], &mut p[..m], &mut gauss[..m]);
                panel.sums(k, p, [&f2[..], &g2[..], &fx[..], &fy[..]], &mut near, slots);
                (near, i + 1)
            }
            None => {
                // Innermost piece: G grows linearly from 0, F² is constant to 1e-10.
                let g_inner = self.w_l * r0.k;
                let j0 = top_variance_half(p0, cg * g_inner) / cg;
                let piece = |f: f64| (f * j0, 1e-9 * f * j0);
                let near = Near {
                    g_raw: g_inner,
                    g_raw_err: 1e-9 * g_inner,
                    sigma: piece(r0.f2),
                    tau: piece(r0.g2),
                    friction: fr0.map(piece),
                    evaluations: 1,
                };
                (near, 0)
            }
        };
        let lo = self.offsets[first];
        let (q, u) = (&self.nodes.0[lo..], &self.nodes.1[lo..]);
        let m = q.len();
        let GradedScratch { buf, formed } = s;
        let [k, f2, g2, x, p, gauss, fx, fy] = buf;
        if formed.is_none() {
            kernels.k_many(q, u, sized(k, m, 0.0));
        }
        let friction_buf = if friction {
            Some([&mut sized(fx, m, 0.0)[..], sized(fy, m, 0.0)])
        } else {
            None
        };
        kernels.interface_many(q, u, sized(f2, m, 0.0), sized(g2, m, 0.0), friction_buf);
        let range = |i: usize| self.offsets[i] - lo..self.offsets[i + 1] - lo;
        match *formed {
            Some(g) => (near.g_raw, near.g_raw_err, near.evaluations) = g,
            None => {
                sized(x, m, 0.0);
                for (i, panel) in self.panels.iter().enumerate().skip(first) {
                    let r = range(i);
                    panel.arguments(&k[r.clone()], &mut near, p0, cg, &mut x[r]);
                }
                erf_and_gauss_many(x, sized(p, m, 0.0), sized(gauss, m, 0.0));
                *formed = Some((near.g_raw, near.g_raw_err, near.evaluations));
            }
        }
        for (i, panel) in self.panels.iter().enumerate().skip(first) {
            let r = range(i);
            // The friction slots are empty unless asked for.
            let kernels = [
                &f2[r.clone()],
                &g2[r.clone()],
                fx.get(r.clone()).unwrap_or(&[]),
                fy.get(r.clone()).unwrap_or(&[]),
            ];
            panel.sums(&k[r.clone()], &p[r], kernels, &mut near, slots);
        }
        near
    }
}

/// The graded region's buffers ([`Graded::integrate`]): S⁻², f², g², x, P, e^{−x²} and the
/// friction slots at its nodes beyond the innermost piece, and whether S⁻², x and P there are
/// formed, with G over the region (raw sum, its error, the kernel evaluations counted): the
/// evaluations on one grid whose kernels share S⁻² (a stack's interfaces) form them once.
#[derive(Default)]
pub(super) struct GradedScratch {
    buf: [Vec<f64>; 8],
    formed: Option<(f64, f64, usize)>,
}

impl GradedScratch {
    /// Forget S⁻², x and P: the next [`Graded::integrate`] forms them (another grid, S⁻², p0
    /// or E*).
    pub(super) fn forget(&mut self) {
        self.formed = None;
    }
}

/// Which of the four interface slots (σ, τ, friction along x and y) a sum is formed for.
#[derive(Clone, Copy)]
struct Slots {
    req: Request,
    friction: bool,
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

    /// The panel's sums of the slots asked for (n nodes; error: the difference to the
    /// companion's) added to `near`, from S⁻², P and the slots' kernels (σ, τ, friction along x
    /// and y) at its 2n − 1 nodes (ascending).
    fn sums(&self, k: &[f64], p: &[f64], slots: [&[f64]; 4], near: &mut Near, on: Slots) {
        let n = self.n;
        let add = |acc: &mut (f64, f64), k2: &[f64]| {
            let term = |w: f64, j: usize| w * k[j] * p[j] * k2[j];
            let i_n: f64 = (0..n).map(|i| term(self.w[i], self.at[i])).sum();
            let i_c: f64 = (0..n - 1).map(|i| term(self.wc[i], self.atc[i])).sum();
            acc.0 += i_n;
            acc.1 += (i_n - i_c).abs() + 8.0 * EPS * i_n.abs();
        };
        let [f2, g2, fx, fy] = slots;
        if on.req.sigma_interface {
            add(&mut near.sigma, f2);
        }
        if on.req.tau_interface {
            add(&mut near.tau, g2);
        }
        if on.friction {
            add(&mut near.friction[0], fx);
            add(&mut near.friction[1], fy);
        }
    }
}
