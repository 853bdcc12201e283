//! The interpreter: numeric evaluation of expressions, for differential
//! tests against emitted code. Iterative over the DAG in topological order,
//! so each shared node is evaluated once and depth is no concern.

use std::collections::HashMap;

use super::{Env, ExprId, Func, Node, Pool, Sym, SymKinds};

impl Func {
    /// `self(x)` in `f64`.
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
            Func::Tan => x.tan(),
            Func::Sqrt => x.sqrt(),
            Func::Exp => x.exp(),
            Func::Ln => x.ln(),
            Func::Abs => x.abs(),
        }
    }
}

/// The environment of a constant: it has no symbols to value.
struct NoSymbols;

impl Env for NoSymbols {
    fn value(&self, _: Sym) -> f64 {
        f64::NAN
    }
}

impl Pool {
    /// The value of `e` if it is a constant (it contains no symbol):
    /// `ln(0)` is `-inf`, `sqrt(-1)` NaN.
    pub fn constant_value(&self, e: ExprId) -> Option<f64> {
        (self.kinds(e) == SymKinds::EMPTY).then(|| self.eval(e, &NoSymbols))
    }

    /// The value of `e` with symbols valued by `env`.
    pub fn eval(&self, e: ExprId, env: &dyn Env) -> f64 {
        self.eval_many(&[e], env)[0]
    }

    /// The values of all `roots` in one pass: nodes they share are
    /// evaluated once.
    pub fn eval_many(&self, roots: &[ExprId], env: &dyn Env) -> Vec<f64> {
        let mut values: HashMap<ExprId, f64> = HashMap::new();
        for n in self.topo_order(roots) {
            let value = self.eval_node(n, env, &values);
            values.insert(n, value);
        }
        roots.iter().map(|r| values[r]).collect()
    }

    /// The value of one node given those of its children.
    fn eval_node(&self, n: ExprId, env: &dyn Env, values: &HashMap<ExprId, f64>) -> f64 {
        let of = |c: &ExprId| values[c];
        match self.node(n) {
            Node::Number(x) => x.to_f64(),
            Node::Sym(s) => env.value(*s),
            Node::Add(terms) => terms.iter().map(of).sum(),
            Node::Mul(factors) => factors.iter().map(of).product(),
            Node::Pow(base, exp) => of(base).powi(*exp),
            Node::Func(f, arg) => f.apply(of(arg)),
            Node::Group(sum) => of(sum),
        }
    }
}

#[cfg(test)]
mod tests {
    use std::cell::RefCell;

    use super::super::Sym;
    use super::super::test_util::{Point, Scratch};
    use super::*;

    /// An environment that counts how often each symbol is read.
    struct Counting(Point, RefCell<HashMap<Sym, usize>>);

    impl Env for Counting {
        fn value(&self, sym: Sym) -> f64 {
            *self.1.borrow_mut().entry(sym).or_default() += 1;
            self.0.value(sym)
        }
    }

    #[test]
    fn evaluates_every_node_kind() {
        let mut s = Scratch::default();
        let e = s.e("1/2*sin(q0) + p0^-2 + sqrt(p0) + ln(exp(q0)) + abs(q0 - p0) + 3 + tan(q0)");
        let env = Point([(Sym::Coord(0), 0.3), (Sym::Param(0), 2.0)].into());
        let x = 0.3f64;
        let expected = 0.5 * x.sin() + 0.25 + 2f64.sqrt() + x + 1.7 + 3.0 + x.tan();
        assert!((s.pool.eval(e, &env) - expected).abs() < 1e-13);
    }

    #[test]
    fn eval_many_shares_nodes() {
        let mut s = Scratch::default();
        let (a, b) = (s.e("sin(q0)^2"), s.e("sin(q0) + 1"));
        let env = Counting(Point([(Sym::Coord(0), 0.5)].into()), RefCell::default());
        let values = s.pool.eval_many(&[a, b, a], &env);
        let sin = 0.5f64.sin();
        assert_eq!(values, vec![sin * sin, sin + 1.0, sin * sin]);
        assert_eq!(env.1.borrow()[&Sym::Coord(0)], 1, "q0 read more than once");
    }
}
