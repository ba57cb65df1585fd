//! Alternating-pair timing shared by the ratio benchmarks (`bench_sliding`,
//! `bench_stack_check`; included with `#[path = "common/pairs.rs"]`): two jobs run in turn, so
//! that drift and load from other processes fall on both.

use std::time::Instant;

/// Wall times in µs of `a` and `b` run in alternating pairs: `warm_up` pairs first, not kept,
/// then the `reps` pairs returned.
pub fn alternating(
    warm_up: usize,
    reps: usize,
    mut a: impl FnMut(),
    mut b: impl FnMut(),
) -> Vec<(f64, f64)> {
    let time = |f: &mut dyn FnMut()| {
        let t = Instant::now();
        f();
        t.elapsed().as_secs_f64() * 1e6
    };
    let mut pairs = Vec::with_capacity(reps);
    for i in 0..warm_up + reps {
        let pair = (time(&mut a), time(&mut b));
        if i >= warm_up {
            pairs.push(pair);
        }
    }
    pairs
}

/// The median of `v` (the upper middle value of an even count).
pub fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}
