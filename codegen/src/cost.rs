//! What emitted code costs: the operation counts by which the generator
//! chooses between two forms of the same results (the articulated-body
//! recursion or the factorisation of `M`; the world-frame or the symbolic
//! partials of the derivatives; an entry's DAG or its compact form).

use crate::expr::{ExprId, Func, Node, Pool, Sym};

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
        Node::Number(_) | Node::Sym(_) | Node::Func(Func::Group, _) => 0,
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
