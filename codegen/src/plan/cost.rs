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
