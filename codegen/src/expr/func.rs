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
    /// number), the exact sine and cosine of a whole number of quarter
    /// turns, and the nearest double of the sine, cosine and tangent of
    /// any other number (a constant rotation costs nothing at run time);
    /// `None` leaves the call symbolic.
    fn fold(self, n: Number) -> Option<Number> {
        match self {
            Func::Sin | Func::Tan if n.is_zero() => Some(Number::ZERO),
            Func::Cos | Func::Exp if n.is_zero() => Some(Number::ONE),
            Func::Sin | Func::Cos => {
                let x = n.to_f64();
                let sine = self == Func::Sin;
                match quarter_turns(x) {
                    // cos(k π/2) = sin((k + 1) π/2).
                    Some(k) => {
                        let k = if sine { k } else { k + 1 };
                        Some(Number::ratio([0, 1, 0, -1][k.rem_euclid(4) as usize], 1))
                    }
                    None => finite(if sine { x.sin() } else { x.cos() }),
                }
            }
            Func::Tan => finite(n.to_f64().tan()),
            Func::Ln if n.is_one() => Some(Number::ZERO),
            Func::Sqrt => n.as_rational()?.sqrt_exact().map(Number::Rational),
            Func::Abs => Some(n.abs()),
            _ => None,
        }
    }
}

/// `k` if `x` is the double nearest to `k π/2` (as URDF files write
/// `1.5707963267948966` for a quarter turn, whose cosine, `6.1e-17`, would
/// otherwise keep every term it multiplies alive in the equations).
fn quarter_turns(x: f64) -> Option<i64> {
    let k = (x / std::f64::consts::FRAC_PI_2).round();
    let exact = k.abs() < 1e6 && x == k * std::f64::consts::FRAC_PI_2;
    (exact && k != 0.0).then_some(k as i64)
}

/// `x` as a number, if finite.
fn finite(x: f64) -> Option<Number> {
    x.is_finite().then_some(Number::Float(x))
}

impl Pool {
    /// `f(arg)`, folded where the value is exact (`sin 0 = 0`, `cos 0 = 1`,
    /// `tan 0 = 0`, `exp 0 = 1`, `ln 1 = 0`, `sqrt(9/4) = 3/2`, `abs` of a
    /// number), and with odd/even functions of a negative argument
    /// rewritten: `sin(-x) = -sin(x)`, `cos(-x) = cos(x)` (also `tan`,
    /// `abs`). An argument is negative if its coefficient is, or if it is a
    /// sum whose leading term's is, so `cos(q2 - q1)` and `cos(q1 - q2)` are
    /// one node. Sines, cosines and tangents of other numbers are floats
    /// (`sin(1)`); other functions of them stay symbolic (`sqrt(2)`).
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
            return Some(self.scale(-c, rest));
        }
        let terms = match self.node(arg) {
            Node::Add(terms) if self.split_coefficient(terms[0]).0.is_negative() => terms.to_vec(),
            _ => return None,
        };
        let negated: Vec<ExprId> = terms.into_iter().map(|t| self.neg(t)).collect();
        Some(self.sum(negated))
    }

    /// `a` as one operand ([`Node::Group`]) if it is a sum, or a numeric
    /// multiple of one (the coefficient outside); anything else is already
    /// one.
    pub fn group(&mut self, a: ExprId) -> ExprId {
        let (c, rest) = self.split_coefficient(a);
        match self.node(rest) {
            Node::Add(_) => {
                let group = self.intern(Node::Group(rest));
                self.scale(c, group)
            }
            _ => a,
        }
    }

    /// `arg` as one operand where a pass rebuilds a group over a new
    /// argument: a number is itself, and a group is odd like `sin` (the
    /// group of an argument that counts as negative, see [`Pool::func`],
    /// is the negated group of its negation), so that the readable forms'
    /// expansion keeps `(a − b)` and `−(b − a)` one node.
    pub fn regroup(&mut self, arg: ExprId) -> ExprId {
        if self.as_number(arg).is_some() {
            return arg;
        }
        match self.negated(arg) {
            Some(positive) => {
                let group = self.intern(Node::Group(positive));
                self.neg(group)
            }
            None => self.intern(Node::Group(arg)),
        }
    }

    /// `roots` with every [`Node::Group`] replaced by its sum, so that its
    /// terms flatten into their surroundings again.
    pub fn ungroup(&mut self, roots: &[ExprId]) -> Vec<ExprId> {
        self.rebuild(roots, |pool, node, images| match pool.node(node) {
            Node::Group(_) => images[0],
            _ => pool.with_children(node, images),
        })
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
    use super::super::test_util::Scratch;
    use super::*;

    #[test]
    fn special_values_fold_exactly() {
        let mut s = Scratch::default();
        for (text, value) in [
            ("sin(0)", "0"),
            ("cos(0)", "1"),
            ("tan(0)", "0"),
            ("exp(0)", "1"),
            ("ln(1)", "0"),
            ("sqrt(9/4)", "3/2"),
            ("abs(-5/3)", "5/3"),
            ("sin(q0 - q0)", "0"),
        ] {
            assert_eq!(s.e(text), s.e(value), "{text}");
        }
    }

    #[test]
    fn other_roots_and_logarithms_stay_symbolic() {
        let mut s = Scratch::default();
        let two = s.e("2");
        for (text, node) in [
            ("sqrt(2)", Node::Func(Func::Sqrt, two)),
            ("ln(2)", Node::Func(Func::Ln, two)),
        ] {
            let e = s.e(text);
            assert_eq!(s.pool.node(e), &node);
        }
    }

    #[test]
    fn trigonometry_of_numbers_folds_to_floats() {
        let mut s = Scratch::default();
        for (text, value) in [
            ("sin(-1.8)", (-1.8f64).sin()),
            ("cos(-1.8)", 1.8f64.cos()),
            ("tan(3/4)", 0.75f64.tan()),
        ] {
            let e = s.e(text);
            assert_eq!(
                s.pool.as_number(e).map(Number::to_f64),
                Some(value),
                "{text}"
            );
        }
        assert_eq!(s.e("sin(-1)"), s.e("-sin(1)"));
    }

    #[test]
    #[allow(
        clippy::approx_constant,
        reason = "angles near a quarter turn, on purpose"
    )]
    fn quarter_turns_fold_exactly() {
        let mut s = Scratch::default();
        for (text, value) in [
            ("sin(1.5707963267948966)", "1"),
            ("cos(1.5707963267948966)", "0"),
            ("sin(-1.5707963267948966)", "-1"),
            ("cos(-1.5707963267948966)", "0"),
            ("sin(3.141592653589793)", "0"),
            ("cos(3.141592653589793)", "-1"),
            ("cos(4.71238898038469)", "0"),
            ("sin(4.71238898038469)", "-1"),
        ] {
            assert_eq!(s.e(text), s.e(value), "{text}");
        }
        // Near a quarter turn but not the double nearest to it: a float.
        let e = s.e("cos(1.5708)");
        assert_eq!(
            s.pool.as_number(e).map(Number::to_f64),
            Some(1.5708f64.cos())
        );
    }

    #[test]
    fn parity_rules() {
        let mut s = Scratch::default();
        assert_eq!(s.e("sin(-2*q0)"), s.e("-sin(2*q0)"));
        assert_eq!(s.e("cos(-2*q0)"), s.e("cos(2*q0)"));
        assert_eq!(s.e("tan(-q0/3)"), s.e("-tan(q0/3)"));
        assert_eq!(s.e("abs(-q0)"), s.e("abs(q0)"));
        assert_ne!(s.e("exp(-q0)"), s.e("exp(q0)"));
        assert_eq!(s.e("sin(-q0) + sin(q0)"), s.pool.zero());
    }

    #[test]
    fn differences_have_one_orientation() {
        let mut s = Scratch::default();
        assert_eq!(s.e("cos(q0 - q1)"), s.e("cos(q1 - q0)"));
        assert_eq!(s.e("sin(q1 - q0)"), s.e("-sin(q0 - q1)"));
        assert_eq!(s.e("cos(-(q0 + q1))"), s.e("cos(q0 + q1)"));
        assert_eq!(s.e("sin(-1 - q0) + sin(1 + q0)"), s.pool.zero());
        let e = s.e("cos(q1 - q0)");
        assert_eq!(s.show(e), "cos(q0 - q1)");
    }
}
