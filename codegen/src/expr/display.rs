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
        let mut printer = Printer {
            pool: self,
            name,
            out: String::new(),
        };
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
            Node::Group(sum) => {
                self.out.push('(');
                self.expr(*sum, Prec::Sum);
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
            Node::Number(_) | Node::Sym(_) | Node::Func(..) | Node::Group(_) => Prec::Atom,
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
        match (numerator.is_empty(), c.is_one(), c == -Number::ONE) {
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
    use super::super::test_util::Scratch;

    /// Builds `text` and displays it.
    fn shown(text: &str) -> String {
        let mut s = Scratch::default();
        // Create the symbols in index order so that factor order is stable.
        s.e("p0 + p1 + p2 + q0 + q1 + u0");
        let e = s.e(text);
        s.show(e)
    }

    #[test]
    fn products_and_powers() {
        for (text, display) in [
            ("1/2*p0*p1^2*cos(q1)", "1/2*p0*p1^2*cos(q1)"),
            ("cos(q1)*p1*p1*p0/2", "1/2*p0*p1^2*cos(q1)"),
            ("p2*p0/p1", "p0*p2/p1"),
            ("p1^-2", "1/p1^2"),
            ("-q1", "-q1"),
            ("-3/q1", "-3/q1"),
            ("-7/2", "-7/2"),
            ("sin(q0)^2", "sin(q0)^2"),
            ("1.5*q0", "3/2*q0"),
        ] {
            assert_eq!(shown(text), display, "{text}");
        }
    }

    #[test]
    fn sums_and_parentheses() {
        for (text, display) in [
            ("1 - q0 + 2*q1", "1 - q0 + 2*q1"),
            ("-q0 - 1", "-1 - q0"),
            ("u0*(q0 + q1)", "u0*(q0 + q1)"),
            ("(q0 + q1)^2", "(q0 + q1)^2"),
            ("(q0 + q1)^-1", "1/(q0 + q1)"),
            ("sqrt(q1 + q0)", "sqrt(q0 + q1)"),
            ("-2*(q0 + q1)", "-2*(q0 + q1)"),
            ("u0 - 2*q1*(q0 + q1)", "u0 - 2*q1*(q0 + q1)"),
            ("p0/(q0 + q1)^2", "p0/(q0 + q1)^2"),
            ("(sin(q0) + 1)*cos(q1 - q0)", "(1 + sin(q0))*cos(q0 - q1)"),
        ] {
            assert_eq!(shown(text), display, "{text}");
        }
    }

    #[test]
    fn floats_show_their_value() {
        let mut s = Scratch::default();
        let e = s.e("10^20 * 10^20");
        assert_eq!(s.show(e), "1e40");
        let e = s.e("1/0");
        assert_eq!(s.show(e), "inf");
    }
}
