//! Full expansion into a sum of monomials, for rendering the equations of
//! small systems in documentation. Expansion can grow expressions
//! exponentially: the derivation itself never uses it.

use super::{ExprId, Node, Pool};

impl Pool {
    /// `e` with products distributed over sums and positive integer powers
    /// of sums multiplied out, also inside function arguments and bases of
    /// negative powers; the result is a sum of monomials (products of
    /// symbols, calls and powers). Like terms are merged after each
    /// multiplication, so `(a + b)¹⁰` has 11 terms throughout.
    pub fn expand(&mut self, e: ExprId) -> ExprId {
        self.rebuild(&[e], |pool, node, images| match *pool.node(node) {
            Node::Mul(_) => pool.distribute(images.iter().copied()),
            Node::Pow(_, exp) => pool.expand_power(images[0], exp),
            _ => pool.with_children(node, images),
        })[0]
    }

    /// `base ^ exp` for an expanded `base`, multiplied out if `base` is a
    /// sum and `exp` positive.
    fn expand_power(&mut self, base: ExprId, exp: i32) -> ExprId {
        match (self.node(base), usize::try_from(exp)) {
            (Node::Add(_), Ok(count)) => self.distribute(std::iter::repeat_n(base, count)),
            _ => self.powi(base, exp),
        }
    }

    /// The expanded product of already expanded `factors`.
    fn distribute(&mut self, factors: impl IntoIterator<Item = ExprId>) -> ExprId {
        let mut acc = self.one();
        for factor in factors {
            let left = self.terms(acc);
            let right = self.terms(factor);
            let products: Vec<ExprId> = left
                .iter()
                .flat_map(|&l| right.iter().map(move |&r| (l, r)))
                .map(|(l, r)| self.mul(l, r))
                .collect();
            acc = self.sum(products);
        }
        acc
    }

    /// The terms of `e` if it is a sum, else `[e]`.
    fn terms(&self, e: ExprId) -> Vec<ExprId> {
        match self.node(e) {
            Node::Add(terms) => terms.to_vec(),
            _ => vec![e],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_util::Scratch;
    use super::*;

    /// `expand(text)` and the canonical form of `expected`.
    fn check(text: &str, expected: &str) {
        let mut s = Scratch::default();
        s.e("q0 + q1");
        let e = s.e(text);
        let expanded = s.pool.expand(e);
        assert_eq!(s.show(expanded), expected, "expand({text})");
        assert_eq!(expanded, s.e(expected));
    }

    #[test]
    fn square_of_a_sum() {
        check("(q0 + q1)^2", "q0^2 + 2*q0*q1 + q1^2");
        check("(q0 - q1)*(q0 + q1) - q0^2 + q1^2", "0");
        check("2*(q0 + 1)*(q1 - 3)", "-6 - 6*q0 + 2*q1 + 2*q0*q1");
    }

    #[test]
    fn expands_inside_calls_and_negative_powers() {
        check("sin(2*(q0 + q1))", "sin(2*q0 + 2*q1)");
        check("1/((q0 + q1)^2 + 1)", "1/(1 + q0^2 + 2*q0*q1 + q1^2)");
        check("exp(q0)*(exp(q0) - q1)", "-q1*exp(q0) + exp(q0)^2");
    }

    #[test]
    fn like_terms_merge_during_expansion() {
        let mut s = Scratch::default();
        let e = s.e("(q0 + q1)^10");
        let expanded = s.pool.expand(e);
        assert!(matches!(s.pool.node(expanded), Node::Add(_)));
        assert_eq!(s.pool.children(expanded).len(), 11);
        assert!(s.pool.len() < 300, "{} nodes", s.pool.len());
    }
}
