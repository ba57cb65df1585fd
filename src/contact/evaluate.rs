//! One evaluation of the contact integrals on one grid (eqs. B8–B12), in phases: G and its
//! error over all nodes ([`g_sum`]), then for the interface stresses the graded region near q_L,
//! f², g² up to the cut ([`interface_kernels`]), G at every node ([`g_at_nodes`]), P there
//! ([`probability_at_nodes`]), its u-derivatives for the error terms ([`probability_derivatives_at`])
//! and the sums ([`interface_sums`]). Each phase is passed the buffers it writes ([`Scratch`],
//! kept by the caller between evaluations).
//!
//! Linear P: P decreases with q (G increases). From the first panel where x = p0/(2√G) ≤ 1 and
//! Taylor's remainder (3/4)|dP/dG|(G1 − G)²/G is below rtol/100 of A, P is taken as
//! A + |dP/dG|(G1)·(G1 − G) with that remainder added to its error ([`linear_probability`]): no
//! erf and no analytic derivatives there. For thin films, where G saturates near q_L, that is
//! most of the range.
//!
//! Interface tail: above q·d = 20 f e^x and g e^x are linear in x to 1e−15 (the far field of
//! `layer::KernelTable`: the stable forms' e^{−2x} terms are below x²e^{−2x} < 2e−15 there), and
//! (a + bx)e^{−x} with a/b ≥ 0 decreases for x > 1: f² and g² decrease. The interface integrals
//! stop at the first panel whose first node has q·d ≥ 20 and F²(node)·∫W K du beyond it (a bound
//! on the rest, P ≤ 1) below tol = rtol/1000 times A·∫W K F² du before it (a lower bound on the
//! integral so far, since P ≥ P(G1) = A everywhere); that bound is added to their error estimate.
//! The cut adapts to the film and the spectrum: f, g and P are evaluated only where they matter.

use super::graded::{Graded, GradedScratch, NEAR_NONE, Near};
use super::grid::Grid;
use super::kernels::Kernels;
use super::probability::{
    contact_probability, probability_and_slope, probability_argument, probability_derivatives,
    probability_slope, top_variance_half,
};
use super::{Contact, ERR_SAFETY, Request, sized};
use crate::error::Error;
use crate::prec::{EPS, Estimate, SMALLEST_SUBNORMAL, Termination};
use crate::special::erf_and_gauss_many;
use std::f64::consts::PI;

/// The share of rtol (relative to A) by which P may differ from its linear model ("Linear P").
const FLAT_SHARE: f64 = 0.01;

/// Where G stays below (p0/2)² divided by this over the graded region, it is not used.
const GRADED_SKIP: f64 = 3.0;

/// Where f² and g² are known to decrease, the lowest q·d at which the interface integrals are
/// cut (module doc, "Interface tail").
const X_CUT: f64 = 20.0;

/// How many nodes' f², g² are evaluated at a time beyond q·d = X_CUT, while the cut is looked
/// for (at most this many are evaluated and not used).
const CUT_CHUNK: usize = 16;

/// The buffers of one evaluation, kept by the caller between evaluations (one per thread:
/// [`super::Engine::evaluate`]) so that they are not allocated and freed every time. Every
/// buffer is resized to what a phase writes and written before it is read.
#[derive(Default)]
pub struct Scratch {
    base: BaseScratch,
    interface: InterfaceScratch,
    /// The graded region's buffers ([`Graded::integrate`]).
    graded: GradedScratch,
}

/// G's sum over all nodes ([`g_sum`]).
#[derive(Default)]
struct BaseScratch {
    /// ρ S⁻² at the nodes (ρ = W/W_ref, 1 on piecewise power-law spectra): ψ of G's integral.
    rho_k: Vec<f64>,
    /// Its divided differences ([`Grid::newton`]).
    rho_k_dd: [Vec<f64>; 4],
    /// Per-panel error estimates of G's sum.
    panel_errs: Vec<f64>,
}

/// The interface integrals' nodes, up to the cut.
#[derive(Default)]
struct InterfaceScratch {
    /// f², g² at the nodes, and the friction slots (under sliding, when asked for).
    f2: Vec<f64>,
    g2: Vec<f64>,
    fx: Vec<f64>,
    fy: Vec<f64>,
    /// G, x = p0/(2√G) and P at the nodes.
    g_node: Vec<f64>,
    x_node: Vec<f64>,
    p_node: Vec<f64>,
    /// |dP/dG| at the nodes (holding e^{−x²} from the batch erf until it is turned into the
    /// slope).
    dp_dg: Vec<f64>,
    /// |dP/dG| times the cumulative G error, and dP/dG times the signed partial-integral error
    /// (the G errors alone until P's slopes are known).
    dp_cum: Vec<f64>,
    dp_part: Vec<f64>,
    /// P and its first four u-derivatives at each panel's first node.
    p_der: Vec<[f64; 5]>,
    /// ρ K F² at the nodes, and its divided differences.
    rho_k_f2: Vec<f64>,
    rho_k_f2_dd: [Vec<f64>; 4],
}

/// What one evaluation is for: the grid, the kernels at one thickness, the depth of the
/// interface (the film thickness, or z_k in a stack: the interface tail's q·d is q times it),
/// the top layer's E*, the pressure, the request, whether the friction slots are asked for too
/// (`super::sliding`: they share G, P and the cut's search with σ and τ), and the tolerance.
pub(super) struct Point<'a> {
    pub(super) grid: &'a Grid,
    pub(super) graded: Option<&'a Graded>,
    pub(super) kernels: &'a Kernels<'a>,
    pub(super) depth: f64,
    pub(super) e_top: f64,
    pub(super) p0: f64,
    pub(super) req: Request,
    pub(super) friction: bool,
    pub(super) rtol: f64,
}

/// The interface stresses of one evaluation and how many kernel evaluations they took.
struct Interface {
    sigma: Option<Estimate>,
    tau: Option<Estimate>,
    /// The friction slots' rms (along x, along y), when asked for.
    friction: Option<[Estimate; 2]>,
    /// The graded region's kernel evaluations.
    near_evaluations: usize,
    /// The nodes of this grid and the graded region that evaluated f, g.
    fg_evaluations: usize,
}

/// One evaluation on one grid, with the friction slots' rms when asked for. `evaluations`:
/// kernel evaluations so far (all grids tried, this one's nodes included). The interface
/// integrals stop where their tail's bound is below rtol/1000 of the rest (module doc,
/// "Interface tail"), and take P as linear in G where that is within [`FLAT_SHARE`]·rtol of A
/// ("Linear P").
pub(super) fn evaluate_on(
    pt: &Point,
    evaluations: usize,
    scratch: &mut Scratch,
) -> Result<(Contact, Option<[Estimate; 2]>), Error> {
    let sums = g_sum_shared(pt, scratch)?;
    evaluate_sharing(pt, evaluations, sums, scratch)
}

/// G's sum on `pt`'s grid with its kernels' S⁻², into `scratch`, for evaluations that share it
/// ([`evaluate_sharing`]: a stack's interfaces, whose kernels share S⁻²; they share S⁻², G and
/// P over the graded region too, formed by the first of them). Returns the sum and its error
/// estimate.
pub(super) fn g_sum_shared(pt: &Point, scratch: &mut Scratch) -> Result<(f64, f64), Error> {
    scratch.graded.forget();
    g_sum(pt.grid, pt.kernels, pt.depth, &mut scratch.base)
}

/// [`evaluate_on`] with G's sum (`sums`) and its nodes' values already in `scratch`
/// ([`g_sum_shared`] on the same grid, with kernels of the same S⁻²).
pub(super) fn evaluate_sharing(
    pt: &Point,
    evaluations: usize,
    (g_sum, g_err): (f64, f64),
    scratch: &mut Scratch,
) -> Result<(Contact, Option<[Estimate; 2]>), Error> {
    let Point {
        grid,
        depth: d,
        e_top: e0,
        p0,
        req,
        ..
    } = *pt;
    let cg = 0.25 * PI * e0 * e0;
    let rho_k = &scratch.base.rho_k;
    let g1 = Estimate::new(cg * g_sum, cg * g_err, Termination::Converged);
    let area = g1.map(
        |g| contact_probability(p0, g),
        |g| probability_and_slope(p0, g).1,
    );

    // Low-octave share: G at 2 q_L over G1.
    let low: f64 = (0..2 * grid.low_octave_panels)
        .map(|j| grid.w[j] * rho_k[j])
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

    let interface = match pt.graded {
        Some(graded) if req.interface() || pt.friction => interface(
            pt,
            graded,
            (g1, area.value, g_sum),
            &scratch.base,
            &mut scratch.interface,
            &mut scratch.graded,
        ),
        _ => Interface {
            sigma: None,
            tau: None,
            friction: None,
            near_evaluations: 0,
            fg_evaluations: 0,
        },
    };

    let e_eff_over_e_film = req.e_eff.then(|| {
        let (bare, bare_err) = grid.bare;
        let ratio = g_sum / bare;
        let ratio_err = g_err / bare + ratio * bare_err / bare;
        sqrt_estimate(ratio, ratio_err, Termination::Converged)
    });

    let contact = Contact {
        thickness: d,
        pressure: p0,
        g1,
        area_fraction: area,
        sigma_rms_top,
        sigma_rms_interface: interface.sigma,
        tau_rms_interface: interface.tau,
        e_eff_over_e_film,
        low_octave_share,
        kernel_evaluations: evaluations + interface.near_evaluations,
        // Here: this grid's nodes that evaluated f, g (the caller adds up the grids tried).
        interface_kernel_evaluations: interface.fg_evaluations,
    };
    Ok((contact, interface.friction))
}

/// Σ_j w_j ρ_j S⁻²_j over all nodes (G1 without the factor cg) and its error estimate, with
/// ρ S⁻² at the nodes left in `s.rho_k` and its divided differences in `s.rho_k_dd`.
fn g_sum(grid: &Grid, kernels: &Kernels, d: f64, s: &mut BaseScratch) -> Result<(f64, f64), Error> {
    let n = grid.q.len();
    let rho_k = sized(&mut s.rho_k, n, 0.0);
    // ρ S⁻² (S⁻² alone where ρ = 1 throughout).
    kernels.k_many(&grid.q, &grid.u, rho_k);
    if let Some(j) = rho_k.iter().position(|k| !k.is_finite()) {
        return Err(Error::Numerical {
            what: "layer response",
            detail: format!("S(qd) = 0 at qd = {:e}", grid.q[j] * d),
        });
    }
    if !grid.unit_rho {
        for (f, &r) in rho_k.iter_mut().zip(&grid.rho) {
            *f *= r;
        }
    }
    grid.newton(rho_k, 0, n, &mut s.rho_k_dd);
    grid.panel_errors(&s.rho_k_dd[3], &mut s.panel_errs);
    Ok(grid.sum_with_errors(rho_k, &s.panel_errs))
}

/// The interface stresses: the graded region near q_L (unless G stays below
/// (p0/2)²/[`GRADED_SKIP`] over it: P flat there, and the base grid's estimates follow P's
/// derivatives), then the two-node panels up to the cut. `(g1, area, g_sum)`: G1, A and G1's raw
/// sum (without cg).
fn interface(
    pt: &Point,
    graded: &Graded,
    (g1, area, g_sum): (Estimate, f64, f64),
    base: &BaseScratch,
    s: &mut InterfaceScratch,
    graded_buf: &mut GradedScratch,
) -> Interface {
    let Point {
        grid,
        e_top: e0,
        p0,
        req,
        ..
    } = *pt;
    let cg = 0.25 * PI * e0 * e0;
    let rho_k = &base.rho_k;
    let span_raw: f64 = (0..2 * graded.base_from)
        .map(|j| grid.w[j] * rho_k[j])
        .sum();
    let (near, from) = if 0.25 * p0 * p0 >= GRADED_SKIP * cg * span_raw {
        (NEAR_NONE, 0)
    } else {
        (
            graded.integrate(pt.kernels, p0, cg, req, pt.friction, graded_buf),
            graded.base_from,
        )
    };
    let running = if from > 0 { span_raw } else { 0.0 };
    let (to, done) = interface_kernels(pt, (from, running), &near, area, g_sum, rho_k, s);
    // G and P up to the later cut; each slot's sums up to its own.
    let last = to[0].max(to[1]);
    g_at_nodes(grid, cg, (from, last), &near, base, s);
    let (flat, linear) = probability_at_nodes(pt, g1, area, (from, last), s);
    probability_derivatives_at(grid, cg, p0, (from, last, flat), linear, rho_k, s);
    let [sig, tau, fx, fy] = interface_sums(grid, (from, to), &near, (req, pt.friction), rho_k, s);
    let rms = |acc: (f64, f64)| {
        let scaled = sqrt_estimate(2.0 * cg * acc.0, 2.0 * cg * acc.1, Termination::Converged);
        decayed(scaled, pt.kernels.shift())
    };
    Interface {
        sigma: req.sigma_interface.then(|| rms(sig)),
        tau: req.tau_interface.then(|| rms(tau)),
        friction: pt.friction.then(|| [rms(fx), rms(fy)]),
        near_evaluations: near.evaluations,
        fg_evaluations: done - 2 * from + near.evaluations,
    }
}

/// The interface slots' kernels (f², g², and the friction slots when asked for) in ascending q
/// from the first base node, until for each group of slots (σ and τ as requested; the two
/// friction slots) the first panel whose first node has q·d ≥ X_CUT and whose tail bound,
/// F²(node)·Σ_{j ≥ node} w_j ρK_j (P ≤ 1, F² decreasing), is below tol = rtol/1000 times a lower
/// bound of the integral before it for each F of the group: the graded region's sum plus
/// A·Σ_{from ≤ j < node} w_j ρK_j F²_j (P ≥ P(G1) = A at every node). Σ_{j ≥ node} is `g_sum`
/// less the running sum (`running`: the sum before panel `from`), plus both sums' rounding (all
/// terms are positive). Then four more nodes beyond the later cut for the divided differences.
/// The kernels are evaluated in batches ([`Kernels::interface_many`]): below q·d = X_CUT in one,
/// then [`CUT_CHUNK`] nodes at a time while the cuts are looked for. Returns the first panel cut
/// for each group (`to`; the friction slots' is σ and τ's when they are not asked for) and how
/// far the kernels were evaluated.
fn interface_kernels(
    pt: &Point,
    (from, mut running): (usize, f64),
    near: &Near,
    area: f64,
    g_sum: f64,
    rho_k: &[f64],
    s: &mut InterfaceScratch,
) -> ([usize; 2], usize) {
    let Point {
        grid,
        kernels,
        req,
        friction,
        ..
    } = *pt;
    let d = pt.depth;
    let tol = 1e-3 * pt.rtol;
    let n = grid.q.len();
    let rounding = 4.0 * EPS * n as f64 * g_sum;
    let m = if friction { n } else { 0 };
    let mut k2 = [
        &mut sized(&mut s.f2, n, 0.0)[..],
        sized(&mut s.g2, n, 0.0),
        sized(&mut s.fx, m, 0.0),
        sized(&mut s.fy, m, 0.0),
    ];
    // The slots each group's cut looks at.
    let groups = [
        [req.sigma_interface, req.tau_interface],
        [friction, friction],
    ];
    let mut to = [grid.panels(); 2];
    let mut open = [true, friction];
    let mut before = [near.sigma, near.tau, near.friction[0], near.friction[1]].map(|a| a.0);
    let start = 2 * from;
    let checked = start + grid.q[start..].partition_point(|&q| q * d < X_CUT);
    let mut done = start;
    let evaluate = |to: usize, done: &mut usize, k2: &mut [&mut [f64]; 4]| {
        if to > *done {
            let r = *done..to;
            let [f2, g2, fx, fy] = k2;
            let fr = if friction {
                Some([&mut fx[r.clone()], &mut fy[r.clone()]])
            } else {
                None
            };
            kernels.interface_many(
                &grid.q[r.clone()],
                &grid.u[r.clone()],
                &mut f2[r.clone()],
                &mut g2[r],
                fr,
            );
            *done = to;
        }
    };
    let slots = if friction { 4 } else { 2 };
    let add = |before: &mut [f64; 4], k2: &[&mut [f64]; 4], wf: f64, j: usize| {
        for (b, k) in before.iter_mut().zip(k2).take(slots) {
            *b += area * wf * k[j];
        }
    };
    evaluate(checked, &mut done, &mut k2);
    let below = Below {
        w: &grid.w[start..checked],
        rho_k: &rho_k[start..checked],
        area,
    };
    below.add(&k2, start, friction, (&mut running, &mut before));
    for j in checked..n {
        if j == done {
            evaluate((j + CUT_CHUNK).min(n), &mut done, &mut k2);
        }
        if j % 2 == 0 {
            let rest = (g_sum - running).max(0.0) + rounding;
            let small = |want: bool, k: usize| !want || k2[k][j] * rest <= tol * before[k];
            for (g, want) in groups.iter().enumerate() {
                if open[g] && small(want[0], 2 * g) && small(want[1], 2 * g + 1) {
                    (to[g], open[g]) = (j / 2, false);
                }
            }
            if open == [false; 2] {
                break;
            }
        }
        let wf = grid.w[j] * rho_k[j];
        running += wf;
        add(&mut before, &k2, wf, j);
    }
    if !friction {
        to[1] = to[0];
    }
    evaluate((2 * to[0].max(to[1]) + 5).min(n), &mut done, &mut k2);
    (to, done)
}

/// The nodes below the cut's search: their weights w and ρK, and A.
struct Below<'a> {
    w: &'a [f64],
    rho_k: &'a [f64],
    area: f64,
}

impl Below<'_> {
    /// Σ w ρK over the nodes added to `running`, and A·Σ w ρK F² to `before` for σ and τ's
    /// slots and with `friction` the friction slots' (`k2`: the four slots from node `start`).
    fn add(
        &self,
        k2: &[&mut [f64]; 4],
        start: usize,
        friction: bool,
        (running, before): (&mut f64, &mut [f64; 4]),
    ) {
        let r = start..start + self.w.len();
        let [f2, g2, fx, fy] = k2;
        let nodes = self.w.iter().zip(self.rho_k);
        let static_slots = f2[r.clone()].iter().zip(&g2[r.clone()]);
        let area = self.area;
        if friction {
            let slots = static_slots.zip(fx[r.clone()].iter().zip(&fy[r]));
            for ((&w, &fj), ((&a, &b), (&c, &d))) in nodes.zip(slots) {
                let wf = w * fj;
                *running += wf;
                before[0] += area * wf * a;
                before[1] += area * wf * b;
                before[2] += area * wf * c;
                before[3] += area * wf * d;
            }
        } else {
            for ((&w, &fj), (&a, &b)) in nodes.zip(static_slots) {
                let wf = w * fj;
                *running += wf;
                before[0] += area * wf * a;
                before[1] += area * wf * b;
            }
        }
    }
}

/// G at every node of the panels [from, to) (forward pass: running sum plus the panel's
/// partial integral, from the graded region's G), with G's cumulative error and the partial
/// integral's signed curvature error at each node (into `dp_cum`, `dp_part`).
fn g_at_nodes(
    grid: &Grid,
    cg: f64,
    (from, to): (usize, usize),
    near: &Near,
    base: &BaseScratch,
    s: &mut InterfaceScratch,
) {
    let n = grid.q.len();
    let (f, f_dd) = (&base.rho_k, &base.rho_k_dd);
    let g_node = sized(&mut s.g_node, 2 * to, 0.0);
    let dp_cum = sized(&mut s.dp_cum, 2 * to, 0.0);
    let dp_part = sized(&mut s.dp_part, 2 * to, 0.0);
    let mut g_left = near.g_raw;
    let mut g_left_err = near.g_raw_err;
    for (p, g_err) in base.panel_errs.iter().enumerate().take(to).skip(from) {
        let (j0, j1) = (2 * p, 2 * p + 1);
        let start = j0.saturating_sub(1).min(n.saturating_sub(3));
        let psi2 = if n >= 3 { 2.0 * f_dd[1][start] } else { 0.0 };
        // The curvature terms of a panel's two nodes cancel in the sums (`Grid::interface_sum`
        // takes their signed sum), but not the variation of ψ[u1, u2, u] across the panel: it
        // differs from its mid-panel value by at most |ψ'''|·width/12, and ∫|(u − u1)(u − u2)|
        // from the left end to either Gauss node is at most 3.3 times |∫(u − u1)(u − u2)|, so
        // per node that part is at most 0.55·|ψ'''|·width times the leading term per unit ψ''
        // (with ERR_SAFETY on ψ''' from divided differences); it goes with G's other errors.
        let start3 = j0.saturating_sub(1).min(n.saturating_sub(4));
        let psi3 = if n >= 4 { 6.0 * f_dd[2][start3] } else { 0.0 };
        let drift = ERR_SAFETY * 0.55 * psi3.abs() * grid.width[p];
        for (jj, j) in [j0, j1].into_iter().enumerate() {
            g_node[j] =
                cg * (g_left + grid.partial[p][jj][0] * f[j0] + grid.partial[p][jj][1] * f[j1]);
            dp_cum[j] = cg * (g_left_err + drift * grid.partial_curv[p][jj].abs());
            dp_part[j] = cg * psi2 * grid.partial_curv[p][jj];
        }
        g_left += grid.w[j0] * f[j0] + grid.w[j1] * f[j1];
        g_left_err += g_err;
    }
}

/// P at the nodes of the panels [from, to), and the errors of P from the errors of G: erf and
/// the slopes |dP/dG| in one batch up to the panel `flat` from which P is linear in G (module
/// doc, "Linear P"), the linear model beyond. Returns `flat` and the linear model (s₁, its
/// remainder bound), if any.
fn probability_at_nodes(
    pt: &Point,
    g1: Estimate,
    area: f64,
    (from, to): (usize, usize),
    s: &mut InterfaceScratch,
) -> (usize, Option<(f64, f64)>) {
    let p0 = pt.p0;
    let InterfaceScratch {
        g_node,
        x_node,
        p_node,
        dp_dg,
        dp_cum,
        dp_part,
        ..
    } = s;
    sized(p_node, 2 * to, 0.0);
    sized(x_node, 2 * to, 0.0);
    sized(dp_dg, 2 * to, 0.0);
    let (flat, linear) = linear_probability(
        p0,
        g1,
        area,
        FLAT_SHARE * pt.rtol,
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
        &mut dp_dg[nodes.clone()],
    );
    for j in nodes {
        let slope = probability_slope(p0, x_node[j], dp_dg[j]);
        dp_dg[j] = slope;
        dp_cum[j] *= slope;
        dp_part[j] *= slope;
    }
    if let Some((s1, remainder)) = linear {
        // P = A + s₁(G1 − G) there, its error from G's as above, plus the model's.
        for j in 2 * flat..2 * to {
            p_node[j] = area + s1 * (g1.value - g_node[j]);
            dp_cum[j] = s1 * dp_cum[j] + remainder;
            dp_part[j] *= s1;
        }
    }
    (flat, linear)
}

/// P and its first four u-derivatives at each panel's first node in [from, to), for the error
/// terms: by Faà di Bruno's formula before `flat`, from the linear model beyond.
fn probability_derivatives_at(
    grid: &Grid,
    cg: f64,
    p0: f64,
    (from, to, flat): (usize, usize, usize),
    linear: Option<(f64, f64)>,
    rho_k: &[f64],
    s: &mut InterfaceScratch,
) {
    let f = rho_k;
    let (x_node, p_node, dp_dg) = (&s.x_node, &s.p_node, &s.dp_dg);
    let p_der = sized(&mut s.p_der, to, [0.0; 5]);
    let inv_a2 = 4.0 / (p0 * p0);
    let s1 = linear.map_or(0.0, |l| l.0);
    for (p, der) in p_der.iter_mut().enumerate().take(to).skip(from) {
        let (j0, j1) = (2 * p, 2 * p + 1);
        // G' = cg W K ρ at the node, growing locally like e^{λu}: λ = d ln W/du + d ln(Kρ)/du
        // across the panel's two nodes.
        let gp = cg * grid.w_at[j0] * f[j0];
        let lam = grid.beta[p] + ln_ratio(f[j1], f[j0]) * grid.inv_gap[p];
        *der = if p < flat {
            probability_derivatives(x_node[j0], inv_a2, dp_dg[j0], gp, lam, p_node[j0])
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
}

/// The sums of the slots σ, τ (as requested) and the two friction slots (when asked for),
/// without the factor 2cg, with their error estimates: the graded region's plus the two-node
/// panels' [from, to) (`to`: the cut of σ and τ, and of the friction slots), plus the tail's
/// bound beyond the cut: there P ≤ 1 and F² ≤ its value at the first node left out (F²
/// decreases for q·d ≥ X_CUT), so the tail is at most F²(that node)·Σ w ρ K. Slots not asked
/// for are the graded region's (zero) sums.
fn interface_sums(
    grid: &Grid,
    (from, to): (usize, [usize; 2]),
    near: &Near,
    (req, friction): (Request, bool),
    rho_k: &[f64],
    s: &mut InterfaceScratch,
) -> [(f64, f64); 4] {
    let n = grid.q.len();
    let f = rho_k;
    let tail_weight = |to: usize| -> f64 { (2 * to..n).map(|j| grid.w[j] * f[j]).sum() };
    let InterfaceScratch {
        f2,
        g2,
        fx,
        fy,
        p_node,
        dp_cum,
        dp_part,
        p_der,
        rho_k_f2,
        rho_k_f2_dd,
        ..
    } = s;
    let mut sum = |k2: &[f64], to: usize, tail_weight: f64, acc: (f64, f64)| {
        // ρ K F² at the nodes the sums and their divided differences use.
        let used = (2 * to + 5).min(n);
        let a = sized(rho_k_f2, used, 0.0);
        let r = 2 * from..used;
        for ((a, &fj), &k2) in a[r.clone()].iter_mut().zip(&f[r.clone()]).zip(&k2[r]) {
            *a = fj * k2;
        }
        let (v, e) = grid.interface_sum(a, rho_k_f2_dd, p_node, dp_cum, dp_part, p_der, from, to);
        let tail = k2.get(2 * to).map_or(0.0, |&k2c| k2c * tail_weight);
        (acc.0 + v, acc.1 + e + tail)
    };
    let mut out = [near.sigma, near.tau, near.friction[0], near.friction[1]];
    let weight = tail_weight(to[0]);
    if req.sigma_interface {
        out[0] = sum(f2, to[0], weight, out[0]);
    }
    if req.tau_interface {
        out[1] = sum(g2, to[0], weight, out[1]);
    }
    if friction {
        let weight = tail_weight(to[1]);
        out[2] = sum(fx, to[1], weight, out[2]);
        out[3] = sum(fy, to[1], weight, out[3]);
    }
    out
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

/// σ = e^{−s}·σ̃ for an rms σ̃ computed from f², g² scaled by e^{2s} (`kernels`, thick films):
/// e^{−s/2} applied twice, so that only a result below the normal range rounds (into the
/// subnormals, or to 0 below them); that rounding, at most half the smallest subnormal, is
/// added to the error as the whole smallest subnormal.
fn decayed(e: Estimate, s: f64) -> Estimate {
    if s == 0.0 {
        return e;
    }
    let half = (-0.5 * s).exp();
    let value = e.value * half * half;
    let mut err = e.err * half * half + 4.0 * EPS * value;
    if value < f64::MIN_POSITIVE {
        err += SMALLEST_SUBNORMAL;
    }
    Estimate::new(value, err, e.status)
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

#[cfg(test)]
mod tests {
    use super::*;
    use libm::erf;

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
}
