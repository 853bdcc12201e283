//! Reverse-mode differentiation: the gradient of one weighted sum of
//! expressions, `s = Σᵢ wᵢ eᵢ`, by chosen symbols, as expressions whose
//! size is a small multiple of the DAG of the `eᵢ` — where forward partials
//! ([`Pool::diff`]) build one derivative DAG per symbol.
//!
//! Each node `n` gets an adjoint `n̄ = ∂s/∂n`: the roots their weights, and
//! every other node the sum over its parents `p` of `p̄ · ∂p/∂n`, the local
//! partial of one node by one child (`1` in a sum, the other factors in a
//! product, `k bᵏ⁻¹` for a power, `f′(x)` for a function). Nodes are taken
//! parents before children (the reverse of [`Pool::post_order`]), so an
//! adjoint is complete when its node is reached; a symbol's adjoint is the
//! gradient's entry.
//!
//! The invariant that keeps the result linear in the DAG: every adjoint
//! that is a sum is [`Pool::group`]ed before it is used, so a parent's
//! adjoint stays one operand of its children's sums instead of flattening
//! into them (a chain of sums would otherwise copy each running total into
//! the next). Each edge of the DAG then adds one product and one term, and
//! only the nodes that may contain a chosen symbol are visited.

use super::kinds::SymKinds;
use super::{ExprId, Node, Pool, Sym};
use std::collections::HashMap;

impl Pool {
    /// `∂(Σᵢ wᵢ eᵢ)/∂s` for each `s` of `by`, for the `(eᵢ, wᵢ)` of
    /// `weighted`, by one reverse sweep over the `eᵢ` (see the module's
    /// docs); a symbol no `eᵢ` contains gets zero.
    pub fn gradient(&mut self, weighted: &[(ExprId, ExprId)], by: &[Sym]) -> Vec<ExprId> {
        let kinds = by
            .iter()
            .fold(SymKinds::EMPTY, |kinds, s| kinds.union(s.kind()));
        let roots: Vec<ExprId> = weighted.iter().map(|&(e, _)| e).collect();
        let order = self.post_order(&roots, |n| self.kinds(n).intersects(kinds));
        let mut contributions: HashMap<ExprId, Vec<ExprId>> = HashMap::new();
        for &(e, w) in weighted {
            contributions.entry(e).or_default().push(w);
        }
        let mut adjoints: HashMap<Sym, ExprId> = HashMap::new();
        for &n in order.iter().rev() {
            let Some(terms) = contributions.remove(&n) else {
                continue;
            };
            let sum = self.sum(terms);
            let adjoint = self.group(sum);
            if self.is_zero(adjoint) {
                continue;
            }
            if let Node::Sym(s) = *self.node(n) {
                adjoints.insert(s, adjoint);
                continue;
            }
            for (i, child) in self.children(n).to_vec().into_iter().enumerate() {
                if !self.kinds(child).intersects(kinds) {
                    continue;
                }
                let local = self.local_partial(n, i);
                let contribution = self.mul(adjoint, local);
                contributions.entry(child).or_default().push(contribution);
            }
        }
        by.iter()
            .map(|s| adjoints.get(s).copied().unwrap_or(self.zero()))
            .collect()
    }

    /// `∂n/∂c` for the `i`-th child `c` of `n`, a node with children.
    fn local_partial(&mut self, n: ExprId, i: usize) -> ExprId {
        match self.node(n).clone() {
            Node::Add(_) | Node::Group(_) => self.one(),
            Node::Mul(factors) => {
                let others = factors
                    .iter()
                    .enumerate()
                    .filter(|&(j, _)| j != i)
                    .map(|(_, &f)| f);
                self.product(others.collect::<Vec<_>>())
            }
            Node::Pow(base, exp) => {
                let (k, power) = (self.int(i64::from(exp)), self.powi(base, exp - 1));
                self.mul(k, power)
            }
            Node::Func(f, arg) => self.func_derivative(f, n, arg),
            Node::Number(_) | Node::Sym(_) => self.zero(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_util::{Point, Rng, SYMS, Scratch, assert_close, random_expression};
    use super::*;

    #[test]
    fn gradients_of_random_expressions_match_the_forward_partials() {
        let mut s = Scratch::default();
        let mut rng = Rng::new(11);
        let by = [Sym::Coord(0), Sym::Coord(1), Sym::Speed(0), Sym::Input(0)];
        let mut checked = 0;
        for _ in 0..40 {
            let roots: Vec<ExprId> = (0..3)
                .map(|_| random_expression(&mut s.pool, &mut rng, 4))
                .collect();
            let weights: Vec<ExprId> = (0..3).map(|i| s.pool.sym(Sym::Multiplier(i))).collect();
            let weighted: Vec<(ExprId, ExprId)> = roots.iter().copied().zip(weights).collect();
            let gradient = s.pool.gradient(&weighted, &by);
            let mut point_syms = SYMS.to_vec();
            point_syms.extend((0..3).map(Sym::Multiplier));
            let point = Point::random(&mut rng, &point_syms);
            for (&sym, &entry) in by.iter().zip(&gradient) {
                let forward: f64 = roots
                    .iter()
                    .enumerate()
                    .map(|(i, &e)| {
                        let partial = s.pool.diff(e, sym);
                        point.0[&Sym::Multiplier(i as u32)] * s.pool.eval(partial, &point)
                    })
                    .sum();
                let reverse = s.pool.eval(entry, &point);
                if !forward.is_finite() {
                    continue;
                }
                assert_close(reverse, forward, 1e-10, &format!("∂/∂{sym:?}"));
                checked += 1;
            }
        }
        assert!(checked > 100, "only {checked} finite gradients checked");
    }

    #[test]
    fn symbols_absent_from_the_roots_have_zero_gradient() {
        let mut s = Scratch::default();
        let e = s.e("p0*sin(q0)*u0");
        let w = s.pool.sym(Sym::Multiplier(0));
        let gradient = s.pool.gradient(&[(e, w)], &[Sym::Coord(1), Sym::Input(0)]);
        assert_eq!(gradient, vec![s.pool.zero(); 2]);
        let gradient = s.pool.gradient(&[(e, w)], &[Sym::Speed(0)]);
        assert_eq!(gradient, vec![s.e("l0*p0*sin(q0)")]);
    }

    /// The running totals of a chain of sums, `sₖ = sₖ₋₁ + qₖ sₖ₋₁²`,
    /// grouped as the recursions group them: the gradient of the last has
    /// a bounded number of new nodes per step, not a growing one.
    #[test]
    fn the_gradient_of_a_chain_of_sums_grows_linearly() {
        let new_nodes = |steps: u32| -> usize {
            let mut pool = Pool::with_positive_sums();
            let mut total = pool.sym(Sym::Coord(0));
            for k in 1..=steps {
                let q = pool.sym(Sym::Coord(k));
                let square = pool.powi(total, 2);
                let term = pool.mul(q, square);
                let sum = pool.sum([total, term]);
                total = pool.group(sum);
            }
            let before = pool.len();
            let w = pool.sym(Sym::Multiplier(0));
            let by: Vec<Sym> = (0..=steps).map(Sym::Coord).collect();
            let gradient = pool.gradient(&[(total, w)], &by);
            assert!(gradient.iter().all(|&g| !pool.is_zero(g)));
            pool.len() - before
        };
        let (short, long) = (new_nodes(20), new_nodes(40));
        assert!(
            long <= 2 * short + 20,
            "{short} new nodes for 20 steps, {long} for 40"
        );
    }
}
