//! Per-call cost of the generated equations of the URDF robots imported by
//! `Builder::urdf` (Franka panda, UR5, Solo-12 on a fixed base, and the
//! benchmark trees of `trees/`: cart-poles, limbs, binary tree):
//! `mass_matrix` + `forcing` (the counterpart of Pinocchio's `crba` +
//! `nonLinearEffects`) and `dalembert::accelerations`, which runs the
//! emitted solver (the counterpart of `aba`). Same method as `chains.rs`
//! (`dalembert_fixtures::states`): 1000 fixed pseudo-random states, one call
//! per iteration.
//!
//! Run with `cargo bench -p dalembert-generated --bench robots`; time
//! Pinocchio in the same window with
//! `bash ../shared/peers/pinocchio/run.sh --urdf tests/reference/urdf/panda.urdf`
//! (BENCHMARKS.md).

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use dalembert::MultibodySystem;
use dalembert_fixtures::states::{per_call, states};
use dalembert_generated::{BinaryTree, CartPole1, CartPole3, CartPole6, Limbs, Panda, Solo, Ur5};

/// The two per-call benchmarks of one robot (one input per joint), in group
/// `robots/NAME`.
fn bench_robot<S: MultibodySystem<N, N, N>, const N: usize>(
    c: &mut Criterion,
    name: &str,
    robot: S,
) {
    let states = states::<N, N>(N as u64);
    // Every state must be solvable, or `accelerations` would time an early return.
    for s in &states {
        dalembert::accelerations(&robot, s.t, &s.q, &s.v, &s.u).expect("solvable state");
    }
    let mut group = c.benchmark_group(format!("robots/{name}"));
    group.bench_function("mass_matrix+forcing", |b| {
        b.iter_custom(|iters| {
            per_call(&states, iters, |s| {
                let robot = black_box(&robot);
                (
                    robot.mass_matrix(&s.q),
                    robot.forcing(s.t, &s.q, &s.v, &s.u),
                )
            })
        })
    });
    group.bench_function("accelerations", |b| {
        b.iter_custom(|iters| {
            per_call(&states, iters, |s| {
                dalembert::accelerations(black_box(&robot), s.t, &s.q, &s.v, &s.u)
            })
        })
    });
    group.finish();
}

fn robots(c: &mut Criterion) {
    bench_robot(c, "panda", Panda {});
    bench_robot(c, "ur5", Ur5 {});
    bench_robot(c, "solo12", Solo {});
    bench_robot(c, "cart_pole_1", CartPole1 {});
    bench_robot(c, "cart_pole_3", CartPole3 {});
    bench_robot(c, "cart_pole_6", CartPole6 {});
    bench_robot(c, "limbs", Limbs {});
    bench_robot(c, "binary_tree", BinaryTree {});
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = robots
}
criterion_main!(benches);
