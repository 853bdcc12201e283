//! The symbolic engine: scalar expressions as a hash-consed DAG.
//!
//! Every expression lives in a [`Pool`] and is named by an [`ExprId`]; equal
//! expressions get equal ids, so structural equality is id equality and
//! shared subexpressions are stored (and later emitted) once. Constructors
//! keep expressions canonical as they are built:
//!
//! * sums are flat (`Add` never holds an `Add`), their terms are sorted by
//!   id, like terms are merged (`2ab + 3ab = 5ab`), numbers are folded into a
//!   single leading constant, and zero terms vanish;
//! * products are flat, sorted, with one leading rational coefficient, equal
//!   bases merged by adding integer exponents (`x·x⁻¹ = 1`), and zero
//!   annihilates;
//! * products are *not* distributed over sums: chains stay linear in size.
//!
//! Numbers are exact rationals; a result that would overflow `i128` falls
//! back to a float so that no input can make the engine panic.
//!
//! Differentiation is memoised per (expression, symbol), and the time
//! derivative follows the chain rule through coordinates and speeds.

#![allow(dead_code)] // API filled in by the engine work; users arrive with the kinematics.

/// Index of an expression in its [`Pool`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct ExprId(pub(crate) u32);

/// A symbol: the leaves of expressions besides numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Sym {
    /// Time `t`.
    Time,
    /// The i-th parameter.
    Param(u32),
    /// The i-th generalized coordinate `qᵢ`.
    Coord(u32),
    /// Its rate `q̇ᵢ`.
    Speed(u32),
    /// Its second rate `q̈ᵢ`.
    Accel(u32),
    /// The i-th input `uᵢ`.
    Input(u32),
    /// The i-th Lagrange multiplier `λᵢ` (rendering of constrained equations).
    Multiplier(u32),
}

/// Elementary functions of the language.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Func {
    Sin,
    Cos,
    Tan,
    Sqrt,
    Exp,
    Ln,
    Abs,
}

/// An exact rational `num/den` with `den > 0` and `gcd(num, den) = 1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Rational {
    pub num: i128,
    pub den: i128,
}

/// A number: exact where it can be, a float only after an overflow.
#[derive(Clone, Copy, Debug)]
pub enum Number {
    Rational(Rational),
    /// Stored by value; equality and hashing use the bit pattern.
    Float(f64),
}

/// One node of the DAG. Children are ids in the same pool.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    Number(Number),
    Sym(Sym),
    /// Sum of at least two terms, canonical as described in the module docs.
    Add(Box<[ExprId]>),
    /// Product of at least two factors (or a non-unit coefficient and one
    /// factor), canonical as described in the module docs. A numeric
    /// coefficient, if any, is the first factor.
    Mul(Box<[ExprId]>),
    /// `base ^ exponent` with an integer exponent other than 0 and 1.
    Pow(ExprId, i32),
    Func(Func, ExprId),
}

/// Values of the symbols for numeric evaluation.
pub trait Env {
    fn value(&self, sym: Sym) -> f64;
}

/// The arena of hash-consed expressions.
pub struct Pool {
    // filled in by the engine work
}
