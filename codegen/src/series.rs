//! The Taylor series lowering: the expression DAG of `M` and `f` (and of
//! a constrained system's `A` and `b`) as a program on series (`[f64; K]`,
//! one per node that moves: constants stay scalars), which
//! `taylor_coefficients` runs order by order (see `emit::taylor`).
//!
//! A sum is a linear combination, a product a Cauchy product, a division
//! a quotient, `x^n` products of squares (a reciprocal for `n < 0`), and
//! each elementary function its recurrence (`sin` and `cos` of one
//! argument as one pair). Every operation is a call of the runtime's
//! recurrence (`dalembert::series`) of that name. The program is built over
//! the derivation's pool, after every other function is planned and the
//! docs rendered: its linear combinations' weights (and the recombined
//! form's readable forms) are interned there, after every node the other
//! functions read. Which of the two forms of the equations it lowers is
//! the plan's choice (`plan::Taylor`); the other's nodes stay in the pool,
//! never emitted.

use crate::equations::Equations;
use crate::expr::{ExprId, Func, Node, Pool, Sym, SymKinds};
use crate::readable::{self, ReadableForms};
use std::collections::{HashMap, HashSet};

/// The index of one series of the program.
pub type Slot = usize;

/// How the coefficient of order `k` of a series is computed.
pub enum Operation {
    /// Set by the recursion itself: a coordinate, a speed, an acceleration
    /// (`start` and `integral`), the time.
    State,
    /// Computed with another series' operation: the cosine of a sine, the
    /// `1 + tan²` of a tangent.
    Partner,
    /// `constant + Σ wᵢ xᵢ` (constant weights).
    Linear {
        constant: ExprId,
        terms: Vec<(ExprId, Slot)>,
    },
    /// A function of one or two series: the runtime's recurrence of that
    /// name, called as `name(&mut out, [&mut partner,] &operands.., k)`.
    Call {
        name: &'static str,
        partner: Option<Slot>,
        operands: Vec<Slot>,
    },
}

/// What an expression is in the program: a constant of the step, or a
/// series.
#[derive(Clone, Copy)]
pub enum Operand {
    Constant(ExprId),
    Series(Slot),
}

/// The program of one system: its series and how each is computed, its
/// constants expressions in the derivation's pool.
pub struct Program {
    /// How each series is computed, by slot.
    pub operations: Vec<Operation>,
    /// The series of the coordinates, the speeds, the accelerations and
    /// the multipliers: set by the recursion itself.
    pub coordinates: Vec<Slot>,
    pub speeds: Vec<Slot>,
    pub accelerations: Vec<Slot>,
    pub multipliers: Vec<Slot>,
    /// The series of the time, if the equations read it.
    pub time: Option<Slot>,
}

/// The symbols whose series move within a step (inputs are held).
const MOVING: SymKinds = SymKinds::COORD.union(SymKinds::SPEED).union(SymKinds::TIME);

/// A program being lowered over the derivation's pool.
struct Lowering<'a> {
    pool: &'a mut Pool,
    program: Program,
    /// The series of each node lowered so far.
    nodes: HashMap<ExprId, Slot>,
    /// The series of each call made so far.
    calls: HashMap<(&'static str, Vec<Slot>), Slot>,
    /// The readable forms among the entries: one stands for the flat sum
    /// of its terms ([`readable::terms`]), and `−s` among them is lowered
    /// as that sum (one linear combination), not as `s` negated.
    forms: HashSet<ExprId>,
}

impl<'a> Lowering<'a> {
    /// The series of the state: `q`, `v` and `v̇`, then the multipliers
    /// `λ` of `sizes[2]` constraints.
    fn new(pool: &'a mut Pool, sizes: [usize; 3], forms: HashSet<ExprId>) -> Self {
        let [nq, nv, nc] = sizes;
        let program = Program {
            operations: Vec::new(),
            coordinates: Vec::new(),
            speeds: Vec::new(),
            accelerations: Vec::new(),
            multipliers: Vec::new(),
            time: None,
        };
        let mut lowering = Lowering {
            pool,
            program,
            nodes: HashMap::new(),
            calls: HashMap::new(),
            forms,
        };
        lowering.program.coordinates = lowering.states(nq);
        lowering.program.speeds = lowering.states(nv);
        lowering.program.accelerations = lowering.states(nv);
        lowering.program.multipliers = lowering.states(nc);
        lowering
    }

    /// `n` series set by the recursion itself.
    fn states(&mut self, n: usize) -> Vec<Slot> {
        (0..n).map(|_| self.push(Operation::State)).collect()
    }

    fn push(&mut self, operation: Operation) -> Slot {
        self.program.operations.push(operation);
        self.program.operations.len() - 1
    }

    /// The operand computing `e`, its series lowered (once) if it moves.
    fn lower(&mut self, e: ExprId) -> Operand {
        if !self.pool.kinds(e).intersects(MOVING) {
            return Operand::Constant(e);
        }
        if let Some(&slot) = self.nodes.get(&e) {
            return Operand::Series(slot);
        }
        let slot = match self.pool.node(e).clone() {
            Node::Sym(Sym::Coord(i)) => self.program.coordinates[i as usize],
            Node::Sym(Sym::Speed(i)) => self.program.speeds[i as usize],
            Node::Sym(_) => self.time_slot(),
            Node::Add(terms) => self.sum(&terms),
            Node::Mul(_) if self.forms.contains(&e) => {
                let terms = readable::terms(self.pool, e);
                self.sum(&terms)
            }
            Node::Mul(factors) => self.scaled_product(&factors),
            Node::Pow(..) => self.product(&[e]),
            Node::Func(function, argument) => self.function(function, argument),
            Node::Group(sum) => self.series(sum),
            Node::Number(_) => return Operand::Constant(e),
        };
        self.nodes.insert(e, slot);
        Operand::Series(slot)
    }

    /// The operands of `entries`, in order.
    fn lower_all(&mut self, entries: &[ExprId]) -> Vec<Operand> {
        entries.iter().map(|&e| self.lower(e)).collect()
    }

    /// The operands of a matrix's rows.
    fn lower_rows(&mut self, rows: &[Vec<ExprId>]) -> Vec<Vec<Operand>> {
        rows.iter().map(|row| self.lower_all(row)).collect()
    }

    /// The series of `e` (constant if `e` does not move).
    fn series(&mut self, e: ExprId) -> Slot {
        match self.lower(e) {
            Operand::Series(slot) => slot,
            Operand::Constant(c) => self.constant_series(c),
        }
    }

    /// The series of a constant, `[c, 0, 0, …]`.
    fn constant_series(&mut self, constant: ExprId) -> Slot {
        self.push(Operation::Linear {
            constant,
            terms: Vec::new(),
        })
    }

    fn time_slot(&mut self) -> Slot {
        match self.program.time {
            Some(slot) => slot,
            None => {
                let slot = self.push(Operation::State);
                self.program.time = Some(slot);
                slot
            }
        }
    }

    /// A canonical sum: its constant terms added into one constant, each
    /// moving term `w · x` a weight and a series.
    fn sum(&mut self, terms: &[ExprId]) -> Slot {
        let (mut constants, mut moving) = (Vec::new(), Vec::new());
        for &term in terms {
            if !self.pool.kinds(term).intersects(MOVING) {
                constants.push(term);
                continue;
            }
            let weighted = match self.pool.node(term).clone() {
                Node::Mul(factors) => self.weighted(&factors),
                _ => (self.pool.int(1), self.series(term)),
            };
            moving.push(weighted);
        }
        let constant = self.pool.sum(constants);
        self.push(Operation::Linear {
            constant,
            terms: moving,
        })
    }

    /// A product's constant factors multiplied into a weight, and the series
    /// of its moving factors.
    fn weighted(&mut self, factors: &[ExprId]) -> (ExprId, Slot) {
        let (constant, moving): (Vec<ExprId>, Vec<ExprId>) = factors
            .iter()
            .partition(|&&f| !self.pool.kinds(f).intersects(MOVING));
        let weight = self.pool.product(constant);
        (weight, self.product(&moving))
    }

    /// A product with a constant weight: the weighted series (no operation
    /// for a unit weight).
    fn scaled_product(&mut self, factors: &[ExprId]) -> Slot {
        let (weight, slot) = self.weighted(factors);
        if self.pool.as_number(weight).is_some_and(|w| w.is_one()) {
            return slot;
        }
        let zero = self.pool.int(0);
        self.push(Operation::Linear {
            constant: zero,
            terms: vec![(weight, slot)],
        })
    }

    /// The product of moving factors (`x^n` with `n < 0` among them
    /// dividing): the numerator's Cauchy products over the denominator's.
    fn product(&mut self, factors: &[ExprId]) -> Slot {
        let (mut numerator, mut denominator) = (None, None);
        for &factor in factors {
            let (base, exponent) = match *self.pool.node(factor) {
                Node::Pow(base, n) => (base, n),
                _ => (factor, 1),
            };
            let base = self.series(base);
            let power = self.power(base, exponent.unsigned_abs());
            let side = if exponent < 0 {
                &mut denominator
            } else {
                &mut numerator
            };
            *side = Some(match *side {
                Some(so_far) => self.call("product", None, vec![so_far, power]),
                None => power,
            });
        }
        match (numerator, denominator) {
            (Some(n), Some(d)) => self.call("quotient", None, vec![n, d]),
            (None, Some(d)) => self.call("reciprocal", None, vec![d]),
            (Some(n), None) => n,
            (None, None) => {
                let one = self.pool.int(1);
                self.constant_series(one)
            }
        }
    }

    /// `x^n` (`n ≥ 1`) by squares.
    fn power(&mut self, x: Slot, n: u32) -> Slot {
        match n {
            0 | 1 => x,
            _ if n % 2 == 0 => {
                let half = self.power(x, n / 2);
                self.call("product", None, vec![half, half])
            }
            _ => {
                let below = self.power(x, n - 1);
                self.call("product", None, vec![below, x])
            }
        }
    }

    /// An elementary function of a moving argument.
    fn function(&mut self, function: Func, argument: ExprId) -> Slot {
        let x = self.series(argument);
        let (name, paired) = match function {
            Func::Sin | Func::Cos => ("sin_cos", true),
            Func::Tan => ("tan", true),
            Func::Sqrt => ("sqrt", false),
            Func::Exp => ("exp", false),
            Func::Ln => ("ln", false),
            Func::Abs => ("abs", false),
        };
        let first = match paired {
            true => self.paired_call(name, x),
            false => self.call(name, None, vec![x]),
        };
        // The cosine is the sine's partner, the slot after it.
        match function {
            Func::Cos => first + 1,
            _ => first,
        }
    }

    /// A call writing two series (`sin_cos`, `tan`): the first slot's, its
    /// partner next.
    fn paired_call(&mut self, name: &'static str, x: Slot) -> Slot {
        if let Some(&slot) = self.calls.get(&(name, vec![x])) {
            return slot;
        }
        let slot = self.program.operations.len();
        self.push(Operation::Call {
            name,
            partner: Some(slot + 1),
            operands: vec![x],
        });
        self.push(Operation::Partner);
        self.calls.insert((name, vec![x]), slot);
        slot
    }

    /// `name(operands)`, once per distinct call (products in either order).
    fn call(&mut self, name: &'static str, partner: Option<Slot>, mut operands: Vec<Slot>) -> Slot {
        if name == "product" {
            operands.sort_unstable();
        }
        let key = (name, operands.clone());
        if let Some(&slot) = self.calls.get(&key) {
            return slot;
        }
        let slot = self.push(Operation::Call {
            name,
            partner,
            operands,
        });
        self.calls.insert(key, slot);
        slot
    }
}

/// The expressions of the equations that the program lowers: `M` and `f`,
/// and the constraints' `A` and `b` (none without constraints).
struct Expressions {
    matrix: Vec<Vec<ExprId>>,
    forcing: Vec<ExprId>,
    jacobian: Vec<Vec<ExprId>>,
    bias: Vec<ExprId>,
}

impl Expressions {
    /// The entries of `equations` that the program lowers.
    fn of(equations: &Equations) -> Self {
        Expressions {
            matrix: equations.mass_matrix.clone(),
            forcing: equations.forcing.clone(),
            jacobian: equations.constraint_jacobian.clone(),
            bias: equations.constraint_bias.clone(),
        }
    }

    /// Every expression replaced by `form(expression)`.
    fn map(&self, mut form: impl FnMut(ExprId) -> ExprId) -> Self {
        let mut rows = |rows: &[Vec<ExprId>]| -> Vec<Vec<ExprId>> {
            rows.iter()
                .map(|row| row.iter().map(|&e| form(e)).collect())
                .collect()
        };
        let (matrix, jacobian) = (rows(&self.matrix), rows(&self.jacobian));
        Expressions {
            matrix,
            forcing: self.forcing.iter().map(|&e| form(e)).collect(),
            jacobian,
            bias: self.bias.iter().map(|&e| form(e)).collect(),
        }
    }
}

/// The program of the equations, the operands of their entries, and the
/// series of the coordinates' rates `N(q) v`.
pub struct Lowered {
    /// The series and how each is computed.
    pub program: Program,
    /// The operands of `M`'s entries, row by row.
    pub matrix: Vec<Vec<Operand>>,
    /// The operands of `f`'s.
    pub forcing: Vec<Operand>,
    /// The operands of `A`'s entries, row by row.
    pub jacobian: Vec<Vec<Operand>>,
    /// The operands of `b`'s.
    pub bias: Vec<Operand>,
    /// The series of the coordinates' rates.
    pub rates: Vec<Slot>,
}

impl Lowered {
    /// The equations as derived, lowered over `pool`, then the rates of
    /// `nq` coordinates.
    pub fn derived(pool: &mut Pool, nq: usize, equations: &Equations) -> Self {
        Lowered::new(pool, nq, &Expressions::of(equations), HashSet::new())
    }

    /// The equations with their angle sums recombined (their readable
    /// `forms`, for the entries that expand to at most `budget`
    /// monomials), lowered over `pool`, then the rates of `nq`
    /// coordinates.
    pub fn recombined(
        pool: &mut Pool,
        forms: &mut ReadableForms,
        nq: usize,
        equations: &Equations,
        budget: usize,
    ) -> Self {
        let mut found = HashSet::new();
        let recombined = Expressions::of(equations).map(|e| match forms.get(pool, e, budget) {
            Some(form) => {
                found.insert(form);
                form
            }
            None => e,
        });
        Lowered::new(pool, nq, &recombined, found)
    }

    /// The entries of `expressions` lowered over `pool`, then the rates of
    /// `nq` coordinates (a speed where it is its coordinate's rate).
    fn new(pool: &mut Pool, nq: usize, expressions: &Expressions, forms: HashSet<ExprId>) -> Self {
        let sizes = [nq, expressions.forcing.len(), expressions.bias.len()];
        let mut lowering = Lowering::new(pool, sizes, forms);
        let matrix = lowering.lower_rows(&expressions.matrix);
        let forcing = lowering.lower_all(&expressions.forcing);
        let jacobian = lowering.lower_rows(&expressions.jacobian);
        let bias = lowering.lower_all(&expressions.bias);
        let rates = (0..nq as u32)
            .map(|i| {
                let rate = lowering.pool.rate(i);
                lowering.series(rate)
            })
            .collect();
        Lowered {
            program: lowering.program,
            matrix,
            forcing,
            jacobian,
            bias,
            rates,
        }
    }

    /// The recurrences of each order that are sums over the lower orders
    /// (Cauchy products, quotients, elementary functions): what an order
    /// costs, linear combinations being cheap beside them.
    pub fn recurrences(&self) -> usize {
        self.program
            .operations
            .iter()
            .filter(|operation| matches!(operation, Operation::Call { .. }))
            .count()
    }
}
