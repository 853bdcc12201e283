//! Differentiation: partial and total time derivatives, memoised in the
//! pool.
//!
//! Both are *derivations*: they follow the same sum, product and chain
//! rules and differ only at the leaves, so one routine does both. Passes
//! visit the DAG in post-order with an explicit stack (no recursion on
//! expression depth) and skip every node that provably lacks the symbols
//! involved (O(1) via the per-node summaries).

use super::kinds::SymKinds;
use super::{ExprId, Func, Node, Pool, Sym};

/// What is being differentiated with respect to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Derivation {
    /// `∂/∂s`.
    Partial(Sym),
    /// `d/dt` with `dt(qᵢ) = Nᵢ(q) v` (the pool's rates), `dt(vᵢ) = v̇ᵢ`,
    /// everything else but `t` constant.
    Time,
}

impl Pool {
    /// `∂e/∂s`, memoised per `(e, s)` for the life of the pool.
    pub fn diff(&mut self, e: ExprId, s: Sym) -> ExprId {
        self.derive(e, Derivation::Partial(s))
    }

    /// The rate `q̇ᵢ` of coordinate `i` in the speeds: `Nᵢ(q) v` as set by
    /// [`set_rate`](Pool::set_rate), else the speed `vᵢ`.
    pub fn rate(&mut self, i: u32) -> ExprId {
        match self.rates.get(i as usize) {
            Some(&rate) => rate,
            None => self.sym(Sym::Speed(i)),
        }
    }

    /// Declares `q̇ᵢ = rate` for coordinate `i` (a kinematic differential
    /// equation, linear in the speeds), before any time derivative involves
    /// it; the coordinates before `i` without one keep `q̇ⱼ = vⱼ`.
    pub fn set_rate(&mut self, i: u32, rate: ExprId) {
        while self.rates.len() < i as usize {
            let j = self.rates.len() as u32;
            let speed = self.sym(Sym::Speed(j));
            self.rates.push(speed);
        }
        match self.rates.get_mut(i as usize) {
            Some(slot) => *slot = rate,
            None => self.rates.push(rate),
        }
    }

    /// The rates set by [`set_rate`](Pool::set_rate), by coordinate (empty
    /// while every rate is its own speed).
    pub fn rates(&self) -> &[ExprId] {
        &self.rates
    }

    /// Whether every coordinate's rate is its own speed (`q̇ᵢ = vᵢ`): no
    /// [`set_rate`](Pool::set_rate) so far.
    pub fn rates_are_speeds(&self) -> bool {
        self.rates.is_empty()
    }

    /// The total time derivative `∂e/∂t + Σ ∂e/∂qᵢ q̇ᵢ + Σ ∂e/∂vᵢ v̇ᵢ`;
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
            Derivation::Time => self
                .kinds(e)
                .intersects(SymKinds::TIME | SymKinds::COORD | SymKinds::SPEED),
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
        let pending = self.post_order(&[e], |n| {
            self.may_vary(n, d) && !self.derivatives.contains_key(&(n, d))
        });
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
            // A group's derivative stays one operand: the derivative of a
            // recursion's grouped running totals is then a recursion of the
            // same shape, not its steps flattened into one another.
            Node::Group(sum) => {
                let dsum = self.known_derivative(sum, d);
                self.group(dsum)
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
            (Derivation::Time, Sym::Coord(i)) => self.rate(i),
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
    pub(super) fn func_derivative(&mut self, f: Func, call: ExprId, arg: ExprId) -> ExprId {
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
}

#[cfg(test)]
mod tests {
    use super::super::test_util::{Point, Rng, Scratch, assert_close};
    use super::*;

    /// `(∂e/∂s)(env)` by central differences.
    fn numeric_partial(p: &Pool, e: ExprId, s: Sym, env: &Point) -> f64 {
        let h = 1e-6;
        let f = |delta: f64| p.eval(e, &env.shifted(s, delta));
        (f(h) - f(-h)) / (2.0 * h)
    }

    /// Checks `diff(text, s)` against finite differences at random points
    /// for each of `syms`.
    fn check_diff(text: &str, syms: &[Sym]) {
        let mut s = Scratch::default();
        let e = s.e(text);
        let mut rng = Rng::new(7);
        for &by in syms {
            let de = s.pool.diff(e, by);
            for _ in 0..5 {
                let env = Point::random(&mut rng, syms);
                let exact = s.pool.eval(de, &env);
                let numeric = numeric_partial(&s.pool, e, by, &env);
                assert_close(
                    exact,
                    numeric,
                    1e-6,
                    &format!("d({text})/d{by:?} = {}", s.show(de)),
                );
            }
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let syms = [Sym::Coord(0), Sym::Coord(1), Sym::Param(0)];
        for text in [
            "p0*sin(q0*q1) + cos(q0 - q1)^3",
            "tan(p0*q0/3) + sqrt(q0^2 + 2)*exp(q1/3)",
            "ln(p0^2 + 1)*q1 + abs(q0 - 5)*q0 + (q0 + 4)^-3",
            "sin(cos((q0*q1)^2))",
            "q0*q1*p0*sin(q0)/(1 + q1^2)",
            "sqrt(exp(q0) + ln(2 + sin(q1)))",
        ] {
            check_diff(text, &syms);
        }
    }

    #[test]
    fn simple_rules_are_exact() {
        let mut s = Scratch::default();
        let x = Sym::Coord(0);
        for (text, derivative) in [
            ("sin(q0)", "cos(q0)"),
            ("cos(q0)", "-sin(q0)"),
            ("q0^3", "3*q0^2"),
            ("q0^-1", "-q0^-2"),
            ("exp(q0)", "exp(q0)"),
            ("ln(q0)", "1/q0"),
            ("tan(q0)", "1 + tan(q0)^2"),
            ("sqrt(q0)", "1/(2*sqrt(q0))"),
            ("abs(q0)", "q0/abs(q0)"),
            ("p0*q0*q1", "p0*q1"),
            ("sin(2*q0)", "2*cos(2*q0)"),
            ("q1^3", "0"),
        ] {
            let e = s.e(text);
            let expected = s.e(derivative);
            assert_eq!(s.pool.diff(e, x), expected, "d({text})/dq0");
        }
    }

    #[test]
    fn diff_is_memoised_and_skips_absent_symbols() {
        let mut s = Scratch::default();
        let e = s.e("p0*sin(q0)");
        let first = s.pool.diff(e, Sym::Coord(0));
        let len = s.pool.len();
        assert_eq!(s.pool.diff(e, Sym::Coord(0)), first);
        assert_eq!(s.pool.len(), len, "second call built nodes");
        assert_eq!(s.pool.diff(e, Sym::Speed(0)), s.pool.zero());
        let key = (e, Derivation::Partial(Sym::Speed(0)));
        assert!(
            !s.pool.derivatives.contains_key(&key),
            "absent symbol was traversed"
        );
    }

    #[test]
    fn time_derivative_of_sin_q0_times_q1() {
        let mut s = Scratch::default();
        for (text, rate) in [
            ("sin(q0)*q1", "cos(q0)*u0*q1 + sin(q0)*u1"),
            ("p0*sin(q0)*q1", "p0*(cos(q0)*u0*q1 + sin(q0)*u1)"),
            ("t^2 + u1 + f0", "2*t + a1"),
            ("p0*a0 + l0", "0"),
        ] {
            let e = s.e(text);
            let td = s.pool.time_derivative(e);
            let expected = s.e(rate);
            // p0*(...) is not distributed: compare the expanded forms.
            assert_eq!(s.pool.expand(td), s.pool.expand(expected), "d/dt {text}");
        }
        let e = s.e("sin(q0)*q1");
        let td = s.pool.time_derivative(e);
        assert_eq!(
            td,
            s.e("u0*q1*cos(q0) + u1*sin(q0)"),
            "canonical without expansion"
        );
    }
}
