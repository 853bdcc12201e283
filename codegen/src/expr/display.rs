//! Plain infix rendering for debugging and test messages:
//! `1/2*L^2*m*cos(q1)`, `a^2 + 2*a*b - b^2`, `g*m/L`.
//!
//! The printer recurses on the structure, so its depth is the DAG's depth
//! (a few hundred levels for long chains), not the expression's size. It
//! prints the tree: shared subexpressions are repeated, so the output of a
//! large DAG can be far larger than the DAG.

use super::{ExprId, Node, Number, Pool, Sym};

/// Binding strength of a rendered form, weakest first.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Prec {
    Sum,
    Product,
    Power,
    Atom,
}

/// Renders expressions of one pool with one naming of symbols.
struct Printer<'a> {
    pool: &'a Pool,
    name: &'a dyn Fn(Sym) -> String,
    out: String,
}

impl Pool {
    /// `e` in plain infix: `+ - * / ^`, calls by name, symbols named by
    /// `name`, exact numbers as `3` or `1/2`; parentheses only where needed.
    pub fn display(&self, e: ExprId, name: &dyn Fn(Sym) -> String) -> String {
        let mut printer = Printer { pool: self, name, out: String::new() };
        printer.expr(e, Prec::Sum);
        printer.out
    }
}

impl Printer<'_> {
    /// Writes `e`, parenthesised if it binds weaker than `min`.
    fn expr(&mut self, e: ExprId, min: Prec) {
        let parens = self.precedence(e) < min;
        if parens {
            self.out.push('(');
        }
        match self.pool.node(e) {
            Node::Sym(s) => self.out.push_str(&(self.name)(*s)),
            Node::Func(f, arg) => {
                self.out.push_str(f.name());
                self.out.push('(');
                self.expr(*arg, Prec::Sum);
                self.out.push(')');
            }
            Node::Add(terms) => self.sum(terms),
            Node::Number(_) | Node::Mul(_) | Node::Pow(..) => {
                let (c, factors) = self.monomial(e);
                self.term(c, &factors);
            }
        }
        if parens {
            self.out.push(')');
        }
    }

    /// How tightly the rendering of `e` binds.
    fn precedence(&self, e: ExprId) -> Prec {
        match self.pool.node(e) {
            Node::Add(_) => Prec::Sum,
            Node::Mul(_) => Prec::Product,
            Node::Pow(_, exp) if *exp < 0 => Prec::Product,
            Node::Pow(..) => Prec::Power,
            Node::Number(Number::Rational(r)) if r.num >= 0 && r.is_integer() => Prec::Atom,
            Node::Number(n) if n.is_negative() || n.as_rational().is_some() => Prec::Product,
            Node::Number(_) | Node::Sym(_) | Node::Func(..) => Prec::Atom,
        }
    }

    /// `e` as a coefficient and its other factors.
    fn monomial(&self, e: ExprId) -> (Number, Vec<ExprId>) {
        let (c, rest) = self.pool.split_coefficient(e);
        let factors = match self.pool.node(rest) {
            _ if rest == self.pool.one() => Vec::new(),
            Node::Mul(factors) => factors.to_vec(),
            _ => vec![rest],
        };
        (c, factors)
    }

    /// Writes the terms of a sum, pulling negative coefficients into the
    /// operator: `a - 2*b`.
    fn sum(&mut self, terms: &[ExprId]) {
        for (i, &t) in terms.iter().enumerate() {
            let (c, factors) = self.monomial(t);
            let sign = match (i, c.is_negative()) {
                (0, false) => "",
                (0, true) => "-",
                (_, false) => " + ",
                (_, true) => " - ",
            };
            self.out.push_str(sign);
            self.term(c.abs(), &factors);
        }
    }

    /// Writes `c · Π factors`, factors with negative exponents as divisors.
    fn term(&mut self, c: Number, factors: &[ExprId]) {
        let (numerator, denominator): (Vec<_>, Vec<_>) = factors
            .iter()
            .map(|&f| match self.pool.node(f) {
                &Node::Pow(base, exp) => (base, exp),
                _ => (f, 1),
            })
            .partition(|&(_, exp)| exp > 0);
        match (numerator.is_empty(), c.is_one(), c == Number::ONE.neg()) {
            (false, true, _) => {}
            (false, _, true) => self.out.push('-'),
            (false, _, _) => self.out.push_str(&format!("{c}*")),
            (true, _, _) => self.out.push_str(&c.to_string()),
        }
        for (i, &(base, exp)) in numerator.iter().enumerate() {
            if i > 0 {
                self.out.push('*');
            }
            self.power(base, exp.unsigned_abs());
        }
        for &(base, exp) in &denominator {
            self.out.push('/');
            self.power(base, exp.unsigned_abs());
        }
    }

    /// Writes `base^exp` (just `base` if `exp` is one) as a factor.
    fn power(&mut self, base: ExprId, exp: u32) {
        if exp == 1 {
            self.expr(base, Prec::Power);
        } else {
            self.expr(base, Prec::Atom);
            self.out.push_str(&format!("^{exp}"));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::Func;
    use super::*;

    fn name(s: Sym) -> String {
        match s {
            Sym::Param(0) => "m".into(),
            Sym::Param(1) => "L".into(),
            Sym::Param(2) => "g".into(),
            Sym::Coord(i) => format!("q{i}"),
            Sym::Speed(i) => format!("u{i}"),
            _ => format!("{s:?}"),
        }
    }

    fn show(p: &Pool, e: ExprId) -> String {
        p.display(e, &name)
    }

    #[test]
    fn products_and_powers() {
        let mut p = Pool::new();
        let [m, l, g, q1] = [Sym::Param(0), Sym::Param(1), Sym::Param(2), Sym::Coord(1)].map(|s| p.sym(s));
        let e = p.product([p.rational(1, 2), m, p.powi(l, 2), p.cos(q1)]);
        assert_eq!(show(&p, e), "1/2*m*L^2*cos(q1)");
        let e = p.div(p.mul(g, m), l);
        assert_eq!(show(&p, e), "m*g/L");
        assert_eq!(show(&p, p.powi(l, -2)), "1/L^2");
        assert_eq!(show(&p, p.neg(q1)), "-q1");
        assert_eq!(show(&p, p.mul(p.int(-3), p.powi(q1, -1))), "-3/q1");
        assert_eq!(show(&p, p.rational(-7, 2)), "-7/2");
    }

    #[test]
    fn sums_and_parentheses() {
        let mut p = Pool::new();
        let [q0, q1, u0] = [Sym::Coord(0), Sym::Coord(1), Sym::Speed(0)].map(|s| p.sym(s));
        let e = p.sum([p.int(1), p.neg(q0), p.mul(p.int(2), q1)]);
        assert_eq!(show(&p, e), "1 - q0 + 2*q1");
        let e = p.sub(p.neg(q0), p.int(1));
        assert_eq!(show(&p, e), "-1 - q0");
        let s = p.add(q0, q1);
        assert_eq!(show(&p, p.mul(u0, s)), "u0*(q0 + q1)");
        assert_eq!(show(&p, p.powi(s, 2)), "(q0 + q1)^2");
        assert_eq!(show(&p, p.powi(s, -1)), "1/(q0 + q1)");
        assert_eq!(show(&p, p.func(Func::Sqrt, s)), "sqrt(q0 + q1)");
        let t = p.mul(p.int(-2), s);
        assert_eq!(show(&p, p.add(t, u0)), "u0 - 2*(q0 + q1)");
        let sin = p.powi(p.sin(q0), 2);
        assert_eq!(show(&p, sin), "sin(q0)^2");
        assert_eq!(show(&p, p.number(Number::Float(1e60))), "1e60");
    }
}
