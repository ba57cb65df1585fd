//! The layer kernels S⁻², f², g² of one material pair at the quadrature nodes for one
//! thickness (eqs. B8–B12 take them at q·d): from the pair's [`KernelTable`] (checked against
//! the exact forms to [`crate::prec::TABLE_RTOL`]), or the exact forms where no table resolves
//! them; or a layer stack's S⁻² and one interface's f_k², g_k² (`layer::stack`), exact at every
//! node. The batch forms (`k_many`, `interface_many`) evaluate all nodes of a range at once.
//!
//! Thick films: f and g fall like e^{−qd}, so f² and g² leave the f64 range from q·d ≈ 355
//! while the interface stresses (∝ f(q_L d)) stay representable up to q_L d ≈ 745. Where
//! q_L d exceeds [`X_SHIFT`], f² and g² are returned times e^{2 q_L d} (the `shift`): from the
//! undecayed forms (f e^{qd})², (g e^{qd})² (`Bilayer::interface_undecayed`) times
//! e^{−2(qd − q_L d)} ≤ 1, all within the normal range; the caller applies e^{−q_L d} to the
//! rms ([`Kernels::shift`]). Every node there has q·d > [`X_SHIFT`] > [`crate::layer::X_FAR`],
//! where S = 1 and the table holds no f, g panels, and the integrals stop within a few q·d of
//! q_L d, so the exact forms cost a few hundred evaluations.
//!
//! Under sliding ([`super::sliding`]) the interface integrals take σ's slot mixed with f_t²
//! ([`Mix`]) and two more slots, the friction kernels, from the squares of the tangential
//! kernels ([`crate::layer::tangential`]) in the pair's [`TangentialTable`] (built over the
//! static table's range, checked like it; read in the same batches as the static table, all
//! three squares at once), or exact where there is no table: every slot is a sum of
//! squares, and like f², g² decreases above q·d = 20 (each of g_t, f_t, h is (a + b x)e^{−x}
//! there, with its zero, if any, below x = 2), which the interface integrals' cut relies on.
//! Where the kernels are scaled (thick films), the tangential kernels are scaled alike, from
//! their undecayed forms.

use crate::layer::stack::StackCache;
use crate::layer::{
    Bilayer, KernelTable, Nodes, Squared, TangentialTable, friction_squares, undecayed_squares,
};
use std::cell::RefCell;

/// Above this q_L·d the interface kernels are scaled by e^{2 q_L d}: below it f², g² at q_L d
/// exceed e^{−400}·(f e^{qd})² ≈ 1e-174·(f e^{qd})², and sums of them stay far inside the normal
/// range.
pub(super) const X_SHIFT: f64 = 200.0;

/// What the interface integrals' two slots (σ, τ) integrate against P and S⁻²; under sliding
/// the evaluation may also ask for the two friction slots, the friction-driven shear per unit
/// μ²: ((g_t + h)/2)² + (g_t − h)²/8 along x and (g_t − h)²/8 along y ([`super::sliding`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Mix {
    /// f², g² (eqs. B8–B9).
    Static,
    /// f² + μ² f_t²/2 (the interface normal stress with the friction-driven part) and g².
    Sliding { mu2: f64 },
}

/// Where the kernels come from.
#[derive(Clone, Copy)]
enum Source<'a> {
    Table {
        table: &'a KernelTable,
        d: f64,
        ln_d: f64,
    },
    Exact {
        layers: &'a Bilayer,
        d: f64,
    },
    /// The stack served by `memo`: its S⁻² and, at its interface `k` (0 = below the top
    /// layer), f_k², g_k², exact at q ([`StackCache::response`], each q evaluated once for all
    /// interfaces).
    Stack {
        k: usize,
        memo: &'a StackMemo,
    },
}

/// The kernels of the stack being evaluated, per node ([`StackCache`]).
pub(super) type StackMemo = RefCell<StackCache>;

/// S and (f_k, g_k) of the stack served by `memo` at q.
fn stack_at(memo: &StackMemo, k: usize, q: f64) -> (f64, f64, f64) {
    let mut memo = memo.borrow_mut();
    let (s, out) = memo.response(q);
    (s, out[k].0, out[k].1)
}

/// The layer kernels at nodes q (with u = ln q) for one thickness: tabulated, or exact when no
/// table resolves them (`layer::KernelTable`); f², g² scaled by e^{2·shift} (module doc).
pub(super) struct Kernels<'a> {
    source: Source<'a>,
    shift: f64,
    mix: Mix,
    /// The friction kernels' table, used with a tabulated source.
    tangential: Option<&'a TangentialTable>,
}

impl<'a> Kernels<'a> {
    /// The kernels of `layers` at thickness `d` for a spectrum starting at `q_low`, from `table`
    /// where there is one.
    pub(super) fn new(
        table: Option<&'a KernelTable>,
        layers: &'a Bilayer,
        d: f64,
        q_low: f64,
    ) -> Self {
        let source = match table {
            Some(table) => Source::Table {
                table,
                d,
                ln_d: d.ln(),
            },
            None => Source::Exact { layers, d },
        };
        let x_low = q_low * d;
        let shift = if x_low > X_SHIFT { x_low } else { 0.0 };
        Self {
            source,
            shift,
            mix: Mix::Static,
            tangential: None,
        }
    }

    /// These kernels with the interface slots mixed by `mix` (sliding), the friction kernels
    /// from `tangential` where the static ones come from a table (a stack's from
    /// [`crate::layer::stack::Stack::tangential`], with g_t,k − h_k formed as a difference).
    pub(super) fn mixed(self, mix: Mix, tangential: Option<&'a TangentialTable>) -> Self {
        Self {
            mix,
            tangential,
            ..self
        }
    }

    /// The friction kernels' squares at the node q (u = ln q), scaled like f², g²: from the
    /// table where there is one and no scaling, else from the undecayed exact forms times
    /// e^{−2(qd − s)}.
    #[inline]
    fn friction_squares(&self, q: f64, u: f64) -> [f64; 3] {
        let (layers, d) = match (self.source, self.tangential) {
            (Source::Table { d, ln_d, .. }, Some(t)) if self.shift == 0.0 => {
                return t.squares(q * d, u + ln_d);
            }
            (Source::Table { table, d, .. }, _) => (table.layers(), d),
            (Source::Exact { layers, d }, _) => (layers, d),
            (Source::Stack { k, memo }, _) => {
                let t = memo.borrow().stack().tangential(q)[k];
                return friction_squares(t.f_t, t.h, t.g_t - t.h);
            }
        };
        let x = q * d;
        let e = (-(x - self.shift)).exp();
        undecayed_squares(layers, x).map(|v| v * e * e)
    }

    /// The σ and τ slots at q from the static f², g² there (times e^{2s}), and the friction
    /// slots (zero under [`Mix::Static`]).
    #[inline]
    fn mixed_at(&self, q: f64, u: f64, (f2, g2): (f64, f64)) -> ((f64, f64), [f64; 2]) {
        match self.mix {
            Mix::Static => ((f2, g2), [0.0; 2]),
            Mix::Sliding { mu2 } => {
                let [f_t2, along, across] = self.friction_squares(q, u);
                ((f2 + 0.5 * mu2 * f_t2, g2), [along, across])
            }
        }
    }

    /// The kernels of the stack `memo` serves at its interface `k` (unscaled: the stack's
    /// interface integrals stop at q·z_k = 20, `contact::stack`).
    pub(super) fn stack(k: usize, memo: &'a StackMemo) -> Self {
        Self {
            source: Source::Stack { k, memo },
            shift: 0.0,
            mix: Mix::Static,
            tangential: None,
        }
    }

    /// Whether the interface slots are mixed for sliding (and the friction slots can be asked
    /// for).
    pub(super) fn sliding(&self) -> bool {
        matches!(self.mix, Mix::Sliding { .. })
    }

    /// s: the f², g² returned are f² e^{2s}, g² e^{2s} (0 unless q_L d > [`X_SHIFT`]).
    pub(super) fn shift(&self) -> f64 {
        self.shift
    }

    #[inline]
    pub(super) fn k(&self, q: f64, u: f64) -> f64 {
        match self.source {
            Source::Table { table, d, ln_d } => table.k(q * d, u + ln_d),
            Source::Exact { layers, d } => layers.s(q * d).powi(-2),
            Source::Stack { memo, .. } => memo.borrow_mut().s(q).powi(-2),
        }
    }

    /// f² e^{2s}, g² e^{2s} at q·d > s from the undecayed forms (module doc).
    fn shifted(&self, q: f64) -> (f64, f64) {
        let (layers, d) = match self.source {
            Source::Table { table, d, .. } => (table.layers(), d),
            Source::Exact { layers, d } => (layers, d),
            Source::Stack { k, memo } => {
                let (_, f, g) = stack_at(memo, k, q);
                let e = self.shift.exp();
                return ((f * e).powi(2), (g * e).powi(2));
            }
        };
        let x = q * d;
        let (f, g) = layers.interface_undecayed(x);
        let e = (-(x - self.shift).max(0.0)).exp();
        ((f * e).powi(2), (g * e).powi(2))
    }

    /// f², g² at the node (times e^{2s}), before the mix.
    #[inline]
    fn static_interface(&self, q: f64, u: f64) -> (f64, f64) {
        if self.shift > 0.0 {
            return self.shifted(q);
        }
        match self.source {
            Source::Table { table, d, ln_d } => table.interface(q * d, u + ln_d),
            Source::Exact { layers, d } => {
                let r = layers.response(q * d);
                (r.f * r.f, r.g * r.g)
            }
            Source::Stack { k, memo } => {
                let (_, f, g) = stack_at(memo, k, q);
                (f * f, g * g)
            }
        }
    }

    /// S⁻² at the ascending nodes (q, u), into `out`.
    pub(super) fn k_many(&self, q: &[f64], u: &[f64], out: &mut [f64]) {
        match self.source {
            Source::Table { table, d, ln_d } => table.k_many(Nodes { q, u, d, ln_d }, out),
            Source::Stack { memo, .. } => memo.borrow_mut().k_many(q, out),
            Source::Exact { .. } => {
                for ((o, &q), &u) in out.iter_mut().zip(q).zip(u) {
                    *o = self.k(q, u);
                }
            }
        }
    }

    /// The σ and τ slots (f², g² times e^{2s}, mixed) at the ascending nodes (q, u), into `f2`
    /// and `g2`, and with `friction` the friction slots into its two slices (under
    /// [`Mix::Sliding`] only).
    pub(super) fn interface_many(
        &self,
        q: &[f64],
        u: &[f64],
        f2: &mut [f64],
        g2: &mut [f64],
        mut friction: Option<[&mut [f64]; 2]>,
    ) {
        match (self.source, self.mix) {
            (Source::Table { table, d, ln_d }, mix) if self.shift == 0.0 => {
                let at = Nodes { q, u, d, ln_d };
                table.interface_many(at, f2, g2);
                match (mix, self.tangential) {
                    (Mix::Static, _) => return,
                    (Mix::Sliding { mu2 }, Some(t)) => {
                        return t.slots_many(at, 0.5 * mu2, f2, friction);
                    }
                    (Mix::Sliding { .. }, None) => {}
                }
                for (j, (&q, &u)) in q.iter().zip(u).enumerate() {
                    let (fg, fr) = self.mixed_at(q, u, (f2[j], g2[j]));
                    (f2[j], g2[j]) = fg;
                    if let Some([a, c]) = friction.as_mut() {
                        (a[j], c[j]) = (fr[0], fr[1]);
                    }
                }
            }
            (Source::Stack { k, memo }, Mix::Static) => {
                memo.borrow_mut().interface_many(k, q, f2, g2);
            }
            _ => {
                for (j, (&q, &u)) in q.iter().zip(u).enumerate() {
                    let (fg, fr) = self.mixed_at(q, u, self.static_interface(q, u));
                    (f2[j], g2[j]) = fg;
                    if let Some([a, c]) = friction.as_mut() {
                        (a[j], c[j]) = (fr[0], fr[1]);
                    }
                }
            }
        }
    }

    /// S⁻², the σ and τ slots (f², g² times e^{2s}, mixed) and the friction slots (zero under
    /// [`Mix::Static`]) at the node.
    #[inline]
    pub(super) fn squared(&self, q: f64, u: f64) -> (Squared, [f64; 2]) {
        let s = self.static_squared(q, u);
        let ((f2, g2), friction) = self.mixed_at(q, u, (s.f2, s.g2));
        (Squared { k: s.k, f2, g2 }, friction)
    }

    /// S⁻², f², g² (the latter times e^{2s}) at the node, before the mix.
    #[inline]
    fn static_squared(&self, q: f64, u: f64) -> Squared {
        if self.shift > 0.0 {
            let (f2, g2) = self.shifted(q);
            return Squared {
                k: self.k(q, u),
                f2,
                g2,
            };
        }
        match self.source {
            Source::Table { table, d, ln_d } => table.squared(q * d, u + ln_d),
            Source::Exact { layers, d } => {
                let r = layers.response(q * d);
                Squared {
                    k: r.s.powi(-2),
                    f2: r.f * r.f,
                    g2: r.g * r.g,
                }
            }
            Source::Stack { k, memo } => {
                let (s, f, g) = stack_at(memo, k, q);
                Squared {
                    k: s.powi(-2),
                    f2: f * f,
                    g2: g * g,
                }
            }
        }
    }
}
