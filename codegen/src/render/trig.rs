//! Readable forms of derived expressions, for the generated docs: expand
//! into a sum of monomials within a budget, then recombine trigonometric
//! pairs until no rule applies:
//!
//! * `c·R·sin²x + c·R·cos²x = c·R`, and with different coefficients
//!   `a·R·sin²x + b·R·cos²x = b·R + (a − b)·R·sin²x` when a term `R` is
//!   already there to absorb `b·R` (so the sum gets shorter);
//! * `c·R·(cos a cos b ± sin a sin b) = c·R·cos(a ∓ b)` and
//!   `c·R·(sin a cos b ± cos a sin b) = c·R·sin(a ± b)`, for `a ≠ b`;
//!
//! where `R` is the rest of the monomial. Every rule is an identity, so the
//! result equals the input exactly, and every rewrite makes the sum shorter,
//! so recombination ends.
//!
//! The orientation of a difference (`cos(θ₂ − θ₁)` or `cos(θ₁ − θ₂)`) is not
//! chosen here: the pool keeps one canonical node for both (`cos` is even,
//! `sin` odd). The printers pick the orientation that puts the
//! highest-indexed coordinate first (see [`super::text`]).

use std::collections::{BTreeMap, BTreeSet, HashMap};

use crate::expr::{ExprId, Func, Node, Number, Pool};

/// How many products (before like terms merge) one multiplication of two
/// expanded sums may form, in multiples of the budget: a little room for
/// cancellation, and a bound on the work.
const PRODUCT_SLACK: usize = 4;

/// The number of top-level terms of `e`: its terms if it is a sum, 0 for
/// zero, 1 otherwise.
pub fn term_count(pool: &Pool, e: ExprId) -> usize {
    match pool.node(e) {
        Node::Add(terms) => terms.len(),
        _ if pool.is_zero(e) => 0,
        _ => 1,
    }
}

/// `e` as a short sum of monomials for humans: expanded, then with
/// trigonometric pairs recombined (see the module docs). `None` if the
/// expansion of `e`, or of any part of it, would have more than `budget`
/// terms: the work is bounded by the size of `e`'s DAG times the budget.
pub fn readable(pool: &mut Pool, e: ExprId, budget: usize) -> Option<ExprId> {
    let expanded = expand_within(pool, e, budget)?;
    let mut sum = Monomials::of(pool, expanded);
    while let Some(shorter) = sum.recombined(pool) {
        sum = shorter;
    }
    Some(sum.to_expr(pool))
}

/// Like [`Pool::expand`], but giving up as soon as an intermediate result
/// exceeds `budget` terms.
fn expand_within(pool: &mut Pool, e: ExprId, budget: usize) -> Option<ExprId> {
    let mut expanded: HashMap<ExprId, ExprId> = HashMap::new();
    for n in pool.topo_order(&[e]) {
        let image = expand_node(pool, n, &expanded, budget)?;
        if term_count(pool, image) > budget {
            return None;
        }
        expanded.insert(n, image);
    }
    expanded.get(&e).copied()
}

/// The expansion of node `n`, given those of its children.
fn expand_node(
    pool: &mut Pool,
    n: ExprId,
    expanded: &HashMap<ExprId, ExprId>,
    budget: usize,
) -> Option<ExprId> {
    let images = |children: &[ExprId]| -> Option<Vec<ExprId>> {
        children.iter().map(|c| expanded.get(c).copied()).collect()
    };
    match pool.node(n).clone() {
        Node::Number(_) | Node::Sym(_) => Some(n),
        Node::Add(terms) => {
            let terms = images(&terms)?;
            Some(pool.sum(terms))
        }
        Node::Mul(factors) => distribute(pool, &images(&factors)?, budget),
        Node::Pow(base, exp) => {
            let base = *images(&[base])?.first()?;
            expand_power(pool, base, exp, budget)
        }
        Node::Func(f, arg) => {
            let arg = *images(&[arg])?.first()?;
            Some(pool.func(f, arg))
        }
    }
}

/// `base ^ exp` for an expanded `base`, multiplied out if `base` is a sum
/// and `exp` positive.
fn expand_power(pool: &mut Pool, base: ExprId, exp: i32, budget: usize) -> Option<ExprId> {
    match (pool.node(base), usize::try_from(exp)) {
        (Node::Add(_), Ok(count)) if count > budget => None,
        (Node::Add(_), Ok(count)) => distribute(pool, &vec![base; count], budget),
        _ => Some(pool.powi(base, exp)),
    }
}

/// The expanded product of expanded `factors`, or `None` past the budget.
fn distribute(pool: &mut Pool, factors: &[ExprId], budget: usize) -> Option<ExprId> {
    let mut acc = pool.one();
    for &factor in factors {
        let (left, right) = (terms(pool, acc), terms(pool, factor));
        if left.len().saturating_mul(right.len()) > budget.saturating_mul(PRODUCT_SLACK) {
            return None;
        }
        let products: Vec<ExprId> = left
            .iter()
            .flat_map(|&l| right.iter().map(move |&r| (l, r)))
            .map(|(l, r)| pool.mul(l, r))
            .collect();
        acc = pool.sum(products);
        if term_count(pool, acc) > budget {
            return None;
        }
    }
    Some(acc)
}

/// The terms of `e` if it is a sum, else `[e]`.
fn terms(pool: &Pool, e: ExprId) -> Vec<ExprId> {
    match pool.node(e) {
        Node::Add(terms) => terms.to_vec(),
        _ => vec![e],
    }
}

/// The factors of a coefficient-free monomial as `(base, exponent)`.
fn factors(pool: &Pool, monomial: ExprId) -> Vec<(ExprId, i32)> {
    let as_power = |f: ExprId| match pool.node(f) {
        &Node::Pow(base, exp) => (base, exp),
        _ => (f, 1),
    };
    match pool.node(monomial) {
        _ if monomial == pool.one() => Vec::new(),
        Node::Mul(fs) => fs.iter().map(|&f| as_power(f)).collect(),
        _ => vec![as_power(monomial)],
    }
}

/// A trigonometric pattern in a monomial `R · pattern`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Pattern {
    /// `sin²x`.
    SinSquared(ExprId),
    /// `cos²x`.
    CosSquared(ExprId),
    /// `cos a · cos b` with `a < b`.
    CosCos(ExprId, ExprId),
    /// `sin a · sin b` with `a < b`.
    SinSin(ExprId, ExprId),
    /// `sin a · cos b` with `a ≠ b`.
    SinCos(ExprId, ExprId),
}

impl Pattern {
    /// The pattern a partner term must show for a rule to apply.
    fn partner(self) -> Pattern {
        match self {
            Pattern::SinSquared(x) => Pattern::CosSquared(x),
            Pattern::CosSquared(x) => Pattern::SinSquared(x),
            Pattern::CosCos(a, b) => Pattern::SinSin(a, b),
            Pattern::SinSin(a, b) => Pattern::CosCos(a, b),
            Pattern::SinCos(a, b) => Pattern::SinCos(b, a),
        }
    }

    /// The pattern of one trigonometric factor squared.
    fn squared(f: Func, x: ExprId) -> Pattern {
        match f {
            Func::Sin => Pattern::SinSquared(x),
            _ => Pattern::CosSquared(x),
        }
    }

    /// The pattern of two distinct trigonometric factors, if they pair.
    fn pair((f, a): (Func, ExprId), (g, b): (Func, ExprId)) -> Option<Pattern> {
        let (lo, hi) = (a.min(b), a.max(b));
        match (f, g) {
            _ if a == b => None,
            (Func::Cos, Func::Cos) => Some(Pattern::CosCos(lo, hi)),
            (Func::Sin, Func::Sin) => Some(Pattern::SinSin(lo, hi)),
            (Func::Sin, _) => Some(Pattern::SinCos(a, b)),
            _ => Some(Pattern::SinCos(b, a)),
        }
    }
}

/// A term of a sum seen as `R · pattern`.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    /// The coefficient-free monomial it was found in.
    monomial: ExprId,
    /// `R`: the monomial without the pattern.
    rest: ExprId,
    /// The pattern.
    pattern: Pattern,
}

/// The trigonometric factors `(f, argument, exponent)` of a monomial.
fn trig_factors(pool: &Pool, monomial: ExprId) -> Vec<(ExprId, Func, ExprId, i32)> {
    factors(pool, monomial)
        .into_iter()
        .filter_map(|(base, exp)| match pool.node(base) {
            &Node::Func(f @ (Func::Sin | Func::Cos), arg) if exp > 0 => Some((base, f, arg, exp)),
            _ => None,
        })
        .collect()
}

/// Every way of reading `monomial` as `R · pattern`.
fn candidates(pool: &mut Pool, monomial: ExprId) -> Vec<Candidate> {
    let trig = trig_factors(pool, monomial);
    let mut found = Vec::new();
    for (i, &(base, f, x, exp)) in trig.iter().enumerate() {
        if exp >= 2 {
            let rest = divide(pool, monomial, &[base, base]);
            found.push(Candidate { monomial, rest, pattern: Pattern::squared(f, x) });
        }
        for &(other, g, y, _) in &trig[i + 1..] {
            if let Some(pattern) = Pattern::pair((f, x), (g, y)) {
                let rest = divide(pool, monomial, &[base, other]);
                found.push(Candidate { monomial, rest, pattern });
            }
        }
    }
    found
}

/// `monomial / Π divisors`.
fn divide(pool: &mut Pool, monomial: ExprId, divisors: &[ExprId]) -> ExprId {
    let inverses: Vec<ExprId> = divisors.iter().map(|&d| pool.powi(d, -1)).collect();
    pool.product(std::iter::once(monomial).chain(inverses))
}

/// A sum as coefficients of coefficient-free monomials (`1` for the
/// constant), ordered by id so that passes are deterministic.
#[derive(Clone, Debug)]
struct Monomials(BTreeMap<ExprId, Number>);

impl Monomials {
    /// The monomials of an expanded expression.
    fn of(pool: &Pool, e: ExprId) -> Monomials {
        let mut sum = Monomials(BTreeMap::new());
        for t in terms(pool, e) {
            let (c, rest) = pool.split_coefficient(t);
            sum.add(c, rest);
        }
        sum
    }

    /// The expression `Σ c·m`.
    fn to_expr(&self, pool: &mut Pool) -> ExprId {
        let terms: Vec<ExprId> = self
            .0
            .iter()
            .map(|(&m, &c)| {
                let c = pool.number(c);
                pool.mul(c, m)
            })
            .collect();
        pool.sum(terms)
    }

    /// Adds `c · monomial`, dropping it if it cancels.
    fn add(&mut self, c: Number, monomial: ExprId) {
        let sum = self.0.get(&monomial).map_or(c, |&old| old + c);
        if sum.is_zero() {
            self.0.remove(&monomial);
        } else {
            self.0.insert(monomial, sum);
        }
    }

    /// Adds `c · e` for any expression `e` (its coefficient and terms
    /// split off), returning the monomials it touched.
    fn add_expr(&mut self, pool: &Pool, c: Number, e: ExprId) -> Vec<ExprId> {
        terms(pool, e)
            .into_iter()
            .map(|t| {
                let (k, monomial) = pool.split_coefficient(t);
                self.add(c * k, monomial);
                monomial
            })
            .collect()
    }

    /// One pass of recombination: every rule applied once where it can be,
    /// each monomial taking part in at most one rewrite. `None` if the sum
    /// did not get shorter (then no rule applies).
    fn recombined(&self, pool: &mut Pool) -> Option<Monomials> {
        let all: Vec<Candidate> =
            self.0.keys().flat_map(|&m| candidates(pool, m)).collect();
        let by_shape: HashMap<(ExprId, Pattern), ExprId> =
            all.iter().map(|c| ((c.rest, c.pattern), c.monomial)).collect();
        let mut next = self.clone();
        let mut touched = BTreeSet::new();
        for candidate in all {
            let Some(&partner) = by_shape.get(&(candidate.rest, candidate.pattern.partner()))
            else {
                continue;
            };
            if touched.contains(&candidate.monomial) || touched.contains(&partner) {
                continue;
            }
            let rewrite = Rewrite { candidate, partner, sum: &next, touched: &touched };
            if let Some(replacement) = rewrite.replacement(pool) {
                touched.extend([candidate.monomial, partner]);
                next.0.remove(&candidate.monomial);
                next.0.remove(&partner);
                for (c, e) in replacement {
                    let monomials = next.add_expr(pool, c, e);
                    touched.extend(monomials);
                }
            }
        }
        (next.0.len() < self.0.len()).then_some(next)
    }
}

/// A candidate and its partner term in the sum being rewritten.
struct Rewrite<'a> {
    /// The term read as `R · pattern`.
    candidate: Candidate,
    /// The term with `R · pattern.partner()`.
    partner: ExprId,
    /// The sum as rewritten so far in this pass.
    sum: &'a Monomials,
    /// Monomials already changed in this pass.
    touched: &'a BTreeSet<ExprId>,
}

impl Rewrite<'_> {
    /// The terms `(c, e)` replacing the pair, or `None` if no rule shortens
    /// the sum.
    fn replacement(&self, pool: &mut Pool) -> Option<Vec<(Number, ExprId)>> {
        let c = *self.sum.0.get(&self.candidate.monomial)?;
        let d = *self.sum.0.get(&self.partner)?;
        let rest = self.candidate.rest;
        let same_sign = if d == c {
            Some(true)
        } else {
            (d == -c).then_some(false)
        };
        let (coefficient, f, a, b, same_sign) = match (self.candidate.pattern, same_sign) {
            (Pattern::SinSquared(_) | Pattern::CosSquared(_), Some(true)) => {
                return Some(vec![(c, rest)]);
            }
            (Pattern::SinSquared(_) | Pattern::CosSquared(_), _) => {
                return self.unequal_squares(c, d);
            }
            (_, None) => return None,
            (Pattern::CosCos(a, b), Some(same)) => (c, Func::Cos, a, b, same),
            // The coefficient of `cos a cos b` carries over.
            (Pattern::SinSin(a, b), Some(same)) => (d, Func::Cos, a, b, same),
            (Pattern::SinCos(a, b), Some(same)) => (c, Func::Sin, a, b, same),
        };
        // cos a cos b ± sin a sin b = cos(a ∓ b); sin a cos b ± cos a sin b = sin(a ± b).
        let difference = same_sign == (f == Func::Cos);
        let angle = if difference { pool.sub(a, b) } else { pool.add(a, b) };
        let call = pool.func(f, angle);
        Some(vec![(coefficient, pool.mul(rest, call))])
    }

    /// `c·R·p + d·R·q` with `{p, q} = {sin²x, cos²x}` and `c ≠ d`, as
    /// `d·R + (c − d)·R·p`, when a term `R` is there to absorb `d·R` (so
    /// the sum gets shorter).
    fn unequal_squares(&self, c: Number, d: Number) -> Option<Vec<(Number, ExprId)>> {
        let rest = self.candidate.rest;
        let absorbs = self.sum.0.contains_key(&rest) && !self.touched.contains(&rest);
        absorbs.then(|| vec![(d, rest), (c + -d, self.candidate.monomial)])
    }
}
