//! The plan of `M v̇ = f`'s solve in an unconstrained system: the unrolled
//! square-root-free Cholesky factorisation `M = L D Lᵀ`, which skips every
//! entry of `L` that the structural zeros of `M` make zero, with the
//! speeds eliminated in their order or in the reverse, whichever fills in
//! less (for a tree, parents before children, the reverse eliminates every
//! child before its parent and fills in nothing: Featherstone's `Lᵀ D L`
//! of branch-induced sparsity, where a floating base eliminated first
//! would fill in every block); and the route of `accelerations`, that
//! factorisation or, for kinematic trees, the articulated-body recursion
//! derived with the equations (`O(n)`, see `equations::articulated`),
//! which never forms `M` and wins for long chains.

use super::cost::operations;
use super::{
    ARTICULATED_PERCENT, FLOATING_ARTICULATED_PERCENT, LANES_ARTICULATED_PERCENT, MIN_ARTICULATED,
};
use crate::equations::Equations;
use crate::expr::{ExprId, Pool};
use crate::model::Model;

/// The unrolled `L D Lᵀ` factorisation of `M`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Factorisation {
    /// The speeds in the order of elimination: `order[i]` is the `i`-th
    /// eliminated.
    pub order: Vec<usize>,
    /// `pattern[i][j]` (`j ≤ i`, rows of the elimination order): whether
    /// `Lᵢⱼ` can be nonzero.
    pub pattern: Vec<Vec<bool>>,
}

/// How `accelerations` solves `M q̈ = f`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Accelerations {
    /// By the unrolled factorisation.
    Factorised,
    /// By the articulated-body recursion (`M` is never formed).
    Articulated,
}

/// The elimination of `M x = f` that fills in less, in the speeds' order
/// or the reverse; `None` for a system with constraints or no
/// coordinates.
pub fn factorisation(model: &Model, pool: &Pool, equations: &Equations) -> Option<Factorisation> {
    let nv = model.nv();
    if !model.constraints.is_empty() || nv == 0 {
        return None;
    }
    [false, true]
        .map(|reversed| {
            let order: Vec<usize> = match reversed {
                true => (0..nv).rev().collect(),
                false => (0..nv).collect(),
            };
            let pattern = fill_pattern(pool, equations, &order);
            Factorisation { order, pattern }
        })
        .into_iter()
        .min_by_key(|f| factorisation_operations(&f.pattern))
}

/// The routes of `accelerations` (`scalar`) and of `accelerations_x4`
/// (`lanes`, four states at once).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Routes {
    /// The route of `accelerations`.
    pub scalar: Accelerations,
    /// The route of `accelerations_x4`.
    pub lanes: Accelerations,
}

/// The articulated-body recursion where the model has one and it costs
/// fewer operations, charged at [`ARTICULATED_PERCENT`] (on a floating
/// base [`FLOATING_ARTICULATED_PERCENT`]; over the lanes
/// [`LANES_ARTICULATED_PERCENT`] where that is lower), than forming `M`
/// and `f` (together, sharing their subexpressions) and factorising;
/// systems of fewer than [`MIN_ARTICULATED`] coordinates keep the
/// factorisation.
pub fn accelerations(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    factorisation: &Factorisation,
) -> Routes {
    let Some(articulated) = &equations.articulated else {
        return Routes {
            scalar: Accelerations::Factorised,
            lanes: Accelerations::Factorised,
        };
    };
    let mass_and_forcing: Vec<ExprId> = equations
        .mass_matrix
        .iter()
        .flatten()
        .chain(&equations.forcing)
        .copied()
        .collect();
    let factorised =
        operations(pool, &mass_and_forcing) + factorisation_operations(&factorisation.pattern);
    let recursion = operations(pool, &articulated.roots());
    let charged_at = |percent: usize| match model.nq() >= MIN_ARTICULATED
        && recursion * percent < factorised * 100
    {
        true => Accelerations::Articulated,
        false => Accelerations::Factorised,
    };
    let percent = articulated_percent(model);
    Routes {
        scalar: charged_at(percent),
        lanes: charged_at(percent.min(LANES_ARTICULATED_PERCENT)),
    }
}

/// The charge of the articulated-body recursion's operations, in percent:
/// [`FLOATING_ARTICULATED_PERCENT`] on a floating base (a free joint),
/// [`ARTICULATED_PERCENT`] otherwise.
fn articulated_percent(model: &Model) -> usize {
    match model.balls.iter().any(|b| b.translation.is_some()) {
        true => FLOATING_ARTICULATED_PERCENT,
        false => ARTICULATED_PERCENT,
    }
}

/// Multiplications, subtractions and divisions of the unrolled `L D Lᵀ`
/// solve with fill pattern `pattern`.
fn factorisation_operations(pattern: &[Vec<bool>]) -> usize {
    let nq = pattern.len();
    let shared = |i: usize, j: usize| (0..j).filter(|&k| pattern[i][k] && pattern[j][k]).count();
    (0..nq)
        .map(|j| {
            // Lᵢⱼ Dⱼ, then Lᵢⱼ, and its share of both substitutions.
            let column: usize = (j + 1..nq)
                .filter(|&i| pattern[i][j])
                .map(|i| 2 * shared(i, j) + 5)
                .sum();
            // The pivot, its reciprocal, and the column.
            2 * shared(j, j) + 2 + column
        })
        .sum()
}

/// `pattern[i][j]` (`j ≤ i`, rows of the elimination `order`): whether
/// `Lᵢⱼ` can be nonzero — `M`'s entry is not structurally zero, or fill-in
/// through an earlier column.
fn fill_pattern(pool: &Pool, equations: &Equations, order: &[usize]) -> Vec<Vec<bool>> {
    let nq = order.len();
    let mut pattern: Vec<Vec<bool>> = (0..nq)
        .map(|i| {
            (0..=i)
                .map(|j| !pool.is_zero(equations.mass_matrix[order[i]][order[j]]))
                .collect()
        })
        .collect();
    for j in 0..nq {
        for i in j + 1..nq {
            let fill = (0..j).any(|k| pattern[i][k] && pattern[j][k]);
            pattern[i][j] |= fill;
        }
    }
    pattern
}
