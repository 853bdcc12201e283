//! What each integrator costs per evaluation of the accelerations, beside
//! the floor: a bare loop of the generated `accelerations` (semi-implicit
//! Euler over the same span in steps four times smaller than RK4's: one call
//! and four flops per coordinate per iteration, along a trajectory close to
//! the integrators').
//!
//! The compiler inlines the generated `accelerations` into the floor's
//! loop; one more caller of the same system's `accelerations` in this file
//! has left it out of line, and the floor a fifth slower on the planar
//! chain of 12 (BENCHMARKS.md): keep the file's calls as they are.
//!
//! Systems: seed example 1 (the chaotic double pendulum of
//! `tests/reference/chaotic_double_pendulum.json`, θ₁ = θ₂ = 2 rad at rest)
//! and the planar chain of 12 links (every angle 0.3 rad at rest). Each
//! benchmark runs one whole integration per iteration and reports the time
//! **per right-hand-side evaluation** (the run's time divided by its
//! evaluation count), so every line compares directly with the floor.
//!
//! Group `throughput` times fixed-step RK4 at `h = 1 ms` (MuJoCo's step in
//! the peers' harness) on the planar and spatial chains, n = 2, 6, 12, 30,
//! **per step**, for the simulated seconds per CPU second against MuJoCo's
//! `mj_step` with its RK4 integrator.
//!
//! Run with `cargo bench -p dalembert-generated --bench integrators`; see
//! BENCHMARKS.md.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use dalembert::MultibodySystem;
use dalembert::integrate::{
    Adaptive, AdaptiveOptions, ExplicitPair, Gauss, GaussLegendre, Integration, Rk4, Solution,
    State, Unconstrained,
};
use dalembert_fixtures::cpu_time::thread_time;
use dalembert_generated::{
    DoublePendulum, PlanarChain2, PlanarChain6, PlanarChain12, PlanarChain30, SpatialChain2,
    SpatialChain6, SpatialChain12, SpatialChain30,
};

/// Simulated time of every run, s.
const DURATION: f64 = 10.0;
/// Fixed steps of RK4 and Gauss–Legendre over [`DURATION`].
const STEPS: u64 = 10_000;
/// Tolerance of the adaptive runs.
const TOLERANCE: f64 = 1e-12;

/// `iters` runs of `run`, timed in thread CPU time, divided by the count one
/// run returns (its evaluations, or its steps).
fn per_count(iters: u64, mut run: impl FnMut() -> u64) -> Duration {
    let mut elapsed = Duration::ZERO;
    let mut evaluations = 1;
    for _ in 0..iters {
        let start = thread_time();
        evaluations = black_box(run());
        elapsed += thread_time() - start;
    }
    elapsed / u32::try_from(evaluations).expect("fewer than 2³² evaluations")
}

/// The evaluations an integration made.
fn evaluations<const N: usize>(solution: Solution<N, N>) -> u64 {
    solution.statistics.rhs_evaluations
}

/// The per-evaluation benchmarks of one system from rest at `angles`.
fn bench_system<S: MultibodySystem<N, N, 0>, const N: usize>(
    c: &mut Criterion,
    name: &str,
    system: S,
    angles: [f64; N],
) {
    let initial = State {
        t: 0.0,
        q: angles,
        v: [0.0; N],
    };
    let system = &system;
    let dynamics = Unconstrained::without_inputs(system);
    let mut group = c.benchmark_group(format!("integrators/{name}"));
    group.bench_function("floor: bare accelerations loop", |b| {
        b.iter_custom(|iters| {
            per_count(iters, || {
                let h = DURATION / (4 * STEPS) as f64;
                let (mut q, mut v) = (initial.q, initial.v);
                for k in 0..4 * STEPS {
                    let a = dalembert::accelerations(black_box(system), k as f64 * h, &q, &v, &[])
                        .expect("regular");
                    for i in 0..N {
                        v[i] += h * a[i];
                        q[i] += h * v[i];
                    }
                }
                black_box((q, v));
                4 * STEPS
            })
        })
    });
    group.bench_function("rk4", |b| {
        b.iter_custom(|iters| {
            per_count(iters, || {
                evaluations(
                    Integration::new(&dynamics, initial, DURATION, Rk4 { steps: STEPS })
                        .run()
                        .unwrap(),
                )
            })
        })
    });
    for (label, pair) in [
        ("dopri5", ExplicitPair::DormandPrince54),
        ("dop853", ExplicitPair::Dop853),
    ] {
        group.bench_function(label, |b| {
            let options = AdaptiveOptions::with_tolerance(TOLERANCE);
            b.iter_custom(|iters| {
                per_count(iters, || {
                    evaluations(
                        Integration::new(&dynamics, initial, DURATION, Adaptive { pair, options })
                            .run()
                            .unwrap(),
                    )
                })
            })
        });
    }
    group.bench_function("gauss4", |b| {
        b.iter_custom(|iters| {
            per_count(iters, || {
                let method = GaussLegendre::Order4;
                evaluations(
                    Integration::new(
                        &dynamics,
                        initial,
                        DURATION,
                        Gauss {
                            rule: method,
                            steps: STEPS,
                        },
                    )
                    .run()
                    .unwrap(),
                )
            })
        })
    });
    group.finish();
}

/// Steps of each throughput run (one simulated second at `h = 1 ms`).
const THROUGHPUT_STEPS: u64 = 1_000;

/// RK4 at `h = 1 ms` on one chain from rest at 0.3 rad, time per step.
fn bench_throughput<S: MultibodySystem<N, N, 0>, const N: usize>(
    c: &mut Criterion,
    family: &str,
    system: S,
) {
    let initial = State {
        t: 0.0,
        q: [0.3; N],
        v: [0.0; N],
    };
    let system = &system;
    let dynamics = Unconstrained::without_inputs(system);
    let duration = THROUGHPUT_STEPS as f64 * 1e-3;
    c.bench_function(&format!("throughput/rk4_1ms/{family}/{N}"), |b| {
        b.iter_custom(|iters| {
            per_count(iters, || {
                let run = Integration::new(
                    &dynamics,
                    initial,
                    duration,
                    Rk4 {
                        steps: THROUGHPUT_STEPS,
                    },
                )
                .run();
                evaluations(run.unwrap()) / 4
            })
        })
    });
}

fn throughput(c: &mut Criterion) {
    bench_throughput(c, "planar", PlanarChain2 {});
    bench_throughput(c, "planar", PlanarChain6 {});
    bench_throughput(c, "planar", PlanarChain12 {});
    bench_throughput(c, "planar", PlanarChain30 {});
    bench_throughput(c, "spatial", SpatialChain2 {});
    bench_throughput(c, "spatial", SpatialChain6 {});
    bench_throughput(c, "spatial", SpatialChain12 {});
    bench_throughput(c, "spatial", SpatialChain30 {});
}

fn integrators(c: &mut Criterion) {
    let pendulum = DoublePendulum {
        m: 1.0,
        L: 1.0,
        g: 9.81,
    };
    bench_system(c, "seed_1", pendulum, [2.0, 2.0]);
    bench_system(c, "planar_12", PlanarChain12 {}, [0.3; 12]);
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = integrators, throughput
}
criterion_main!(benches);
