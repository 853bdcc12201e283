//! The route of the partials of the inverse dynamics `τ = M v̇ − f`, which
//! `inverse_dynamics_jacobian`, `accelerations_jacobian` and `linearize`
//! return: `τ` differentiated symbolically, or (for a tree of revolute,
//! prismatic, spherical and free joints) the world-frame recursion's
//! partials, unrolled or in the runtime's loops.
//!
//! The choice is by operation count ([`operations`]), and an operation
//! count is a property of expressions: both candidates are derived here
//! and measured, and the outputs receive the partials of the route chosen
//! (their nodes stay in the pool; the other candidate's are never
//! emitted, and shared subexpressions of the two are interned once).

use super::Partials;
use super::TREE_LOOPED_ABOVE;
use super::cost::operations;
use crate::equations::derivatives::{ResidualJacobian, residual_jacobian, tangent_directions};
use crate::equations::{Equations, TreeJacobian, inverse_dynamics, tree_jacobian};
use crate::expr::{ExprId, Pool};
use crate::model::Model;

/// The partials of `τ` by the route chosen.
pub struct TauPartials {
    /// `∂τ/∂δ`, `∂τ/∂v`, `∂τ/∂u`.
    pub jacobian: ResidualJacobian,
    /// The route.
    pub route: Partials,
    /// Whether `τ` itself was derived by the Newton–Euler recursion (over
    /// the mass matrix and the forcing otherwise), for the docs of
    /// [`Partials::Symbolic`].
    pub recursive_tau: bool,
    /// With [`Partials::Looped`], the tree's recursion in its parts.
    pub tree: Option<TreeJacobian>,
}

/// The partials of `τ` of `model` by the cheaper route: those of the
/// world-frame recursion where they cost fewer operations than the
/// symbolic ones, or where both cost more than [`TREE_LOOPED_ABOVE`]
/// (then in loops, which cost no code); else `τ` differentiated.
pub fn tau_partials(model: &Model, equations: &Equations, pool: &mut Pool) -> TauPartials {
    let (tau, recursive_tau) = inverse_dynamics(model, equations, pool);
    let directions = tangent_directions(model, pool);
    let symbolic = residual_jacobian(pool, &tau, &directions, model.inputs.len());
    if let Some(tree) = tree_jacobian(model, equations, pool) {
        let combined = tree.combined(pool);
        let route = route(pool, &entries(&combined), &entries(&symbolic));
        if route != Partials::Symbolic {
            return TauPartials {
                jacobian: combined,
                route,
                recursive_tau,
                tree: (route == Partials::Looped).then_some(tree),
            };
        }
    }
    TauPartials {
        jacobian: symbolic,
        route: Partials::Symbolic,
        recursive_tau,
        tree: None,
    }
}

/// The route of the partials of a tree whose recursion's partials are
/// `recursive` and whose symbolic ones are `symbolic` (every entry).
fn route(pool: &Pool, recursive: &[ExprId], symbolic: &[ExprId]) -> Partials {
    let cost = operations(pool, recursive);
    let symbolic_cost = operations(pool, symbolic);
    if cost.min(symbolic_cost) > TREE_LOOPED_ABOVE {
        Partials::Looped
    } else if cost < symbolic_cost {
        Partials::Recursive
    } else {
        Partials::Symbolic
    }
}

/// Every entry of `jacobian`.
fn entries(jacobian: &ResidualJacobian) -> Vec<ExprId> {
    let blocks = [&jacobian.coordinates, &jacobian.speeds, &jacobian.inputs];
    blocks.into_iter().flatten().flatten().copied().collect()
}
