//! Readable forms of derived expressions: expand into a sum of monomials
//! within a budget, then recombine trigonometric pairs until no rule
//! applies:
//!
//! * `c·R·sin²x + c·R·cos²x = c·R`, and with different coefficients
//!   `a·R·sin²x + b·R·cos²x = b·R + (a − b)·R·sin²x` when a term `R` is
//!   already there to absorb `b·R` (so the sum gets shorter);
//! * `c·R − c·R·sin²x = c·R·cos²x` and `c·R − c·R·cos²x = c·R·sin²x`;
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
//! highest-indexed coordinate first (see [`crate::render::text`]).
//!
//! Two layers read them: the optimiser (an entry's compact form starts from
//! its readable form) and the renderer (the docs print them). Both ask
//! through one [`ReadableForms`] per derivation, so each form is computed
//! once.

use std::collections::{BTreeMap, BTreeSet, HashMap};

use crate::expr::{ExprId, Func, Node, Number, Pool};

/// The readable forms of one derivation's expressions, each computed once
/// for the optimiser and the renderer, which ask about the same
/// expressions within different budgets.
#[derive(Default)]
pub struct ReadableForms {
    /// What is known of each expression asked about (looked up, never
    /// iterated).
    known: HashMap<ExprId, Known>,
    /// The expansions of every node met so far, by budget (`None`: past
    /// it): the entries of one derivation share most of their DAG, which
    /// is expanded once.
    expansions: HashMap<usize, Expansions>,
}

/// The expansion of each node within one budget, `None` past it.
type Expansions = HashMap<ExprId, Option<ExprId>>;

/// What the budgets tried so far tell of one expression's readable form.
#[derive(Clone, Copy, Default)]
struct Known {
    /// The form, and the smallest budget it was found within.
    fits: Option<(ExprId, usize)>,
    /// The largest budget its expansion exceeded.
    too_large: Option<usize>,
}

impl ReadableForms {
    /// `e` as a short sum of monomials for humans, or `None` if its
    /// expansion, or that of any part of it, would have more than `budget`
    /// terms (see the module docs); computed only if what is known of `e`
    /// does not decide it. The budget only stops the work, so a form
    /// found within a budget is the same within any larger one, and an
    /// expansion too large for a budget is too large for any smaller one.
    /// The expansions of the nodes met in earlier calls within the same
    /// budget are reused too ([`Pool::try_rebuild_remembering`]).
    /// The reuse is exact: a computation it saves would retrace the steps
    /// of an earlier one (or a prefix of them, when it fails sooner), so it
    /// would intern no new node, and the pool's ids (which order sums and
    /// products, and so the emitted code) are as without it.
    pub fn get(&mut self, pool: &mut Pool, e: ExprId, budget: usize) -> Option<ExprId> {
        let known = *self.known.entry(e).or_default();
        match (known.fits, known.too_large) {
            (Some((form, within)), _) if within <= budget => return Some(form),
            (_, Some(over)) if budget <= over => return None,
            _ => {}
        }
        let expansions = self.expansions.entry(budget).or_default();
        let form = readable_remembering(pool, e, budget, expansions);
        let known = self.known.entry(e).or_default();
        match form {
            Some(form) => known.fits = Some((form, budget)),
            None => known.too_large = Some(budget),
        }
        form
    }
}

/// How many products (before like terms merge) one multiplication of two
/// expanded sums may form, in multiples of the budget: a little room for
/// cancellation, and a bound on the work.
const PRODUCT_SLACK: usize = 4;

/// The number of terms of `e` read as a sum ([`terms`]): 0 for zero, 1
/// for anything but a sum or a multiple of one.
pub fn term_count(pool: &Pool, e: ExprId) -> usize {
    match multiple_of_sum(pool, e) {
        Some((_, sum)) => pool
            .children(sum)
            .iter()
            .map(|&t| term_count(pool, t))
            .sum(),
        None if pool.is_zero(e) => 0,
        None => 1,
    }
}

/// `e` as `c · sum` if it is a sum (`c = 1`) or a numeric multiple of one:
/// the pool builds a sum whose first term is negative as `−1` times the
/// sum with every sign turned, and keeps a multiple of a sum whole inside
/// another sum where no term meets.
fn multiple_of_sum(pool: &Pool, e: ExprId) -> Option<(Number, ExprId)> {
    let (c, rest) = pool.split_coefficient(e);
    matches!(pool.node(rest), Node::Add(_)).then_some((c, rest))
}

/// `e` as a short sum of monomials for humans: expanded, then with
/// trigonometric pairs recombined (see the module docs). `None` if the
/// expansion of `e`, or of any part of it, would have more than `budget`
/// terms: the work is bounded by the size of `e`'s DAG times the budget.
/// Computed afresh: the reference [`ReadableForms`] is tested against.
#[cfg(test)]
pub fn readable(pool: &mut Pool, e: ExprId, budget: usize) -> Option<ExprId> {
    readable_remembering(pool, e, budget, &mut Expansions::new())
}

/// [`readable`], with the expansions of the nodes of `e` taken from and
/// added to `expansions` (all within `budget`).
fn readable_remembering(
    pool: &mut Pool,
    e: ExprId,
    budget: usize,
    expansions: &mut Expansions,
) -> Option<ExprId> {
    let expanded = expand_within(pool, e, budget, expansions)?;
    let mut sum = Monomials::of(pool, expanded);
    while let Some(shorter) = sum.recombined(pool) {
        sum = shorter;
    }
    Some(sum.to_expr(pool))
}

/// Like [`Pool::expand`], but giving up as soon as an intermediate result
/// exceeds `budget` terms; the nodes already in `expansions` are not
/// expanded again.
fn expand_within(
    pool: &mut Pool,
    e: ExprId,
    budget: usize,
    expansions: &mut Expansions,
) -> Option<ExprId> {
    let expanded = pool.try_rebuild_remembering(&[e], expansions, |pool, node, images| {
        let image = expand_node(pool, node, images, budget)?;
        (term_count(pool, image) <= budget).then_some(image)
    })?;
    Some(expanded[0])
}

/// The expansion of `node`, given those of its children: a sum is the sum
/// of its children's monomials ([`terms`]), so that a child the pool holds
/// as a multiple of a sum (`−(a + b)` beside `c`, where no term meets)
/// has its constant and terms merged with the others as a flat polynomial
/// would.
fn expand_node(pool: &mut Pool, node: ExprId, images: &[ExprId], budget: usize) -> Option<ExprId> {
    match *pool.node(node) {
        Node::Add(_) => {
            let mut monomials = Vec::new();
            for &image in images {
                monomials.extend(terms(pool, image));
            }
            Some(pool.sum(monomials))
        }
        Node::Mul(_) => distribute(pool, images, budget),
        Node::Pow(_, exp) => expand_power(pool, images[0], exp, budget),
        _ => Some(pool.with_children(node, images)),
    }
}

/// `base ^ exp` for an expanded `base`, multiplied out if `base` is a sum
/// and `exp` positive.
fn expand_power(pool: &mut Pool, base: ExprId, exp: i32, budget: usize) -> Option<ExprId> {
    let is_sum = multiple_of_sum(pool, base).is_some();
    match (is_sum, usize::try_from(exp)) {
        (true, Ok(count)) if count > budget => None,
        (true, Ok(count)) => distribute(pool, &vec![base; count], budget),
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

/// The terms of `e` read as a sum of monomials, every sign seen: the
/// terms of a sum, those of a multiple of a sum (`−(a − b)` is `−a + b`,
/// read through [`multiple_of_sum`] here rather than built flat in the
/// pool), else `[e]`.
pub fn terms(pool: &mut Pool, e: ExprId) -> Vec<ExprId> {
    let Some((c, sum)) = multiple_of_sum(pool, e) else {
        return vec![e];
    };
    let coefficient = (c != Number::ONE).then(|| pool.number(c));
    let mut flat = Vec::new();
    for t in pool.children(sum).to_vec() {
        let scaled = coefficient.map_or(t, |coefficient| pool.mul(coefficient, t));
        flat.extend(terms(pool, scaled));
    }
    flat
}

/// The factors of a coefficient-free monomial as `(base, exponent)`.
pub fn factors(pool: &Pool, monomial: ExprId) -> Vec<(ExprId, i32)> {
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
            found.push(Candidate {
                monomial,
                rest,
                pattern: Pattern::squared(f, x),
            });
        }
        for &(other, g, y, _) in &trig[i + 1..] {
            if let Some(pattern) = Pattern::pair((f, x), (g, y)) {
                let rest = divide(pool, monomial, &[base, other]);
                found.push(Candidate {
                    monomial,
                    rest,
                    pattern,
                });
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
    fn of(pool: &mut Pool, e: ExprId) -> Monomials {
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
    fn add_expr(&mut self, pool: &mut Pool, c: Number, e: ExprId) -> Vec<ExprId> {
        terms(pool, e)
            .into_iter()
            .map(|t| {
                let (k, monomial) = pool.split_coefficient(t);
                self.add(c * k, monomial);
                monomial
            })
            .collect()
    }

    /// `c·R − c·R·p = c·R·q` with `{p, q} = {sin²x, cos²x}`, where the
    /// `candidate` is `R·p` and a term `R` is there with the opposite
    /// coefficient (two terms become one); every monomial it changes is
    /// `touched`.
    fn complement(
        &mut self,
        pool: &mut Pool,
        candidate: &Candidate,
        touched: &mut BTreeSet<ExprId>,
    ) {
        let (monomial, rest) = (candidate.monomial, candidate.rest);
        let (f, x) = match candidate.pattern {
            Pattern::SinSquared(x) => (Func::Cos, x),
            Pattern::CosSquared(x) => (Func::Sin, x),
            _ => return,
        };
        let (Some(&a), Some(&b)) = (self.0.get(&monomial), self.0.get(&rest)) else {
            return;
        };
        if b != -a || touched.contains(&monomial) || touched.contains(&rest) {
            return;
        }
        let other = pool.func(f, x);
        let square = pool.powi(other, 2);
        let replaced = pool.mul(rest, square);
        self.0.remove(&monomial);
        self.0.remove(&rest);
        touched.extend(self.add_expr(pool, b, replaced));
        touched.extend([monomial, rest]);
    }

    /// One pass of recombination: every rule applied once where it can be,
    /// each monomial taking part in at most one rewrite. `None` if the sum
    /// did not get shorter (then no rule applies).
    fn recombined(&self, pool: &mut Pool) -> Option<Monomials> {
        let all: Vec<Candidate> = self.0.keys().flat_map(|&m| candidates(pool, m)).collect();
        let by_shape: HashMap<(ExprId, Pattern), ExprId> = all
            .iter()
            .map(|c| ((c.rest, c.pattern), c.monomial))
            .collect();
        let mut next = self.clone();
        let mut touched = BTreeSet::new();
        for candidate in all {
            let Some(&partner) = by_shape.get(&(candidate.rest, candidate.pattern.partner()))
            else {
                next.complement(pool, &candidate, &mut touched);
                continue;
            };
            if touched.contains(&candidate.monomial) || touched.contains(&partner) {
                continue;
            }
            let rewrite = Rewrite {
                candidate,
                partner,
                sum: &next,
                touched: &touched,
            };
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
        let angle = if difference {
            pool.sub(a, b)
        } else {
            pool.add(a, b)
        };
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

#[cfg(test)]
pub(crate) mod tests {
    use std::hash::{DefaultHasher, Hash, Hasher};

    use super::*;
    use crate::expr::{Env, Sym};

    /// Symbol values in `[-2, 2)` drawn from a hash of `(seed, symbol)`:
    /// deterministic on every machine.
    struct Sample(u64);

    impl Env for Sample {
        fn value(&self, sym: Sym) -> f64 {
            let mut hasher = DefaultHasher::new();
            (self.0, sym).hash(&mut hasher);
            (hasher.finish() >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
        }
    }

    /// Asserts that `a` and `b` agree at 20 sample points.
    fn assert_same_value(pool: &Pool, a: ExprId, b: ExprId) {
        for seed in 0..20 {
            let (x, y) = (pool.eval(a, &Sample(seed)), pool.eval(b, &Sample(seed)));
            let scale = x.abs().max(y.abs()).max(1.0);
            assert!(
                (x - y).abs() <= 1e-10 * scale,
                "{x} vs {y} at sample {seed}"
            );
        }
    }

    /// The readable form of `e`, checked to have the value of `e`.
    fn checked(pool: &mut Pool, e: ExprId) -> ExprId {
        let form = readable(pool, e, 400).expect("within the budget");
        assert_same_value(pool, e, form);
        form
    }

    /// Small constructors for building test expressions without nested
    /// `&mut` borrows.
    pub(crate) trait Build {
        fn num(&mut self, num: i128, den: i128) -> ExprId;
        fn prod(&mut self, factors: &[ExprId]) -> ExprId;
        fn plus(&mut self, terms: &[ExprId]) -> ExprId;
        fn minus(&mut self, a: ExprId, b: ExprId) -> ExprId;
        fn pow(&mut self, base: ExprId, exp: i32) -> ExprId;
        fn sin_pow(&mut self, x: ExprId, exp: i32) -> ExprId;
        fn cos_pow(&mut self, x: ExprId, exp: i32) -> ExprId;
    }

    impl Build for Pool {
        fn num(&mut self, num: i128, den: i128) -> ExprId {
            self.rational(num, den)
        }
        fn prod(&mut self, factors: &[ExprId]) -> ExprId {
            self.product(factors.iter().copied())
        }
        fn plus(&mut self, terms: &[ExprId]) -> ExprId {
            self.sum(terms.iter().copied())
        }
        fn minus(&mut self, a: ExprId, b: ExprId) -> ExprId {
            self.sub(a, b)
        }
        fn pow(&mut self, base: ExprId, exp: i32) -> ExprId {
            self.powi(base, exp)
        }
        fn sin_pow(&mut self, x: ExprId, exp: i32) -> ExprId {
            let s = self.sin(x);
            self.powi(s, exp)
        }
        fn cos_pow(&mut self, x: ExprId, exp: i32) -> ExprId {
            let c = self.cos(x);
            self.powi(c, exp)
        }
    }

    /// `m, L, g, d, l` (parameters 0–4), `θ₁, θ₂` and `θ̇₁, θ̇₂`.
    pub(crate) struct Symbols {
        pub m: ExprId,
        pub big_l: ExprId,
        pub g: ExprId,
        pub d: ExprId,
        pub l: ExprId,
        pub q: [ExprId; 2],
        pub u: [ExprId; 2],
    }

    pub(crate) fn symbols(p: &mut Pool) -> Symbols {
        let [m, big_l, g, d, l] = [0, 1, 2, 3, 4].map(|i| p.sym(Sym::Param(i)));
        Symbols {
            m,
            big_l,
            g,
            d,
            l,
            q: [0, 1].map(|i| p.sym(Sym::Coord(i))),
            u: [0, 1].map(|i| p.sym(Sym::Speed(i))),
        }
    }

    #[test]
    fn term_counts() {
        let mut p = Pool::new();
        let s = symbols(&mut p);
        assert_eq!(term_count(&p, p.zero()), 0);
        let three = p.int(3);
        assert_eq!(term_count(&p, three), 1);
        let product = p.prod(&[s.m, s.g, s.q[0]]);
        assert_eq!(term_count(&p, product), 1);
        let sum = p.plus(&[s.m, s.g, product]);
        assert_eq!(term_count(&p, sum), 3);
    }

    #[test]
    fn cosine_of_a_difference_is_one_term() {
        let mut p = Pool::new();
        let [a, b] = symbols(&mut p).q;
        let (ca, cb, sa, sb) = (p.cos(a), p.cos(b), p.sin(a), p.sin(b));
        let (cc, ss) = (p.mul(ca, cb), p.mul(sa, sb));
        let e = p.add(cc, ss);
        let form = checked(&mut p, e);
        assert_eq!(term_count(&p, form), 1);
        let difference = p.sub(a, b);
        assert_eq!(form, p.cos(difference));
    }

    /// The diagonal of an inertia tensor turned about an axis, its trace
    /// kept: `m + L − m sin²θ₁ − L cos²θ₁ = m cos²θ₁ + L sin²θ₁`.
    #[test]
    fn one_minus_a_square_is_the_other_square() {
        let mut p = Pool::new();
        let s = symbols(&mut p);
        let (sin2, cos2) = (p.sin_pow(s.q[0], 2), p.cos_pow(s.q[0], 2));
        let (m_sin2, l_cos2) = (p.mul(s.m, sin2), p.mul(s.big_l, cos2));
        let trace = p.add(s.m, s.big_l);
        let turned = p.add(m_sin2, l_cos2);
        let e = p.minus(trace, turned);
        let form = checked(&mut p, e);
        let (m_cos2, l_sin2) = (p.mul(s.m, cos2), p.mul(s.big_l, sin2));
        assert_eq!(form, p.add(m_cos2, l_sin2));
    }

    #[test]
    fn all_four_angle_sum_rules_with_a_common_rest() {
        let mut p = Pool::new();
        let s = symbols(&mut p);
        let [a, b] = s.q;
        // R = -3/2 m L² θ̇₂², shared by both terms of each pair.
        let (c, l2, u2) = (p.num(-3, 2), p.pow(s.big_l, 2), p.pow(s.u[1], 2));
        let rest = p.prod(&[c, s.m, l2, u2]);
        let (sa, ca, sb, cb) = (p.sin(a), p.cos(a), p.sin(b), p.cos(b));
        let (difference, total) = (p.sub(a, b), p.add(a, b));
        let cases = [
            ([ca, cb], [sa, sb], 1, p.cos(difference)),
            ([ca, cb], [sa, sb], -1, p.cos(total)),
            ([sa, cb], [ca, sb], 1, p.sin(total)),
            ([sa, cb], [ca, sb], -1, p.sin(difference)),
        ];
        for (first, second, sign, expected) in cases {
            let sign_e = p.int(sign);
            let first = p.prod(&first);
            let second = p.prod(&[sign_e, second[0], second[1]]);
            let pair = p.add(first, second);
            let e = p.mul(rest, pair);
            let form = checked(&mut p, e);
            assert_eq!(form, p.mul(rest, expected), "sign {sign}");
        }
    }

    /// Seed 2: `M₁₁ = m d² (sin²φ + cos²φ) + 1/12 m l² cos²θ`.
    pub(crate) fn seed_rotating_bar_m11(p: &mut Pool, s: &Symbols) -> ExprId {
        let [phi, theta] = s.q;
        let (sin2, cos2) = (p.sin_pow(phi, 2), p.cos_pow(phi, 2));
        let squares = p.add(sin2, cos2);
        let d2 = p.pow(s.d, 2);
        let orbit = p.prod(&[s.m, d2, squares]);
        let (twelfth, l2, cos2_theta) = (p.num(1, 12), p.pow(s.l, 2), p.cos_pow(theta, 2));
        let spin = p.prod(&[twelfth, s.m, l2, cos2_theta]);
        p.add(orbit, spin)
    }

    #[test]
    fn pythagoras_with_equal_coefficients() {
        let mut p = Pool::new();
        let s = symbols(&mut p);
        let e = seed_rotating_bar_m11(&mut p, &s);
        let form = checked(&mut p, e);
        assert_eq!(term_count(&p, form), 2);
        let (d2, l2, twelfth, cos2_theta) = (
            p.pow(s.d, 2),
            p.pow(s.l, 2),
            p.num(1, 12),
            p.cos_pow(s.q[1], 2),
        );
        let orbit = p.mul(s.m, d2);
        let spin = p.prod(&[twelfth, s.m, l2, cos2_theta]);
        assert_eq!(form, p.add(orbit, spin));
    }

    #[test]
    fn pythagoras_with_different_coefficients_only_when_shorter() {
        let mut p = Pool::new();
        let x = symbols(&mut p).q[0];
        let (sin2, cos2, three, five, two) = (
            p.sin_pow(x, 2),
            p.cos_pow(x, 2),
            p.int(3),
            p.int(5),
            p.int(2),
        );
        let (a, b) = (p.mul(three, sin2), p.mul(five, cos2));
        let mixed = p.add(a, b);
        // Nothing absorbs the constant part: left as it is.
        assert_eq!(checked(&mut p, mixed), mixed);
        // With a constant to absorb it, two terms instead of three.
        let e = p.add(mixed, two);
        let form = checked(&mut p, e);
        assert_eq!(term_count(&p, form), 2);
        assert!(p.free_symbols(form).contains(&Sym::Coord(0)));
    }

    #[test]
    fn recombination_repeats_until_nothing_applies() {
        // cos a cos b sin²c + sin a sin b sin²c + cos(a − b) cos²c = cos(a − b),
        // in two rounds.
        let mut p = Pool::new();
        let [a, b] = symbols(&mut p).q;
        let c = p.sym(Sym::Coord(2));
        let (sin2c, cos2c) = (p.sin_pow(c, 2), p.cos_pow(c, 2));
        let (ca, cb, sa, sb) = (p.cos(a), p.cos(b), p.sin(a), p.sin(b));
        let a_minus_b = p.sub(a, b);
        let difference = p.cos(a_minus_b);
        let first = p.prod(&[ca, cb, sin2c]);
        let second = p.prod(&[sa, sb, sin2c]);
        let third = p.mul(difference, cos2c);
        let e = p.plus(&[first, second, third]);
        assert_eq!(checked(&mut p, e), difference);
    }

    /// `scale · e_θ = scale · (cos θ, sin θ)`.
    fn e_theta(p: &mut Pool, theta: ExprId, scale: ExprId) -> [ExprId; 2] {
        let (c, s) = (p.cos(theta), p.sin(theta));
        [p.mul(scale, c), p.mul(scale, s)]
    }

    /// `v · w` in components.
    fn dot(p: &mut Pool, v: [ExprId; 2], w: [ExprId; 2]) -> ExprId {
        let terms = [p.mul(v[0], w[0]), p.mul(v[1], w[1])];
        p.plus(&terms)
    }

    /// The bias acceleration `−r θ̇² e_r` with `e_r = (sin θ, −cos θ)`.
    fn centripetal(p: &mut Pool, theta: ExprId, rate: ExprId, r: ExprId) -> [ExprId; 2] {
        let rate2 = p.pow(rate, 2);
        let k = p.mul(r, rate2);
        let (s, c) = (p.sin(theta), p.cos(theta));
        let x = p.mul(k, s);
        [p.neg(x), p.mul(k, c)]
    }

    /// Seed example 1 as d'Alembert produces it, with vectors in `N`
    /// components: `(M₁₂, f₁)`.
    pub(crate) fn seed_double_pendulum(p: &mut Pool, s: &Symbols) -> (ExprId, ExprId) {
        let ([t1, t2], [u1, u2]) = (s.q, s.u);
        let half = p.num(1, 2);
        let half_l = p.mul(half, s.big_l);
        // M₁₂ = m (∂v_G2/∂θ̇₁) · (∂v_G2/∂θ̇₂).
        let (v21, v22) = (e_theta(p, t1, s.big_l), e_theta(p, t2, half_l));
        let v21_v22 = dot(p, v21, v22);
        let m12 = p.mul(s.m, v21_v22);
        // f₁ = −m a_G1·∂v_G1/∂θ̇₁ − m a_G2·∂v_G2/∂θ̇₁ − m g j·(∂v_G1/∂θ̇₁ + ∂v_G2/∂θ̇₁).
        let a1 = centripetal(p, t1, u1, half_l);
        let (x, y) = (
            centripetal(p, t1, u1, s.big_l),
            centripetal(p, t2, u2, half_l),
        );
        let a2 = [p.add(x[0], y[0]), p.add(x[1], y[1])];
        let v11 = e_theta(p, t1, half_l);
        let inertia = [dot(p, a1, v11), dot(p, a2, v21)];
        let inertia = p.plus(&inertia);
        let inertia = p.mul(s.m, inertia);
        let lever = p.add(v11[1], v21[1]);
        let gravity = p.prod(&[s.m, s.g, lever]);
        let active_minus_inertia = p.add(inertia, gravity);
        (m12, p.neg(active_minus_inertia))
    }

    #[test]
    fn seed_double_pendulum_entries() {
        let mut p = Pool::new();
        let s = symbols(&mut p);
        let ([t1, t2], u2) = (s.q, s.u[1]);
        let (m12, f1) = seed_double_pendulum(&mut p, &s);
        let (half, l2, u2_2, minus_three_halves) =
            (p.num(1, 2), p.pow(s.big_l, 2), p.pow(u2, 2), p.num(-3, 2));
        let t2_minus_t1 = p.sub(t2, t1);
        let (cos21, sin21, sin1) = (p.cos(t2_minus_t1), p.sin(t2_minus_t1), p.sin(t1));
        let form = checked(&mut p, m12);
        assert_eq!(form, p.prod(&[half, s.m, l2, cos21]));
        let form = checked(&mut p, f1);
        let coriolis = p.prod(&[half, s.m, l2, u2_2, sin21]);
        let weight = p.prod(&[minus_three_halves, s.m, s.g, s.big_l, sin1]);
        assert_eq!(form, p.add(coriolis, weight));
        assert_eq!(term_count(&p, form), 2);
    }

    /// Shared forms give `readable`'s answer at every budget, asked in any
    /// order, and what they save would have interned nothing new.
    #[test]
    fn shared_forms_answer_as_readable_and_save_only_repeated_work() {
        let mut p = Pool::new();
        let s = symbols(&mut p);
        let (m12, f1) = seed_double_pendulum(&mut p, &s);
        let a_plus_b = p.add(s.q[0], s.q[1]);
        let cube = p.pow(a_plus_b, 3);
        let mut forms = ReadableForms::default();
        for e in [m12, f1, cube] {
            for budget in [400, 2, 200, 1, 400, 3, 4, 8, 2] {
                let shared = forms.get(&mut p, e, budget);
                let nodes = p.len();
                assert_eq!(shared, readable(&mut p, e, budget), "budget {budget}");
                assert_eq!(p.len(), nodes, "a saved computation interns a node");
            }
        }
    }

    #[test]
    fn the_budget_bounds_the_expansion() {
        let mut p = Pool::new();
        let [a, b] = symbols(&mut p).q;
        let a_plus_b = p.add(a, b);
        let cube = p.pow(a_plus_b, 3);
        let form = readable(&mut p, cube, 4);
        assert_eq!(form.map(|f| term_count(&p, f)), Some(4));
        assert_eq!(readable(&mut p, cube, 3), None);
        let huge = p.pow(a_plus_b, i32::MAX);
        assert_eq!(readable(&mut p, huge, 400), None);
        // A product of 40 binomials would have 2⁴⁰ terms.
        let binomials: Vec<ExprId> = (0..40)
            .map(|i| {
                let x = p.sym(Sym::Coord(i));
                let c = p.cos(x);
                let one = p.one();
                p.add(one, c)
            })
            .collect();
        let product = p.prod(&binomials);
        assert_eq!(readable(&mut p, product, 400), None);
        let zero = p.zero();
        assert_eq!(readable(&mut p, zero, 0), Some(zero));
    }

    #[test]
    fn random_trigonometric_polynomials_stay_exact() {
        let mut p = Pool::new();
        let s = symbols(&mut p);
        let [a, b] = s.q;
        let angles = [a, b, p.sub(a, b), p.add(a, b)];
        let scales = [s.m, s.big_l, s.u[0]];
        for seed in 0..40u64 {
            let pick = |i: u64, n: usize| {
                let mut hasher = DefaultHasher::new();
                (seed, i).hash(&mut hasher);
                (hasher.finish() % n as u64) as usize
            };
            let mut factors = Vec::new();
            for i in 0..3 {
                let mut terms = Vec::new();
                for j in 0..3 {
                    let angle = angles[pick(10 * i + j, angles.len())];
                    let call = if pick(100 + 10 * i + j, 2) == 0 {
                        p.sin(angle)
                    } else {
                        p.cos(angle)
                    };
                    let c = p.int(pick(200 + 10 * i + j, 5) as i64 - 2);
                    terms.push(p.prod(&[c, call, scales[pick(300 + i, 3)]]));
                }
                factors.push(p.plus(&terms));
            }
            let e = p.prod(&factors);
            let form = checked(&mut p, e);
            let expanded = p.expand(e);
            assert!(term_count(&p, form) <= term_count(&p, expanded));
        }
    }
}
