//! Per-call cost of the generated equations of the URDF robots imported by
//! `Builder::urdf` (Franka panda, UR5, Solo-12 on a fixed base and on a
//! floating one, and the benchmark trees of `trees/`: cart-poles, limbs,
//! binary tree; and dm_control's cheetah and humanoid, imported by
//! `Builder::mjcf`):
//! `mass_matrix` + `forcing` (the counterpart of Pinocchio's `crba` +
//! `nonLinearEffects`), each of the two alone (their sum against the pair
//! shows what calling one after the other costs: BENCHMARKS.md) and
//! `dalembert::accelerations`, which runs the
//! emitted solver (the counterpart of `aba`). Same method as `chains.rs`
//! (`dalembert_fixtures::states`): 1000 fixed pseudo-random states, one call
//! per iteration; the floating Solo-12's states put a unit quaternion (the
//! rotation by a random rotation vector) in place of three of the angles.
//!
//! The robots with derivatives (the floating Solo-12 of
//! `dalembert_generated::derivatives` and, with the `humanoids` feature, the
//! floating Unitree G1 and Talos) also time `accelerations_jacobian`, the
//! counterpart of `computeABADerivatives`.
//!
//! Run with `cargo bench -p dalembert-generated --bench robots [--features
//! humanoids]`; `scripts/benchmarks.sh --peers DIR robots` runs it with
//! Pinocchio (the peers' harness, `run.sh --urdf ROBOT.urdf [--floating]`) in
//! the same window. The MJCF models against MuJoCo's `mj_forward`
//! (`scripts/bench/mj_forward.c`) are the `humanoid` section's.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use dalembert::MultibodySystem;
use dalembert_fixtures::states::{per_call, states};
use dalembert_generated::{
    BinaryTree, CartPole1, CartPole3, CartPole6, Cheetah, FloatingSolo, Humanoid, Limbs, Panda,
    Solo, Ur5,
};

/// One call's arguments.
struct Call<const NQ: usize, const NV: usize, const NU: usize> {
    t: f64,
    q: [f64; NQ],
    v: [f64; NV],
    u: [f64; NU],
}

/// The fixtures' states of a fixed-base robot with one input per joint.
fn fixed_base<const N: usize>() -> Vec<Call<N, N, N>> {
    let states = states::<N, N>(N as u64);
    let call = |s: &dalembert_fixtures::states::Sample<N, N>| Call {
        t: s.t,
        q: s.q,
        v: s.v,
        u: s.u,
    };
    states.iter().map(call).collect()
}

/// States of a robot on a free joint (the floating Solo-12, the humanoid):
/// the fixtures' `NV` coordinates with the three after the position read as
/// a rotation vector and turned into its unit quaternion `(x, y, z, w)`.
fn floating<const NQ: usize, const NV: usize, const NU: usize>() -> Vec<Call<NQ, NV, NU>> {
    assert_eq!(NQ, NV + 1, "a free joint adds one coordinate");
    let states = states::<NV, NU>(NV as u64);
    let call = |s: &dalembert_fixtures::states::Sample<NV, NU>| {
        let [rx, ry, rz] = [s.q[3], s.q[4], s.q[5]];
        let angle = (rx * rx + ry * ry + rz * rz).sqrt();
        let (sine, cosine) = (angle / 2.0).sin_cos();
        let scale = if angle > 0.0 { sine / angle } else { 0.5 };
        let mut q = [0.0; NQ];
        q[..3].copy_from_slice(&s.q[..3]);
        q[3..7].copy_from_slice(&[scale * rx, scale * ry, scale * rz, cosine]);
        q[7..].copy_from_slice(&s.q[6..]);
        Call {
            t: s.t,
            q,
            v: s.v,
            u: s.u,
        }
    };
    states.iter().map(call).collect()
}

/// The two per-call benchmarks of one robot, in group `robots/NAME`.
fn bench_robot<S, const NQ: usize, const NV: usize, const NU: usize>(
    c: &mut Criterion,
    name: &str,
    robot: S,
    states: &[Call<NQ, NV, NU>],
) where
    S: MultibodySystem<NQ, NV, NU>,
{
    // Every state must be solvable, or `accelerations` would time an early return.
    for s in states {
        dalembert::accelerations(&robot, s.t, &s.q, &s.v, &s.u).expect("solvable state");
    }
    let mut group = c.benchmark_group(format!("robots/{name}"));
    group.bench_function("mass_matrix+forcing", |b| {
        b.iter_custom(|iters| {
            per_call(states, iters, |s| {
                let robot = black_box(&robot);
                (
                    robot.mass_matrix(&s.q),
                    robot.forcing(s.t, &s.q, &s.v, &s.u),
                )
            })
        })
    });
    group.bench_function("mass_matrix", |b| {
        b.iter_custom(|iters| per_call(states, iters, |s| black_box(&robot).mass_matrix(&s.q)))
    });
    group.bench_function("forcing", |b| {
        b.iter_custom(|iters| {
            per_call(states, iters, |s| {
                black_box(&robot).forcing(s.t, &s.q, &s.v, &s.u)
            })
        })
    });
    group.bench_function("accelerations", |b| {
        b.iter_custom(|iters| {
            per_call(states, iters, |s| {
                dalembert::accelerations(black_box(&robot), s.t, &s.q, &s.v, &s.u)
            })
        })
    });
    group.finish();
}

/// A generated `accelerations_jacobian(&self, t, q, v, u)`.
type Jacobian<S, R, const NQ: usize, const NV: usize, const NU: usize> =
    fn(&S, f64, &[f64; NQ], &[f64; NV], &[f64; NU]) -> R;

/// `accelerations_jacobian` of a robot with derivatives, in group
/// `robots/NAME` beside its dynamics.
fn bench_jacobian<S, R, const NQ: usize, const NV: usize, const NU: usize>(
    c: &mut Criterion,
    name: &str,
    robot: S,
    states: &[Call<NQ, NV, NU>],
    jacobian: Jacobian<S, R, NQ, NV, NU>,
) {
    let mut group = c.benchmark_group(format!("robots/{name}"));
    group.bench_function("accelerations_jacobian", |b| {
        b.iter_custom(|iters| {
            per_call(states, iters, |s| {
                jacobian(black_box(&robot), s.t, &s.q, &s.v, &s.u)
            })
        })
    });
    group.finish();
}

/// The floating robots with derivatives: their dynamics and
/// `accelerations_jacobian`.
fn floating_with_derivatives(c: &mut Criterion) {
    use dalembert_generated::derivatives::floating_solo12::FloatingSolo as Solo;
    bench_jacobian(
        c,
        "floating_solo12",
        Solo {},
        &floating(),
        Solo::accelerations_jacobian,
    );
    #[cfg(feature = "humanoids")]
    {
        use dalembert_generated::{g1::G1, talos_reduced::Talos};
        let (g1, talos) = (floating(), floating());
        bench_robot(c, "g1", G1 {}, &g1);
        bench_jacobian(c, "g1", G1 {}, &g1, G1::accelerations_jacobian);
        bench_robot(c, "talos_reduced", Talos {}, &talos);
        bench_jacobian(
            c,
            "talos_reduced",
            Talos {},
            &talos,
            Talos::accelerations_jacobian,
        );
    }
}

fn robots(c: &mut Criterion) {
    bench_robot(c, "panda", Panda {}, &fixed_base());
    bench_robot(c, "ur5", Ur5 {}, &fixed_base());
    bench_robot(c, "solo12", Solo {}, &fixed_base());
    bench_robot(c, "floating_solo12", FloatingSolo {}, &floating());
    bench_robot(c, "cart_pole_1", CartPole1 {}, &fixed_base());
    bench_robot(c, "cart_pole_3", CartPole3 {}, &fixed_base());
    bench_robot(c, "cart_pole_6", CartPole6 {}, &fixed_base());
    bench_robot(c, "limbs", Limbs {}, &fixed_base());
    bench_robot(c, "binary_tree", BinaryTree {}, &fixed_base());
    bench_robot(c, "cheetah", Cheetah {}, &fixed_base());
    bench_robot(c, "humanoid", Humanoid {}, &floating());
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = robots, floating_with_derivatives
}
criterion_main!(benches);
