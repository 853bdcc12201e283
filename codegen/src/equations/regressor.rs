//! The regressor of the inverse dynamics: `M v̇ − f = Y π` at zero inputs,
//! with `π` the *base parameters*, found symbolically.
//!
//! Every entry of `M v̇ − f` is expanded as a polynomial in the parameters
//! only — the parameter-free parts stay shared DAGs, so the expansion is as
//! large as the number of parameter products, not of trigonometric terms:
//! `Σ μ · Y_μ(q, v, v̇)`, with `μ` a product of parameters (`m₂ l₁²`,
//! `g m₁ c₁`; `1` for none). A parameter inside a function or under a
//! negative power of a sum is not a polynomial one there: that part stays
//! in `Y` (read from the struct). The distinct products are the parameters
//! that enter linearly; the `Y_μ` are the columns of `Y`. Products whose
//! columns are equal up to a constant factor — compared in expanded,
//! trigonometrically recombined form — cannot be told apart by any motion,
//! so they are regrouped into one base parameter, their combination: for a
//! two-link arm `m₁ c₁² + m₂ l₁² + I₁`. Columns that vanish never appear; a
//! column too large to expand stays a base parameter of its own. Inputs are
//! set to zero (`Y π` is the force the motion needs beyond the inputs);
//! time must not appear.

use crate::expr::{ExprId, Func, Node, Number, Pool, Sym, SymKinds};
use crate::render::trig::readable;
use std::collections::{BTreeMap, HashMap};

/// Most monomials an entry of a column may expand to for regrouping.
const BUDGET: usize = 2000;

/// Most parameter products one expression may hold.
const MOST_PRODUCTS: usize = 5000;

/// A product of parameters: `(parameter index, exponent)`, by index.
pub type Monomial = Vec<(u32, i32)>;

/// A base parameter: `Σ cᵢ μᵢ` over products of parameters `μᵢ`.
pub type Combination = Vec<(Number, Monomial)>;

/// `Y` and the base parameters `π` of `M v̇ − f = Y π`.
pub struct Regressor {
    /// `Y`, row by row (one row per speed, one column per base parameter).
    pub rows: Vec<Vec<ExprId>>,
    /// Each base parameter as a combination `Σ cᵢ μᵢ` of parameter products.
    pub combinations: Vec<Combination>,
}

/// Why a model has no regressor.
pub enum Failure {
    /// `M v̇ − f` holds too many products of parameters.
    TooLarge,
    /// `M v̇ − f` depends on time outside the inputs' terms.
    TimeDependent,
}

/// An expression as a polynomial in the parameters: the coefficient of
/// each product, free of polynomial parameters.
type Polynomial = BTreeMap<Monomial, ExprId>;

/// The regressor of `inverse_dynamics` (`M q̈ − f`, in the symbols `q̈`).
pub fn regressor(pool: &mut Pool, inverse_dynamics: &[ExprId]) -> Result<Regressor, Failure> {
    let nv = inverse_dynamics.len();
    let mut polynomials: HashMap<ExprId, Polynomial> = HashMap::new();
    for e in pool.topo_order(inverse_dynamics) {
        let p = polynomial(pool, e, &polynomials).ok_or(Failure::TooLarge)?;
        polynomials.insert(e, p);
    }
    let mut columns: BTreeMap<Monomial, Vec<ExprId>> = BTreeMap::new();
    for (row, entry) in inverse_dynamics.iter().enumerate() {
        for (monomial, &coefficient) in &polynomials[entry] {
            if pool.kinds(coefficient).intersects(SymKinds::TIME) {
                return Err(Failure::TimeDependent);
            }
            let column = columns
                .entry(monomial.clone())
                .or_insert_with(|| vec![pool.zero(); nv]);
            column[row] = coefficient;
        }
    }
    Ok(grouped(pool, columns.into_iter().collect()))
}

/// The polynomial of `e`, from those of its children; `None` past
/// [`MOST_PRODUCTS`].
fn polynomial(
    pool: &mut Pool,
    e: ExprId,
    known: &HashMap<ExprId, Polynomial>,
) -> Option<Polynomial> {
    let kinds = pool.kinds(e);
    if !kinds.intersects(SymKinds::PARAM.union(SymKinds::INPUT)) {
        return Some(constant(pool, e));
    }
    let p = match pool.node(e).clone() {
        Node::Number(_) => constant(pool, e),
        Node::Sym(Sym::Param(i)) => BTreeMap::from([(vec![(i, 1)], pool.one())]),
        // The inputs are zero.
        Node::Sym(Sym::Input(_)) => Polynomial::new(),
        Node::Sym(_) => constant(pool, e),
        Node::Add(terms) => {
            let mut sum = Polynomial::new();
            for term in terms.iter() {
                add_into(pool, &mut sum, &known[term]);
            }
            sum
        }
        Node::Mul(factors) => {
            let mut product = constant(pool, pool.one());
            for factor in factors.iter() {
                product = multiply(pool, &product, &known[factor]);
                if product.len() > MOST_PRODUCTS {
                    return None;
                }
            }
            product
        }
        Node::Pow(base, n) => power(pool, e, &known[&base], n)?,
        Node::Func(Func::Group, arg) => known[&arg].clone(),
        Node::Func(f, arg) => match as_constant(pool, &known[&arg]) {
            Some(argument) => {
                let value = pool.func(f, argument);
                constant(pool, value)
            }
            None => opaque(pool, e, &known[&arg]),
        },
    };
    Some(p)
}

/// `{1: e}` (the empty map for zero).
fn constant(pool: &Pool, e: ExprId) -> Polynomial {
    match pool.is_zero(e) {
        true => Polynomial::new(),
        false => BTreeMap::from([(Monomial::new(), e)]),
    }
}

/// The value of a polynomial without parameter products, if it is one.
fn as_constant(pool: &Pool, p: &Polynomial) -> Option<ExprId> {
    match p.len() {
        0 => Some(pool.zero()),
        1 => p.get(&Monomial::new()).copied(),
        _ => None,
    }
}

/// `e` kept whole (a parameter inside a function stays in `Y`), with the
/// inputs in its argument set to zero by rebuilding it from `argument`.
fn opaque(pool: &mut Pool, e: ExprId, argument: &Polynomial) -> Polynomial {
    let Node::Func(f, _) = *pool.node(e) else {
        return constant(pool, e);
    };
    let terms: Vec<ExprId> = argument
        .iter()
        .map(|(monomial, &c)| {
            let product = monomial_expr(pool, monomial);
            pool.mul(c, product)
        })
        .collect();
    let argument = pool.sum(terms);
    let value = pool.func(f, argument);
    constant(pool, value)
}

/// `base ^ n`: each product's exponents times `n` for a single product,
/// multiplied out for a sum and `n > 0`, kept whole otherwise.
fn power(pool: &mut Pool, e: ExprId, base: &Polynomial, n: i32) -> Option<Polynomial> {
    if base.len() == 1 {
        let (monomial, &c) = base.iter().next()?;
        let scaled: Monomial = monomial.iter().map(|&(i, k)| (i, k * n)).collect();
        let c = pool.powi(c, n);
        return Some(BTreeMap::from([(scaled, c)]));
    }
    match usize::try_from(n) {
        Ok(count) if count <= 8 => {
            let mut product = constant(pool, pool.one());
            for _ in 0..count {
                product = multiply(pool, &product, base);
                if product.len() > MOST_PRODUCTS {
                    return None;
                }
            }
            Some(product)
        }
        _ => Some(constant(pool, e)),
    }
}

/// `sum += p`.
fn add_into(pool: &mut Pool, sum: &mut Polynomial, p: &Polynomial) {
    for (monomial, &c) in p {
        let total = match sum.get(monomial) {
            Some(&previous) => pool.add(previous, c),
            None => c,
        };
        if pool.is_zero(total) {
            sum.remove(monomial);
        } else {
            sum.insert(monomial.clone(), total);
        }
    }
}

/// `a · b`.
fn multiply(pool: &mut Pool, a: &Polynomial, b: &Polynomial) -> Polynomial {
    let mut product = Polynomial::new();
    for (ma, &ca) in a {
        for (mb, &cb) in b {
            let c = pool.mul(ca, cb);
            let term = BTreeMap::from([(merged(ma, mb), c)]);
            add_into(pool, &mut product, &term);
        }
    }
    product
}

/// The product of two parameter products.
fn merged(a: &Monomial, b: &Monomial) -> Monomial {
    let mut exponents: BTreeMap<u32, i32> = a.iter().copied().collect();
    for &(i, k) in b {
        *exponents.entry(i).or_default() += k;
    }
    exponents.into_iter().filter(|&(_, k)| k != 0).collect()
}

/// A product of parameters as an expression.
fn monomial_expr(pool: &mut Pool, monomial: &Monomial) -> ExprId {
    let factors: Vec<ExprId> = monomial
        .iter()
        .map(|&(i, n)| {
            let p = pool.sym(Sym::Param(i));
            pool.powi(p, n)
        })
        .collect();
    pool.product(factors)
}

/// Columns equal up to a constant factor merged into one base parameter.
/// Each column is compared in its expanded, recombined form (kept as it is
/// if too large to expand).
fn grouped(pool: &mut Pool, products: Vec<(Monomial, Vec<ExprId>)>) -> Regressor {
    let mut columns: Vec<Vec<ExprId>> = Vec::new();
    let mut combinations: Vec<Combination> = Vec::new();
    let mut index: HashMap<Vec<ExprId>, usize> = HashMap::new();
    for (monomial, column) in products {
        let plain = pool.ungroup(&column);
        let expanded: Option<Vec<ExprId>> =
            plain.iter().map(|&e| readable(pool, e, BUDGET)).collect();
        let column = expanded.unwrap_or(column);
        let Some(scale) = leading_coefficient(pool, &column) else {
            continue;
        };
        let inverse = pool.number(scale.powi(-1));
        let normalised: Vec<ExprId> = column
            .iter()
            .map(|&e| termwise_product(pool, inverse, e))
            .collect();
        match index.get(&normalised) {
            Some(&group) => combinations[group].push((scale, monomial)),
            None => {
                index.insert(normalised.clone(), columns.len());
                columns.push(normalised);
                combinations.push(vec![(scale, monomial)]);
            }
        }
    }
    // Products in order within a base parameter, base parameters in the
    // order of their first products: an order that does not depend on the
    // pool's history. Each first product enters with coefficient 1, so that
    // `π` does not depend on which term of a column comes first either.
    let mut groups: Vec<(Vec<ExprId>, Combination)> =
        columns.into_iter().zip(combinations).collect();
    for (_, combination) in &mut groups {
        combination.sort_by(|a, b| a.1.cmp(&b.1));
    }
    groups.sort_by(|a, b| a.1[0].1.cmp(&b.1[0].1));
    let (mut columns, mut combinations): (Vec<_>, Vec<_>) = groups.into_iter().unzip();
    for (column, combination) in columns.iter_mut().zip(&mut combinations) {
        let first = combination[0].0;
        let inverse = first.powi(-1);
        combination.iter_mut().for_each(|(c, _)| *c = *c * inverse);
        let first = pool.number(first);
        column
            .iter_mut()
            .for_each(|e| *e = termwise_product(pool, first, *e));
    }
    let nv = columns.first().map_or(0, Vec::len);
    let rows = (0..nv)
        .map(|k| columns.iter().map(|column| column[k]).collect())
        .collect();
    Regressor { rows, combinations }
}

/// `c e` with `c` multiplied into each term of a sum `e`, so that
/// proportional sums of monomials become the same expression.
fn termwise_product(pool: &mut Pool, c: ExprId, e: ExprId) -> ExprId {
    match pool.node(e) {
        Node::Add(terms) => {
            let terms = terms.to_vec();
            let scaled: Vec<ExprId> = terms.into_iter().map(|t| pool.mul(c, t)).collect();
            pool.sum(scaled)
        }
        _ => pool.mul(c, e),
    }
}

/// The numeric coefficient of the first term of the first nonzero entry:
/// the scale that makes proportional columns equal. `None` for a zero
/// column.
fn leading_coefficient(pool: &Pool, column: &[ExprId]) -> Option<Number> {
    let first = *column.iter().find(|&&e| !pool.is_zero(e))?;
    let term = match pool.node(first) {
        Node::Add(terms) => terms[0],
        _ => first,
    };
    Some(pool.split_coefficient(term).0)
}

impl Regressor {
    /// Each base parameter as an expression of the model's parameters.
    pub fn base_parameters(&self, pool: &mut Pool) -> Vec<ExprId> {
        self.combinations
            .iter()
            .map(|combination| {
                let terms: Vec<ExprId> = combination
                    .iter()
                    .map(|(c, monomial)| {
                        let mut factors = vec![pool.number(*c)];
                        for &(i, n) in monomial {
                            let p = pool.sym(Sym::Param(i));
                            factors.push(pool.powi(p, n));
                        }
                        pool.product(factors)
                    })
                    .collect();
                pool.sum(terms)
            })
            .collect()
    }

    /// Each base parameter written with the parameters' names:
    /// `I1 + c1^2*m1 + l1^2*m2`.
    pub fn names(&self, parameters: &[impl std::fmt::Display]) -> Vec<String> {
        self.combinations
            .iter()
            .map(|combination| {
                let mut text = String::new();
                for (i, (c, monomial)) in combination.iter().enumerate() {
                    let negative = c.is_negative();
                    text.push_str(match (i, negative) {
                        (0, false) => "",
                        (0, true) => "-",
                        (_, false) => " + ",
                        (_, true) => " - ",
                    });
                    let magnitude = c.abs();
                    let mut factors: Vec<String> = monomial
                        .iter()
                        .map(|&(p, n)| match n {
                            1 => parameters[p as usize].to_string(),
                            _ => format!("{}^{n}", parameters[p as usize]),
                        })
                        .collect();
                    if !magnitude.is_one() || factors.is_empty() {
                        factors.insert(0, number_text(magnitude));
                    }
                    text.push_str(&factors.join("*"));
                }
                text
            })
            .collect()
    }
}

/// A rational as `3` or `3/4`, a float as Rust prints it.
fn number_text(n: Number) -> String {
    match n.as_rational() {
        Some(r) if r.den == 1 => r.num.to_string(),
        Some(r) => format!("{}/{}", r.num, r.den),
        None => n.to_f64().to_string(),
    }
}
