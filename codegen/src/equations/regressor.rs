//! The regressor of the inverse dynamics: `M v̇ − f = Y π` at zero inputs,
//! with `π` the *base parameters*.
//!
//! Every entry of `M v̇ − f` is expanded, symbolically, as a polynomial in
//! the parameters only — the parameter-free parts stay shared DAGs, so the
//! expansion is as large as the number of parameter products, not of
//! trigonometric terms: `Σ μ · Y_μ(q, v, v̇)`, with `μ` a product of
//! parameters (`m₂ l₁²`, `g m₁ c₁`; `1` for none). A parameter inside a
//! function or under a negative power of a sum is not a polynomial one
//! there: that part stays in `Y` (read from the struct). The distinct
//! products are the parameters that enter linearly; the `Y_μ` are the
//! candidate columns of `Y`.
//!
//! A column that is a constant combination `Σ xⱼ Yⱼ` of earlier ones cannot
//! be told apart from them by any motion: it is removed, and its product
//! joins each base parameter `πⱼ` with the exact rational factor `xⱼ` — for
//! a two-link arm `π = m₁ c₁² + m₂ l₁² + I₁`. Dependence is decided by
//! polynomial identity testing (the columns' values at random points, a QR
//! factorisation, the factors recovered as small rationals and checked);
//! columns that vanish are left out. Inputs are set to zero (`Y π` is the
//! force the motion needs beyond the inputs); time must not appear.

use crate::expr::{ExprId, Node, Number, Pool, Sym, SymKinds};
use std::collections::{BTreeMap, HashMap};

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
        Node::Group(sum) => known[&sum].clone(),
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

/// The columns reduced to independent ones. A column that is a
/// combination `Σ xⱼ Yⱼ` of earlier independent columns, with constant
/// rational `xⱼ`, cannot be told apart from them by any motion: its product
/// `μ` joins each `πⱼ` as `xⱼ μ`. Dependence is decided on the columns'
/// values at random points (polynomial identity testing: expressions of
/// the engine's functions that differ agree at random points with
/// probability zero), the `xⱼ` recovered as exact small rationals and
/// checked against every value.
fn grouped(pool: &mut Pool, products: Vec<(Monomial, Vec<ExprId>)>) -> Regressor {
    let nv = products.first().map_or(0, |(_, column)| column.len());
    let points = (2 * products.len()).div_ceil(nv.max(1)) as u64 + 2;
    let mut basis = Basis::default();
    let mut columns: Vec<Vec<ExprId>> = Vec::new();
    let mut combinations: Vec<Combination> = Vec::new();
    let sampled: Vec<Vec<f64>> = products
        .iter()
        .map(|(_, column)| sampled(pool, column, points))
        .collect();
    // A column that cancels symbolically may leave rounding: it vanishes
    // next to the largest column.
    let largest = sampled.iter().map(|v| norm(v)).fold(0.0, f64::max);
    for ((monomial, column), values) in products.into_iter().zip(sampled) {
        if norm(&values) <= 1e-12 * largest {
            continue;
        }
        match basis.dependence(&values) {
            Some(coefficients) => {
                for (group, c) in coefficients {
                    combinations[group].push((c, monomial.clone()));
                }
            }
            None => {
                // Independent, or dependent only with coefficients that
                // are not constants: a base parameter of its own.
                basis.push(values, columns.len());
                columns.push(column);
                combinations.push(vec![(Number::ONE, monomial)]);
            }
        }
    }
    let rows = (0..nv)
        .map(|k| columns.iter().map(|column| column[k]).collect())
        .collect();
    Regressor { rows, combinations }
}

/// The values of `column` at `points` random points: parameters in
/// `[0.5, 1.5)`, coordinates, speeds and their rates in `[−3, 3)`, time and
/// inputs zero.
fn sampled(pool: &Pool, column: &[ExprId], points: u64) -> Vec<f64> {
    (0..points)
        .flat_map(|seed| pool.eval_many(column, &RandomPoint(seed)))
        .collect()
}

/// A random value for every symbol, fixed by a seed.
struct RandomPoint(u64);

impl crate::expr::Env for RandomPoint {
    fn value(&self, sym: Sym) -> f64 {
        let (kind, index, low, high) = match sym {
            Sym::Param(i) => (1, i, 0.5, 1.5),
            Sym::Coord(i) => (2, i, -3.0, 3.0),
            Sym::Speed(i) => (3, i, -3.0, 3.0),
            Sym::Accel(i) => (4, i, -3.0, 3.0),
            Sym::Time | Sym::Input(_) | Sym::Multiplier(_) => return 0.0,
        };
        let seed = (self.0 << 40) ^ (kind << 32) ^ u64::from(index);
        crate::random::Random::new(seed).uniform(low, high)
    }
}

/// Independent sampled columns, as a QR factorisation by modified
/// Gram–Schmidt: `columns = Q R`.
#[derive(Default)]
struct Basis {
    /// Orthonormal columns.
    q: Vec<Vec<f64>>,
    /// `R` by columns: `r[j]` has `j + 1` entries.
    r: Vec<Vec<f64>>,
    /// The sampled columns themselves.
    columns: Vec<Vec<f64>>,
    /// The base parameter of each column.
    groups: Vec<usize>,
}

impl Basis {
    /// `Qᵀ v` and what of `v` is left outside the basis.
    fn project(&self, v: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let mut rest = v.to_vec();
        let coordinates = self
            .q
            .iter()
            .map(|q| {
                let c: f64 = q.iter().zip(&rest).map(|(a, b)| a * b).sum();
                rest.iter_mut().zip(q).for_each(|(x, q)| *x -= c * q);
                c
            })
            .collect();
        (coordinates, rest)
    }

    /// The exact rationals `xⱼ ≠ 0` with `v = Σ xⱼ columnⱼ`, by the base
    /// parameter of each column, if `v` is such a combination.
    fn dependence(&self, v: &[f64]) -> Option<Vec<(usize, Number)>> {
        let scale = norm(v);
        let (coordinates, rest) = self.project(v);
        if self.q.is_empty() || norm(&rest) > 1e-9 * scale {
            return None;
        }
        // R x = Qᵀ v, by back substitution.
        let n = self.q.len();
        let mut x = vec![0.0; n];
        for i in (0..n).rev() {
            let above: f64 = (i + 1..n).map(|j| self.r[j][i] * x[j]).sum();
            x[i] = (coordinates[i] - above) / self.r[i][i];
        }
        let exact: Vec<Number> = x
            .iter()
            .map(|&c| small_rational(c))
            .collect::<Option<_>>()?;
        let fits = v.iter().enumerate().all(|(k, &value)| {
            let combined: f64 = exact
                .iter()
                .zip(&self.columns)
                .map(|(c, column)| c.to_f64() * column[k])
                .sum();
            (combined - value).abs() <= 1e-10 * scale
        });
        let nonzero = self.groups.iter().zip(exact).filter(|(_, c)| !c.is_zero());
        fits.then(|| nonzero.map(|(&g, c)| (g, c)).collect())
    }

    /// Adds `v`, the column of base parameter `group`, if it is
    /// independent of the basis.
    fn push(&mut self, v: Vec<f64>, group: usize) {
        let (mut coordinates, rest) = self.project(&v);
        let left = norm(&rest);
        if left <= 1e-9 * norm(&v) {
            return;
        }
        coordinates.push(left);
        self.q.push(rest.iter().map(|x| x / left).collect());
        self.r.push(coordinates);
        self.columns.push(v);
        self.groups.push(group);
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// `c` as an exact rational with a denominator up to 1000, if it is one
/// (to 1e-8 relative); zero below 1e-10.
fn small_rational(c: f64) -> Option<Number> {
    if c.abs() < 1e-10 {
        return Some(Number::ZERO);
    }
    (1..=1000_i128).find_map(|den| {
        let num = (c * den as f64).round();
        ((num / den as f64 - c).abs() <= 1e-8 * c.abs()).then(|| Number::ratio(num as i128, den))
    })
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
