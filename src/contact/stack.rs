//! Persson's theory on a layer stack (eqs. B8–B12 with the stack's kernels, notes.md "Layer
//! stacks"): G(q), A/A0 and σ_rms at the top from S⁻² of the whole stack (normalised by the top
//! layer's E*, so E0* in eq. B12 is the top layer's), and at every interface k, at depth z_k,
//! σ_rms and τ_rms from f_k² and g_k² in place of f², g².
//!
//! Each interface is one evaluation of [`super::evaluate`] with the kernels
//! `Kernels::stack(…, k, …)` and the interface's depth z_k in place of the film thickness (the
//! interface tail's cut at q·z_k ≥ 20 assumes f_k² and g_k² decrease there, as e^{−2q z_k}
//! times a rational function of q whose degree is at most twice the number of layers: checked
//! for the stacks of the tests, `tests/it/stack_scene.rs`). The evaluations are refined
//! together, grid by grid, and share G's sum on each grid (their kernels share S⁻²:
//! [`Engine::refine_sharing`]); each is refined as it would be alone. G, A/A0 and σ_rms at the
//! top are the first interface's evaluation's. The kernels' error bound [`STACK_RTOL`] enters the rounding floor of every estimate.
//! The stack's kernels are evaluated once per node for all interfaces (one call gives S and
//! every f_k, g_k) and kept for the evaluation, in the engine's [`StackCache`]: between the
//! evaluations of a minimum-thickness search, where one layer changes, the recursion through
//! the layers below it is kept per node (the nodes are the same at every thickness), to the
//! last bit the same values.

use super::engine::At;
use super::kernels::{Kernels, Mix, StackMemo};
use super::{Contact, Engine, Request};
use crate::error::Error;
use crate::layer::stack::{STACK_RTOL, Stack, StackCache};
use crate::prec::Estimate;
use serde::Serialize;
use std::cell::RefCell;

/// Every interface's friction slots under sliding ([`Engine::refine`]), top first.
type FrictionSlots = Vec<Option<[Estimate; 2]>>;

/// σ_rms and τ_rms at one interface of a stack.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InterfaceContact {
    /// Depth z_k of the interface below the top surface (m).
    pub depth: f64,
    pub sigma_rms: Option<Estimate>,
    pub tau_rms: Option<Estimate>,
}

/// The contact on a stack: the top surface's quantities as for a film (in `top`, whose
/// interface fields are those of the first interface, below the top layer), and every
/// interface's, top first.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StackContact {
    pub top: Contact,
    pub interfaces: Vec<InterfaceContact>,
}

impl Engine {
    /// Evaluate on a layer stack at nominal pressure p0 (Pa): `request`'s top quantities once,
    /// its interface quantities at every interface.
    pub fn evaluate_stack(
        &self,
        stack: &Stack,
        p0: f64,
        request: Request,
    ) -> Result<StackContact, Error> {
        Ok(self
            .evaluate_stack_mixed(stack, p0, request, Mix::Static)?
            .0)
    }

    /// [`Self::evaluate_stack`] with the interface slots mixed by `mix` (sliding,
    /// [`super::stack_sliding`]), with every interface's friction slots ([`Engine::refine`];
    /// `None` unless `mix` is sliding and τ is requested).
    pub(super) fn evaluate_stack_mixed(
        &self,
        stack: &Stack,
        p0: f64,
        request: Request,
        mix: Mix,
    ) -> Result<(StackContact, FrictionSlots), Error> {
        if !(p0.is_finite() && p0 > 0.0) {
            return Err(Error::invalid(
                "nominal pressure p0",
                p0,
                "a finite pressure > 0 in Pa",
            ));
        }
        // The cache of the engine's last stack, taken out for this evaluation (a new one if
        // another evaluation holds it) and put back afterwards.
        let taken = self
            .stack_cache()
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take();
        let mut cache = taken.unwrap_or_else(|| StackCache::new(stack.clone()));
        cache.serve(stack);
        let memo = RefCell::new(cache);
        let result = self.evaluate_stack_with(&memo, p0, request, mix);
        *self.stack_cache().lock().unwrap_or_else(|e| e.into_inner()) = Some(memo.into_inner());
        result
    }

    /// [`Self::evaluate_stack`] with the kernels of the stack `memo` serves.
    fn evaluate_stack_with(
        &self,
        memo: &StackMemo,
        p0: f64,
        request: Request,
        mix: Mix,
    ) -> Result<(StackContact, FrictionSlots), Error> {
        let stack = memo.borrow().stack().clone();
        let e_top = stack.layers()[0].material.e_star();
        let depths = stack.depths();
        let each: Vec<_> = depths
            .iter()
            .enumerate()
            .map(|(k, &depth)| {
                let req = Request {
                    sigma_top: request.sigma_top && k == 0,
                    e_eff: request.e_eff && k == 0,
                    ..request
                };
                let at = At {
                    depth,
                    e_top,
                    p0,
                    kernel_rtol: STACK_RTOL,
                };
                (Kernels::stack(k, memo).mixed(mix, None), at, req)
            })
            .collect();
        let mut top = None;
        let mut interfaces = Vec::with_capacity(depths.len());
        let mut friction = Vec::with_capacity(depths.len());
        for ((c, pair), depth) in self.refine_sharing(&each)?.into_iter().zip(depths) {
            friction.push(pair);
            interfaces.push(InterfaceContact {
                depth,
                sigma_rms: c.sigma_rms_interface,
                tau_rms: c.tau_rms_interface,
            });
            top.get_or_insert(c);
        }
        let contact = StackContact {
            top: top.expect("a stack has a layer"),
            interfaces,
        };
        Ok((contact, friction))
    }
}
