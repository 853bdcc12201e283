//! `inverse_dynamics_adjoint`: the vector–jacobian product
//! `μᵀ ∂τ/∂(q, v, u)` of the inverse dynamics `τ = M v̇ − f` at given
//! weights `μ`, without forming `∂τ/∂x`: the gradient of the scalar
//! `μᵀ τ` by one reverse sweep over the DAG of `τ` ([`Pool::gradient`]),
//! so its cost is a small multiple of `τ`'s own — `O(n)` on a tree, whose
//! `τ` is the Newton–Euler recursion. The runtime's adjoints
//! (`dalembert::control::accelerations_adjoint` and the steps') call it at
//! `μ = M⁻ᵀ λ`.

use super::{Argument, Body, Function, Value, doc_lines};
use crate::equations::derivatives::tangent_directions;
use crate::equations::{Equations, inverse_dynamics};
use crate::expr::{ExprId, Pool, Sym};
use crate::model::Model;
use proc_macro2::{Ident, Span};

use Argument::{Accelerations, Coordinates, Inputs, Speeds, Time, Weights};

/// `inverse_dynamics_adjoint(t, q, v, v̇, u, μ) -> (μᵀ∂τ/∂q, μᵀ∂τ/∂v, μᵀ∂τ/∂u)`,
/// `∂/∂q` in the tangent space. The weights are the symbols
/// [`Sym::Multiplier`], which the unconstrained `τ` it is for does not hold
/// (the checks after the derivation refuse it with constraints).
pub fn inverse_dynamics_adjoint(model: &Model, equations: &Equations, pool: &mut Pool) -> Function {
    let (nq, nv, nu) = (model.nq(), model.nv(), model.inputs.len());
    let (tau, recursive) = inverse_dynamics(model, equations, pool);
    let weighted: Vec<(ExprId, ExprId)> = tau
        .iter()
        .enumerate()
        .map(|(i, &t)| (t, pool.sym(Sym::Multiplier(i as u32))))
        .collect();
    let by: Vec<Sym> = (0..nq as u32)
        .map(Sym::Coord)
        .chain((0..nv as u32).map(Sym::Speed))
        .chain((0..nu as u32).map(Sym::Input))
        .collect();
    let gradient = pool.gradient(&weighted, &by);
    let (by_q, rest) = gradient.split_at(nq);
    let (by_v, by_u) = rest.split_at(nv);
    // `Σ_c ∂(μᵀτ)/∂q_c · ∂q_c/∂δₖ` along each tangent direction.
    let by_tangent: Vec<ExprId> = tangent_directions(model, pool)
        .iter()
        .map(|direction| {
            let terms: Vec<ExprId> = direction
                .iter()
                .map(|&(c, moved)| pool.mul(by_q[c], moved))
                .collect();
            pool.sum(terms)
        })
        .collect();
    let derived_by = match recursive {
        true => "the Newton–Euler recursion over the kinematic tree, `O(n)`",
        false => "the mass matrix and the forcing",
    };
    let tangent = match model.balls.is_empty() {
        true => "",
        false => {
            "\n`∂/∂q` is in the tangent space, one entry per speed, along `q ⊕ δ` as\n\
             `integrate_configuration` moves (as `accelerations_jacobian`'s)."
        }
    };
    Function {
        name: Ident::new("inverse_dynamics_adjoint", Span::call_site()),
        docs: doc_lines(&format!(
            "The vector–jacobian product of the inverse dynamics\n\
             `τ(t, q, v, v̇, u) = M v̇ − f` at weights `mu` (`μ`, one per speed):\n\
             `(μᵀ ∂τ/∂q, μᵀ ∂τ/∂v, μᵀ ∂τ/∂u)`, without forming `∂τ/∂x`. Exact: the\n\
             gradient of `μᵀ τ` by one reverse sweep over `τ` (derived by\n\
             {derived_by}), each node's adjoint computed once, so it costs a\n\
             small multiple of `inverse_dynamics`. At `μ = M⁻ᵀ λ` and the solved\n\
             `v̇`, `−μᵀ ∂τ/∂x = λᵀ ∂v̇/∂x`: what\n\
             `dalembert::control::accelerations_adjoint` computes with it.{tangent}"
        )),
        arguments: vec![Time, Coordinates, Speeds, Accelerations, Inputs, Weights],
        results: vec![
            Value::vector(by_tangent),
            Value::vector(by_v.to_vec()),
            Value::vector(by_u.to_vec()),
        ],
        body: Body::Explicit,
    }
}
