//! Unrolled against looped, per call: the generated, fully unrolled
//! `accelerations` (`unrolled`), and `mass_matrix` + `forcing`
//! (`unrolled M+f`), of the benchmark chains against the looped form of the
//! same dynamics (`dalembert_fixtures::looped`: the articulated-body,
//! composite-rigid-body and Newton–Euler algorithms as loops over a table of
//! per-link constants; `looped`, `looped M+f`), both families, n = 6, 12,
//! 30 (and 60 with the `large` feature). Each chain is one group,
//! `forms/FAMILY/n`, whose functions run one after the other, in the same
//! window of a shared machine. Same method as `chains.rs` (`dalembert_fixtures::states`):
//! 1000 fixed pseudo-random states, one call per iteration, thread CPU time.
//!
//! Run with `cargo bench -p dalembert-generated --features large --bench
//! looped -- --save-baseline NAME`, a few times, and tabulate the rounds with
//! `python3 benches/looped_table.py NAME...`; see BENCHMARKS.md.

use std::hint::black_box;
use std::time::Duration;

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, criterion_group, criterion_main};
use dalembert::{DynamicsError, MultibodySystem};
use dalembert_codegen::chain::{Family, chain};
use dalembert_fixtures::looped::Chain;
use dalembert_fixtures::states::{mass_matrix_and_forcing, per_call, states};
use dalembert_generated::*;

/// The generated `accelerations` method of a system.
type Accelerations<S, const N: usize> =
    fn(&S, f64, &[f64; N], &[f64; N], &[f64; 0]) -> Result<[f64; N], DynamicsError>;

/// The two forms of one chain, in group `forms/FAMILY/n`.
fn bench_chain<S: MultibodySystem<N, N, 0>, const N: usize>(
    c: &mut Criterion,
    family: Family,
    system: S,
    unrolled: Accelerations<S, N>,
) {
    let states = states::<N, 0>(N as u64);
    let looped = Chain::<N>::of_model(&chain(family, N));
    let mut group = c.benchmark_group(format!("forms/{}/{N}", family.name()));
    time(&mut group, "unrolled", &states, |s| {
        unrolled(black_box(&system), s.t, &s.q, &s.v, &s.u)
    });
    time(&mut group, "looped", &states, |s| {
        black_box(&looped).accelerations(&s.q, &s.v)
    });
    time(&mut group, "unrolled M+f", &states, |s| {
        mass_matrix_and_forcing(black_box(&system), s)
    });
    time(&mut group, "looped M+f", &states, |s| {
        let looped = black_box(&looped);
        (looped.mass_matrix(&s.q), looped.forcing(&s.q, &s.v))
    });
    group.finish();
}

/// Times `call`, one state per call, as `name` in `group`.
fn time<T, R>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    states: &[T],
    mut call: impl FnMut(&T) -> R,
) {
    group.bench_function(name, |b| {
        b.iter_custom(|iters| per_call(states, iters, &mut call))
    });
}

/// Every chain, the spatial family first.
fn chains(c: &mut Criterion) {
    let (planar, spatial) = (Family::Planar, Family::Spatial);
    bench_chain(c, spatial, SpatialChain6 {}, SpatialChain6::accelerations);
    bench_chain(c, spatial, SpatialChain12 {}, SpatialChain12::accelerations);
    bench_chain(c, spatial, SpatialChain30 {}, SpatialChain30::accelerations);
    #[cfg(feature = "large")]
    bench_chain(c, spatial, SpatialChain60 {}, SpatialChain60::accelerations);
    bench_chain(c, planar, PlanarChain6 {}, PlanarChain6::accelerations);
    bench_chain(c, planar, PlanarChain12 {}, PlanarChain12::accelerations);
    bench_chain(c, planar, PlanarChain30 {}, PlanarChain30::accelerations);
    #[cfg(feature = "large")]
    bench_chain(c, planar, PlanarChain60 {}, PlanarChain60::accelerations);
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2));
    targets = chains
}
criterion_main!(benches);
