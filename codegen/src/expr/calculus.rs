//! Differentiation (partial and total time derivatives, memoised in the
//! pool) and substitution of symbols.
//!
//! Both are *derivations*: they follow the same sum, product and chain
//! rules and differ only at the leaves, so one routine does both. Passes
//! visit the DAG in post-order with an explicit stack (no recursion on
//! expression depth) and skip every node that provably lacks the symbols
//! involved (O(1) via the per-node summaries).

use std::collections::HashMap;

use super::kinds::SymKinds;
use super::{ExprId, Func, Node, Pool, Sym};

/// What is being differentiated with respect to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Derivation {
    /// `∂/∂s`.
    Partial(Sym),
    /// `d/dt` with `dt(qᵢ) = q̇ᵢ`, `dt(q̇ᵢ) = q̈ᵢ`, everything else but `t`
    /// constant.
    Time,
}

impl Pool {
    /// `∂e/∂s`, memoised per `(e, s)` for the life of the pool.
    pub fn diff(&mut self, e: ExprId, s: Sym) -> ExprId {
        self.derive(e, Derivation::Partial(s))
    }

    /// The total time derivative `∂e/∂t + Σ ∂e/∂qᵢ q̇ᵢ + Σ ∂e/∂q̇ᵢ q̈ᵢ`;
    /// parameters, inputs, multipliers and accelerations are constants.
    /// Memoised per node like [`diff`](Pool::diff).
    pub fn time_derivative(&mut self, e: ExprId) -> ExprId {
        self.derive(e, Derivation::Time)
    }

    /// Whether `e` may depend on what `d` differentiates by; `false` means
    /// the derivative is zero.
    fn may_vary(&self, e: ExprId, d: Derivation) -> bool {
        match d {
            Derivation::Partial(s) => self.may_contain(e, s),
            Derivation::Time => {
                self.kinds(e).intersects(SymKinds::TIME | SymKinds::COORD | SymKinds::SPEED)
            }
        }
    }

    /// The derivative of a node whose derivative is known: memoised, or
    /// zero because it cannot vary.
    fn known_derivative(&self, e: ExprId, d: Derivation) -> ExprId {
        match self.derivatives.get(&(e, d)) {
            Some(&de) => de,
            None => self.zero(),
        }
    }

    /// Differentiates `e`: every node below it that may vary and is not yet
    /// memoised is differentiated once, children first.
    fn derive(&mut self, e: ExprId, d: Derivation) -> ExprId {
        let pending =
            self.post_order(&[e], |n| self.may_vary(n, d) && !self.derivatives.contains_key(&(n, d)));
        for n in pending {
            let dn = self.derive_node(n, d);
            self.derivatives.insert((n, d), dn);
        }
        self.known_derivative(e, d)
    }

    /// The derivative of one node from those of its children.
    fn derive_node(&mut self, n: ExprId, d: Derivation) -> ExprId {
        match self.node(n).clone() {
            Node::Number(_) => self.zero(),
            Node::Sym(s) => self.derive_leaf(s, d),
            Node::Add(terms) => {
                let dterms: Vec<ExprId> =
                    terms.iter().map(|&t| self.known_derivative(t, d)).collect();
                self.sum(dterms)
            }
            Node::Mul(factors) => self.derive_product(&factors, d),
            Node::Pow(base, exp) => {
                // d(bⁿ) = n · bⁿ · b⁻¹ · db (the product merges bⁿ·b⁻¹).
                let db = self.known_derivative(base, d);
                let (k, inverse) = (self.int(i64::from(exp)), self.powi(base, -1));
                self.product([k, n, inverse, db])
            }
            Node::Func(f, arg) => {
                let darg = self.known_derivative(arg, d);
                if self.is_zero(darg) {
                    return darg;
                }
                let outer = self.func_derivative(f, n, arg);
                self.mul(outer, darg)
            }
        }
    }

    /// The derivative of a symbol.
    fn derive_leaf(&mut self, s: Sym, d: Derivation) -> ExprId {
        match (d, s) {
            (Derivation::Partial(by), _) if by == s => self.one(),
            (Derivation::Time, Sym::Time) => self.one(),
            (Derivation::Time, Sym::Coord(i)) => self.sym(Sym::Speed(i)),
            (Derivation::Time, Sym::Speed(i)) => self.sym(Sym::Accel(i)),
            _ => self.zero(),
        }
    }

    /// Product rule: `Σᵢ (Πⱼ≠ᵢ fⱼ) · dfᵢ`.
    fn derive_product(&mut self, factors: &[ExprId], d: Derivation) -> ExprId {
        let mut terms = Vec::new();
        for (i, &f) in factors.iter().enumerate() {
            let df = self.known_derivative(f, d);
            if self.is_zero(df) {
                continue;
            }
            let mut replaced = factors.to_vec();
            replaced[i] = df;
            terms.push(self.product(replaced));
        }
        self.sum(terms)
    }

    /// `f'(arg)`, where `call` is the node `f(arg)`.
    fn func_derivative(&mut self, f: Func, call: ExprId, arg: ExprId) -> ExprId {
        match f {
            Func::Sin => self.cos(arg),
            Func::Cos => {
                let sin = self.sin(arg);
                self.neg(sin)
            }
            // 1 + tan²
            Func::Tan => {
                let square = self.powi(call, 2);
                self.add(self.one(), square)
            }
            // 1 / (2 √x)
            Func::Sqrt => {
                let (half, inverse) = (self.rational(1, 2), self.powi(call, -1));
                self.mul(half, inverse)
            }
            Func::Exp => call,
            Func::Ln => self.powi(arg, -1),
            // x / |x|
            Func::Abs => self.div(arg, call),
        }
    }

    /// `e` with every symbol `s` for which `map(s)` is `Some(r)` replaced by
    /// `r`, re-canonicalised. Memoised within the call: shared
    /// subexpressions are rebuilt once.
    pub fn substitute(&mut self, e: ExprId, map: &dyn Fn(Sym) -> Option<ExprId>) -> ExprId {
        let mut rebuilt: HashMap<ExprId, ExprId> = HashMap::new();
        // Constants cannot change: they are neither visited nor rebuilt.
        let order = self.post_order(&[e], |n| !self.kinds(n).is_empty());
        for n in order {
            let image = |c: ExprId| rebuilt.get(&c).copied().unwrap_or(c);
            let new = match self.node(n).clone() {
                Node::Sym(s) => map(s).unwrap_or(n),
                Node::Add(terms) => {
                    let terms: Vec<ExprId> = terms.iter().map(|&t| image(t)).collect();
                    self.sum(terms)
                }
                Node::Mul(factors) => {
                    let factors: Vec<ExprId> = factors.iter().map(|&f| image(f)).collect();
                    self.product(factors)
                }
                Node::Pow(base, exp) => self.powi(image(base), exp),
                Node::Func(f, arg) => self.func(f, image(arg)),
                Node::Number(_) => n,
            };
            rebuilt.insert(n, new);
        }
        rebuilt.get(&e).copied().unwrap_or(e)
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_util::{Point, Rng, assert_close};
    use super::*;

    /// `(∂e/∂s)(env)` by central differences.
    fn numeric_partial(p: &Pool, e: ExprId, s: Sym, env: &Point) -> f64 {
        let h = 1e-6;
        let f = |delta: f64| p.eval(e, &env.shifted(s, delta));
        (f(h) - f(-h)) / (2.0 * h)
    }

    /// Checks `diff(e, s)` against finite differences at random points.
    fn check_diff(p: &mut Pool, e: ExprId, syms: &[Sym]) {
        let mut rng = Rng::new(7);
        for &s in syms {
            let de = p.diff(e, s);
            for _ in 0..5 {
                let env = Point::random(&mut rng, syms);
                let (exact, numeric) = (p.eval(de, &env), numeric_partial(p, e, s, &env));
                assert_close(exact, numeric, 1e-6, &p.display(de, &|s| format!("{s:?}")));
            }
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let mut p = Pool::new();
        let syms = [Sym::Coord(0), Sym::Coord(1), Sym::Param(0)];
        let [x, y, a] = syms.map(|s| p.sym(s));
        let xy = p.mul(x, y);
        let s = p.sin(xy);
        let c = p.cos(p.sub(x, y));
        let t = p.func(Func::Tan, p.mul(a, x));
        let sq = p.func(Func::Sqrt, p.add(p.mul(x, x), p.int(2)));
        let ex = p.func(Func::Exp, p.div(y, p.int(3)));
        let ln = p.func(Func::Ln, p.add(p.mul(a, a), p.int(1)));
        let ab = p.func(Func::Abs, p.sub(x, p.int(5)));
        let inv = p.powi(p.add(x, p.int(4)), -3);
        let terms = [p.mul(s, a), c, t, p.mul(sq, ex), p.mul(ln, y), p.mul(ab, x), inv];
        let e = p.sum(terms);
        check_diff(&mut p, e, &syms);
        // Chain rule through nested calls.
        let nested = p.sin(p.cos(p.powi(xy, 2)));
        check_diff(&mut p, nested, &syms);
    }

    #[test]
    fn simple_rules_are_exact() {
        let mut p = Pool::new();
        let x = p.sym(Sym::Coord(0));
        let sin = p.sin(x);
        assert_eq!(p.diff(sin, Sym::Coord(0)), p.cos(x));
        let cos = p.cos(x);
        assert_eq!(p.diff(cos, Sym::Coord(0)), p.neg(sin));
        let x3 = p.powi(x, 3);
        assert_eq!(p.diff(x3, Sym::Coord(0)), p.mul(p.int(3), p.powi(x, 2)));
        assert_eq!(p.diff(x3, Sym::Coord(1)), p.zero());
        let exp = p.func(Func::Exp, x);
        assert_eq!(p.diff(exp, Sym::Coord(0)), exp);
        let ln = p.func(Func::Ln, x);
        assert_eq!(p.diff(ln, Sym::Coord(0)), p.powi(x, -1));
    }

    #[test]
    fn diff_is_memoised_and_skips_absent_symbols() {
        let mut p = Pool::new();
        let (x, m) = (p.sym(Sym::Coord(0)), p.sym(Sym::Param(0)));
        let e = p.mul(m, p.sin(x));
        let first = p.diff(e, Sym::Coord(0));
        let len = p.len();
        assert_eq!(p.diff(e, Sym::Coord(0)), first);
        assert_eq!(p.len(), len, "second call built nodes");
        assert_eq!(p.diff(e, Sym::Speed(0)), p.zero());
        assert!(!p.derivatives.contains_key(&(e, Derivation::Partial(Sym::Speed(0)))));
    }

    #[test]
    fn time_derivative_of_sin_q0_times_q1() {
        let mut p = Pool::new();
        let [q0, q1, u0, u1, a1, m] = [
            Sym::Coord(0),
            Sym::Coord(1),
            Sym::Speed(0),
            Sym::Speed(1),
            Sym::Accel(1),
            Sym::Param(0),
        ]
        .map(|s| p.sym(s));
        let e = p.product([p.sin(q0), q1, m]);
        // d/dt (m sin(q0) q1) = m cos(q0) q̇0 q1 + m sin(q0) q̇1
        let expected = {
            let a = p.product([m, p.cos(q0), u0, q1]);
            let b = p.product([m, p.sin(q0), u1]);
            p.add(a, b)
        };
        assert_eq!(p.time_derivative(e), expected);
        // Speeds differentiate to accelerations, time to one.
        let t = p.sym(Sym::Time);
        let f = p.add(p.mul(t, t), u1);
        assert_eq!(p.time_derivative(f), p.add(p.mul(p.int(2), t), a1));
        assert_eq!(p.time_derivative(m), p.zero());
    }

    #[test]
    fn substitute_replaces_and_recanonicalises() {
        let mut p = Pool::new();
        let (x, y) = (p.sym(Sym::Coord(0)), p.sym(Sym::Coord(1)));
        let e = p.add(p.sin(x), p.mul(x, y));
        let zero = p.zero();
        let at_zero = p.substitute(e, &|s| (s == Sym::Coord(0)).then_some(zero));
        assert_eq!(at_zero, zero);
        let minus_y = p.neg(y);
        let swapped = p.substitute(e, &|s| (s == Sym::Coord(0)).then_some(minus_y));
        // sin(-y) + (-y)·y = -sin(y) - y²
        let expected = {
            let (sin, square) = (p.sin(y), p.powi(y, 2));
            p.sub(p.neg(sin), square)
        };
        assert_eq!(swapped, expected);
        assert_eq!(p.substitute(e, &|_| None), e);
    }
}
