//! `dalembert::control::rk4_group_step_x4`: the RK4 step of four states at once,
//! its stages through `accelerations_x4`, against four scalar
//! `dalembert::control::rk4_group_step` (and, where every speed is a coordinate's
//! rate, `integrate::Rk4::step`) on the models of `dalembert_generated::lanes`,
//! on both routes of the solve and on a floating base; a system without the
//! output (the trait's four scalar calls); and the errors of states that
//! fail, the other lanes untouched.

use dalembert::control::{ControlError, rk4_group_step, rk4_group_step_x4};
use dalembert::integrate::Rk4;
use dalembert::{DynamicsError, MultibodySystem, State, Unconstrained};
use dalembert_codegen::testing::Random;
use dalembert_generated::lanes::*;

use super::lanes::batch;

/// The step, long enough for the stages to differ well from the start.
const H: f64 = 1e-2;

/// Relative agreement of a batched step with the scalar one (to the
/// largest entry of the scalar step's end, at least one). The stages are
/// the same operations in the same order, so the ends differ only where
/// `accelerations_x4` differs from `accelerations`: nowhere where both
/// take the unrolled factorisation (the chains of 6, the panda, the UR5:
/// the ends are asserted equal bit for bit there); by rounding where the
/// lanes take the articulated-body recursion and the scalar call the
/// factorisation (the chain of 12: 1.5e-13 of the largest acceleration);
/// within 1.7e-12 of the largest
/// acceleration where both take the recursion (the chain of 30: `libm`'s
/// `sincos` of an angle taken alone against the lanes' kernel,
/// `lanes.rs`), which a step scales by `h` and which the four stages carry
/// on through the state. 1e-11 leaves room for that and for the
/// accelerations' size, as the lanes' own tolerance does.
const TOLERANCE: f64 = 1e-11;

/// Batches of four random states per model.
const BATCHES: usize = 10;

/// The batched step of `BATCHES` batches of random states against four
/// scalar steps; with `exact`, equal bit for bit. Returns the worst
/// relative difference.
fn check<S, const NQ: usize, const NV: usize, const NU: usize>(
    what: &str,
    system: &S,
    exact: bool,
) -> f64
where
    S: MultibodySystem<NQ, NV, NU>,
{
    let mut random = Random::new(39);
    let (mut worst, mut compared) = (0.0_f64, 0);
    for _ in 0..BATCHES {
        let (t, q, v, u) = batch(system, &mut random);
        let states = std::array::from_fn(|k| State {
            t: t[k],
            q: q[k],
            v: v[k],
        });
        let ends = rk4_group_step_x4(system, &states, &u, H);
        for (k, end) in ends.iter().enumerate() {
            let scalar = rk4_group_step(system, &states[k], &u[k], H);
            let (Ok(ours), Ok(theirs)) = (end, &scalar) else {
                assert_eq!(end, &scalar, "{what}, state {k}");
                continue;
            };
            compared += 1;
            if exact {
                assert_eq!(ours, theirs, "{what}, state {k}");
            }
            let entries = |s: &State<NQ, NV>| s.q.into_iter().chain(s.v);
            let scale = entries(theirs).fold(1.0_f64, |m, x| m.max(x.abs()));
            assert_eq!(ours.t, theirs.t, "{what}, state {k}");
            for (a, b) in entries(ours).zip(entries(theirs)) {
                let error = (a - b).abs() / scale;
                worst = worst.max(error);
                assert!(
                    error <= TOLERANCE,
                    "{what}, state {k}: {ours:?} vs {theirs:?}"
                );
            }
        }
    }
    assert!(
        compared > 3 * BATCHES,
        "{what}: only {compared} steps taken"
    );
    worst
}

#[test]
fn chains_and_robots_step_as_four_scalar_steps() {
    let worst = [
        check(
            "double_pendulum",
            &double_pendulum::DoublePendulum {
                m: 1.0,
                L: 1.3,
                g: 9.81,
            },
            true,
        ),
        check("planar_chain_06", &planar_chain_06::PlanarChain6 {}, true),
        check(
            "spatial_chain_06",
            &spatial_chain_06::SpatialChain6 {},
            true,
        ),
        check(
            "spatial_chain_12",
            &spatial_chain_12::SpatialChain12 {},
            false,
        ),
        check("panda", &panda::Panda {}, true),
        check("ur5", &ur5_robot::Ur5 {}, true),
        check(
            "spatial_chain_30",
            &spatial_chain_30::SpatialChain30 {},
            false,
        ),
        check("floating_solo12", &floating_solo12::FloatingSolo {}, false),
    ];
    println!("worst relative differences: {worst:?}");
}

/// A system without `outputs accelerations_x4;`: the trait's four scalar
/// calls, so the same steps bit for bit.
#[test]
fn a_system_without_lanes_steps_by_the_scalar_calls() {
    let system = dalembert_generated::derivatives::spatial_chain_12::SpatialChain12 {};
    check("spatial_chain_12 (no lanes)", &system, true);
}

/// Where every speed is its coordinate's rate, the batched step is
/// `integrate::Rk4::step` of each state with its inputs held.
#[test]
fn on_a_vector_space_it_is_the_integrators_step() {
    let system = spatial_chain_06::SpatialChain6 {};
    let (t, q, v, u) = batch(&system, &mut Random::new(12));
    let states = std::array::from_fn(|k| State {
        t: t[k],
        q: q[k],
        v: v[k],
    });
    let ends = rk4_group_step_x4(&system, &states, &u, H);
    let dynamics = Unconstrained::without_inputs(&system);
    for (k, (end, state)) in ends.iter().zip(&states).enumerate() {
        let scalar = Rk4::step(&dynamics, state, H).expect("a solvable state");
        assert_eq!(end, &Ok(scalar), "state {k}");
    }
}

/// A state with a NaN, or one that reaches a singular mass matrix, gets the
/// scalar step's error; the others their steps.
#[test]
fn a_failing_state_gets_the_scalar_error_and_leaves_the_others() {
    let system = double_pendulum::DoublePendulum {
        m: 1.0,
        L: 1.3,
        g: 9.81,
    };
    let at = |q: [f64; 2]| State {
        t: 0.0,
        q,
        v: [0.0, 1.0],
    };
    let states = [
        at([0.1, 0.2]),
        at([f64::NAN, 0.0]),
        at([0.3, -0.4]),
        at([0.5, 0.6]),
    ];
    let u = [[]; 4];
    let ends = rk4_group_step_x4(&system, &states, &u, H);
    assert_eq!(
        ends[1],
        Err(ControlError::Dynamics(DynamicsError::NonFiniteState))
    );
    for k in [0, 2, 3] {
        let scalar = rk4_group_step(&system, &states[k], &u[k], H);
        assert!(scalar.is_ok());
        assert_eq!(ends[k], scalar, "state {k}");
    }
    // A massless pendulum: every stage fails its pivots.
    let massless = double_pendulum::DoublePendulum { m: 0.0, ..system };
    let ends = rk4_group_step_x4(&massless, &states, &u, H);
    for (k, (end, state)) in ends.iter().zip(&states).enumerate() {
        let scalar = rk4_group_step(&massless, state, &[], H);
        assert!(scalar.is_err());
        assert_eq!(end, &scalar, "state {k}");
    }
}
