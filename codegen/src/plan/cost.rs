//! What emitted code costs: the operation counts by which the plan
//! chooses between two forms of the same results. A route ([`operations`]:
//! the articulated-body recursion or the factorisation of `M`, the
//! world-frame or the symbolic partials, unrolled or looped code) is
//! charged every node once, a `sin_cos` of a coordinate at
//! [`SIN_COS_COST`]; a result's form within its function ([`cost_past`]:
//! its DAG or its compact form) only the nodes its function does not
//! compute already, the sines and cosines of single symbols free (the
//! function binds them once whatever the form).

use crate::expr::{ExprId, Func, Node, Pool, Sym};
use std::collections::HashSet;

/// Operations charged for the `sin_cos` of a coordinate (a libm call,
/// about as long as 40 multiplications).
pub const SIN_COS_COST: usize = 40;

/// Operations charged for any other elementary function.
pub const FUNCTION_COST: usize = 20;

/// Arithmetic operations (and charged functions) of the code computing
/// `roots`, each shared node once.
pub fn operations(pool: &Pool, roots: &[ExprId]) -> usize {
    pool.topo_order(roots)
        .into_iter()
        .map(|e| node_operations(pool, e))
        .sum()
}

/// Arithmetic operations (and charged functions) of the node `e` alone,
/// its children computed.
pub fn node_operations(pool: &Pool, e: ExprId) -> usize {
    match pool.node(e) {
        Node::Number(_) | Node::Sym(_) | Node::Group(_) => 0,
        Node::Add(terms) => terms.len() - 1,
        Node::Mul(factors) => factors.len() - 1,
        Node::Pow(_, _) => 1,
        Node::Func(Func::Sin | Func::Cos, arg)
            if matches!(pool.node(*arg), Node::Sym(Sym::Coord(_))) =>
        {
            SIN_COS_COST / 2
        }
        Node::Func(_, _) => FUNCTION_COST,
    }
}

/// Arithmetic operations of a function computing `results`, each shared
/// node counted once (as [`cost_past`] counts them).
pub fn function_cost(pool: &Pool, results: &[ExprId]) -> usize {
    let mut computed = HashSet::new();
    let mut total = 0;
    for &r in results {
        total += cost_past(pool, r, &computed, usize::MAX);
        pool.post_order(&[r], |n| computed.insert(n));
    }
    total
}

/// Arithmetic operations to evaluate `e` once, shared nodes counted once
/// and the nodes already `computed` not at all; sines and cosines of
/// single symbols are free (the code shares them). The count stops as soon
/// as it passes `limit` (a large DAG need not be walked to lose to a small
/// form): the result is exact up to `limit`, and above `limit` whenever the
/// exact cost is.
pub fn cost_past(pool: &Pool, e: ExprId, computed: &HashSet<ExprId>, limit: usize) -> usize {
    let mut total = 0usize;
    pool.post_order(&[e], |n| {
        if total > limit || computed.contains(&n) {
            return false;
        }
        total = total.saturating_add(node_cost(pool, n));
        true
    });
    total
}

/// The operations of one node, its children computed.
fn node_cost(pool: &Pool, n: ExprId) -> usize {
    match pool.node(n) {
        Node::Number(_) | Node::Sym(_) | Node::Group(_) => 0,
        Node::Add(items) | Node::Mul(items) => items.len() - 1,
        Node::Pow(_, exp) => exp.unsigned_abs() as usize,
        Node::Func(_, arg) if matches!(pool.node(*arg), Node::Sym(_)) => 0,
        Node::Func(..) => FUNCTION_COST,
    }
}

/// Operations of the runtime's loops over a tree's links in a looped
/// `accelerations_jacobian` (`TreeRecursion::sweep`, `mass_and_bias`,
/// `link_vectors`, `add_tree_pairs`), each link given by its parent and
/// the index of its joint's first link (its own for a one-speed joint), as
/// counted in their source (`src/dynamics/tree_vectors.rs`, `pairs.rs`;
/// `scripts/bench/op_counts.py` counts the same from the generated table):
/// per link 995 (the first pass's 189 outwards, 351 for its own inertia in
/// `N`, 42 for `y`, 11 for `f`; the second's 114 and 288), less the 351 of
/// a joint's speeds before its last (massless: skipped), plus 27 for
/// `Φ = v × S` of a joint of several speeds; 43 a child added into its
/// parent; 3 for gravity; per pair of a link and its ancestor-or-self 48
/// in the pairs and 11 in `M`; per strict ancestor 24 more, 48 within one
/// joint (the general paths of each step: a turn's or a diagonal inertia's
/// zero products are counted).
pub fn tree_loop_operations(links: &[(Option<usize>, usize)]) -> usize {
    let several = |joint: usize| {
        links
            .iter()
            .enumerate()
            .any(|(i, &(_, j))| j == joint && i != joint)
    };
    let per_link = links.iter().enumerate().map(|(i, &(parent, joint))| {
        let last = links.get(i + 1).is_none_or(|&(_, next)| next != joint);
        let own = match (several(joint), last) {
            (true, true) => 995 + 27,
            (true, false) => 995 + 27 - 351,
            (false, _) => 995,
        } + parent.map_or(0, |_| 43);
        let mut pairs = 0;
        let mut ancestor = Some(i);
        while let Some(a) = ancestor {
            pairs += 48 + 11;
            if a != i {
                pairs += if links[a].1 == joint { 48 } else { 24 };
            }
            ancestor = links[a].0;
        }
        own + pairs
    });
    3 + per_link.sum::<usize>()
}

#[cfg(test)]
mod tests {
    use super::tree_loop_operations;

    /// A free joint (six links, each the parent of the next) carrying a
    /// chain of two hinges and a hinge beside it: the count that
    /// `scripts/bench/op_counts.py` makes of the same table of links.
    #[test]
    fn the_loops_cost_what_the_op_count_script_counts() {
        let links = [
            (None, 0),
            (Some(0), 0),
            (Some(1), 0),
            (Some(2), 0),
            (Some(3), 0),
            (Some(4), 0),
            (Some(5), 6),
            (Some(6), 7),
            (Some(5), 8),
        ];
        assert_eq!(tree_loop_operations(&links), 11422);
    }
}
