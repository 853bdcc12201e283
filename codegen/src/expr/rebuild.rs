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
        f: impl FnMut(&mut Pool, ExprId, &[ExprId]) -> Option<ExprId>,
    ) -> Option<Vec<ExprId>> {
        self.try_rebuild_remembering(roots, &mut HashMap::new(), f)
    }

    /// [`try_rebuild`](Pool::try_rebuild) with the images kept in `known`
    /// across calls, failures included (`None`): a node already there is
    /// neither rewritten again nor descended into, and meeting a known
    /// failure fails the call at once. So rewriting many roots that share
    /// subexpressions, one call each, costs what one call over all of them
    /// would. A call that fails leaves the ancestors of the failing node
    /// unknown.
    ///
    /// The calls of `f` are those of [`try_rebuild`](Pool::try_rebuild)
    /// on the same roots, in the same order, less the ones whose image is
    /// known: the same depth-first post-order, pruned at known nodes, and
    /// stopped where a known failure would be rewritten (to fail) again.
    /// So a pure rewrite interns the same nodes in the same order, and
    /// the ids are as if nothing had been remembered.
    pub fn try_rebuild_remembering(
        &mut self,
        roots: &[ExprId],
        known: &mut HashMap<ExprId, Option<ExprId>>,
        mut f: impl FnMut(&mut Pool, ExprId, &[ExprId]) -> Option<ExprId>,
    ) -> Option<Vec<ExprId>> {
        // An explicit stack of (node, next child), so that deep
        // expressions cannot overflow the call stack.
        let mut stack: Vec<(ExprId, usize)> = Vec::new();
        for &root in roots {
            match known.get(&root) {
                Some(None) => return None,
                Some(Some(_)) => continue,
                None => stack.push((root, 0)),
            }
            while let Some((node, next)) = stack.last_mut() {
                let node = *node;
                match self.children(node).get(*next).copied() {
                    Some(child) => {
                        *next += 1;
                        match known.get(&child) {
                            Some(None) => return None,
                            Some(Some(_)) => {}
                            None => stack.push((child, 0)),
                        }
                    }
                    None => {
                        stack.pop();
                        let images: Vec<ExprId> = self
                            .children(node)
                            .iter()
                            .map(|c| known[c])
                            .collect::<Option<_>>()?;
                        let rebuilt = f(self, node, &images);
                        known.insert(node, rebuilt);
                        rebuilt?;
                    }
                }
            }
        }
        roots.iter().map(|r| known[r]).collect()
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
            Node::Group(_) => self.regroup(children[0]),
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

    /// The rewrite of the tests: squares every sine, refuses tangents.
    fn square_sines(pool: &mut Pool, node: ExprId, images: &[ExprId]) -> Option<ExprId> {
        match pool.node(node) {
            Node::Func(Func::Tan, _) => None,
            Node::Func(Func::Sin, _) => {
                let sine = pool.with_children(node, images);
                Some(pool.powi(sine, 2))
            }
            _ => Some(pool.with_children(node, images)),
        }
    }

    #[test]
    fn remembered_images_are_those_of_one_rewrite_each_node_once() {
        let mut s = Scratch::default();
        let roots = [
            s.e("sin(q0)*q1 + q2"),
            s.e("(sin(q0)*q1)^2 + cos(q2)"),
            s.e("sin(q0)*q1"),
        ];
        let mut known = HashMap::new();
        let mut calls = 0;
        let mut counted = |pool: &mut Pool, node: ExprId, images: &[ExprId]| {
            calls += 1;
            square_sines(pool, node, images)
        };
        let remembered: Vec<ExprId> = roots
            .iter()
            .map(|&r| {
                s.pool
                    .try_rebuild_remembering(&[r], &mut known, &mut counted)
            })
            .map(|images| images.expect("no tangent")[0])
            .collect();
        assert_eq!(
            calls,
            s.pool.topo_order(&roots).len(),
            "a node rewritten twice"
        );
        let at_once = s.pool.try_rebuild(&roots, square_sines);
        assert_eq!(Some(remembered), at_once);
    }

    #[test]
    fn a_remembered_failure_fails_its_ancestors_without_a_call() {
        let mut s = Scratch::default();
        let failing = s.e("tan(q1)*q0");
        let root = s.e("tan(q1)*q0 + sin(q2)");
        let mut known = HashMap::new();
        assert_eq!(
            s.pool
                .try_rebuild_remembering(&[failing], &mut known, square_sines),
            None
        );
        let mut asked = Vec::new();
        let images = s
            .pool
            .try_rebuild_remembering(&[root], &mut known, |pool, node, images| {
                asked.push(node);
                square_sines(pool, node, images)
            });
        assert_eq!(images, None);
        let tan = s.e("tan(q1)");
        assert!(!asked.contains(&tan), "the known failure was asked again");
        assert!(
            !asked.contains(&root),
            "the root was asked with a failed child"
        );
    }
}
