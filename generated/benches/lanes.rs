//! Four states at once against one: the generated `accelerations_x4`
//! (`outputs accelerations_x4;`, one state in each lane of a `wide::f64x4`)
//! against the scalar `accelerations`, per state, on the spatial chains of
//! n = 6, 12, 30 (the unrolled factorisation at 6 and 12, the
//! articulated-body recursion at 30), the panda and Solo-12 on a free joint,
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
//! state: `dalembert::integrate::Rk4::step` against the same four stages
//! written over `accelerations_x4` for four states at once (`rk4_x4`
//! below), the figure to set beside MuJoCo's `mj_step` with its RK4.
//!
//! Run with `cargo bench -p dalembert-generated --bench lanes` (and with
//! `RUSTFLAGS="-C target-cpu=x86-64-v3"` for AVX2 and FMA);
//! `scripts/bench/lanes.sh` prints the table.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
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

/// `a + h b`, entry by entry, for each of four states.
fn step<const N: usize>(a: &[[f64; N]; 4], h: f64, b: &[[f64; N]; 4]) -> [[f64; N]; 4] {
    std::array::from_fn(|k| std::array::from_fn(|i| a[k][i] + h * b[k][i]))
}

/// The accelerations of four states, a failed state's as zeros (the bench's
/// states all solve).
fn accelerations_x4<S: MultibodySystem<N, N, 0>, const N: usize>(
    system: &S,
    t: [f64; 4],
    q: &[[f64; N]; 4],
    v: &[[f64; N]; 4],
) -> [[f64; N]; 4] {
    system
        .accelerations_x4(t, q, v, &[[]; 4])
        .map(|a| a.unwrap_or([0.0; N]))
}

/// One classical RK4 step of length `h` of four states of a system whose
/// speeds are its coordinates' rates, the stages through `accelerations_x4`.
fn rk4_x4<S: MultibodySystem<N, N, 0>, const N: usize>(
    system: &S,
    h: f64,
    (t, q, v): ([f64; 4], &[[f64; N]; 4], &[[f64; N]; 4]),
) -> ([[f64; N]; 4], [[f64; N]; 4]) {
    let at = |fraction: f64| t.map(|t| t + fraction * h);
    let a1 = accelerations_x4(system, t, q, v);
    let (q2, v2) = (step(q, h / 2.0, v), step(v, h / 2.0, &a1));
    let a2 = accelerations_x4(system, at(0.5), &q2, &v2);
    let (q3, v3) = (step(q, h / 2.0, &v2), step(v, h / 2.0, &a2));
    let a3 = accelerations_x4(system, at(0.5), &q3, &v3);
    let (q4, v4) = (step(q, h, &v3), step(v, h, &a3));
    let a4 = accelerations_x4(system, at(1.0), &q4, &v4);
    let sum = |a: &[[f64; N]; 4], b: &[[f64; N]; 4], c: &[[f64; N]; 4], d: &[[f64; N]; 4]| {
        std::array::from_fn(|k| {
            std::array::from_fn(|i| a[k][i] + 2.0 * (b[k][i] + c[k][i]) + d[k][i])
        })
    };
    (
        step(q, h / 6.0, &sum(v, &v2, &v3, &v4)),
        step(v, h / 6.0, &sum(&a1, &a2, &a3, &a4)),
    )
}

/// One RK4 step of 1 ms, one state a call and four a call (per state), in
/// group `lanes/NAME`.
fn bench_rk4<S: MultibodySystem<N, N, 0>, const N: usize>(
    c: &mut Criterion,
    name: &str,
    system: S,
) {
    let batches = batches(&system);
    let states: Vec<_> = batches
        .iter()
        .flat_map(|(t, q, v, _)| {
            (0..4).map(move |k| State {
                t: t[k],
                q: q[k],
                v: v[k],
            })
        })
        .collect();
    let dynamics = Unconstrained::without_inputs(&system);
    let h = 1e-3;
    let mut group = c.benchmark_group(format!("lanes/{name}"));
    group.bench_function("rk4 step", |b| {
        b.iter_custom(|iters| per_call(&states, iters, |s| Rk4::step(black_box(&dynamics), s, h)))
    });
    group.bench_function("rk4 step x4 per state", |b| {
        b.iter_custom(|iters| {
            per_call(&batches, iters.div_ceil(4), |(t, q, v, _)| {
                rk4_x4(black_box(&system), h, (*t, q, v))
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
