//! The canonicalising constructors of sums, products and powers (the rules
//! are in the [module docs](super)).
//!
//! Choices beyond those rules: sum terms are ordered by the id of their
//! coefficient-free part, so the constant (whose part is `1`) leads and a
//! term keeps its place when its coefficient changes; product factors are
//! ordered by the id of their base; an integer power of a product is
//! distributed over its factors (`(2xy)⁻¹ = 1/2·x⁻¹·y⁻¹`), never over a sum.

use super::{ExprId, Node, Number, Pool};

impl Pool {
    /// `a + b`.
    pub fn add(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.sum([a, b])
    }

    /// `a - b`.
    pub fn sub(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let minus_b = self.neg(b);
        self.sum([a, minus_b])
    }

    /// `-a`, that is `(-1) · a` (a sum is not distributed over).
    pub fn neg(&mut self, a: ExprId) -> ExprId {
        let minus_one = self.int(-1);
        self.product([minus_one, a])
    }

    /// The canonical sum of `terms` (zero if there are none).
    pub fn sum<I: IntoIterator<Item = ExprId>>(&mut self, terms: I) -> ExprId {
        let mut constant = Number::ZERO;
        let mut parts = Vec::new();
        for term in terms {
            self.collect_term(term, &mut constant, &mut parts);
        }
        parts.sort_by_key(|&(rest, _)| rest);
        let merged = merge_sorted(parts, |a, b| Some(a.add(b)));
        let mut out = Vec::with_capacity(merged.len() + 1);
        if !constant.is_zero() {
            out.push(self.number(constant));
        }
        for (rest, c) in merged {
            if !c.is_zero() {
                out.push(self.scale(c, rest));
            }
        }
        match out.as_slice() {
            [] => self.zero(),
            [single] => *single,
            _ => self.intern(Node::Add(out.into())),
        }
    }

    /// Adds `term` to a sum under construction: numbers to `constant`,
    /// others as `(rest, coefficient)` to `parts`; sums are flattened.
    fn collect_term(&self, term: ExprId, constant: &mut Number, parts: &mut Vec<(ExprId, Number)>) {
        match self.node(term) {
            Node::Number(n) => *constant = constant.add(*n),
            // Terms of a canonical sum are never sums: one level suffices.
            Node::Add(terms) => {
                for &t in terms.iter() {
                    self.collect_term(t, constant, parts);
                }
            }
            _ => {
                let (c, rest) = self.split_coefficient(term);
                parts.push((rest, c));
            }
        }
    }

    /// `c · rest` for a coefficient-free, non-numeric `rest`.
    pub(super) fn scale(&mut self, c: Number, rest: ExprId) -> ExprId {
        if c.is_zero() {
            return self.zero();
        }
        if c.is_one() {
            return rest;
        }
        let coefficient = self.number(c);
        let factors: Box<[ExprId]> = match self.node(rest) {
            Node::Mul(factors) => std::iter::once(coefficient).chain(factors.iter().copied()).collect(),
            _ => [coefficient, rest].into(),
        };
        self.intern(Node::Mul(factors))
    }

    /// `a · b`.
    pub fn mul(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.product([a, b])
    }

    /// `a / b`, that is `a · b⁻¹`.
    pub fn div(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let recip = self.powi(b, -1);
        self.product([a, recip])
    }

    /// The canonical product of `factors` (one if there are none).
    pub fn product<I: IntoIterator<Item = ExprId>>(&mut self, factors: I) -> ExprId {
        let mut coefficient = Number::ONE;
        let mut powers = Vec::new();
        for factor in factors {
            self.collect_factor(factor, &mut coefficient, &mut powers);
        }
        if coefficient.is_zero() {
            return self.zero();
        }
        powers.sort_by_key(|&(base, _)| base);
        // An exponent sum beyond i32 keeps the powers apart (never panics).
        let merged = merge_sorted(powers, i32::checked_add);
        let mut out = Vec::with_capacity(merged.len() + 1);
        if !coefficient.is_one() {
            out.push(self.number(coefficient));
        }
        for (base, exp) in merged {
            match exp {
                0 => {}
                1 => out.push(base),
                _ => out.push(self.intern(Node::Pow(base, exp))),
            }
        }
        match out.as_slice() {
            [] => self.number(coefficient),
            [single] => *single,
            _ => self.intern(Node::Mul(out.into())),
        }
    }

    /// Multiplies `factor` into a product under construction: numbers into
    /// `coefficient`, others as `(base, exponent)` to `powers`; products are
    /// flattened.
    fn collect_factor(
        &self,
        factor: ExprId,
        coefficient: &mut Number,
        powers: &mut Vec<(ExprId, i32)>,
    ) {
        match self.node(factor) {
            Node::Number(n) => *coefficient = coefficient.mul(*n),
            // Factors of a canonical product are never products.
            Node::Mul(factors) => {
                for &f in factors.iter() {
                    self.collect_factor(f, coefficient, powers);
                }
            }
            Node::Pow(base, exp) => powers.push((*base, *exp)),
            _ => powers.push((factor, 1)),
        }
    }

    /// `base ^ exp`, folded for numbers, nested powers and products.
    pub fn powi(&mut self, base: ExprId, exp: i32) -> ExprId {
        match (exp, self.node(base)) {
            (0, _) => self.one(),
            (1, _) => base,
            (_, Node::Number(n)) => self.number(n.powi(exp)),
            (_, &Node::Pow(inner, e)) => match e.checked_mul(exp) {
                Some(total) => self.powi(inner, total),
                // Left nested rather than wrong or panicking.
                None => self.intern(Node::Pow(base, exp)),
            },
            (_, Node::Mul(factors)) => {
                let factors = factors.to_vec();
                let powers: Vec<ExprId> = factors.into_iter().map(|f| self.powi(f, exp)).collect();
                self.product(powers)
            }
            _ => self.intern(Node::Pow(base, exp)),
        }
    }
}

/// Merges runs of equal keys in a sorted list by combining their values;
/// where `combine` fails, the run is split there.
fn merge_sorted<V: Copy>(
    sorted: Vec<(ExprId, V)>,
    combine: impl Fn(V, V) -> Option<V>,
) -> Vec<(ExprId, V)> {
    let mut out: Vec<(ExprId, V)> = Vec::with_capacity(sorted.len());
    for (key, value) in sorted {
        let combined = match out.last() {
            Some(&(last, acc)) if last == key => combine(acc, value),
            _ => None,
        };
        match combined {
            Some(v) => out.last_mut().expect("a run to merge into").1 = v,
            None => out.push((key, value)),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::Sym;
    use super::*;

    fn xyz(p: &mut Pool) -> (ExprId, ExprId, ExprId) {
        (p.sym(Sym::Coord(0)), p.sym(Sym::Coord(1)), p.sym(Sym::Param(0)))
    }

    #[test]
    fn like_terms_merge_and_cancel() {
        let mut p = Pool::new();
        let (x, y, _) = xyz(&mut p);
        let two_x = p.mul(p.int(2), x);
        assert_eq!(p.add(x, x), two_x);
        assert_eq!(p.sub(x, x), p.zero());
        let xy = p.mul(x, y);
        let yx = p.mul(y, x);
        assert_eq!(xy, yx);
        let a = p.sum([xy, y, x, xy]);
        let b = p.sum([y, x, p.mul(p.int(2), yx)]);
        assert_eq!(a, b);
        assert_eq!(p.sum([]), p.zero());
        assert_eq!(p.sum([x]), x);
    }

    #[test]
    fn rational_constants_fold() {
        let mut p = Pool::new();
        let (a, b, c) = (p.rational(1, 3), p.rational(1, 6), p.rational(-1, 2));
        assert_eq!(p.sum([a, b, c]), p.zero());
        let (x, _, _) = xyz(&mut p);
        let s = p.sum([x, a, x, b]);
        assert_eq!(p.node(s).clone(), Node::Add([p.rational(1, 2), p.mul(p.int(2), x)].into()));
    }

    #[test]
    fn products_merge_powers() {
        let mut p = Pool::new();
        let (x, y, m) = xyz(&mut p);
        let half_x = p.div(x, p.int(2));
        assert_eq!(p.mul(p.int(2), half_x), x);
        let x2 = p.mul(x, x);
        assert_eq!(x2, p.powi(x, 2));
        let inv = p.powi(x2, -1);
        assert_eq!(p.mul(inv, x2), p.one());
        assert_eq!(p.div(x, x), p.one());
        assert_eq!(p.product([]), p.one());
        assert_eq!(p.product([x, p.zero(), y]), p.zero());
        let a = p.product([m, x, y, x]);
        let b = p.product([y, x2, m]);
        assert_eq!(a, b);
        let Node::Mul(factors) = p.node(p.product([x, p.int(3), y])).clone() else { panic!() };
        assert_eq!(factors[0], p.int(3), "coefficient leads");
    }

    #[test]
    fn products_do_not_distribute_over_sums() {
        let mut p = Pool::new();
        let (x, y, _) = xyz(&mut p);
        let s = p.add(x, y);
        let e = p.mul(p.int(3), s);
        assert_eq!(p.node(e).clone(), Node::Mul([p.int(3), s].into()));
        let minus = p.neg(e);
        assert_eq!(p.add(e, minus), p.zero());
        assert_eq!(p.split_coefficient(minus), (Number::from(-3), s));
    }

    #[test]
    fn powers_fold() {
        let mut p = Pool::new();
        let (x, y, _) = xyz(&mut p);
        assert_eq!(p.powi(x, 0), p.one());
        assert_eq!(p.powi(x, 1), x);
        let x2 = p.powi(x, 2);
        assert_eq!(p.powi(x2, 3), p.powi(x, 6));
        assert_eq!(p.powi(p.rational(2, 3), -2), p.rational(9, 4));
        let e = p.product([p.int(2), x, y]);
        let inv = p.powi(e, -1);
        let expected = p.product([p.rational(1, 2), p.powi(x, -1), p.powi(y, -1)]);
        assert_eq!(inv, expected);
        assert_eq!(p.mul(inv, x), p.div(p.rational(1, 2), y));
        let s = p.add(x, y);
        assert_eq!(p.node(p.powi(s, 2)).clone(), Node::Pow(s, 2));
    }

    #[test]
    fn overflow_falls_back_to_floats() {
        let mut p = Pool::new();
        let big = p.powi(p.int(10), 30);
        assert_eq!(p.as_rational(big).map(|r| r.num), Some(10i128.pow(30)));
        let square = p.mul(big, big);
        let value = p.as_number(square).map(Number::to_f64).unwrap();
        assert!(p.as_rational(square).is_none() && (value / 1e60 - 1.0).abs() < 1e-12);
        let (x, _, _) = xyz(&mut p);
        let huge = p.powi(x, i32::MAX);
        let nested = p.powi(huge, 2);
        assert_ne!(nested, huge);
        let twice = p.mul(huge, huge);
        assert_ne!(twice, p.zero(), "exponent overflow must not panic or vanish");
        let inf = p.div(p.one(), p.zero());
        assert_eq!(p.as_number(inf).map(Number::to_f64), Some(f64::INFINITY));
    }
}
