//! Run-time choice of an AVX2 build for the batched loops (`layer::KernelTable::k_many` and
//! `interface_many`, `special::erf_and_gauss_many`, the contact integrals' divided differences
//! `contact::Grid::newton`, a layer stack's per-node kernels `layer::stack::StackCache`, where
//! the 2×2 algebra gains from AVX's three-operand forms, the sliding tail's θ-panels
//! `tail::Polar::panel`): each loop body is an `#[inline(always)]` function, compiled once as is
//! and once inside a `#[target_feature(enable = "avx2")]` wrapper, and [`with_avx2!`] calls the
//! wrapper where the CPU has AVX2. The same operations run in both (no fused multiply-adds are
//! formed), so both give the same values to the last bit (tested at each site); the AVX2 build
//! has four lanes instead of two.

/// `return $avx2` (an expression calling the AVX2 wrapper) when the CPU has AVX2, else evaluate
/// `$baseline`. The crate's one `unsafe`: the wrapper may only run where AVX2 exists, which is
/// checked right before the call.
macro_rules! with_avx2 {
    ($avx2:expr, $baseline:expr) => {{
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2, checked just above.
            return unsafe { $avx2 };
        }
        $baseline
    }};
}

pub(crate) use with_avx2;
