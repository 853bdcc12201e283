//! The exact jacobian of one integration step (`dalembert::control`:
//! semi-implicit Euler and RK4), against central
//! differences of the steps themselves: on the chains, the UR5 and the
//! panda, a floating quadruped (Solo-12 on a free joint: SE(3)), a body on
//! a spherical joint (SO(3)) and a constrained pendulum. A perturbation of
//! the configuration is `q ⊕ δ` (`integrate_configuration`), and that of
//! the step's end is read back in the tangent space by
//! `ConfigurationSpace::difference`.

use dalembert::State;
use dalembert::control::{
    ConfigurationSpace, ControlError, Differentiable, Differentiated, StepJacobian, euler_step,
    euler_step_jacobian, rk4_group_step, rk4_step_jacobian,
};
use dalembert::{MultibodySystem, Unconstrained, integrate};
use dalembert_codegen::testing::Random;
use dalembert_generated::derivatives::*;

/// Relative agreement required of the central differences.
pub(super) const TOLERANCE: f64 = 1e-6;

/// Step of the central differences.
pub(super) const STEP: f64 = 1e-6;

/// Time step of the integration steps.
pub(super) const H: f64 = 0.01;

/// Random states checked per system.
pub(super) const STATES: usize = 3;

dalembert::dalembert! {
    /// Seed example 3 (a bar whose centre is held on a circle by two
    /// holonomic constraints) asking for the derivatives of its constrained
    /// accelerations.
    pub ConstrainedPendulum {
        parameters m, l, g;
        coordinates x, y, theta;
        inputs M;
        frame B = N.rotate_z(theta);
        point G = O + x * N.x + y * N.y;
        body bar { mass: m, center: G, frame: B, inertia: [0, 0, m*l^2/12] };
        gravity -g * N.y;
        torque M * N.z on B;
        constraint x - l/2 * sin(theta) == 0;
        constraint y + l/2 * cos(theta) == 0;
        outputs accelerations_jacobian;
    }
}

dalembert::dalembert! {
    /// A body in Euler angles with its body-axis angular velocity as speeds
    /// (a `speeds` statement): no group the step derivatives know.
    pub BodyRates {
        parameters I1, I2, I3;
        coordinates psi, theta, phi;
        speeds wx, wy, wz {
            psi: (sin(phi) * wy + cos(phi) * wz) / cos(theta),
            theta: cos(phi) * wy - sin(phi) * wz,
            phi: wx + tan(theta) * (sin(phi) * wy + cos(phi) * wz)
        };
        frame A = N.rotate_z(psi);
        frame C = A.rotate_y(theta);
        frame B = C.rotate_x(phi);
        body b { mass: 1, center: O, frame: B, inertia: [I1, I2, I3] };
    }
}

/// A random state with inputs: coordinates in `[−π, π)` (each quaternion
/// normalised), speeds and inputs in `[−2, 2)`.
pub(super) fn random_state<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    random: &mut Random,
) -> (State<NQ, NV>, [f64; NU])
where
    S: MultibodySystem<NQ, NV, NU>,
{
    let pi = std::f64::consts::PI;
    let q = std::array::from_fn(|_| random.uniform(-pi, pi));
    let state = State {
        t: random.uniform(0.0, 1.0),
        q: system.integrate_configuration(&q, &[0.0; NV], 0.0),
        v: std::array::from_fn(|_| random.uniform(-2.0, 2.0)),
    };
    (state, std::array::from_fn(|_| random.uniform(-2.0, 2.0)))
}

/// A step and its jacobian.
pub(super) type Step<S, const NQ: usize, const NV: usize, const NU: usize> =
    fn(&S, &State<NQ, NV>, &[f64; NU], f64) -> Result<State<NQ, NV>, ControlError>;
pub(super) type StepWithJacobian<S, const NQ: usize, const NV: usize, const NU: usize> =
    fn(
        &S,
        &State<NQ, NV>,
        &[f64; NU],
        f64,
    ) -> Result<(State<NQ, NV>, StepJacobian<NV, NU>), ControlError>;

/// `|exact − numeric| ≤ TOLERANCE (1 + |numeric|_max)` over one column.
pub(super) fn assert_column<const N: usize>(what: &str, exact: [f64; N], numeric: [f64; N]) {
    let scale = 1.0 + numeric.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    for i in 0..N {
        assert!(
            (exact[i] - numeric[i]).abs() <= TOLERANCE * scale,
            "{what}, row {i}: exact {}, central differences {}",
            exact[i],
            numeric[i]
        );
    }
}

/// Column `j` of `matrix`.
fn column<const N: usize, const M: usize>(matrix: &[[f64; M]; N], j: usize) -> [f64; N] {
    std::array::from_fn(|i| matrix[i][j])
}

/// The step's jacobian against central differences of the step, column by
/// column of `(δq, δv, δu)`; the step's end equal to `step`'s.
fn check_step<S, const NQ: usize, const NV: usize, const NU: usize>(
    name: &str,
    system: &S,
    (step, with_jacobian): (Step<S, NQ, NV, NU>, StepWithJacobian<S, NQ, NV, NU>),
    seed: u64,
) where
    S: Differentiable<NQ, NV, NU>,
{
    let space = ConfigurationSpace::of(system).expect("a known group");
    let mut random = Random::new(seed);
    for _ in 0..STATES {
        let (start, u) = random_state(system, &mut random);
        let (end, jacobian) = with_jacobian(system, &start, &u, H).expect("a step");
        assert_eq!(end, step(system, &start, &u, H).expect("a step"), "{name}");
        // The step's end from a perturbed start, in the tangent space at `end`.
        let moved = |start: &State<NQ, NV>, u: &[f64; NU]| -> ([f64; NV], [f64; NV]) {
            let next = step(system, start, u, H).expect("a step");
            (space.difference(&end.q, &next.q), next.v)
        };
        let differences = |plus: ([f64; NV], [f64; NV]), minus: ([f64; NV], [f64; NV])| {
            let d =
                |a: [f64; NV], b: [f64; NV]| std::array::from_fn(|i| (a[i] - b[i]) / (2.0 * STEP));
            (d(plus.0, minus.0), d(plus.1, minus.1))
        };
        for j in 0..NV {
            let mut delta = [0.0; NV];
            let mut at = |s: f64| {
                delta[j] = s;
                let q = system.integrate_configuration(&start.q, &delta, 1.0);
                moved(&State { q, ..start }, &u)
            };
            let (plus, minus) = (at(STEP), at(-STEP));
            let (dq, dv) = differences(plus, minus);
            assert_column(
                &format!("{name} ∂q⁺/∂q, column {j}"),
                column(&jacobian.q_by_q, j),
                dq,
            );
            assert_column(
                &format!("{name} ∂v⁺/∂q, column {j}"),
                column(&jacobian.v_by_q, j),
                dv,
            );
            let at = |s: f64| {
                let mut v = start.v;
                v[j] += s;
                moved(&State { v, ..start }, &u)
            };
            let (dq, dv) = differences(at(STEP), at(-STEP));
            assert_column(
                &format!("{name} ∂q⁺/∂v, column {j}"),
                column(&jacobian.q_by_v, j),
                dq,
            );
            assert_column(
                &format!("{name} ∂v⁺/∂v, column {j}"),
                column(&jacobian.v_by_v, j),
                dv,
            );
        }
        for j in 0..NU {
            let at = |s: f64| {
                let mut u = u;
                u[j] += s;
                moved(&start, &u)
            };
            let (dq, dv) = differences(at(STEP), at(-STEP));
            assert_column(
                &format!("{name} ∂q⁺/∂u, column {j}"),
                column(&jacobian.q_by_u, j),
                dq,
            );
            assert_column(
                &format!("{name} ∂v⁺/∂u, column {j}"),
                column(&jacobian.v_by_u, j),
                dv,
            );
        }
    }
}

/// Both steps' jacobians of `system` against central differences.
fn check_both<S, const NQ: usize, const NV: usize, const NU: usize>(
    name: &str,
    system: &S,
    seed: u64,
) where
    S: Differentiable<NQ, NV, NU>,
{
    check_step(
        &format!("{name} (Euler)"),
        system,
        (euler_step, euler_step_jacobian),
        seed,
    );
    check_step(
        &format!("{name} (RK4)"),
        system,
        (rk4_group_step, rk4_step_jacobian),
        seed + 1,
    );
}

/// Each listed system, with its generated `accelerations_jacobian`.
macro_rules! check {
    ($seed:expr; $($module:ident :: $system:ident $fields:tt),* $(,)?) => {$(
        check_both(
            stringify!($system),
            &Differentiated::new(&$module::$system $fields, $module::$system::accelerations_jacobian),
            $seed,
        );
    )*};
}

#[test]
fn chains_step_jacobians_match_central_differences() {
    check!(11;
        planar_chain_06::PlanarChain6 {},
        spatial_chain_06::SpatialChain6 {},
        spatial_chain_12::SpatialChain12 {},
    );
}

#[test]
fn robot_arms_step_jacobians_match_central_differences() {
    check!(12; ur5_robot::Ur5 {}, panda::Panda {});
}

#[test]
fn a_floating_quadruped_step_jacobians_match_central_differences_in_the_tangent_space() {
    check!(13; floating_solo12::FloatingSolo {});
}

#[test]
fn a_spherical_joint_step_jacobians_match_central_differences_in_the_tangent_space() {
    check!(14; dzhanibekov::Dzhanibekov { m: 12.0, a: 3.0, b: 2.0, c: 1.0 });
}

#[test]
fn a_constrained_pendulum_step_jacobians_match_central_differences() {
    let pendulum = ConstrainedPendulum {
        m: 1.3,
        l: 0.8,
        g: 9.81,
    };
    check_both(
        "ConstrainedPendulum",
        &Differentiated::new(&pendulum, ConstrainedPendulum::accelerations_jacobian),
        15,
    );
}

#[test]
fn rk4_is_the_runtime_rk4_where_the_speeds_are_rates() {
    let system = panda::Panda {};
    let mut random = Random::new(16);
    for _ in 0..STATES {
        let (start, u) = random_state(&system, &mut random);
        let runtime = integrate::Rk4::step(&Unconstrained::new(&system, |_, _, _| u), &start, H)
            .expect("a step");
        assert_eq!(
            rk4_group_step(&system, &start, &u, H).expect("a step"),
            runtime
        );
    }
}

#[test]
fn speeds_of_a_speeds_statement_are_refused_by_name() {
    let error = ConfigurationSpace::of(&BodyRates {
        I1: 1.0,
        I2: 2.0,
        I3: 3.0,
    })
    .expect_err("no group");
    assert_eq!(error, ControlError::UnsupportedSpeed { speed: "wx" });
    assert!(error.to_string().contains("`wx`"), "{error}");
}

#[test]
fn difference_inverts_the_configuration_update_on_se3_and_so3() {
    /// `a ⊕ (b ⊖ a) = b` at random `a`, `b`, the quaternion at
    /// `quaternion` up to its sign (the same rotation).
    fn check<S: MultibodySystem<NQ, NV, NU>, const NQ: usize, const NV: usize, const NU: usize>(
        system: &S,
        quaternion: std::ops::Range<usize>,
        seed: u64,
    ) {
        let space = ConfigurationSpace::of(system).expect("a known group");
        assert!(!space.is_vector_space());
        let mut random = Random::new(seed);
        for _ in 0..10 {
            let (a, _) = random_state::<S, NQ, NV, NU>(system, &mut random);
            let (b, _) = random_state::<S, NQ, NV, NU>(system, &mut random);
            let back = system.integrate_configuration(&a.q, &space.difference(&a.q, &b.q), 1.0);
            let gap = |sign: f64| {
                (0..NQ)
                    .map(|i| match quaternion.contains(&i) {
                        true => (back[i] - sign * b.q[i]).abs(),
                        false => (back[i] - b.q[i]).abs(),
                    })
                    .fold(0.0, f64::max)
            };
            assert!(
                gap(1.0).min(gap(-1.0)) < 1e-12,
                "a ⊕ (b ⊖ a) = {back:?}, b = {:?}",
                b.q
            );
        }
    }
    check(&floating_solo12::FloatingSolo {}, 3..7, 18);
    check(
        &dzhanibekov::Dzhanibekov {
            m: 12.0,
            a: 3.0,
            b: 2.0,
            c: 1.0,
        },
        0..4,
        19,
    );
}
