//! The symbolic engine: scalar expressions as a hash-consed DAG.
//!
//! Every expression lives in a [`Pool`] and is named by an [`ExprId`]; equal
//! expressions get equal ids, so structural equality is id equality and
//! shared subexpressions are stored (and later emitted) once. Constructors
//! keep expressions canonical as they are built:
//!
//! * sums are flat (`Add` never holds an `Add`), their terms are sorted by
//!   the id of their coefficient-free part, like terms are merged
//!   (`2ab + 3ab = 5ab`), numbers are folded into a single leading
//!   constant, and zero terms vanish;
//! * products are flat, sorted by the id of each factor's base, with one
//!   leading rational coefficient, equal bases merged by adding integer
//!   exponents (`x·x⁻¹ = 1`), and zero annihilates;
//! * products are *not* distributed over sums: chains stay linear in size
//!   (`3·(x + y)` stays a product, and stays one term of a sum, so the sum
//!   `x + y` remains shared with its other uses); a numeric multiple of a
//!   sum is spread into the sum around it only where one of its terms
//!   meets another term there, so that like terms still merge and cancel
//!   (`x − (x + y)` is `−y`, `(x + y) − (x + z)` is `y − z`);
//! * in a pool made [`Pool::with_positive_sums`] (every derivation's), a
//!   sum whose first non-constant term has a negative coefficient is `−1`
//!   times the sum with every sign turned, so that `a − b` and `b − a`
//!   share one sum. The setting is chosen when the pool is made and holds
//!   for all its life, so every pool holds one form per sum (in this one,
//!   `b − a` and `−(a − b)` are one id). The readable forms
//!   (`crate::readable`, and the docs' collected sums) are expanded in
//!   the same pool and read a multiple of a sum as its terms, each with
//!   its sign, so that their recombination rules see every sign without
//!   building a second form. Where `−s` ([`Pool::negated_sum`]) stands
//!   for a flat sum it is read as one: the printers write it as the terms
//!   of `s` negated, the emitter too where `s` is not shared (so the
//!   optimiser costs a compact form `−s` as `s`), the emitter writes a sum
//!   holding an earlier sum's terms negated as the rest minus that sum,
//!   and the Taylor lowering takes a recombined form `−s` as one linear
//!   combination;
//! * a group ([`Node::Group`], made by [`Pool::group`]) holds a sum as one
//!   operand: its value is the sum's, its derivative the sum's derivative
//!   grouped, and construction never spreads a coefficient into it nor
//!   merges its terms with the terms around it. The derivations group
//!   only sums (a coefficient stays outside); a pass that rebuilds a group
//!   over a new argument ([`Pool::regroup`]) keeps it odd (never over a
//!   negative argument) and never over a number. Groups are not in the
//!   language: the recursive derivations group each step's running totals
//!   so that the next step costs a few operations, not as many as the
//!   terms so far (canonical sums would flatten one step into the next);
//!   [`Pool::ungroup`] flattens them again for the readable forms. Every
//!   pass has one arm for the kind (the identity where it computes, free
//!   in the cost model, parentheses where it renders);
//! * integer powers of products are distributed over the factors
//!   (`(2xy)⁻¹ = ½x⁻¹y⁻¹`), never over sums;
//! * odd and even functions take a non-negative argument:
//!   `sin(-x) = -sin x`, `cos(q2 - q1) = cos(q1 - q2)`.
//!
//! Ids are handed out in construction order, so the same construction
//! gives the same DAG on every machine; no pass iterates a hash map in a way
//! that affects its result.
//!
//! Numbers are exact rationals; a result that would overflow `i128` falls
//! back to a float so that no input can make the engine panic.
//!
//! Differentiation is memoised per (expression, symbol), and the time
//! derivative follows the chain rule through coordinates and speeds.
//!
//! Files: `number` (exact arithmetic), `decimal` (literal values), `kinds`
//! (symbol summaries), `pool` (interning, queries, traversal), `canon`
//! (sums, products, powers), `func` (elementary functions), `rebuild`
//! (bottom-up rewriting), `calculus` (derivatives), `reverse` (gradients
//! by reverse accumulation), `eval` (the interpreter), and for tests `expand` and
//! `display`.

mod calculus;
mod canon;
mod decimal;
#[cfg(test)]
mod display;
mod eval;
#[cfg(test)]
mod expand;
mod func;
mod kinds;
mod number;
mod pool;
mod rebuild;
mod reverse;
#[cfg(test)]
pub(crate) mod test_util;
#[cfg(test)]
mod tests;

pub use kinds::SymKinds;

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
    /// The i-th speed `vᵢ`: the rate `q̇ᵢ` of the i-th coordinate unless
    /// [`Pool::set_rate`] says otherwise.
    Speed(u32),
    /// Its rate `v̇ᵢ`.
    Accel(u32),
    /// The i-th input `uᵢ`.
    Input(u32),
    /// The i-th Lagrange multiplier `λᵢ` (rendering of constrained equations).
    Multiplier(u32),
}

/// Elementary functions of the language.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Func {
    /// `sin`.
    Sin,
    /// `cos`.
    Cos,
    /// `tan`.
    Tan,
    /// `sqrt` (principal square root).
    Sqrt,
    /// `exp`.
    Exp,
    /// `ln` (natural logarithm).
    Ln,
    /// `abs`.
    Abs,
}

/// An exact rational `num/den` with `den > 0` and `gcd(num, den) = 1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Rational {
    /// Numerator.
    pub num: i128,
    /// Denominator, positive.
    pub den: i128,
}

/// A number: exact where it can be, a float only after an overflow.
#[derive(Clone, Copy, Debug)]
pub enum Number {
    /// An exact value.
    Rational(Rational),
    /// Stored by value; equality and hashing use the bit pattern.
    Float(f64),
}

/// One node of the DAG. Children are ids in the same pool.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A constant.
    Number(Number),
    /// A symbol.
    Sym(Sym),
    /// Sum of at least two terms, canonical as described in the module docs.
    Add(Box<[ExprId]>),
    /// Product of at least two factors (or a non-unit coefficient and one
    /// factor), canonical as described in the module docs. A numeric
    /// coefficient, if any, is the first factor.
    Mul(Box<[ExprId]>),
    /// `base ^ exponent` with an integer exponent other than 0 and 1.
    Pow(ExprId, i32),
    /// An elementary function of one argument.
    Func(Func, ExprId),
    /// A sum held as one operand (see the module docs): its value is the
    /// sum's, and so is its derivative's, grouped again.
    Group(ExprId),
}

/// Values of the symbols for numeric evaluation.
pub trait Env {
    /// The value of `sym`.
    fn value(&self, sym: Sym) -> f64;
}

/// The arena of hash-consed expressions.
#[derive(Clone)]
pub struct Pool {
    /// The nodes, indexed by id.
    nodes: Vec<Node>,
    /// Symbol summaries and coefficient splits, indexed by id.
    meta: Vec<pool::Meta>,
    /// Node to id, for hash-consing (looked up, never iterated). Fx hash
    /// (`rustc-hash`): the keys are the engine's own small integers, so
    /// SipHash's resistance to chosen collisions buys nothing, and hashing
    /// with it was a quarter of a derivation's time; the maps are never
    /// iterated, so the output does not depend on the hasher.
    index: rustc_hash::FxHashMap<Node, ExprId>,
    /// Memoised derivatives (looked up, never iterated; Fx hash as `index`).
    derivatives: rustc_hash::FxHashMap<(ExprId, calculus::Derivation), ExprId>,
    /// The kinematic differential equations `q̇ᵢ = Nᵢ(q) v` that
    /// [`Pool::time_derivative`] follows, by coordinate; a coordinate
    /// beyond them has `q̇ᵢ = vᵢ`.
    rates: Vec<ExprId>,
    /// Whether a sum whose first term is negative is built as `−1` times
    /// the sum with every sign turned ([`Pool::with_positive_sums`]).
    positive_sums: bool,
}
