//! Four states at once against one: the generated `accelerations_x4`
//! (`outputs accelerations_x4;`, one state in each lane of a `wide::f64x4`)
//! against the scalar `accelerations`, per state, on the spatial chains of
//! n = 6, 12, 30 (the scalar call factorises at 6 and 12, the lanes at 6
//! only: the chain of 12 is on the articulated-body recursion over lanes),
//! the panda and Solo-12 on a free joint,
//! from `dalembert_generated::lanes`. Same method as `chains.rs`: 1000
//! fixed pseudo-random states in batches of four, thread CPU time; the
//! batched figure is per state (a call's time over four).
//!
//! The same states through `accelerations_jacobian` of the spatial chain
//! of 12, the panda and the floating Solo-12 (`dalembert_generated::derivatives`),
//! one state a call: its solve `−M⁻¹ ∂τ/∂x` runs over the `2 NV + NU`
//! columns of each row (`dalembert::__private::scale_and_subtract`).
//!
//! And one fixed RK4 step (h = 1 ms) of the spatial chain of 12, per
//! state: `dalembert::integrate::Rk4::step` against
//! `dalembert::control::rk4_group_step_x4` (the same four stages, over
//! `accelerations_x4`, for four states at once), the figure to set beside
//! MuJoCo's `mj_step` with its RK4.
//!
//! Run with `cargo bench -p dalembert-generated --bench lanes` (and with
//! `RUSTFLAGS="-C target-cpu=x86-64-v3"` for AVX2 and FMA);
//! `scripts/bench/lanes.sh` prints the table.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use dalembert::control::rk4_group_step_x4;
use dalembert::integrate::Rk4;
use dalembert::{DynamicsError, MultibodySystem, State, Unconstrained};
use dalembert_codegen::testing::Random;
use dalembert_fixtures::states::{STATES, per_call};
use dalembert_generated::lanes::*;

/// Four states: times, coordinates, speeds, inputs.
type Batch<const NQ: usize, const NV: usize, const NU: usize> =
    ([f64; 4], [[f64; NQ]; 4], [[f64; NV]; 4], [[f64; NU]; 4]);

/// `STATES / 4` batches: angles in `[−π, π)` (quaternions normalised),
/// speeds in `[−3, 3)`, inputs in `[−2, 2)`, time in `[0, 10)`.
fn batches<S: MultibodySystem<NQ, NV, NU>, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
) -> Vec<Batch<NQ, NV, NU>> {
    let mut random = Random::new(NV as u64);
    let pi = std::f64::consts::PI;
    let mut one = |_| {
        let q = std::array::from_fn(|_| random.uniform(-pi, pi));
        (
            random.uniform(0.0, 10.0),
            system.integrate_configuration(&q, &[0.0; NV], 0.0),
            std::array::from_fn(|_| random.uniform(-3.0, 3.0)),
            std::array::from_fn(|_| random.uniform(-2.0, 2.0)),
        )
    };
    (0..STATES / 4)
        .map(|_| {
            let [a, b, c, d] = std::array::from_fn(&mut one);
            (
                [a.0, b.0, c.0, d.0],
                [a.1, b.1, c.1, d.1],
                [a.2, b.2, c.2, d.2],
                [a.3, b.3, c.3, d.3],
            )
        })
        .collect()
}

/// The states of `batches`, one by one.
#[allow(clippy::type_complexity)]
fn singles<const NQ: usize, const NV: usize, const NU: usize>(
    batches: &[Batch<NQ, NV, NU>],
) -> Vec<(f64, [f64; NQ], [f64; NV], [f64; NU])> {
    batches
        .iter()
        .flat_map(|(t, q, v, u)| (0..4).map(move |k| (t[k], q[k], v[k], u[k])))
        .collect()
}

/// The batched call of a system.
type X4<S, const NQ: usize, const NV: usize, const NU: usize> =
    fn(
        &S,
        [f64; 4],
        &[[f64; NQ]; 4],
        &[[f64; NV]; 4],
        &[[f64; NU]; 4],
    ) -> [Result<[f64; NV], DynamicsError>; 4];

/// The jacobian of a system.
type Jacobian<S, const NQ: usize, const NV: usize, const NU: usize> =
    fn(&S, f64, &[f64; NQ], &[f64; NV], &[f64; NU]) -> Result<JacobianValue<NV, NU>, DynamicsError>;

/// `(∂v̇/∂q, ∂v̇/∂v, ∂v̇/∂u)`.
type JacobianValue<const NV: usize, const NU: usize> =
    ([[f64; NV]; NV], [[f64; NV]; NV], [[f64; NU]; NV]);

/// `accelerations_jacobian`, one state a call, in group `lanes/NAME`.
fn bench_jacobian<S, const NQ: usize, const NV: usize, const NU: usize>(
    c: &mut Criterion,
    name: &str,
    system: S,
    jacobian: Jacobian<S, NQ, NV, NU>,
) where
    S: MultibodySystem<NQ, NV, NU>,
{
    let states = singles(&batches(&system));
    let mut group = c.benchmark_group(format!("lanes/{name}"));
    group.bench_function("accelerations_jacobian", |b| {
        b.iter_custom(|iters| {
            per_call(&states, iters, |(t, q, v, u)| {
                jacobian(black_box(&system), *t, q, v, u)
            })
        })
    });
    group.finish();
}

/// `accelerations` (one state a call) and `accelerations_x4` (four a call,
/// its time divided by four), per state, in group `lanes/NAME`.
fn bench_system<S, const NQ: usize, const NV: usize, const NU: usize>(
    c: &mut Criterion,
    name: &str,
    system: S,
    x4: X4<S, NQ, NV, NU>,
) where
    S: MultibodySystem<NQ, NV, NU>,
{
    let batches = batches(&system);
    // Every state must be solvable, or the calls would time an early return.
    for (t, q, v, u) in &batches {
        for k in 0..4 {
            dalembert::accelerations(&system, t[k], &q[k], &v[k], &u[k]).expect("solvable state");
        }
    }
    let states = singles(&batches);
    let mut group = c.benchmark_group(format!("lanes/{name}"));
    group.bench_function("accelerations", |b| {
        b.iter_custom(|iters| {
            per_call(&states, iters, |(t, q, v, u)| {
                dalembert::accelerations(black_box(&system), *t, q, v, u)
            })
        })
    });
    group.bench_function("accelerations_x4 per state", |b| {
        b.iter_custom(|iters| {
            // `iters` states, four a call: criterion divides by `iters`.
            let calls = iters.div_ceil(4);
            per_call(&batches, calls, |(t, q, v, u)| {
                x4(black_box(&system), *t, q, v, u)
            })
        })
    });
    group.finish();
}

/// One RK4 step of 1 ms, one state a call and four a call (per state), in
/// group `lanes/NAME`.
fn bench_rk4<S: MultibodySystem<N, N, 0>, const N: usize>(
    c: &mut Criterion,
    name: &str,
    system: S,
) {
    let quads: Vec<[State<N, N>; 4]> = batches(&system)
        .iter()
        .map(|(t, q, v, _)| {
            std::array::from_fn(|k| State {
                t: t[k],
                q: q[k],
                v: v[k],
            })
        })
        .collect();
    let states: Vec<State<N, N>> = quads.iter().flatten().copied().collect();
    let dynamics = Unconstrained::without_inputs(&system);
    let h = 1e-3;
    let mut group = c.benchmark_group(format!("lanes/{name}"));
    group.bench_function("rk4 step", |b| {
        b.iter_custom(|iters| per_call(&states, iters, |s| Rk4::step(black_box(&dynamics), s, h)))
    });
    group.bench_function("rk4 step x4 per state", |b| {
        b.iter_custom(|iters| {
            per_call(&quads, iters.div_ceil(4), |quad| {
                rk4_group_step_x4(black_box(&system), quad, &[[]; 4], h)
            })
        })
    });
    group.finish();
}

fn lanes(c: &mut Criterion) {
    /// Benchmarks every listed system (by its module in `lanes`).
    macro_rules! bench {
        ($($module:ident :: $system:ident),* $(,)?) => {$(
            bench_system(c, stringify!($module), $module::$system {}, $module::$system::accelerations_x4);
        )*};
    }
    bench!(
        spatial_chain_06::SpatialChain6,
        spatial_chain_12::SpatialChain12,
        spatial_chain_30::SpatialChain30,
        panda::Panda,
        floating_solo12::FloatingSolo,
    );
    /// Benchmarks the jacobian of every listed system (by its module in
    /// `derivatives`).
    macro_rules! jacobian {
        ($($module:ident :: $system:ident),* $(,)?) => {$(
            bench_jacobian(
                c,
                stringify!($module),
                dalembert_generated::derivatives::$module::$system {},
                dalembert_generated::derivatives::$module::$system::accelerations_jacobian,
            );
        )*};
    }
    bench_rk4(c, "spatial_chain_12", spatial_chain_12::SpatialChain12 {});
    jacobian!(
        spatial_chain_12::SpatialChain12,
        panda::Panda,
        floating_solo12::FloatingSolo,
    );
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = lanes
}
criterion_main!(benches);
