//! Per-call cost of the adjoint `λᵀ ∂v̇/∂(q, v, u)` against forming the
//! jacobian, on the spatial chains of 6, 12, 30 and 60 links (30 and 60
//! with the `large` feature): `inverse_dynamics_adjoint` (the generated
//! reverse sweep alone), `accelerations_adjoint` (`accelerations`, one
//! solve with `M`, the sweep) and `accelerations_jacobian` followed by the
//! product `λᵀ J` (what the adjoint replaces). Same method as
//! `derivatives.rs`: 1000 fixed pseudo-random states, one call per
//! iteration.
//!
//! Run with `cargo bench -p dalembert-generated --bench adjoint --features
//! large`; `scripts/bench/adjoint.sh` prints the table.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use dalembert::control::adjoint::InverseDynamicsAdjoint;
use dalembert::control::{AccelerationsJacobian, Differentiated, accelerations_adjoint};
use dalembert::{DynamicsError, MultibodySystem};
use dalembert_generated::derivatives::*;

use dalembert_fixtures::states::{per_call, states};

/// A generated `accelerations_jacobian`.
type Jacobian<S, const N: usize> = fn(
    &S,
    f64,
    &[f64; N],
    &[f64; N],
    &[f64; 0],
) -> Result<AccelerationsJacobian<N, 0>, DynamicsError>;

/// A generated `inverse_dynamics_adjoint`.
type Sweep<S, const N: usize> = fn(
    &S,
    f64,
    &[f64; N],
    &[f64; N],
    &[f64; N],
    &[f64; 0],
    &[f64; N],
) -> InverseDynamicsAdjoint<N, 0>;

/// The three routes of one chain of `N` links, in group `adjoint/N`.
fn bench_chain<S: MultibodySystem<N, N, 0>, const N: usize>(
    c: &mut Criterion,
    system: &S,
    (jacobian, sweep): (Jacobian<S, N>, Sweep<S, N>),
) {
    let states = states::<N, 0>(N as u64);
    let lambda: [f64; N] = std::array::from_fn(|i| 1.0 / (1.0 + i as f64));
    let differentiated = Differentiated::new(system, jacobian).with_inverse(sweep);
    // Every state must be solvable, or the calls would time an early return.
    for s in &states {
        accelerations_adjoint(&differentiated, s.t, &s.q, &s.v, &s.u, &lambda)
            .expect("solvable state");
    }
    let mut group = c.benchmark_group(format!("adjoint/{N}"));
    group.bench_function("inverse_dynamics_adjoint", |b| {
        b.iter_custom(|iters| {
            per_call(&states, iters, |s| {
                sweep(black_box(system), s.t, &s.q, &s.v, &s.v, &s.u, &lambda)
            })
        })
    });
    group.bench_function("accelerations_adjoint", |b| {
        b.iter_custom(|iters| {
            per_call(&states, iters, |s| {
                accelerations_adjoint(black_box(&differentiated), s.t, &s.q, &s.v, &s.u, &lambda)
            })
        })
    });
    group.bench_function("accelerations_jacobian_product", |b| {
        b.iter_custom(|iters| {
            per_call(&states, iters, |s| {
                let (by_q, by_v, _) = jacobian(black_box(system), s.t, &s.q, &s.v, &s.u)?;
                let product = |m: &[[f64; N]; N]| -> [f64; N] {
                    std::array::from_fn(|j| (0..N).map(|i| lambda[i] * m[i][j]).sum())
                };
                Ok::<_, DynamicsError>((product(&by_q), product(&by_v)))
            })
        })
    });
    group.finish();
}

fn adjoint(c: &mut Criterion) {
    /// Benchmarks every listed chain (by its module in `derivatives`).
    macro_rules! bench {
        ($($module:ident :: $system:ident),* $(,)?) => {$(
            bench_chain(
                c,
                &$module::$system {},
                ($module::$system::accelerations_jacobian, $module::$system::inverse_dynamics_adjoint),
            );
        )*};
    }
    bench!(
        spatial_chain_06::SpatialChain6,
        spatial_chain_12::SpatialChain12
    );
    #[cfg(feature = "large")]
    bench!(
        spatial_chain_30::SpatialChain30,
        spatial_chain_60::SpatialChain60
    );
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = adjoint
}
criterion_main!(benches);
