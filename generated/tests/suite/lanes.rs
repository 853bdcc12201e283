//! `accelerations_x4` (`outputs accelerations_x4;`, the models of
//! `dalembert_generated::lanes`): four states at once, in SIMD lanes, give
//! each state what the scalar `accelerations` gives it — to a few units in
//! the last place on every route of the solve (the unrolled factorisation,
//! the articulated-body recursion), with every elementary function, time,
//! a ball joint, a floating base and two robots — and the scalar call's
//! error for a state that has one, the other lanes untouched.

use dalembert::{DynamicsError, MultibodySystem};
use dalembert_codegen::testing::Random;
use dalembert_generated::lanes::*;

/// Relative agreement of the lanes with the scalar call (to the largest
/// entry). The arithmetic is the same operations in the same order and the
/// sines and cosines of the angles taken together are the scalar body's
/// kernel: where both take the same route, the seed examples, the chains
/// of 6, the panda, the UR5 and floating Solo-12 agree exactly (0 here);
/// the chain of 12, on the recursion over lanes and factorised by the
/// scalar call, to 1.5e-13. An angle taken
/// alone (the articulated-body recursion's, where it is needed) is `libm`'s
/// `sincos` in the scalar body, whose two-part argument reduction can
/// differ from the lanes' kernel by a unit in the last place above π/4;
/// the chain of 30, the worst conditioned, carries that to 1.7e-12.
const TOLERANCE: f64 = 1e-11;

/// Batches of four random states per model.
const BATCHES: usize = 25;

/// The four states of a batch.
pub(crate) type Batch<const NQ: usize, const NV: usize, const NU: usize> =
    ([f64; 4], [[f64; NQ]; 4], [[f64; NV]; 4], [[f64; NU]; 4]);

/// Four random states: coordinates in `[−π, π)` (each quaternion then
/// normalised), speeds and inputs in `[−2, 2)`, times in `[0, 3)`.
pub(crate) fn batch<
    S: MultibodySystem<NQ, NV, NU>,
    const NQ: usize,
    const NV: usize,
    const NU: usize,
>(
    system: &S,
    random: &mut Random,
) -> Batch<NQ, NV, NU> {
    let pi = std::f64::consts::PI;
    let t = std::array::from_fn(|_| random.uniform(0.0, 3.0));
    let q = std::array::from_fn(|_| {
        let q = std::array::from_fn(|_| random.uniform(-pi, pi));
        // `q ⊕ 0` normalises the quaternions and moves nothing else.
        system.integrate_configuration(&q, &[0.0; NV], 0.0)
    });
    let v = std::array::from_fn(|_| std::array::from_fn(|_| random.uniform(-2.0, 2.0)));
    let u = std::array::from_fn(|_| std::array::from_fn(|_| random.uniform(-2.0, 2.0)));
    (t, q, v, u)
}

/// The lanes' answer for each state against the scalar call's: the same
/// error, or values within [`TOLERANCE`] relative to the largest.
fn assert_agree<const NV: usize>(
    what: &str,
    lanes: &[Result<[f64; NV], DynamicsError>; 4],
    scalar: &[Result<[f64; NV], DynamicsError>; 4],
) -> f64 {
    let mut worst: f64 = 0.0;
    for (k, (ours, theirs)) in lanes.iter().zip(scalar).enumerate() {
        match (ours, theirs) {
            (Ok(ours), Ok(theirs)) => {
                let scale = theirs.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
                for (a, b) in ours.iter().zip(theirs) {
                    let error = (a - b).abs() / scale;
                    worst = worst.max(error);
                    assert!(
                        error <= TOLERANCE,
                        "{what}, state {k}: {ours:?} vs {theirs:?}"
                    );
                }
            }
            _ => assert_eq!(ours, theirs, "{what}, state {k}"),
        }
    }
    worst
}

/// `BATCHES` batches of random states through `x4` (the inherent
/// `accelerations_x4`) and through `dalembert::accelerations_x4` (the
/// trait's, which the generated system forwards to it), against the scalar
/// `accelerations`; returns the worst relative difference.
fn check<S, const NQ: usize, const NV: usize, const NU: usize>(
    what: &str,
    system: &S,
    x4: impl Fn(&S, Batch<NQ, NV, NU>) -> [Result<[f64; NV], DynamicsError>; 4],
) -> f64
where
    S: MultibodySystem<NQ, NV, NU>,
{
    let mut random = Random::new(39);
    let mut worst: f64 = 0.0;
    let mut compared = 0;
    for _ in 0..BATCHES {
        let states = batch(system, &mut random);
        let (t, q, v, u) = &states;
        let scalar: [_; 4] =
            std::array::from_fn(|k| dalembert::accelerations(system, t[k], &q[k], &v[k], &u[k]));
        let inherent = x4(system, states);
        let through_trait = dalembert::accelerations_x4(system, *t, q, v, u);
        assert_eq!(inherent, through_trait, "{what}: the trait forwards");
        worst = worst.max(assert_agree(what, &inherent, &scalar));
        compared += scalar.iter().filter(|r| r.is_ok()).count();
    }
    assert!(
        compared > 3 * BATCHES,
        "{what}: only {compared} states solved"
    );
    worst
}

/// Calls `check` on a model of `dalembert_generated::lanes` with its
/// parameters' values `$system`.
macro_rules! check {
    ($module:ident, $system:expr) => {{
        use $module::*;
        let system = $system;
        check(stringify!($module), &system, |s, (t, q, v, u)| {
            s.accelerations_x4(t, &q, &v, &u)
        })
    }};
}

#[test]
fn seed_examples_ball_joint_and_every_function_agree_with_the_scalar_call() {
    let worst = [
        check!(
            double_pendulum,
            DoublePendulum {
                m: 1.0,
                L: 1.3,
                g: 9.81
            }
        ),
        check!(
            dzhanibekov,
            Dzhanibekov {
                m: 2.0,
                a: 0.3,
                b: 0.2,
                c: 0.1
            }
        ),
        check!(
            taylor_functions,
            TaylorFunctions {
                m: 1.5,
                k: 2.0,
                c: 0.3
            }
        ),
    ];
    println!("worst relative differences: {worst:?}");
}

#[test]
fn chains_agree_with_the_scalar_call_on_both_routes() {
    let worst = [
        check!(planar_chain_06, PlanarChain6 {}),
        check!(spatial_chain_06, SpatialChain6 {}),
        check!(spatial_chain_12, SpatialChain12 {}),
        check!(spatial_chain_30, SpatialChain30 {}),
    ];
    println!("worst relative differences: {worst:?}");
}

#[test]
fn robots_fixed_and_floating_agree_with_the_scalar_call() {
    let worst = [
        check!(panda, Panda {}),
        check!(ur5_robot, Ur5 {}),
        check!(floating_solo12, FloatingSolo {}),
    ];
    println!("worst relative differences: {worst:?}");
}

/// A state with a NaN, or whose mass matrix is singular, gets the scalar
/// call's error; the other lanes their values.
#[test]
fn a_bad_state_gets_the_scalar_error_and_leaves_the_others() {
    use double_pendulum::DoublePendulum;
    let system = DoublePendulum {
        m: 1.0,
        L: 1.3,
        g: 9.81,
    };
    let q = [[0.1, 0.2], [f64::NAN, 0.0], [0.3, -0.4], [0.5, 0.6]];
    let v = [[0.0, 1.0]; 4];
    let u: [[f64; 0]; 4] = [[]; 4];
    let results = system.accelerations_x4([0.0; 4], &q, &v, &u);
    assert_eq!(results[1], Err(DynamicsError::NonFiniteState));
    for k in [0, 2, 3] {
        let scalar = system.accelerations(0.0, &q[k], &v[k], &u[k]);
        assert!(scalar.is_ok());
        assert_agree("a good lane", &[results[k]; 4], &[scalar; 4]);
    }
    // A massless pendulum: every pivot is zero.
    let massless = DoublePendulum { m: 0.0, ..system };
    let results = massless.accelerations_x4([0.0; 4], &q, &v, &u);
    for k in 0..4 {
        let scalar = massless.accelerations(0.0, &q[k], &v[k], &u[k]);
        assert!(scalar.is_err());
        assert_eq!(results[k], scalar, "state {k}");
    }
}
