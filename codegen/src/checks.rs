//! The checks that need the derived equations, in one phase after the
//! derivation and its optimisation: the model layer checks everything the
//! text alone decides; what only the equations tell (a speed that moves
//! no mass, a regressor the model does not have) is checked here, once,
//! every violation collected at the user's token and reported together.
//! The stages after this one (outputs, emission) trust the model and the
//! equations and report nothing about the text (the size guard, which
//! refuses a model too large for rustc, is the one later refusal).

use crate::equations::Equations;
use crate::equations::inverse_dynamics;
use crate::equations::regressor::{Failure, regressor};
use crate::expr::Pool;
use crate::model::{Errors, Model, OutputKind};

/// Every check of the derived equations; `Ok` if the model passes all.
pub fn after_derivation(model: &Model, pool: &Pool, equations: &Equations) -> syn::Result<()> {
    let mut errors = Errors::default();
    check_inertia(model, pool, equations, &mut errors);
    check_regressor(model, pool, equations, &mut errors);
    check_adjoint(model, &mut errors);
    check_lanes(model, &mut errors);
    errors.finish(())
}

/// Every speed must move some mass: a coordinate (or speed) whose diagonal
/// entry of `M` is zero (and that no constraint ties) makes `M` singular
/// everywhere. Reported at the coordinate's declaration.
fn check_inertia(model: &Model, pool: &Pool, equations: &Equations, errors: &mut Errors) {
    for (k, speed) in model.speeds.iter().enumerate() {
        let massless = pool.is_zero(equations.mass_matrix[k][k]);
        let constrained = equations
            .constraint_jacobian
            .iter()
            .any(|row| !pool.is_zero(row[k]));
        if massless && !constrained {
            let name = &speed.name;
            let what = if speed.rate_of_coordinate {
                "coordinate"
            } else {
                "speed"
            };
            errors.push(
                name.span(),
                format!(
                    "the {what} `{name}` moves no mass, so the mass matrix is singular \
                     everywhere: make a body or particle depend on it, or remove it"
                ),
            );
        }
    }
}

/// A `regressor` output needs `M v̇ − f` linear in products of parameters
/// that do not move with time. Derived on a copy of the pool, so that the
/// pool the code is generated from is the same with or without the check
/// (the outputs derive the regressor again where they need it).
fn check_regressor(model: &Model, pool: &Pool, equations: &Equations, errors: &mut Errors) {
    let Some(output) = model
        .outputs
        .iter()
        .find(|o| o.kind == OutputKind::Regressor)
    else {
        return;
    };
    let mut scratch = pool.clone();
    let (tau, _) = inverse_dynamics(model, equations, &mut scratch);
    if let Err(failure) = regressor(&mut scratch, &tau) {
        let why = match failure {
            Failure::TooLarge => "`M v̇ − f` holds too many products of parameters",
            Failure::TimeDependent => "`M v̇ − f` depends on time `t` (outside the inputs)",
        };
        errors.push(
            output.function.span(),
            format!("this model has no regressor: {why}; remove `regressor` from `outputs`"),
        );
    }
}

/// `inverse_dynamics_adjoint` is the reverse sweep of the unconstrained
/// `M v̇ − f`: with constraints the accelerations solve the saddle-point
/// system `M v̇ = f + Aᵀ λ`, `A v̇ = b`, whose adjoint (a solve with that
/// system, then the sweep of the residuals `M v̇ − f − Aᵀ λ` and `A v̇ − b`
/// weighted by both halves of its solution) is not generated.
fn check_adjoint(model: &Model, errors: &mut Errors) {
    let Some(output) = model
        .outputs
        .iter()
        .find(|o| o.kind == OutputKind::InverseDynamicsAdjoint)
    else {
        return;
    };
    if model.constraints.is_empty() {
        return;
    }
    errors.push(
        output.function.span(),
        "`inverse_dynamics_adjoint` is the vector–jacobian product of the unconstrained \
         inverse dynamics `M v̇ − f`, and this system has constraints (`M v̇ = f + Aᵀ λ`, \
         `A v̇ = b`), whose adjoint is not generated: ask for `accelerations_jacobian`, whose \
         step jacobians (`dalembert::control::euler_step_jacobian`, `rk4_step_jacobian`) hold \
         with constraints, and remove `inverse_dynamics_adjoint` from `outputs`"
            .to_string(),
    );
}

/// `accelerations_x4` writes the unconstrained solve of `accelerations`
/// over SIMD lanes; a system with constraints solves a saddle point at run
/// time (`dalembert::accelerations_x4` takes its four states one by one).
fn check_lanes(model: &Model, errors: &mut Errors) {
    let Some(output) = model
        .outputs
        .iter()
        .find(|o| o.kind == OutputKind::AccelerationsX4)
    else {
        return;
    };
    if !model.constraints.is_empty() {
        errors.push(
            output.function.span(),
            "`accelerations_x4` is for systems without constraints; remove it from `outputs` \
             (`dalembert::accelerations_x4` solves four states of this system one by one)"
                .to_string(),
        );
    }
}
