//! Per-call cost of the exact derivatives against the forward dynamics: the
//! generated `accelerations_jacobian` (∂v̇/∂q, ∂v̇/∂v, ∂v̇/∂u) and
//! `accelerations` of the chains (n = 2, 6, 12, both families) and of the
//! panda and ur5 robots and of a branching tree of 14 links, from
//! `dalembert_generated::derivatives`. Same
//! method as `chains.rs`: 1000 fixed pseudo-random states, one call per
//! iteration.
//!
//! Run with `cargo bench -p dalembert-generated --bench derivatives`; see
//! BENCHMARKS.md.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use dalembert::MultibodySystem;
use dalembert_generated::derivatives::*;

use dalembert_fixtures::states::{per_call, states};

/// `accelerations` and `accelerations_jacobian` of one system, in group
/// `derivatives/NAME`.
#[allow(clippy::type_complexity)]
fn bench_system<S: MultibodySystem<N, N, NU>, R, const N: usize, const NU: usize>(
    c: &mut Criterion,
    name: &str,
    system: S,
    jacobian: fn(&S, f64, &[f64; N], &[f64; N], &[f64; NU]) -> R,
) {
    let states = states::<N, NU>(N as u64);
    // Every state must be solvable (both functions factorise the same `M`),
    // or the calls would time an early return.
    for s in &states {
        dalembert::accelerations(&system, s.t, &s.q, &s.v, &s.u).expect("solvable state");
    }
    let mut group = c.benchmark_group(format!("derivatives/{name}"));
    group.bench_function("accelerations", |b| {
        b.iter_custom(|iters| {
            per_call(&states, iters, |s| {
                dalembert::accelerations(black_box(&system), s.t, &s.q, &s.v, &s.u)
            })
        })
    });
    group.bench_function("accelerations_jacobian", |b| {
        b.iter_custom(|iters| {
            per_call(&states, iters, |s| {
                jacobian(black_box(&system), s.t, &s.q, &s.v, &s.u)
            })
        })
    });
    group.finish();
}

fn derivatives(c: &mut Criterion) {
    /// Benchmarks every listed system (by its module in `derivatives`).
    macro_rules! bench {
        ($($module:ident :: $system:ident),* $(,)?) => {$(
            bench_system(
                c,
                stringify!($module),
                $module::$system {},
                $module::$system::accelerations_jacobian,
            );
        )*};
    }
    dalembert_generated::chains_and_robots_with_derivatives!(bench);
    bench!(spatial_tree_14::SpatialTree14);
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = derivatives
}
criterion_main!(benches);
