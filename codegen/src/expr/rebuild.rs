//! Bottom-up rewriting of a DAG into the same pool: the one traversal
//! behind every pass that maps each node to a new expression built from
//! the images of its children (ungrouping, expansion, the addition
//! formulas).

use std::collections::HashMap;

use super::{ExprId, Node, Pool};

impl Pool {
    /// The images of `roots` under the rewrite `f`, in the order of
    /// `roots`. `f(pool, node, images)` gives the image of `node` from the
    /// images of its children (`images[i]` is that of
    /// [`children`](Pool::children)`(node)[i]`; empty for a leaf).
    ///
    /// Invariant: `f` is called exactly once per distinct node reachable
    /// from `roots` and for no other, children before parents, so every
    /// child has its image when its parent is rewritten and a shared
    /// subexpression is rewritten once, all its parents seeing the same
    /// image. The order of the calls depends only on the DAG and the order
    /// of `roots` ([`topo_order`](Pool::topo_order)), so the ids the
    /// rewrite interns do too.
    pub fn rebuild(
        &mut self,
        roots: &[ExprId],
        mut f: impl FnMut(&mut Pool, ExprId, &[ExprId]) -> ExprId,
    ) -> Vec<ExprId> {
        let images = self.try_rebuild(roots, |pool, node, images| Some(f(pool, node, images)));
        let Some(images) = images else {
            unreachable!("every node has an image")
        };
        images
    }

    /// [`rebuild`](Pool::rebuild) with a rewrite that may fail: `None` as
    /// soon as `f` gives `None` for a node (no node is visited after it),
    /// else the images of `roots`. The same invariant.
    pub fn try_rebuild(
        &mut self,
        roots: &[ExprId],
        mut f: impl FnMut(&mut Pool, ExprId, &[ExprId]) -> Option<ExprId>,
    ) -> Option<Vec<ExprId>> {
        let mut image: HashMap<ExprId, ExprId> = HashMap::new();
        for node in self.topo_order(roots) {
            let images: Vec<ExprId> = self.children(node).iter().map(|c| image[c]).collect();
            let rebuilt = f(self, node, &images)?;
            image.insert(node, rebuilt);
        }
        Some(roots.iter().map(|r| image[r]).collect())
    }

    /// `node` built again over `children` (one per child of `node`, in
    /// order) by the canonicalising constructors; a leaf is itself. The
    /// identity rewrite of [`rebuild`](Pool::rebuild), for the nodes a
    /// pass leaves alone.
    pub fn with_children(&mut self, node: ExprId, children: &[ExprId]) -> ExprId {
        match *self.node(node) {
            Node::Number(_) | Node::Sym(_) => node,
            Node::Add(_) => self.sum(children.iter().copied()),
            Node::Mul(_) => self.product(children.iter().copied()),
            Node::Pow(_, exp) => self.powi(children[0], exp),
            Node::Func(f, _) => self.func(f, children[0]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_util::Scratch;
    use super::*;
    use crate::expr::{Func, Sym};

    #[test]
    fn the_identity_rewrite_gives_the_roots_back() {
        let mut s = Scratch::default();
        let roots = [
            s.e("(2*sin(q0)*q1 + sin(q0))^3"),
            s.e("q1/cos(q0 - q1)"),
            s.e("5"),
        ];
        let images = s.pool.rebuild(&roots, Pool::with_children);
        assert_eq!(images, roots);
    }

    #[test]
    fn each_node_is_rewritten_once_children_first() {
        let mut s = Scratch::default();
        let shared = s.e("sin(q0)*q1");
        let roots = [s.e("sin(q0)*q1 + q2"), s.e("(sin(q0)*q1)^2"), shared];
        let mut visited: Vec<ExprId> = Vec::new();
        s.pool.rebuild(&roots, |pool, node, images| {
            assert_eq!(images.len(), pool.children(node).len());
            for child in pool.children(node) {
                assert!(visited.contains(child), "a child after its parent");
            }
            assert!(!visited.contains(&node), "a node rewritten twice");
            visited.push(node);
            pool.with_children(node, images)
        });
        assert_eq!(visited, s.pool.topo_order(&roots));
    }

    #[test]
    fn a_rewrite_reaches_every_occurrence_and_recanonicalises() {
        let mut s = Scratch::default();
        let roots = [s.e("q0*cos(q1) + q0^2"), s.e("sin(q0 + q1)")];
        let q1 = s.e("q1");
        // q0 ↦ q1: like terms and factors meet and merge.
        let images = s
            .pool
            .rebuild(&roots, |pool, node, images| match pool.node(node) {
                Node::Sym(Sym::Coord(0)) => q1,
                _ => pool.with_children(node, images),
            });
        let expected = [s.e("q1*cos(q1) + q1^2"), s.e("sin(2*q1)")];
        assert_eq!(images, expected);
    }

    #[test]
    fn a_failing_rewrite_stops_at_the_first_failure() {
        let mut s = Scratch::default();
        let roots = [s.e("sqrt(q0) + tan(q1) + tan(q2)")];
        let mut calls = 0;
        let images = s.pool.try_rebuild(&roots, |pool, node, images| {
            calls += 1;
            match pool.node(node) {
                Node::Func(Func::Tan, _) => None,
                _ => Some(pool.with_children(node, images)),
            }
        });
        assert_eq!(images, None);
        let first_tan = s
            .pool
            .topo_order(&roots)
            .iter()
            .position(|&n| matches!(s.pool.node(n), Node::Func(Func::Tan, _)));
        assert_eq!(Some(calls - 1), first_tan);
    }
}
