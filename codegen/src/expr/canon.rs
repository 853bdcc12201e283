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
            self.collect_term(term, Number::ONE, &mut constant, &mut parts);
        }
        let (merged, negated) = self.merged_and_signed(parts, &mut constant);
        let mut out = Vec::with_capacity(merged.len() + 1);
        if !constant.is_zero() {
            out.push(self.number(constant));
        }
        for (rest, c) in merged {
            out.push(self.scale(c, rest));
        }
        let sum = match out.as_slice() {
            [] => self.zero(),
            [single] => *single,
            _ => self.intern(Node::Add(out.into())),
        };
        if negated {
            let minus_one = self.int(-1);
            self.product([minus_one, sum])
        } else {
            sum
        }
    }

    /// [`Self::merge_terms`], and in a pool
    /// [with positive sums](Pool::with_positive_sums) every sign turned
    /// (`true`) if the first non-constant term of two or more is negative.
    /// Turning a `−1` multiple of a sum makes it a sum to spread; after that
    /// the first term may be negative again, so this repeats (each round
    /// spreads a multiple: it ends).
    fn merged_and_signed(
        &self,
        mut parts: Vec<(ExprId, Number)>,
        constant: &mut Number,
    ) -> (Vec<(ExprId, Number)>, bool) {
        let mut negated = false;
        loop {
            let mut merged = self.merge_terms(parts, constant);
            merged.retain(|(_, c)| !c.is_zero());
            let turn = self.positive_sums
                && merged.len() + usize::from(!constant.is_zero()) > 1
                && merged.first().is_some_and(|(_, c)| c.is_negative());
            if !turn {
                return (merged, negated);
            }
            negated = !negated;
            *constant = -*constant;
            for (_, c) in merged.iter_mut() {
                *c = -*c;
            }
            // Turning made no new like terms; only a multiple turned to one
            // may need spreading.
            if !self.must_flatten(&merged).contains(&true) {
                return (merged, negated);
            }
            parts = merged;
        }
    }

    /// Like terms of `parts` merged, sorted by their coefficient-free part,
    /// with the multiples of sums among them that must not stay whole
    /// ([`Self::must_flatten`]) spread into their terms, until none is left.
    fn merge_terms(
        &self,
        mut parts: Vec<(ExprId, Number)>,
        constant: &mut Number,
    ) -> Vec<(ExprId, Number)> {
        loop {
            parts.sort_by_key(|&(rest, _)| rest);
            let merged = merge_sorted(parts, |a, b| Some(a + b));
            let flatten = self.must_flatten(&merged);
            if flatten.iter().all(|&f| !f) {
                return merged;
            }
            parts = Vec::with_capacity(merged.len());
            for (&(rest, c), flat) in merged.iter().zip(flatten) {
                if flat {
                    self.collect_term(rest, c, constant, &mut parts);
                } else {
                    parts.push((rest, c));
                }
            }
        }
    }

    /// Which of the merged `parts` (sorted by their rest) are multiples of
    /// a sum to spread into their terms: those whose coefficient merged to
    /// one (a sum's term is never a sum), and those sharing a term with
    /// another part, so that like terms meet and cancel
    /// (`(x + y) − 2·(x + z)` is `−x + y − 2z`). Any other multiple of a
    /// sum stays one term, and the sum stays shared with its other uses.
    fn must_flatten(&self, parts: &[(ExprId, Number)]) -> Vec<bool> {
        let is_sum = |rest: ExprId| matches!(self.node(rest), Node::Add(_));
        if !parts.iter().any(|&(rest, _)| is_sum(rest)) {
            return vec![false; parts.len()];
        }
        // The coefficient-free, non-constant parts of each multiple's terms.
        let inner: Vec<Option<Vec<ExprId>>> = parts
            .iter()
            .map(|&(rest, _)| match self.node(rest) {
                Node::Add(terms) => Some(
                    terms
                        .iter()
                        .map(|&t| self.split_coefficient(t).1)
                        .filter(|&r| r != self.one())
                        .collect(),
                ),
                _ => None,
            })
            .collect();
        // Every coefficient-free part a term of this sum would bring, once
        // per part it comes from.
        let mut met: Vec<ExprId> = Vec::new();
        for (&(rest, _), terms) in parts.iter().zip(&inner) {
            match terms {
                Some(terms) => met.extend_from_slice(terms),
                None => met.push(rest),
            }
        }
        met.sort_unstable();
        let twice =
            |r: ExprId| met.partition_point(|&m| m <= r) - met.partition_point(|&m| m < r) > 1;
        parts
            .iter()
            .zip(&inner)
            .map(|(&(_, c), terms)| {
                terms
                    .as_ref()
                    .is_some_and(|terms| c.is_one() || terms.iter().any(|&r| twice(r)))
            })
            .collect()
    }

    /// Adds `scale · term` to a sum under construction: numbers to
    /// `constant`, others as `(rest, coefficient)` to `parts`. Sums are
    /// flattened (the terms of a canonical sum are not sums, so this
    /// recurses at most once); a numeric multiple of a sum is kept as one
    /// part, for [`Self::merge_terms`] to decide.
    fn collect_term(
        &self,
        term: ExprId,
        scale: Number,
        constant: &mut Number,
        parts: &mut Vec<(ExprId, Number)>,
    ) {
        match self.node(term) {
            Node::Number(n) => *constant = *constant + scale * *n,
            Node::Add(terms) => {
                for &t in terms.iter() {
                    self.collect_term(t, scale, constant, parts);
                }
            }
            _ => {
                let (c, rest) = self.split_coefficient(term);
                parts.push((rest, scale * c));
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
            Node::Mul(factors) => std::iter::once(coefficient)
                .chain(factors.iter().copied())
                .collect(),
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
            Node::Number(n) => *coefficient = *coefficient * *n,
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
    use super::super::test_util::Scratch;
    use super::*;

    #[test]
    fn like_terms_merge_and_cancel() {
        let mut s = Scratch::default();
        assert_eq!(s.e("q0 + q0"), s.e("2*q0"));
        assert_eq!(s.e("q0 - q0"), s.pool.zero());
        assert_eq!(s.e("q0*q1"), s.e("q1*q0"));
        assert_eq!(s.e("q0*q1 + q1 + q0 + q0*q1"), s.e("q1 + q0 + 2*q1*q0"));
        assert_eq!(s.e("3*q0*q1 - 2*q1*q0 - q0*q1"), s.pool.zero());
        assert_eq!(s.pool.sum([]), s.pool.zero());
        let x = s.e("q0");
        assert_eq!(s.pool.sum([x]), x);
    }

    #[test]
    fn rational_constants_fold() {
        let mut s = Scratch::default();
        assert_eq!(s.e("1/3 + 1/6 - 1/2"), s.pool.zero());
        let e = s.e("q0 + 1/3 + q0 + 1/6");
        let expected = Node::Add([s.e("1/2"), s.e("2*q0")].into());
        assert_eq!(s.pool.node(e), &expected);
        assert_eq!(s.show(e), "1/2 + 2*q0");
    }

    #[test]
    fn products_merge_powers() {
        let mut s = Scratch::default();
        assert_eq!(s.e("2*(q0/2)"), s.e("q0"));
        assert_eq!(s.e("q0*q0"), s.e("q0^2"));
        assert_eq!(s.e("(q0^2)^-1 * q0^2"), s.pool.one());
        assert_eq!(s.e("q0/q0"), s.pool.one());
        assert_eq!(s.pool.product([]), s.pool.one());
        assert_eq!(s.e("q0*0*q1"), s.pool.zero());
        assert_eq!(s.e("p0*q0*q1*q0"), s.e("q1*q0^2*p0"));
        let e = s.e("q0*3*q1");
        let three = s.e("3");
        assert_eq!(s.pool.children(e)[0], three, "coefficient leads");
        assert_eq!(s.show(e), "3*q0*q1");
    }

    #[test]
    fn products_do_not_distribute_over_sums() {
        let mut s = Scratch::default();
        let e = s.e("3*(q0 + q1)");
        let sum = s.e("q0 + q1");
        let expected = Node::Mul([s.e("3"), sum].into());
        assert_eq!(s.pool.node(e), &expected);
        assert_eq!(s.e("3*(q0 + q1) - 3*(q1 + q0)"), s.pool.zero());
        let e = s.e("(q0 + q1 + 1) - (q0 + q1 + 1)");
        assert_eq!(e, s.pool.zero());
        assert_eq!(s.e("2*(q0 + q1) - (q0 + q1)"), sum);
    }

    #[test]
    fn a_multiple_of_a_sum_stays_whole_unless_its_terms_meet_others() {
        let mut s = Scratch::default();
        // Kept whole: `q0 + q1` stays one node, shared with its other uses.
        let e = s.e("q2 - 2*(q0 + q1)");
        let (multiple, q2) = (s.e("-2*(q0 + q1)"), s.e("q2"));
        assert_eq!(s.pool.children(e), [q2, multiple]);
        assert_eq!(s.e("q2 - (q0 + q1)"), s.e("-(q0 + q1) + q2"));
        // Spread where a term meets another, so like terms merge.
        assert_eq!(s.e("q0 - 2*(q0 + q1)"), s.e("-q0 - 2*q1"));
        assert_eq!(s.e("(q0 + q2) - (q0 + q1)"), s.e("q2 - q1"));
        assert_eq!(s.e("(q0 + q1 + 1) - q0 - q1"), s.pool.one());
        assert_eq!(s.e("2*(q0 + q1) - 3*(q0 + q2)"), s.e("-q0 + 2*q1 - 3*q2"));
        // Spreading one multiple can make another meet: all are spread.
        let chain = s.e("(q0 + q1) - (q1 + q2) + 2*(q2 + q3)");
        assert_eq!(chain, s.e("q0 + q2 + 2*q3"));
        let minus = s.e("-3*(q0 + q1)");
        let sum = s.e("q0 + q1");
        assert_eq!(s.pool.split_coefficient(minus), (Number::from(-3), sum));
    }

    #[test]
    fn positive_sums_share_a_sum_with_their_negation() {
        let mut s = Scratch {
            pool: Pool::with_positive_sums(),
        };
        // `q0` is made first, so it leads: `q0 − q1` is a sum, `q1 − q0`
        // is −1 times it.
        let (a, b, minus_one) = (s.e("q0 - q1"), s.e("q1 - q0"), s.e("-1"));
        assert!(matches!(s.pool.node(a), Node::Add(_)));
        assert_eq!(s.pool.node(b), &Node::Mul([minus_one, a].into()));
        assert_eq!((s.pool.neg(a), s.pool.neg(b)), (b, a));
        assert_eq!(s.e("(q0 - q1) + (q1 - q0)"), s.pool.zero());
        // The constant turns with the terms, and a multiple of a sum turned
        // to one is spread.
        let (c, turned) = (s.e("-(q0 - q1) + 2"), s.e("-2 + q0 - q1"));
        assert_eq!(s.pool.node(c), &Node::Mul([minus_one, turned].into()));
    }

    #[test]
    fn powers_fold() {
        let mut s = Scratch::default();
        let x = s.e("q0");
        assert_eq!(s.pool.powi(x, 0), s.pool.one());
        assert_eq!(s.pool.powi(x, 1), x);
        assert_eq!(s.e("(q0^2)^3"), s.e("q0^6"));
        assert_eq!(s.e("(2/3)^-2"), s.e("9/4"));
        assert_eq!(s.e("(2*q0*q1)^-1"), s.e("1/2 * q0^-1 * q1^-1"));
        assert_eq!(s.e("(2*q0*q1)^-1 * q0"), s.e("1/(2*q1)"));
        let (sum, square) = (s.e("q0 + q1"), s.e("(q0 + q1)^2"));
        assert_eq!(s.pool.node(square), &Node::Pow(sum, 2));
    }

    #[test]
    fn overflow_falls_back_to_floats() {
        let mut s = Scratch::default();
        let big = s.e("10^30");
        assert_eq!(s.pool.as_rational(big).map(|r| r.num), Some(10i128.pow(30)));
        let square = s.pool.mul(big, big);
        let value = s.pool.as_number(square).map(Number::to_f64).unwrap();
        assert!(s.pool.as_rational(square).is_none() && (value / 1e60 - 1.0).abs() < 1e-12);
        let huge = s.e("q0^2147483647");
        let nested = s.pool.powi(huge, 2);
        assert_eq!(s.pool.node(nested), &Node::Pow(huge, 2));
        let twice = s.pool.mul(huge, huge);
        assert_eq!(s.pool.children(twice), [huge, huge], "kept apart, no panic");
        let inf = s.e("1/0");
        assert_eq!(
            s.pool.as_number(inf).map(Number::to_f64),
            Some(f64::INFINITY)
        );
    }
}
