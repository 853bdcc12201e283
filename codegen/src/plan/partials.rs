//! The route of the partials of the inverse dynamics `τ = M v̇ − f`, which
//! `inverse_dynamics_jacobian`, `accelerations_jacobian` and `linearize`
//! return: `τ` differentiated symbolically, or (for a tree of revolute,
//! prismatic, spherical and free joints) the world-frame recursion's
//! partials, unrolled or in the runtime's loops.
//!
//! The choice is by operation count ([`operations`], and for the looped
//! route its loops' own, [`tree_loop_operations`]), and an operation
//! count is a property of expressions: both candidates are derived here
//! and measured, and the outputs receive the partials of the route chosen
//! (their nodes stay in the pool; the other candidate's are never
//! emitted, and shared subexpressions of the two are interned once).

use super::Partials;
use super::cost::{operations, tree_loop_operations};
use super::{STREAMED_PERCENT, TREE_LOOPED_ABOVE};
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

/// The partials of `τ` of `model` by the cheapest route ([`route`]);
/// `τ` differentiated where the model is no tree the recursion takes.
pub fn tau_partials(model: &Model, equations: &Equations, pool: &mut Pool) -> TauPartials {
    let (tau, recursive_tau) = inverse_dynamics(model, equations, pool);
    let directions = tangent_directions(model, pool);
    let symbolic = residual_jacobian(pool, &tau, &directions, model.inputs.len());
    if let Some(tree) = tree_jacobian(model, equations, pool) {
        let combined = tree.combined(pool);
        let costs = Costs {
            symbolic: operations(pool, &entries(&symbolic)),
            recursive: operations(pool, &entries(&combined)),
            looped: looped_operations(pool, &tree),
        };
        let route = route(costs);
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

/// The operations of the partials of `τ` by each route.
#[derive(Clone, Copy)]
struct Costs {
    /// `τ` differentiated, unrolled.
    symbolic: usize,
    /// The recursion's partials, unrolled.
    recursive: usize,
    /// The straight-line code of the looped route (the rest of the
    /// partials, the links' states, gravity, the rest of `τ`) and the
    /// runtime's loops ([`tree_loop_operations`]).
    looped: usize,
}

/// The route of least charged operations: the looped route at its count,
/// an unrolled one at its count and, above [`TREE_LOOPED_ABOVE`], the
/// operations past it again at [`STREAMED_PERCENT`] (its code streams from
/// memory); of two unrolled routes at one charge, the symbolic.
fn route(costs: Costs) -> Partials {
    let streamed =
        |ops: usize| ops + ops.saturating_sub(TREE_LOOPED_ABOVE) * (STREAMED_PERCENT - 100) / 100;
    let candidates = [
        (streamed(costs.symbolic), Partials::Symbolic),
        (streamed(costs.recursive), Partials::Recursive),
        (costs.looped, Partials::Looped),
    ];
    candidates
        .into_iter()
        .min_by_key(|&(charged, _)| charged)
        .map_or(Partials::Symbolic, |(_, route)| route)
}

/// The operations of the looped route of `tree`: its straight-line code
/// and the runtime's loops.
fn looped_operations(pool: &Pool, tree: &TreeJacobian) -> usize {
    let mut straight = entries(&tree.rest);
    straight.extend(tree.states.iter().flat_map(|s| s.entries()));
    straight.extend(tree.gravity);
    straight.extend(&tree.residual);
    let links: Vec<(Option<usize>, usize)> =
        tree.links.iter().map(|l| (l.parent, l.joint)).collect();
    operations(pool, &straight) + tree_loop_operations(&links)
}

/// Every entry of `jacobian`.
fn entries(jacobian: &ResidualJacobian) -> Vec<ExprId> {
    let blocks = [&jacobian.coordinates, &jacobian.speeds, &jacobian.inputs];
    blocks.into_iter().flatten().flatten().copied().collect()
}
