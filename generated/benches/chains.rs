//! Per-call cost of the generated equations of the benchmark chains,
//! both families, n = 1, 2, 4, 6, 12, 30 (and 60 with the `large`
//! feature): `mass_matrix` + `forcing` (the counterpart of Pinocchio's
//! `crba` + `nonLinearEffects`), the generated `accelerations` method
//! (unrolled `L D Lᵀ` or articulated-body recursion, the counterpart of
//! `aba`) and the runtime's generic `dalembert::__private::cholesky_accelerations` (nalgebra's
//! Cholesky). Same method as
//! `benches/seed_examples.rs` (shared in `dalembert_fixtures::states`): 1000 fixed
//! pseudo-random states, one call per iteration.
//!
//! Run with `cargo bench -p dalembert-generated --bench chains [--features large]`; see
//! BENCHMARKS.md.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use dalembert::{DynamicsError, MultibodySystem};
use dalembert_generated::*;

use dalembert_fixtures::states::{mass_matrix_and_forcing, per_call, states};

/// The generated `accelerations` method of a system.
type Accelerations<S, const N: usize> =
    fn(&S, f64, &[f64; N], &[f64; N], &[f64; 0]) -> Result<[f64; N], DynamicsError>;

/// The three per-call benchmarks of one chain, in group `FAMILY/n`.
fn bench_chain<S: MultibodySystem<N, N, 0>, const N: usize>(
    c: &mut Criterion,
    family: &str,
    system: S,
    unrolled: Accelerations<S, N>,
) {
    let states = states::<N, 0>(N as u64);
    // Every state must be solvable, or `accelerations` would time an early return.
    for s in &states {
        dalembert::__private::cholesky_accelerations(&system, s.t, &s.q, &s.v, &s.u)
            .expect("solvable state");
    }
    let mut group = c.benchmark_group(format!("{family}/{N}"));
    group.bench_function("mass_matrix+forcing", |b| {
        b.iter_custom(|iters| {
            per_call(&states, iters, |s| {
                mass_matrix_and_forcing(black_box(&system), s)
            })
        })
    });
    group.bench_function("accelerations", |b| {
        b.iter_custom(|iters| {
            per_call(&states, iters, |s| {
                unrolled(black_box(&system), s.t, &s.q, &s.v, &s.u)
            })
        })
    });
    group.bench_function("dalembert::__private::cholesky_accelerations", |b| {
        b.iter_custom(|iters| {
            per_call(&states, iters, |s| {
                dalembert::__private::cholesky_accelerations(
                    black_box(&system),
                    s.t,
                    &s.q,
                    &s.v,
                    &s.u,
                )
            })
        })
    });
    group.finish();
}

fn planar(c: &mut Criterion) {
    bench_chain(c, "planar", PlanarChain1 {}, PlanarChain1::accelerations);
    bench_chain(c, "planar", PlanarChain2 {}, PlanarChain2::accelerations);
    bench_chain(c, "planar", PlanarChain4 {}, PlanarChain4::accelerations);
    bench_chain(c, "planar", PlanarChain6 {}, PlanarChain6::accelerations);
    bench_chain(c, "planar", PlanarChain12 {}, PlanarChain12::accelerations);
    bench_chain(c, "planar", PlanarChain30 {}, PlanarChain30::accelerations);
    #[cfg(feature = "large")]
    bench_chain(c, "planar", PlanarChain60 {}, PlanarChain60::accelerations);
}

fn spatial(c: &mut Criterion) {
    bench_chain(c, "spatial", SpatialChain1 {}, SpatialChain1::accelerations);
    bench_chain(c, "spatial", SpatialChain2 {}, SpatialChain2::accelerations);
    bench_chain(c, "spatial", SpatialChain4 {}, SpatialChain4::accelerations);
    bench_chain(c, "spatial", SpatialChain6 {}, SpatialChain6::accelerations);
    bench_chain(
        c,
        "spatial",
        SpatialChain12 {},
        SpatialChain12::accelerations,
    );
    bench_chain(
        c,
        "spatial",
        SpatialChain30 {},
        SpatialChain30::accelerations,
    );
    #[cfg(feature = "large")]
    bench_chain(
        c,
        "spatial",
        SpatialChain60 {},
        SpatialChain60::accelerations,
    );
}

/// The loop alone: subtract it for the cost of the function by itself.
fn harness_overhead(c: &mut Criterion) {
    let states = states::<2, 0>(3);
    c.bench_function("chains_harness_overhead", |b| {
        b.iter_custom(|iters| per_call(&states, iters, |s| s.q[0]))
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2));
    targets = planar, spatial, harness_overhead
}
criterion_main!(benches);
