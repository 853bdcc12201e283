//! Elementary functions: exact folding of special values and the parity
//! rules that keep `sin(-x)` and `-sin(x)` one node.

use super::{ExprId, Func, Node, Number, Pool};

/// How a function treats a negated argument.
enum Parity {
    /// `f(-x) = -f(x)`.
    Odd,
    /// `f(-x) = f(x)`.
    Even,
    /// Neither.
    None,
}

impl Func {
    /// The name used in the language and in displays (`sin`, `ln`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Sqrt => "sqrt",
            Func::Exp => "exp",
            Func::Ln => "ln",
            Func::Abs => "abs",
        }
    }

    fn parity(self) -> Parity {
        match self {
            Func::Sin | Func::Tan => Parity::Odd,
            Func::Cos | Func::Abs => Parity::Even,
            Func::Sqrt | Func::Exp | Func::Ln => Parity::None,
        }
    }

    /// The exact value of `self(n)` where it is a rational (or `abs` of any
    /// number); `None` leaves the call symbolic.
    fn fold(self, n: Number) -> Option<Number> {
        match self {
            Func::Sin | Func::Tan if n.is_zero() => Some(Number::ZERO),
            Func::Cos | Func::Exp if n.is_zero() => Some(Number::ONE),
            Func::Ln if n.is_one() => Some(Number::ZERO),
            Func::Sqrt => n.as_rational()?.sqrt_exact().map(Number::Rational),
            Func::Abs => Some(n.abs()),
            _ => None,
        }
    }
}

impl Pool {
    /// `f(arg)`, folded where the value is exact (`sin 0 = 0`, `cos 0 = 1`,
    /// `tan 0 = 0`, `exp 0 = 1`, `ln 1 = 0`, `sqrt(9/4) = 3/2`, `abs` of a
    /// number), and with odd/even functions of a negative argument
    /// rewritten: `sin(-x) = -sin(x)`, `cos(-x) = cos(x)` (also `tan`,
    /// `abs`). An argument is negative if its coefficient is, or if it is a
    /// sum whose leading term's is, so `cos(q2 - q1)` and `cos(q1 - q2)` are
    /// one node. Other numeric arguments stay symbolic (`sin(1)`).
    pub fn func(&mut self, f: Func, arg: ExprId) -> ExprId {
        if let Some(value) = self.as_number(arg).and_then(|n| f.fold(n)) {
            return self.number(value);
        }
        let parity = f.parity();
        if !matches!(parity, Parity::None) {
            if let Some(positive) = self.negated(arg) {
                let call = self.intern(Node::Func(f, positive));
                return match parity {
                    Parity::Odd => self.neg(call),
                    _ => call,
                };
            }
        }
        self.intern(Node::Func(f, arg))
    }

    /// `-arg` if `arg` counts as negative (see [`Pool::func`]).
    fn negated(&mut self, arg: ExprId) -> Option<ExprId> {
        let (c, rest) = self.split_coefficient(arg);
        if c.is_negative() {
            return Some(self.scale(c.neg(), rest));
        }
        let terms = match self.node(arg) {
            Node::Add(terms) if self.split_coefficient(terms[0]).0.is_negative() => terms.to_vec(),
            _ => return None,
        };
        let negated: Vec<ExprId> = terms.into_iter().map(|t| self.neg(t)).collect();
        Some(self.sum(negated))
    }

    /// `sin(a)`.
    pub fn sin(&mut self, a: ExprId) -> ExprId {
        self.func(Func::Sin, a)
    }

    /// `cos(a)`.
    pub fn cos(&mut self, a: ExprId) -> ExprId {
        self.func(Func::Cos, a)
    }
}

#[cfg(test)]
mod tests {
    use super::super::Sym;
    use super::*;

    #[test]
    fn special_values_fold_exactly() {
        let mut p = Pool::new();
        let (zero, one) = (p.zero(), p.one());
        assert_eq!(p.sin(zero), zero);
        assert_eq!(p.cos(zero), one);
        assert_eq!(p.func(Func::Tan, zero), zero);
        assert_eq!(p.func(Func::Exp, zero), one);
        assert_eq!(p.func(Func::Ln, one), zero);
        let q = p.rational(9, 4);
        assert_eq!(p.func(Func::Sqrt, q), p.rational(3, 2));
        let m = p.rational(-5, 3);
        assert_eq!(p.func(Func::Abs, m), p.rational(5, 3));
    }

    #[test]
    fn other_numbers_stay_symbolic() {
        let mut p = Pool::new();
        let (one, two) = (p.one(), p.int(2));
        assert_eq!(p.node(p.sin(one)).clone(), Node::Func(Func::Sin, one));
        assert_eq!(p.node(p.func(Func::Sqrt, two)).clone(), Node::Func(Func::Sqrt, two));
        let minus_one = p.int(-1);
        let s = p.sin(minus_one);
        assert_eq!(s, p.neg(p.sin(one)));
        assert!(p.as_number(s).is_none());
    }

    #[test]
    fn parity_rules() {
        let mut p = Pool::new();
        let x = p.sym(Sym::Coord(0));
        let minus_2x = p.mul(p.int(-2), x);
        let two_x = p.mul(p.int(2), x);
        assert_eq!(p.sin(minus_2x), p.neg(p.sin(two_x)));
        assert_eq!(p.cos(minus_2x), p.cos(two_x));
        assert_eq!(p.func(Func::Tan, minus_2x), p.neg(p.func(Func::Tan, two_x)));
        assert_eq!(p.func(Func::Abs, minus_2x), p.func(Func::Abs, two_x));
        assert_ne!(p.func(Func::Exp, minus_2x), p.func(Func::Exp, two_x));
    }

    #[test]
    fn differences_have_one_orientation() {
        let mut p = Pool::new();
        let (a, b) = (p.sym(Sym::Coord(0)), p.sym(Sym::Coord(1)));
        let (ab, ba) = (p.sub(a, b), p.sub(b, a));
        assert_eq!(p.cos(ab), p.cos(ba));
        assert_eq!(p.sin(ba), p.neg(p.sin(ab)));
        let minus_sum = p.neg(p.add(a, b));
        assert_eq!(p.cos(minus_sum), p.cos(p.add(a, b)));
    }
}
