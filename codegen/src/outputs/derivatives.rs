//! The exact derivatives as outputs: `inverse_dynamics_jacobian`,
//! `accelerations_jacobian` and `linearize`, all from the partials of the
//! inverse dynamics `τ = M v̇ − f` (see
//! [`crate::equations::derivatives`]).

use super::{Argument, Body, Function, Value, doc_lines};
use crate::equations::derivatives::{ResidualJacobian, residual_jacobian};
use crate::equations::{Equations, inverse_dynamics};
use crate::expr::Pool;
use crate::model::Model;
use proc_macro2::{Ident, Span};

use Argument::{Accelerations, Coordinates, Inputs, Speeds, Time};

/// The partials of `τ` and the route that derived `τ`, for the docs.
fn partials(
    model: &Model,
    equations: &Equations,
    pool: &mut Pool,
) -> (ResidualJacobian, &'static str) {
    let (tau, recursive) = inverse_dynamics(model, equations, pool);
    let route = match recursive {
        true => "the Newton–Euler recursion over the kinematic tree",
        false => "the mass matrix and the forcing",
    };
    let jacobian = residual_jacobian(pool, &tau, model.nq(), model.inputs.len());
    (jacobian, route)
}

/// A function named `name` computing `results` as `body` says.
fn function(
    name: &str,
    docs: &str,
    arguments: &[Argument],
    results: Vec<Value>,
    body: Body,
) -> Function {
    Function {
        name: Ident::new(name, Span::call_site()),
        docs: doc_lines(docs),
        arguments: arguments.to_vec(),
        results,
        body,
    }
}

/// `inverse_dynamics_jacobian(t, q, v, v̇, u) -> (∂τ/∂q, ∂τ/∂v, M)`.
pub fn inverse_dynamics_jacobian(
    model: &Model,
    equations: &Equations,
    pool: &mut Pool,
) -> Function {
    let nq = model.nq();
    let (jacobian, route) = partials(model, equations, pool);
    function(
        "inverse_dynamics_jacobian",
        &format!(
            "The derivatives of the inverse dynamics `τ(t, q, v, v̇, u) = M v̇ − f`:\n\
             `(∂τ/∂q, ∂τ/∂v, ∂τ/∂v̇ = M)`, entry `[i][j]` the derivative of `τᵢ` by\n\
             the `j`-th variable. Exact: `τ`, derived by {route},\n\
             differentiated symbolically, the shared subexpressions computed once."
        ),
        &[Time, Coordinates, Speeds, Accelerations, Inputs],
        vec![
            Value::matrix(&jacobian.coordinates, nq),
            Value::matrix(&jacobian.speeds, nq),
            Value::matrix(&equations.mass_matrix, nq),
        ],
        Body::Explicit,
    )
}

/// `accelerations_jacobian(t, q, v, u) -> Result<(∂v̇/∂q, ∂v̇/∂v, ∂v̇/∂u), _>`.
pub fn accelerations_jacobian(model: &Model, equations: &Equations, pool: &mut Pool) -> Function {
    let (nq, nu) = (model.nq(), model.inputs.len());
    let (jacobian, route) = partials(model, equations, pool);
    function(
        "accelerations_jacobian",
        &format!(
            "The derivatives of the accelerations `v̇(t, q, v, u)` at a state:\n\
             `(∂v̇/∂q, ∂v̇/∂v, ∂v̇/∂u)`, entry `[i][j]` the derivative of `v̇ᵢ` by the\n\
             `j`-th variable. Exact: differentiating `M v̇ = f` gives\n\
             `M ∂v̇/∂x = −∂τ/∂x` with `τ = M v̇ − f` at the solved `v̇`; the partials\n\
             of `τ` (derived by {route}) are differentiated\n\
             symbolically, and every column goes through the `L D Lᵀ` factorisation\n\
             of `M` that solved for `v̇`. The errors of `accelerations`, and\n\
             `NonFiniteEquations` for a non-finite derivative."
        ),
        &[Time, Coordinates, Speeds, Inputs],
        vec![
            Value::matrix(&jacobian.coordinates, nq),
            Value::matrix(&jacobian.speeds, nq),
            Value::matrix(&jacobian.inputs, nu),
        ],
        Body::AccelerationsJacobian,
    )
}

/// `linearize(t, q, v, u) -> Result<(A, B), _>`.
pub fn linearize() -> Function {
    function(
        "linearize",
        "The linearisation `δẋ = A δx + B δu` of the equations of motion about a\n\
         state `x = (q, v)` and input `u`. The coordinates' rates are the speeds\n\
         (`q̇ = v`), so `A = [[0, I], [∂v̇/∂q, ∂v̇/∂v]]` and `B = [[0], [∂v̇/∂u]]`,\n\
         from `accelerations_jacobian` (and with its errors). About an\n\
         equilibrium, the eigenvalues of `A` are the exponents of the small\n\
         motions. Systems with constraints are not linearised (yet), nor\n\
         Lie-group joints (free, spherical).",
        &[Time, Coordinates, Speeds, Inputs],
        Vec::new(),
        Body::Linearize,
    )
}

#[cfg(test)]
mod tests {
    /// Seed example 3 with `outputs` added before its closing brace.
    fn constrained_pendulum_asking_for(outputs: &str) -> String {
        let source = crate::seeds::CONSTRAINED_PENDULUM;
        let end = source.rfind('}').expect("a closing brace");
        format!(
            "{}    outputs {outputs};\n{}",
            &source[..end],
            &source[end..]
        )
    }

    #[test]
    fn a_constrained_system_is_not_linearised_and_the_error_says_where() {
        let source = constrained_pendulum_asking_for("inverse_dynamics_jacobian, linearize");
        let error = crate::check(&source).expect_err("constraints");
        let message = error.to_string();
        assert!(
            message.contains("`linearize` is not available for a system with constraints"),
            "{message}"
        );
        let line = source
            .lines()
            .position(|l| l.contains("outputs"))
            .expect("the line")
            + 1;
        let start = error.span().start();
        assert_eq!(start.line, line, "{message}");
        let column = source
            .lines()
            .nth(line - 1)
            .and_then(|l| l.find("linearize"));
        assert_eq!(Some(start.column), column, "{message}");
    }

    #[test]
    fn a_constrained_system_has_its_inverse_dynamics_jacobian() {
        let source = constrained_pendulum_asking_for("inverse_dynamics_jacobian");
        let code = crate::generate(&source).expect("generates");
        assert!(code.contains("pub fn inverse_dynamics_jacobian("));
        assert!(!code.contains("pub fn accelerations_jacobian("));
    }
}
