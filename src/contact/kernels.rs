//! The layer kernels S⁻², f², g² of one material pair at the quadrature nodes for one
//! thickness (eqs. B8–B12 take them at q·d): from the pair's [`KernelTable`] (checked against
//! the exact forms to [`crate::prec::TABLE_RTOL`]), or the exact forms where no table resolves
//! them; or a layer stack's S⁻² and one interface's f_k², g_k² (`layer::stack`). The batch forms (`k_many`, `interface_many`) evaluate all nodes of a range at once.

use crate::layer::stack::{MAX_LAYERS, Stack};
use crate::layer::{Bilayer, KernelTable, Nodes, Squared};
use std::cell::RefCell;
use std::collections::HashMap;

/// The layer kernels at nodes q (with u = ln q) for one thickness: tabulated, or exact when no
/// table resolves them (`layer::KernelTable`).
pub(super) enum Kernels<'a> {
    Table {
        table: &'a KernelTable,
        d: f64,
        ln_d: f64,
    },
    Exact {
        layers: &'a Bilayer,
        d: f64,
    },
    /// A layer stack's S⁻² and, at its interface `k` (0 = below the top layer), f_k², g_k²,
    /// exact at q ([`Stack::response_into`]), each q evaluated once for all interfaces
    /// (`memo`).
    Stack {
        stack: &'a Stack,
        k: usize,
        memo: &'a StackMemo,
    },
}

/// A stack's S and every (f_k, g_k) at the q already evaluated (by q's bits): the evaluations
/// of the interfaces of one stack share their nodes.
pub(super) type StackMemo = RefCell<HashMap<u64, (f64, [(f64, f64); MAX_LAYERS])>>;

/// S and (f_k, g_k) of a stack at q.
fn stack_at(stack: &Stack, memo: &StackMemo, k: usize, q: f64) -> (f64, f64, f64) {
    let mut memo = memo.borrow_mut();
    let (s, out) = memo.entry(q.to_bits()).or_insert_with(|| {
        let mut out = [(0.0, 0.0); MAX_LAYERS];
        let s = stack.response_into(q, &mut out[..stack.layers().len()]);
        (s, out)
    });
    (*s, out[k].0, out[k].1)
}

impl Kernels<'_> {
    #[inline]
    pub(super) fn k(&self, q: f64, u: f64) -> f64 {
        match *self {
            Kernels::Table { table, d, ln_d } => table.k(q * d, u + ln_d),
            Kernels::Exact { layers, d } => layers.s(q * d).powi(-2),
            Kernels::Stack { stack, k, memo } => stack_at(stack, memo, k, q).0.powi(-2),
        }
    }

    /// f², g² at the node.
    #[inline]
    pub(super) fn interface(&self, q: f64, u: f64) -> (f64, f64) {
        match *self {
            Kernels::Table { table, d, ln_d } => table.interface(q * d, u + ln_d),
            Kernels::Exact { layers, d } => {
                let r = layers.response(q * d);
                (r.f * r.f, r.g * r.g)
            }
            Kernels::Stack { stack, k, memo } => {
                let (_, f, g) = stack_at(stack, memo, k, q);
                (f * f, g * g)
            }
        }
    }

    /// S⁻² at the ascending nodes (q, u), into `out`.
    pub(super) fn k_many(&self, q: &[f64], u: &[f64], out: &mut [f64]) {
        match *self {
            Kernels::Table { table, d, ln_d } => table.k_many(Nodes { q, u, d, ln_d }, out),
            Kernels::Exact { .. } | Kernels::Stack { .. } => {
                for ((o, &q), &u) in out.iter_mut().zip(q).zip(u) {
                    *o = self.k(q, u);
                }
            }
        }
    }

    /// f², g² at the ascending nodes (q, u), into `f2` and `g2`.
    pub(super) fn interface_many(&self, q: &[f64], u: &[f64], f2: &mut [f64], g2: &mut [f64]) {
        match *self {
            Kernels::Table { table, d, ln_d } => {
                table.interface_many(Nodes { q, u, d, ln_d }, f2, g2)
            }
            Kernels::Exact { .. } | Kernels::Stack { .. } => {
                for (((fo, go), &q), &u) in f2.iter_mut().zip(g2.iter_mut()).zip(q).zip(u) {
                    (*fo, *go) = self.interface(q, u);
                }
            }
        }
    }

    #[inline]
    pub(super) fn squared(&self, q: f64, u: f64) -> Squared {
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
            Kernels::Stack { stack, k, memo } => {
                let (s, f, g) = stack_at(stack, memo, k, q);
                Squared {
                    k: s.powi(-2),
                    f2: f * f,
                    g2: g * g,
                }
            }
        }
    }
}
