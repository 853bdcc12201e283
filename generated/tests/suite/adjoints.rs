//! The adjoints of `dalembert::control` — `λᵀ ∂v̇/∂(q, v, u)` by one solve
//! with `M` and the generated reverse sweep `inverse_dynamics_adjoint`, and
//! the step counterparts of semi-implicit Euler and RK4 — against `λᵀ`
//! times the formed jacobians (to 1e-12 relative) and against central
//! differences (the configuration moved by `integrate_configuration`, a
//! step's end read back by `ConfigurationSpace::difference`), on the
//! chains, the UR5 and the panda, a floating quadruped (Solo-12 on a free
//! joint), a body on a spherical joint; the sweep itself against `μᵀ`
//! times `inverse_dynamics_jacobian`; and the refusal of the sweep for a
//! system with constraints (seed example 3).

use super::step_derivatives::{
    H, STATES, STEP, Step, StepWithJacobian, assert_column, random_state,
};
use dalembert::State;
use dalembert::control::{
    ConfigurationSpace, ControlError, Differentiated, InverseDifferentiable, StepAdjoint,
    accelerations_adjoint, euler_step, euler_step_adjoint, euler_step_jacobian, rk4_group_step,
    rk4_step_adjoint, rk4_step_jacobian,
};
use dalembert_codegen::testing::Random;
use dalembert_generated::derivatives::*;

/// Relative agreement required between two exact routes.
const EXACT: f64 = 1e-12;

/// The floating quadruped's: its `accelerations_jacobian` takes the looped
/// tree route (the runtime's recursion and `L D Lᵀ`), the adjoint a Cholesky
/// solve and the symbolic sweep, and its `M` (a heavy base over light legs)
/// magnifies their different roundings: 2.9e-12 of the largest entry
/// measured, where both took the symbolic partials before.
const FLOATING: f64 = 1e-11;

/// `|got − expected| ≤ tolerance |expected|_max`, entry by entry.
fn assert_exact<const N: usize>(tolerance: f64, what: &str, got: [f64; N], expected: [f64; N]) {
    let scale = expected.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    for i in 0..N {
        assert!(
            (got[i] - expected[i]).abs() <= tolerance * scale,
            "{what}, entry {i}: {} against {} (scale {scale})",
            got[i],
            expected[i]
        );
    }
}

/// `λᵀ J` for a matrix `J` of `N` rows.
fn weighted<const N: usize, const M: usize>(lambda: &[f64; N], matrix: &[[f64; M]; N]) -> [f64; M] {
    std::array::from_fn(|j| (0..N).map(|i| lambda[i] * matrix[i][j]).sum())
}

/// `x + y`.
fn plus<const N: usize>(x: [f64; N], y: [f64; N]) -> [f64; N] {
    std::array::from_fn(|i| x[i] + y[i])
}

/// `λ · x`.
fn dot<const N: usize>(lambda: &[f64; N], x: &[f64; N]) -> f64 {
    lambda.iter().zip(x).map(|(a, b)| a * b).sum()
}

/// `(φ(+STEP eⱼ) − φ(−STEP eⱼ)) / 2 STEP` for each `j`.
fn central<const N: usize>(mut phi: impl FnMut(usize, f64) -> f64) -> [f64; N] {
    std::array::from_fn(|j| (phi(j, STEP) - phi(j, -STEP)) / (2.0 * STEP))
}

/// `δ eⱼ`.
fn along<const N: usize>(j: usize, delta: f64) -> [f64; N] {
    std::array::from_fn(|i| if i == j { delta } else { 0.0 })
}

/// `accelerations_adjoint` against `λᵀ` times `accelerations_jacobian` and
/// against central differences of `λ · v̇`.
fn check_accelerations<S, const NQ: usize, const NV: usize, const NU: usize>(
    name: &str,
    system: &S,
    random: &mut Random,
    tolerance: f64,
) where
    S: InverseDifferentiable<NQ, NV, NU>,
{
    let (State { t, q, v }, u) = random_state(system, random);
    let lambda: [f64; NV] = std::array::from_fn(|_| random.uniform(-1.0, 1.0));
    let (jacobian_q, jacobian_v, jacobian_u) = system
        .accelerations_jacobian(t, &q, &v, &u)
        .expect("solvable");
    let (vdot, adjoint) = accelerations_adjoint(system, t, &q, &v, &u, &lambda).expect("solvable");
    assert_eq!(vdot, system.accelerations(t, &q, &v, &u).expect("solvable"));
    let what = |of: &str| format!("{name} λᵀ∂v̇/∂{of}");
    assert_exact(
        tolerance,
        &what("q"),
        adjoint.by_q,
        weighted(&lambda, &jacobian_q),
    );
    assert_exact(
        tolerance,
        &what("v"),
        adjoint.by_v,
        weighted(&lambda, &jacobian_v),
    );
    assert_exact(
        tolerance,
        &what("u"),
        adjoint.by_u,
        weighted(&lambda, &jacobian_u),
    );
    let phi = |q: &[f64; NQ], v: &[f64; NV], u: &[f64; NU]| {
        dot(
            &lambda,
            &system.accelerations(t, q, v, u).expect("solvable"),
        )
    };
    let by_q = central(|j, d| {
        phi(
            &system.integrate_configuration(&q, &along(j, d), 1.0),
            &v,
            &u,
        )
    });
    let by_v = central(|j, d| phi(&q, &plus(v, along(j, d)), &u));
    let by_u = central(|j, d| phi(&q, &v, &plus(u, along(j, d))));
    let what = |of: &str| format!("{name} λᵀ∂v̇/∂{of} by central differences");
    assert_column(&what("q"), adjoint.by_q, by_q);
    assert_column(&what("v"), adjoint.by_v, by_v);
    assert_column(&what("u"), adjoint.by_u, by_u);
}

/// A step's adjoint.
type StepAdjointFn<S, const NQ: usize, const NV: usize, const NU: usize> =
    fn(
        &S,
        &State<NQ, NV>,
        &[f64; NU],
        f64,
        &[f64; NV],
        &[f64; NV],
    ) -> Result<(State<NQ, NV>, StepAdjoint<NV, NU>), ControlError>;

/// A step, its jacobian and its adjoint.
type StepRoutes<S, const NQ: usize, const NV: usize, const NU: usize> = (
    &'static str,
    Step<S, NQ, NV, NU>,
    StepWithJacobian<S, NQ, NV, NU>,
    StepAdjointFn<S, NQ, NV, NU>,
);

/// Both steps' adjoints against `(λ_q, λ_v)ᵀ` times the step jacobians and
/// against central differences of `λ_q · (q⁺ ⊖ q̄⁺) + λ_v · v⁺`.
fn check_steps<S, const NQ: usize, const NV: usize, const NU: usize>(
    name: &str,
    system: &S,
    random: &mut Random,
    tolerance: f64,
) where
    S: InverseDifferentiable<NQ, NV, NU>,
{
    let space = ConfigurationSpace::of(system).expect("a known group");
    let (start, u) = random_state(system, random);
    let lambda_q: [f64; NV] = std::array::from_fn(|_| random.uniform(-1.0, 1.0));
    let lambda_v: [f64; NV] = std::array::from_fn(|_| random.uniform(-1.0, 1.0));
    let routes: [StepRoutes<S, NQ, NV, NU>; 2] = [
        ("Euler", euler_step, euler_step_jacobian, euler_step_adjoint),
        ("RK4", rk4_group_step, rk4_step_jacobian, rk4_step_adjoint),
    ];
    for (method, step, with_jacobian, adjoint) in routes {
        let (end, jacobian) = with_jacobian(system, &start, &u, H).expect("a step");
        let (adjoint_end, got) =
            adjoint(system, &start, &u, H, &lambda_q, &lambda_v).expect("a step");
        assert_eq!(adjoint_end, end);
        let what = |of: &str| format!("{name} {method} step λᵀ∂x⁺/∂{of}");
        let both = |by_q: &[[f64; NV]; NV], by_v: &[[f64; NV]; NV]| {
            plus(weighted(&lambda_q, by_q), weighted(&lambda_v, by_v))
        };
        let by_u = plus(
            weighted(&lambda_q, &jacobian.q_by_u),
            weighted(&lambda_v, &jacobian.v_by_u),
        );
        assert_exact(
            tolerance,
            &what("q"),
            got.by_q,
            both(&jacobian.q_by_q, &jacobian.v_by_q),
        );
        assert_exact(
            tolerance,
            &what("v"),
            got.by_v,
            both(&jacobian.q_by_v, &jacobian.v_by_v),
        );
        assert_exact(tolerance, &what("u"), got.by_u, by_u);
        let phi = |start: &State<NQ, NV>, u: &[f64; NU]| {
            let next = step(system, start, u, H).expect("a step");
            dot(&lambda_q, &space.difference(&end.q, &next.q)) + dot(&lambda_v, &next.v)
        };
        let by_q = central(|j, d| {
            let q = system.integrate_configuration(&start.q, &along(j, d), 1.0);
            phi(&State { q, ..start }, &u)
        });
        let by_v = central(|j, d| {
            let v = plus(start.v, along(j, d));
            phi(&State { v, ..start }, &u)
        });
        let by_u = central(|j, d| phi(&start, &plus(u, along(j, d))));
        let what = |of: &str| format!("{name} {method} step λᵀ∂x⁺/∂{of} by central differences");
        assert_column(&what("q"), got.by_q, by_q);
        assert_column(&what("v"), got.by_v, by_v);
        assert_column(&what("u"), got.by_u, by_u);
    }
}

/// The adjoints of `system` at [`STATES`] random states.
fn check_adjoints<S, const NQ: usize, const NV: usize, const NU: usize>(
    name: &str,
    system: &S,
    seed: u64,
    tolerance: f64,
) where
    S: InverseDifferentiable<NQ, NV, NU>,
{
    let mut random = Random::new(seed);
    for _ in 0..STATES {
        check_accelerations(name, system, &mut random, tolerance);
        check_steps(name, system, &mut random, tolerance);
    }
}

/// Each listed system, with its generated jacobian and reverse sweep.
macro_rules! check_adjoints {
    ($seed:expr, $tolerance:expr; $($module:ident :: $system:ident $fields:tt),* $(,)?) => {$(
        check_adjoints(
            stringify!($system),
            &Differentiated::new(&$module::$system $fields, $module::$system::accelerations_jacobian)
                .with_inverse($module::$system::inverse_dynamics_adjoint),
            $seed,
            $tolerance,
        );
    )*};
}

#[test]
fn chains_adjoints_match_the_jacobians_and_central_differences() {
    check_adjoints!(21, EXACT;
        planar_chain_06::PlanarChain6 {},
        spatial_chain_06::SpatialChain6 {},
        spatial_chain_12::SpatialChain12 {},
        spatial_tree_14::SpatialTree14 {},
    );
}

#[test]
fn robot_arms_adjoints_match_the_jacobians_and_central_differences() {
    check_adjoints!(22, EXACT; ur5_robot::Ur5 {}, panda::Panda {});
}

#[test]
fn a_floating_quadruped_adjoints_match_the_jacobians_and_central_differences() {
    check_adjoints!(23, FLOATING; floating_solo12::FloatingSolo {});
}

#[test]
fn a_spherical_joint_adjoints_match_the_jacobians_and_central_differences() {
    check_adjoints!(24, EXACT; dzhanibekov::Dzhanibekov { m: 12.0, a: 3.0, b: 2.0, c: 1.0 });
}

/// The generated sweep against `μᵀ` times the formed `∂τ/∂q`, `∂τ/∂v` of
/// `inverse_dynamics_jacobian`, at random accelerations and weights.
macro_rules! check_sweep {
    ($seed:expr; $($module:ident :: $system:ident $fields:tt),* $(,)?) => {$({
        let system = $module::$system $fields;
        let mut random = Random::new($seed);
        for _ in 0..STATES {
            let (State { t, q, v }, u) = random_state(&system, &mut random);
            let draw = |random: &mut Random| std::array::from_fn(|_| random.uniform(-1.0, 1.0));
            let (vdot, mu) = (draw(&mut random), draw(&mut random));
            let (by_q, by_v, _) = system.inverse_dynamics_adjoint(t, &q, &v, &vdot, &u, &mu);
            let (tau_q, tau_v, _) = system.inverse_dynamics_jacobian(t, &q, &v, &vdot, &u);
            let name = stringify!($system);
            assert_exact(EXACT, &format!("{name} μᵀ∂τ/∂q"), by_q, weighted(&mu, &tau_q));
            assert_exact(EXACT, &format!("{name} μᵀ∂τ/∂v"), by_v, weighted(&mu, &tau_v));
        }
    })*};
}

#[test]
fn the_reverse_sweep_is_the_inverse_dynamics_jacobian_weighted() {
    check_sweep!(25;
        double_pendulum::DoublePendulum { m: 1.0, L: 0.7, g: 9.81 },
        spatial_chain_12::SpatialChain12 {},
        panda::Panda {},
        floating_solo12::FloatingSolo {},
        dzhanibekov::Dzhanibekov { m: 12.0, a: 3.0, b: 2.0, c: 1.0 },
    );
}

/// With constraints the accelerations solve `M v̇ = f + Aᵀ λ`, `A v̇ = b`:
/// their adjoint is a solve with that saddle-point system and a sweep of
/// both residuals, which is not generated; the generator says so at the
/// output and points to the step jacobians, which hold with constraints.
#[test]
fn the_reverse_sweep_of_a_constrained_system_is_refused_at_the_output() {
    let source = include_str!("../../models/constrained_pendulum.dal");
    let end = source.rfind('}').expect("a closing brace");
    let source = format!(
        "{}    outputs inverse_dynamics_adjoint;\n{}",
        &source[..end],
        &source[end..]
    );
    let error = dalembert_codegen::check(&source).expect_err("refused");
    let message = error.to_string();
    for needed in [
        "constraints",
        "accelerations_jacobian",
        "euler_step_jacobian",
    ] {
        assert!(message.contains(needed), "{message}");
    }
    let line = source
        .lines()
        .position(|l| l.contains("inverse_dynamics_adjoint"))
        .expect("the line")
        + 1;
    assert_eq!(error.span().start().line, line, "{message}");
}
