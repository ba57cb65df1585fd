//! Tangential-load kernels of a layer stack (sliding friction; not in the paper): at every
//! interface k, g_t,k, f_t,k (in-plane) and h_k (antiplane), the stack form of
//! [`crate::layer::tangential`] (notes.md, "Sliding friction" and "Layer stacks").
//!
//! Conventions as for one film: in-plane load σ_xz(x, 0) = t0 cos(qx), σ_zz(x, 0) = 0 gives
//! σ_xz(x, z_k) = g_t,k t0 cos(qx) and σ_zz(x, z_k) = f_t,k t0 sin(qx); antiplane load
//! σ_yz(x, 0) = t0 cos(qx) gives σ_yz(x, z_k) = h_k t0 cos(qx).
//!
//! In-plane: the state (ũ, t) of the parent module, whose phases are u_x, σ_xz ∝ sin(qx) and
//! u_z, σ_zz ∝ cos(qx), carries the top traction (T, Σ)(0) = (1, 0) down through the same
//! bottom-up stiffness recursion and downward pass as the normal load (only the top traction
//! differs), except that each thin layer's two forms of ũ_b and of t_b (parent module, "Stresses")
//! are chosen by a running estimate of their absolute error, which includes the error each
//! inherits from the state above (tracked through the pass), not by their own cancellation
//! alone: near a zero of g_t,k below a stiff plate on a soft layer, the displacement-forward
//! form of ũ_b inherits the plate's large displacement error, and the pick by cancellation
//! alone lost 9 digits of g_t,k there. Shifting qx by π/2 turns sin into cos and cos into −sin, so g_t,k = T(z_k) and
//! f_t,k = −Σ(z_k).
//!
//! Antiplane: u_y = V(z) cos(qx) and σ_yz = G V'(z) cos(qx) with V harmonic in each layer. Let
//! K be the stiffness of everything below a plane, σ_yz = K q u_y (Pa; −G_s for the substrate).
//! In layer k (shear modulus G, x = q d_k, t = e^{−2x}, m = 1 − t = −expm1(−2x)), with the base
//! below it at a = −K_b/G ≥ 0, the field V = A e^{−qz'} + B e^{q(z'−d)} (z' below the layer's
//! top, both parts bounded) meets σ_yz = K_b q V at the bottom when B = A e^{−x}(1 − a)/(1 + a),
//! which gives, at the top,
//!
//! ```text
//! K_t = −G [m + a(1 + t)] / [(1 + t) + a m],   σ_yz(bottom)/σ_yz(top) = 2a e^{−x} / [m + a(1 + t)]
//! ```
//!
//! Every term is non-negative: nothing cancels at any q·d or modulus ratio; at x = 0 the layer
//! disappears (K_t = K_b, ratio 1), for x → ∞ it is a half-space (K_t = −G). h_k is the product
//! of the ratios from the top down (each ≤ 1). One layer gives h = 2e^{−x}/((1 + t) + r m),
//! r = G_0/G_1, the film's form.
//!
//! Accuracy: against a 120/160-digit solution of the whole boundary-value problem
//! (`tests/data/stack_tangential_ref.py`) every value whose magnitude is at least 1e−30 is within
//! [`super::STACK_RTOL`] relative, g_t,k near its zeros in absolute terms (tests/it/stack.rs).

use super::{EMPTY_STEP, M2, MAX_LAYERS, Stack, Step, V2, mulv, scale_v};
use serde::Serialize;

/// g_t,k, f_t,k and h_k at one interface.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct InterfaceShear {
    /// σ_xz(z_k)/σ_xz(0) under an in-plane tangential mode (may change sign).
    pub g_t: f64,
    /// σ_zz(x, z_k) = f_t t0 sin(qx) under σ_xz(x, 0) = t0 cos(qx).
    pub f_t: f64,
    /// σ_yz(z_k)/σ_yz(0) under an antiplane mode.
    pub h: f64,
}

impl Stack {
    /// g_t,k, f_t,k, h_k at every interface (top first) at wavenumber q ≥ 0 (1/m).
    pub fn tangential(&self, q: f64) -> Vec<InterfaceShear> {
        let mut out = vec![InterfaceShear::default(); self.layers.len()];
        self.tangential_into(q, &mut out);
        out
    }

    /// [`Stack::tangential`] into `out` (length N) without allocating.
    pub fn tangential_into(&self, q: f64, out: &mut [InterfaceShear]) {
        debug_assert!(q >= 0.0 && out.len() == self.layers.len());
        let n = self.layers.len();
        let mut steps = [EMPTY_STEP; MAX_LAYERS];
        self.up_to_top(q, self.substrate_stiffness(), &mut steps[..n]);
        let mut t = [[0.0; 2]; MAX_LAYERS];
        self.tracked_pass(&steps[..n], [1.0, 0.0], &mut t[..n]);
        let mut h = [0.0; MAX_LAYERS];
        self.antiplane_into(q, &mut h[..n]);
        for ((o, t), h) in out.iter_mut().zip(&t).zip(&h) {
            *o = InterfaceShear {
                g_t: t[0],
                f_t: -t[1],
                h: *h,
            };
        }
    }

    /// h_k at every interface (module doc, "Antiplane") into `out` (length N).
    fn antiplane_into(&self, q: f64, out: &mut [f64]) {
        // −K (Pa), the stiffness's magnitude.
        let mut k_b = self.substrate.shear_modulus();
        for (o, layer) in out.iter_mut().zip(&self.layers).rev() {
            let g = layer.material.shear_modulus();
            let x = q * layer.thickness;
            let a = k_b / g;
            let m = -(-2.0 * x).exp_m1();
            let t = (-2.0 * x).exp();
            let num = m + a * (1.0 + t);
            k_b = g * num / ((1.0 + t) + a * m);
            *o = 2.0 * a * (-x).exp() / num;
        }
        let mut h = 1.0;
        for o in out.iter_mut() {
            h *= *o;
            *o = h;
        }
    }
}

/// A value with a bound on its absolute error, per component.
#[derive(Debug, Clone, Copy)]
struct Tracked {
    v: V2,
    e: V2,
}

/// |m|·|v|, entry by entry.
fn abs_mulv(m: &M2, v: V2) -> V2 {
    [
        m[0][0].abs() * v[0].abs() + m[0][1].abs() * v[1].abs(),
        m[1][0].abs() * v[0].abs() + m[1][1].abs() * v[1].abs(),
    ]
}

fn add_v(a: V2, b: V2) -> V2 {
    [a[0] + b[0], a[1] + b[1]]
}

/// m·x with its error: the rounding of the product (relative to Σ|terms|, with a few ulp of
/// each entry of m) and x's own error carried through |m|.
fn apply(m: &M2, x: Tracked) -> Tracked {
    let round = scale_v(abs_mulv(m, x.v), 4.0 * f64::EPSILON);
    Tracked {
        v: mulv(m, x.v),
        e: add_v(round, abs_mulv(m, x.e)),
    }
}

/// x + m·y + n·w with its error (as [`apply`], the terms' rounding and the inherited errors).
fn forward(x: Tracked, m: &M2, y: Tracked, n: &M2, w: Tracked) -> Tracked {
    let (my, nw) = (apply(m, y), apply(n, w));
    let v = add_v(x.v, add_v(my.v, nw.v));
    let terms = add_v(x.v.map(f64::abs), add_v(abs_mulv(m, y.v), abs_mulv(n, w.v)));
    Tracked {
        v,
        e: add_v(
            scale_v(terms, 2.0 * f64::EPSILON),
            add_v(x.e, add_v(my.e, nw.e)),
        ),
    }
}

/// Per component, the value of `a` or `b` with the smaller error bound.
fn pick_tracked(a: Tracked, b: Tracked) -> Tracked {
    let mut out = a;
    for i in 0..2 {
        if b.e[i] < a.e[i] {
            out.v[i] = b.v[i];
            out.e[i] = b.e[i];
        }
    }
    out
}

impl Stack {
    /// The parent's downward pass of the top traction `t0` (module doc): the traction (T, Σ) at
    /// every interface into `out`, each thin layer's forms picked by their tracked errors.
    fn tracked_pass(&self, steps: &[Step], t0: V2, out: &mut [V2]) {
        let top = &self.consts[0];
        let t = Tracked { v: t0, e: [0.0; 2] };
        let u0 = match &steps[0] {
            Step::Thin { x_inv, y, .. } => apply(y, apply(x_inv, t)),
            Step::Thick { v_of_t, i_er, .. } => apply(i_er, apply(v_of_t, t)),
        };
        let mut t = t;
        // Displacement times q (dimensionless): layer k's ũ is 2G_k times this.
        let mut uq = scaled(u0, top.inv_two_g);
        for ((step, c), o) in steps.iter().zip(&self.consts).zip(out.iter_mut()) {
            let ut = scaled(uq, c.two_g);
            let (ub, tb) = tracked_down(step, ut, t);
            *o = tb.v;
            t = tb;
            uq = scaled(ub, c.inv_two_g);
        }
    }
}

fn scaled(x: Tracked, s: f64) -> Tracked {
    Tracked {
        v: scale_v(x.v, s),
        e: scale_v(x.e, s),
    }
}

/// The state (ũ_b, t_b) at a layer's bottom from (ũ_t, t_t) at its top, with error bounds.
fn tracked_down(step: &Step, ut: Tracked, t: Tracked) -> (Tracked, Tracked) {
    match step {
        Step::Thick { kb, v_of_t, b, .. } => {
            let ub = apply(b, apply(v_of_t, t));
            (ub, apply(kb, ub))
        }
        Step::Thin { kb, x_inv, p, .. } => {
            let [puu, put, ptu, ptt] = p;
            let ub = pick_tracked(apply(x_inv, t), forward(ut, puu, ut, put, t));
            let tb_fwd = forward(t, ptu, ut, ptt, t);
            (ub, pick_tracked(apply(kb, ub), tb_fwd))
        }
    }
}
