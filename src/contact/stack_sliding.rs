//! Persson's theory under sliding on a layer stack (notes.md, "Sliding friction" and "Layer
//! stacks"): the film's uncoupled approximation ([`super::sliding`]) with, at every interface
//! k, the stack's kernels f_k, g_k and g_t,k, f_t,k, h_k
//! ([`crate::layer::stack::Stack::tangential`]) in place of the film's.
//!
//! At interface k the shear vector is (μp0 + X_k, Y_k): the mean friction passes every
//! interface unchanged (g_t,k, h_k → 1 as q → 0, tested), and
//!
//! ```text
//! τ_x,rms² = τ_rms²/2 + μ² ∫ [((g_t,k + h_k)/2)² + (g_t,k − h_k)²/8] dV
//! τ_y,rms² = τ_rms²/2 + μ² ∫ (g_t,k − h_k)²/8 dV
//! σ_rms(z_k)² = ∫ (f_k² + μ² f_t,k²/2) dV
//! ```
//!
//! as for the film, each interface integral one evaluation of the stack's ([`super::stack`])
//! with the mixed kernels. The friction kernels decay like e^{−q z_k} times a rational function
//! of q, as f_k and g_k do, which the interface integrals' cut at q·z_k = 20 relies on.
//! g_t,k − h_k is their difference: where both are near 1 (q z_k ≪ 1) it is accurate to
//! about 2e−16 absolute (measured against the film's stable form for one layer), which only the
//! small τ_y friction part sees.

use super::kernels::Mix;
use super::sliding::combine;
use super::{Engine, Request, SlidingShear, StackContact};
use crate::error::Error;
use crate::layer::stack::Stack;
use crate::prec::Estimate;

impl Engine {
    /// The contact on a stack under sliding with friction μ ≥ 0: the static results of
    /// [`Engine::evaluate_stack`], except that every interface's σ_rms includes the
    /// friction-driven part; with `tau_interface` requested, also every interface's shear
    /// vector mean and rms (top first; the friction slots, evaluated with the others, only when
    /// μ > 0).
    pub fn evaluate_stack_sliding(
        &self,
        stack: &Stack,
        p0: f64,
        mu: f64,
        request: Request,
    ) -> Result<(StackContact, Option<Vec<SlidingShear>>), Error> {
        if !(mu.is_finite() && mu >= 0.0) {
            return Err(Error::invalid(
                "friction coefficient",
                mu,
                "a finite value >= 0",
            ));
        }
        let mu2 = mu * mu;
        let mix = if mu > 0.0 {
            Mix::Sliding { mu2 }
        } else {
            Mix::Static
        };
        let (contact, pairs) = self.evaluate_stack_mixed(stack, p0, request, mix)?;
        if !request.tau_interface {
            return Ok((contact, None));
        }
        let none = [Estimate::exact(0.0); 2];
        let friction = pairs.into_iter().map(|p| p.unwrap_or(none));
        let shears = contact
            .interfaces
            .iter()
            .zip(friction)
            .map(|(i, [fx, fy])| {
                let tau = i.tau_rms.expect("tau_interface requested");
                SlidingShear {
                    friction: mu,
                    mean: Estimate::exact(mu * p0),
                    tau_x_rms: combine(tau, mu2, fx),
                    tau_y_rms: combine(tau, mu2, fy),
                    coupling: None,
                }
            })
            .collect();
        Ok((contact, Some(shears)))
    }
}
