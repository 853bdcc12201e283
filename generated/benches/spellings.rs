//! Per-call cost of the benchmark chains in their three spellings (`joint`s
//! with literals, `joint`s with symbolic parameters, the seed's frames and
//! points with torque inputs), both families, n = 2, 6, 12, 30:
//! `mass_matrix` + `forcing` (the counterpart of Pinocchio's `crba` +
//! `nonLinearEffects`) and the generated `accelerations` (the counterpart
//! of `aba`). Same method as `chains.rs` (`dalembert_fixtures::states`): 1000 fixed pseudo-random states,
//! one call per iteration.
//!
//! Run with `cargo bench -p dalembert-generated --bench spellings`; see
//! BENCHMARKS.md.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use dalembert_generated::*;

use dalembert_fixtures::states::{mass_matrix_and_forcing, per_call, states};

/// The two benchmarks of one system, in group `FAMILY/SPELLING/n`.
macro_rules! bench {
    ($c:expr, $family:literal, $spelling:literal, $n:literal, $nu:literal, $system:expr) => {{
        let system = $system;
        let states = states::<$n, $nu>($n as u64);
        let mut group = $c.benchmark_group(format!("{}/{}/{}", $family, $spelling, $n));
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
                    black_box(&system).accelerations(s.t, &s.q, &s.v, &s.u)
                })
            })
        });
        group.finish();
    }};
}

/// Every spelling of the chains of `n` links of both families.
macro_rules! sizes {
    ($c:expr, $($n:literal: $planar:ident, $symbolic_planar:ident, $seed_planar:ident,
        $spatial:ident, $symbolic_spatial:ident, $seed_spatial:ident;)+) => {$(
        bench!($c, "planar", "joints", $n, 0, $planar {});
        bench!($c, "planar", "symbolic", $n, 0, $symbolic_planar::reference());
        bench!($c, "planar", "seed", $n, $n, $seed_planar::reference());
        bench!($c, "spatial", "joints", $n, 0, $spatial {});
        bench!($c, "spatial", "symbolic", $n, 0, $symbolic_spatial::reference());
        bench!($c, "spatial", "seed", $n, $n, $seed_spatial::reference());
    )+};
}

fn spellings(c: &mut Criterion) {
    sizes!(c,
        2: PlanarChain2, SymbolicPlanarChain2, SeedPlanarChain2,
           SpatialChain2, SymbolicSpatialChain2, SeedSpatialChain2;
        6: PlanarChain6, SymbolicPlanarChain6, SeedPlanarChain6,
           SpatialChain6, SymbolicSpatialChain6, SeedSpatialChain6;
        12: PlanarChain12, SymbolicPlanarChain12, SeedPlanarChain12,
           SpatialChain12, SymbolicSpatialChain12, SeedSpatialChain12;
        30: PlanarChain30, SymbolicPlanarChain30, SeedPlanarChain30,
           SpatialChain30, SymbolicSpatialChain30, SeedSpatialChain30;
    );
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2));
    targets = spellings
}
criterion_main!(benches);
