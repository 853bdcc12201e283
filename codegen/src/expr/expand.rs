//! Full expansion into a sum of monomials, for rendering the equations of
//! small systems in documentation. Expansion can grow expressions
//! exponentially: the derivation itself never uses it.

use std::collections::HashMap;

use super::{ExprId, Node, Pool};

impl Pool {
    /// `e` with products distributed over sums and positive integer powers
    /// of sums multiplied out, also inside function arguments and bases of
    /// negative powers; the result is a sum of monomials (products of
    /// symbols, calls and powers). Like terms are merged after each
    /// multiplication, so `(a + b)¹⁰` has 11 terms throughout.
    pub fn expand(&mut self, e: ExprId) -> ExprId {
        let mut expanded: HashMap<ExprId, ExprId> = HashMap::new();
        for n in self.topo_order(&[e]) {
            let image = |c: ExprId| expanded[&c];
            let new = match self.node(n).clone() {
                Node::Number(_) | Node::Sym(_) => n,
                Node::Add(terms) => {
                    let terms: Vec<ExprId> = terms.iter().map(|&t| image(t)).collect();
                    self.sum(terms)
                }
                Node::Mul(factors) => {
                    let factors: Vec<ExprId> = factors.iter().map(|&f| image(f)).collect();
                    self.distribute(factors)
                }
                Node::Pow(base, exp) => self.expand_power(image(base), exp),
                Node::Func(f, arg) => self.func(f, image(arg)),
            };
            expanded.insert(n, new);
        }
        expanded[&e]
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
    use super::super::{Func, Sym};
    use super::*;

    fn name(s: Sym) -> String {
        match s {
            Sym::Coord(0) => "a".into(),
            Sym::Coord(1) => "b".into(),
            _ => format!("{s:?}"),
        }
    }

    #[test]
    fn square_of_a_sum() {
        let mut p = Pool::new();
        let (a, b) = (p.sym(Sym::Coord(0)), p.sym(Sym::Coord(1)));
        let square = p.powi(p.add(a, b), 2);
        let expanded = p.expand(square);
        let expected = {
            let terms = [p.powi(a, 2), p.product([p.int(2), a, b]), p.powi(b, 2)];
            p.sum(terms)
        };
        assert_eq!(expanded, expected);
        assert_eq!(p.display(expanded, &name), "a^2 + 2*a*b + b^2");
    }

    #[test]
    fn products_distribute_and_cancel() {
        let mut p = Pool::new();
        let (a, b) = (p.sym(Sym::Coord(0)), p.sym(Sym::Coord(1)));
        // (a + b)(a - b) - a² + b² = 0 once expanded.
        let e = {
            let product = p.mul(p.add(a, b), p.sub(a, b));
            let rest = p.sub(p.powi(b, 2), p.powi(a, 2));
            p.add(product, rest)
        };
        assert_ne!(e, p.zero());
        assert_eq!(p.expand(e), p.zero());
        // Inside function arguments too, and (a+b)^10 has 11 terms.
        let s = p.sin(p.mul(p.int(2), p.add(a, b)));
        let expected = p.sin(p.add(p.mul(p.int(2), a), p.mul(p.int(2), b)));
        assert_eq!(p.expand(s), expected);
        let tenth = p.powi(p.add(a, b), 10);
        let expanded = p.expand(tenth);
        assert_eq!(p.children(expanded).len(), 11);
        assert!(matches!(p.node(expanded), Node::Add(_)));
        // Negative powers keep their (expanded) base: 1/((a+b)² + 1).
        let inv = p.powi(p.add(p.powi(p.add(a, b), 2), p.one()), -1);
        let expected = {
            let terms = [p.one(), p.powi(a, 2), p.product([p.int(2), a, b]), p.powi(b, 2)];
            let base = p.sum(terms);
            p.powi(base, -1)
        };
        assert_eq!(p.expand(inv), expected);
        assert_eq!(p.expand(p.func(Func::Exp, a)), p.func(Func::Exp, a));
    }
}
