//! Helpers shared by the tests of the engine: points to evaluate at, a
//! small deterministic random generator, random expressions, and a
//! tolerant comparison.

use std::collections::BTreeMap;

use super::{Env, ExprId, Func, Pool, Sym};

/// The project's deterministic generator (tests must not depend on a seed
/// from the environment).
pub use crate::random::Random as Rng;

/// Values of symbols; absent symbols are `NaN` so that a forgotten one
/// shows.
#[derive(Clone, Debug, Default)]
pub struct Point(pub BTreeMap<Sym, f64>);

impl Point {
    /// Each of `syms` uniform in `[-2, 2)`.
    pub fn random(rng: &mut Rng, syms: &[Sym]) -> Point {
        Point(syms.iter().map(|&s| (s, rng.uniform(-2.0, 2.0))).collect())
    }

    /// This point with `s` moved by `delta`.
    pub fn shifted(&self, s: Sym, delta: f64) -> Point {
        let mut moved = self.clone();
        *moved.0.entry(s).or_insert(f64::NAN) += delta;
        moved
    }
}

impl Env for Point {
    fn value(&self, sym: Sym) -> f64 {
        self.0.get(&sym).copied().unwrap_or(f64::NAN)
    }
}

/// Asserts `|a - b| <= tol · max(1, |a|, |b|)`.
pub fn assert_close(a: f64, b: f64, tol: f64, what: &str) {
    let scale = 1f64.max(a.abs()).max(b.abs());
    assert!((a - b).abs() <= tol * scale, "{a} vs {b} for {what}");
}

/// Builds an expression from infix text through the public constructors,
/// so tests read like the math: `parse(p, "p0*sin(q1)^2 - 1/2")`. Symbols
/// are a letter and an index: `q` coordinates, `u` speeds, `a`
/// accelerations, `p` parameters, `f` inputs, `l` multipliers, and `t` is
/// time; calls are the language's functions. `^` takes an integer and binds
/// tighter than unary minus. Panics on malformed text (tests only).
pub fn parse(pool: &mut Pool, text: &str) -> ExprId {
    let mut parser = Parser {
        pool,
        chars: text.chars().filter(|c| !c.is_whitespace()).collect(),
        at: 0,
    };
    let e = parser.sum();
    assert_eq!(parser.at, parser.chars.len(), "trailing text in {text:?}");
    e
}

/// The naming that [`parse`] reads, for [`Pool::display`].
pub fn name(s: Sym) -> String {
    match s {
        Sym::Time => "t".into(),
        Sym::Coord(i) => format!("q{i}"),
        Sym::Speed(i) => format!("u{i}"),
        Sym::Accel(i) => format!("a{i}"),
        Sym::Param(i) => format!("p{i}"),
        Sym::Input(i) => format!("f{i}"),
        Sym::Multiplier(i) => format!("l{i}"),
    }
}

/// Recursive descent over the characters of one expression.
struct Parser<'a> {
    pool: &'a mut Pool,
    chars: Vec<char>,
    at: usize,
}

impl Parser<'_> {
    fn peek(&self) -> Option<char> {
        self.chars.get(self.at).copied()
    }

    fn eat(&mut self, c: char) -> bool {
        let found = self.peek() == Some(c);
        self.at += usize::from(found);
        found
    }

    /// The longest run of characters satisfying `keep`.
    fn run(&mut self, keep: impl Fn(char) -> bool) -> String {
        let start = self.at;
        while self.peek().is_some_and(&keep) {
            self.at += 1;
        }
        self.chars[start..self.at].iter().collect()
    }

    fn sum(&mut self) -> ExprId {
        let mut acc = self.product();
        loop {
            if self.eat('+') {
                let rhs = self.product();
                acc = self.pool.add(acc, rhs);
            } else if self.eat('-') {
                let rhs = self.product();
                acc = self.pool.sub(acc, rhs);
            } else {
                return acc;
            }
        }
    }

    fn product(&mut self) -> ExprId {
        let mut acc = self.unary();
        loop {
            if self.eat('*') {
                let rhs = self.unary();
                acc = self.pool.mul(acc, rhs);
            } else if self.eat('/') {
                let rhs = self.unary();
                acc = self.pool.div(acc, rhs);
            } else {
                return acc;
            }
        }
    }

    fn unary(&mut self) -> ExprId {
        if self.eat('-') {
            let operand = self.unary();
            return self.pool.neg(operand);
        }
        let base = self.atom();
        if !self.eat('^') {
            return base;
        }
        let sign = if self.eat('-') { "-" } else { "" };
        let exp: i32 = format!("{sign}{}", self.run(|c| c.is_ascii_digit()))
            .parse()
            .expect("exponent");
        self.pool.powi(base, exp)
    }

    fn atom(&mut self) -> ExprId {
        if self.eat('(') {
            let inner = self.sum();
            assert!(self.eat(')'), "missing `)`");
            return inner;
        }
        if self.peek().is_some_and(|c| c.is_ascii_digit()) {
            let literal = self.run(|c| c.is_ascii_alphanumeric() || c == '.' || c == '_');
            return self.pool.decimal(&literal).expect("number");
        }
        let word = self.run(|c| c.is_ascii_alphanumeric());
        if self.eat('(') {
            let arg = self.sum();
            assert!(self.eat(')'), "missing `)`");
            return self.pool.func(function(&word), arg);
        }
        let sym = symbol(&word);
        self.pool.sym(sym)
    }
}

/// The function called `word`.
fn function(word: &str) -> Func {
    [
        Func::Sin,
        Func::Cos,
        Func::Tan,
        Func::Sqrt,
        Func::Exp,
        Func::Ln,
        Func::Abs,
    ]
    .into_iter()
    .find(|f| f.name() == word)
    .unwrap_or_else(|| panic!("unknown function {word:?}"))
}

/// The symbol called `word` (see [`parse`]).
fn symbol(word: &str) -> Sym {
    if word == "t" {
        return Sym::Time;
    }
    let (kind, index) = word.split_at(1);
    let i: u32 = index
        .parse()
        .unwrap_or_else(|_| panic!("bad symbol {word:?}"));
    match kind {
        "q" => Sym::Coord(i),
        "u" => Sym::Speed(i),
        "a" => Sym::Accel(i),
        "p" => Sym::Param(i),
        "f" => Sym::Input(i),
        "l" => Sym::Multiplier(i),
        _ => panic!("bad symbol {word:?}"),
    }
}

/// A pool and a shorthand to build and show expressions in it.
#[derive(Default)]
pub struct Scratch {
    pub pool: Pool,
}

impl Scratch {
    /// [`parse`] in this pool.
    pub fn e(&mut self, text: &str) -> ExprId {
        parse(&mut self.pool, text)
    }

    /// [`Pool::display`] with the naming [`parse`] reads.
    pub fn show(&self, e: ExprId) -> String {
        self.pool.display(e, &name)
    }
}

/// The symbols the random expressions are built from and differentiated
/// by (the parameter is a constant of the gradients).
pub const SYMS: [Sym; 5] = [
    Sym::Coord(0),
    Sym::Coord(1),
    Sym::Speed(0),
    Sym::Input(0),
    Sym::Param(0),
];

/// A random expression over [`SYMS`] of about `depth` levels, with every
/// node kind: sums, products with coefficients, powers, each function.
pub fn random_expression(pool: &mut Pool, rng: &mut Rng, depth: usize) -> ExprId {
    let pick = |rng: &mut Rng, n: usize| (rng.uniform(0.0, n as f64) as usize).min(n - 1);
    if depth == 0 {
        return match pick(rng, 6) {
            5 => pool.int(pick(rng, 5) as i64 + 1),
            k => pool.sym(SYMS[k]),
        };
    }
    let operand = |pool: &mut Pool, rng: &mut Rng| random_expression(pool, rng, depth - 1);
    match pick(rng, 8) {
        0 | 1 => {
            let terms: Vec<ExprId> = (0..2 + pick(rng, 3)).map(|_| operand(pool, rng)).collect();
            pool.sum(terms)
        }
        2 | 3 => {
            let factors: Vec<ExprId> = (0..2 + pick(rng, 2)).map(|_| operand(pool, rng)).collect();
            let c = pool.rational(pick(rng, 7) as i128 - 3, 2);
            let product = pool.product(factors);
            pool.mul(c, product)
        }
        4 => {
            let base = operand(pool, rng);
            pool.powi(base, [-1, 2, 3][pick(rng, 3)])
        }
        5 => {
            let inner = operand(pool, rng);
            let one = pool.one();
            let sum = pool.sum([inner, one]);
            pool.group(sum)
        }
        _ => {
            let f = [Func::Sin, Func::Cos, Func::Exp, Func::Tan][pick(rng, 4)];
            let arg = operand(pool, rng);
            let scaled = pool.rational(1, 3);
            let arg = pool.mul(scaled, arg);
            pool.func(f, arg)
        }
    }
}
