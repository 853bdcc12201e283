//! The regressor of the inverse dynamics: `M v̇ − f = Y π` at zero inputs,
//! with `π` the *base parameters*, found symbolically.
//!
//! Every entry of `M v̇ − f` is expanded into a sum of monomials, and each
//! monomial split into its product of parameters (`m₂ l₁²`, `g m₁ c₁`; `1`
//! for none) and the rest (numbers, functions of `q`, `v`, `v̇`, and
//! parameters inside functions or sums, which stay in `Y`). The distinct
//! parameter products are the parameters that enter linearly; the rest,
//! summed per product and per row, are the columns of `Y`. Products whose
//! columns are equal up to a constant factor cannot be told apart by any
//! motion, so they are regrouped into one base parameter, their
//! combination: for a two-link arm `I₁ + m₁ c₁² + m₂ l₁²`. Columns that
//! vanish never appear. Terms with an input are left out (`Y π` is the
//! force the motion needs beyond the inputs); time must not appear.

use crate::expr::{ExprId, Node, Number, Pool, Sym, SymKinds};
use crate::render::trig::readable;
use std::collections::HashMap;

/// Most monomials an entry of `M v̇ − f` may expand to.
const BUDGET: usize = 4000;

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
    /// An entry of `M v̇ − f` expands to more than the budget's monomials.
    TooLarge,
    /// `M v̇ − f` depends on time outside the inputs' terms.
    TimeDependent,
}

/// The regressor of `inverse_dynamics` (`M q̈ − f`, in the symbols `q̈`).
pub fn regressor(pool: &mut Pool, inverse_dynamics: &[ExprId]) -> Result<Regressor, Failure> {
    let nv = inverse_dynamics.len();
    let plain = pool.ungroup(inverse_dynamics);
    let mut products: Vec<(Monomial, Vec<Vec<ExprId>>)> = Vec::new();
    let mut index: HashMap<Monomial, usize> = HashMap::new();
    for (row, &entry) in plain.iter().enumerate() {
        let expanded = readable(pool, entry, BUDGET).ok_or(Failure::TooLarge)?;
        let terms = match pool.node(expanded) {
            Node::Add(terms) => terms.to_vec(),
            _ if pool.is_zero(expanded) => Vec::new(),
            _ => vec![expanded],
        };
        for term in terms {
            let (monomial, rest) = split_parameters(pool, term);
            let kinds = pool.kinds(rest);
            if kinds.intersects(SymKinds::INPUT) {
                continue;
            }
            if kinds.intersects(SymKinds::TIME) {
                return Err(Failure::TimeDependent);
            }
            let column = *index.entry(monomial.clone()).or_insert_with(|| {
                products.push((monomial, vec![Vec::new(); nv]));
                products.len() - 1
            });
            products[column].1[row].push(rest);
        }
    }
    Ok(grouped(pool, products))
}

/// `term` as its product of parameters and the rest (with the number).
fn split_parameters(pool: &mut Pool, term: ExprId) -> (Monomial, ExprId) {
    let (coefficient, body) = pool.split_coefficient(term);
    let factors = match pool.node(body) {
        Node::Mul(factors) => factors.to_vec(),
        _ if body == pool.one() => Vec::new(),
        _ => vec![body],
    };
    let mut monomial = Monomial::new();
    let mut rest = vec![pool.number(coefficient)];
    for factor in factors {
        match pool.node(factor) {
            Node::Sym(Sym::Param(i)) => monomial.push((*i, 1)),
            Node::Pow(base, n) => match pool.node(*base) {
                Node::Sym(Sym::Param(i)) => monomial.push((*i, *n)),
                _ => rest.push(factor),
            },
            _ => rest.push(factor),
        }
    }
    monomial.sort_unstable();
    (monomial, pool.product(rest))
}

/// Columns equal up to a constant factor merged into one base parameter,
/// in the order of their first product.
fn grouped(pool: &mut Pool, products: Vec<(Monomial, Vec<Vec<ExprId>>)>) -> Regressor {
    let mut columns: Vec<Vec<ExprId>> = Vec::new();
    let mut combinations: Vec<Combination> = Vec::new();
    let mut index: HashMap<Vec<ExprId>, usize> = HashMap::new();
    for (monomial, rows) in products {
        let column: Vec<ExprId> = rows.into_iter().map(|terms| pool.sum(terms)).collect();
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
