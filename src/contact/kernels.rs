//! The layer kernels S⁻², f², g² of one material pair at the quadrature nodes for one
//! thickness (eqs. B8–B12 take them at q·d): from the pair's [`KernelTable`] (checked against
//! the exact forms to [`crate::prec::TABLE_RTOL`]), or the exact forms where no table resolves
//! them. The batch forms (`k_many`, `interface_many`) evaluate all nodes of a range at once.
//!
//! Under sliding ([`super::sliding`]) the interface integrals take other kernels in the two
//! slots of f² and g² ([`Mix`]), from the exact tangential kernels
//! ([`crate::layer::tangential`]): every mix is a sum of squares, and like f², g² decreases
//! above q·d = 20 (each of g_t, f_t, h is (a + b x)e^{−x} there, with its zero, if any, below
//! x = 2), which the interface integrals' cut relies on.

use crate::layer::{Bilayer, KernelTable, Nodes, Squared};

/// What the interface integrals' two slots (σ, τ) integrate against P and S⁻².
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Mix {
    /// f², g² (eqs. B8–B9).
    Static,
    /// f² + μ² f_t²/2 (the interface normal stress with the friction-driven part) and g².
    Sliding { mu2: f64 },
    /// The friction-driven shear per unit μ²: ((g_t + h)/2)² + (g_t − h)²/8 along x and
    /// (g_t − h)²/8 along y ([`super::sliding`]).
    Friction,
}

impl Mix {
    /// The two slots from the static f², g² (unused by [`Mix::Friction`]) at x = q·d.
    #[inline]
    fn apply(self, layers: &Bilayer, x: f64, (f2, g2): (f64, f64)) -> (f64, f64) {
        match self {
            Mix::Static => (f2, g2),
            Mix::Sliding { mu2 } => {
                let t = layers.tangential(x);
                (f2 + 0.5 * mu2 * t.f_t * t.f_t, g2)
            }
            Mix::Friction => {
                let t = layers.tangential(x);
                let (half_sum, diff) = (0.5 * (t.g_t + t.h), t.g_t - t.h);
                let y = 0.125 * diff * diff;
                (half_sum * half_sum + y, y)
            }
        }
    }
}

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
    /// `base`'s S⁻², and its f², g² turned into another pair by `mix`.
    Mixed {
        base: &'a Kernels<'a>,
        layers: &'a Bilayer,
        d: f64,
        mix: Mix,
    },
}

impl Kernels<'_> {
    #[inline]
    pub(super) fn k(&self, q: f64, u: f64) -> f64 {
        match *self {
            Kernels::Table { table, d, ln_d } => table.k(q * d, u + ln_d),
            Kernels::Exact { layers, d } => layers.s(q * d).powi(-2),
            Kernels::Mixed { base, .. } => base.k(q, u),
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
            Kernels::Mixed {
                base,
                layers,
                d,
                mix,
            } => {
                let fg = match mix {
                    Mix::Friction => (0.0, 0.0),
                    _ => base.interface(q, u),
                };
                mix.apply(layers, q * d, fg)
            }
        }
    }

    /// S⁻² at the ascending nodes (q, u), into `out`.
    pub(super) fn k_many(&self, q: &[f64], u: &[f64], out: &mut [f64]) {
        match *self {
            Kernels::Table { table, d, ln_d } => table.k_many(Nodes { q, u, d, ln_d }, out),
            Kernels::Exact { .. } => {
                for ((o, &q), &u) in out.iter_mut().zip(q).zip(u) {
                    *o = self.k(q, u);
                }
            }
            Kernels::Mixed { base, .. } => base.k_many(q, u, out),
        }
    }

    /// f², g² at the ascending nodes (q, u), into `f2` and `g2`.
    pub(super) fn interface_many(&self, q: &[f64], u: &[f64], f2: &mut [f64], g2: &mut [f64]) {
        match *self {
            Kernels::Table { table, d, ln_d } => {
                table.interface_many(Nodes { q, u, d, ln_d }, f2, g2)
            }
            Kernels::Exact { .. } => {
                for (((fo, go), &q), &u) in f2.iter_mut().zip(g2.iter_mut()).zip(q).zip(u) {
                    (*fo, *go) = self.interface(q, u);
                }
            }
            Kernels::Mixed {
                base,
                layers,
                d,
                mix,
            } => {
                if mix != Mix::Friction {
                    base.interface_many(q, u, f2, g2);
                }
                for ((fo, go), &q) in f2.iter_mut().zip(g2.iter_mut()).zip(q) {
                    (*fo, *go) = mix.apply(layers, q * d, (*fo, *go));
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
            Kernels::Mixed {
                base,
                layers,
                d,
                mix,
            } => {
                let b = base.squared(q, u);
                let (f2, g2) = mix.apply(layers, q * d, (b.f2, b.g2));
                Squared { k: b.k, f2, g2 }
            }
        }
    }
}
