//! `taylor_coefficients` (`outputs taylor;`): the Taylor coefficients of
//! the motion through a state, to any order.
//!
//! The expression DAG of `M` and `f` is lowered to a program on series
//! (`[f64; K]`, one per node that moves: constants stay scalars): a sum is a
//! linear combination, a product a Cauchy product, a division a quotient,
//! `x^n` products of squares (a reciprocal for `n < 0`), and each elementary
//! function its recurrence (`sin` and `cos` of one argument as one pair).
//! Every operation calls the runtime's recurrence (`dalembert::__private::series`),
//! which reads and writes the series without indexing. Order `k` of every
//! node is computed from the lower orders, then order `k` of the
//! accelerations from `M₀ q̈ₖ = fₖ − Σⱼ₌₁ᵏ Mⱼ q̈ₖ₋ⱼ` with the one `L D Lᵀ`
//! factorisation of `M₀` (only the entries of `M` that move contribute to
//! the sum), and order `k + 1` of the speeds and coordinates by
//! integration. The work of one order is `advance`, a method of a local
//! struct (`Series`) that borrows the series, always inlined and called once
//! per order up to [`UNROLLED_ORDERS`] with the order a literal, so that
//! every recurrence's sum has a compile-time length and unrolls; higher
//! orders run in a loop. The series stay local arrays, one each, which the
//! struct only borrows: owned by one struct, they measured twice as slow
//! (the sums of the inlined copies no longer vectorised), and so did one
//! out-of-line function per order.

use std::collections::HashMap;

use super::body::{Names, number, straight_line};
use super::solve::{Elimination, elimination, mass, state_check};
use super::{allowed_lints, array};
use crate::equations::Equations;
use crate::expr::{ExprId, Func, Node, Pool, Sym, SymKinds};
use crate::model::Model;
use crate::outputs::Function;
use crate::readable::ReadableForms;
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

/// Most monomials an entry of `M` or `f` may expand to for its angle sums
/// to be recombined (`sin a cos b − cos a sin b = sin(a − b)`: one
/// `sin_cos` recurrence of the difference instead of four Cauchy products
/// and two sums); a larger entry is lowered as derived ([`lowered`]).
const RECOMBINATION_BUDGET: usize = 200;

/// The orders emitted one by one, each with its own copy of the
/// recurrences (a constant order, so sums of compile-time length); higher
/// orders run in a loop. The runtime's Taylor integrator uses up to 31
/// (`dalembert::integrate::taylor::MAX_ORDER`).
const UNROLLED_ORDERS: usize = 31;

/// The index of one series of the program.
type Slot = usize;

/// How the coefficient of order `k` of a series is computed.
enum Operation {
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
enum Operand {
    Constant(ExprId),
    Series(Slot),
}

/// The program of one system: its series and how each is computed.
struct Program {
    pool: Pool,
    operations: Vec<Operation>,
    nodes: HashMap<ExprId, Slot>,
    calls: HashMap<(&'static str, Vec<Slot>), Slot>,
    coordinates: Vec<Slot>,
    speeds: Vec<Slot>,
    accelerations: Vec<Slot>,
    multipliers: Vec<Slot>,
    time: Option<Slot>,
}

/// The symbols whose series move within a step (inputs are held).
const MOVING: SymKinds = SymKinds::COORD.union(SymKinds::SPEED).union(SymKinds::TIME);

impl Program {
    /// The series of the state: `q`, `v` and `v̇`, then the multipliers
    /// `λ` of `sizes[2]` constraints.
    fn new(pool: Pool, sizes: [usize; 3]) -> Self {
        let [nq, nv, nc] = sizes;
        let mut program = Program {
            pool,
            operations: Vec::new(),
            nodes: HashMap::new(),
            calls: HashMap::new(),
            coordinates: Vec::new(),
            speeds: Vec::new(),
            accelerations: Vec::new(),
            multipliers: Vec::new(),
            time: None,
        };
        program.coordinates = program.states(nq);
        program.speeds = program.states(nv);
        program.accelerations = program.states(nv);
        program.multipliers = program.states(nc);
        program
    }

    /// `n` series set by the recursion itself.
    fn states(&mut self, n: usize) -> Vec<Slot> {
        (0..n).map(|_| self.push(Operation::State)).collect()
    }

    fn push(&mut self, operation: Operation) -> Slot {
        self.operations.push(operation);
        self.operations.len() - 1
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
            Node::Sym(Sym::Coord(i)) => self.coordinates[i as usize],
            Node::Sym(Sym::Speed(i)) => self.speeds[i as usize],
            Node::Sym(_) => self.time_slot(),
            Node::Add(terms) => self.sum(&terms),
            Node::Mul(factors) => self.scaled_product(&factors),
            Node::Pow(..) => self.product(&[e]),
            Node::Func(function, argument) => self.function(function, argument),
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
        match self.time {
            Some(slot) => slot,
            None => {
                let slot = self.push(Operation::State);
                self.time = Some(slot);
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
            Func::Group => return x,
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
        let slot = self.operations.len();
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
struct Lowered {
    program: Program,
    matrix: Vec<Vec<Operand>>,
    forcing: Vec<Operand>,
    jacobian: Vec<Vec<Operand>>,
    bias: Vec<Operand>,
    rates: Vec<Slot>,
}

impl Lowered {
    /// The entries of `expressions` lowered in `pool`, then the rates of
    /// `nq` coordinates (a speed where it is its coordinate's rate).
    fn new(pool: Pool, nq: usize, expressions: &Expressions) -> Self {
        let sizes = [nq, expressions.forcing.len(), expressions.bias.len()];
        let mut program = Program::new(pool, sizes);
        let matrix = program.lower_rows(&expressions.matrix);
        let forcing = program.lower_all(&expressions.forcing);
        let jacobian = program.lower_rows(&expressions.jacobian);
        let bias = program.lower_all(&expressions.bias);
        let rates = (0..nq as u32)
            .map(|i| {
                let rate = program.pool.rate(i);
                program.series(rate)
            })
            .collect();
        Lowered {
            program,
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
    fn recurrences(&self) -> usize {
        self.program
            .operations
            .iter()
            .filter(|operation| matches!(operation, Operation::Call { .. }))
            .count()
    }
}

/// The equations lowered as derived, or with their angle sums recombined
/// (within [`RECOMBINATION_BUDGET`]) when that takes fewer recurrences.
fn lowered(pool: &Pool, nq: usize, equations: &Equations) -> Lowered {
    let expressions = Expressions {
        matrix: equations.mass_matrix.clone(),
        forcing: equations.forcing.clone(),
        jacobian: equations.constraint_jacobian.clone(),
        bias: equations.constraint_bias.clone(),
    };
    let derived = Lowered::new(pool.clone(), nq, &expressions);
    let mut pool = pool.clone();
    let mut forms = ReadableForms::default();
    let recombined =
        expressions.map(|e| forms.get(&mut pool, e, RECOMBINATION_BUDGET).unwrap_or(e));
    let recombined = Lowered::new(pool, nq, &recombined);
    if recombined.recurrences() < derived.recurrences() {
        recombined
    } else {
        derived
    }
}

/// Names of the program's series and constants in the emitted code.
struct Written<'a> {
    pool: &'a Pool,
    slots: &'a [Ident],
    constants: &'a HashMap<ExprId, Ident>,
}

impl Written<'_> {
    /// A constant: a literal, or its bound name.
    fn constant(&self, e: ExprId) -> TokenStream {
        match (self.pool.node(e), self.constants.get(&e)) {
            // An argument or a tuple's element: a negative literal needs no
            // parentheses.
            (Node::Number(n), _) if n.is_negative() => {
                let magnitude = number(-*n);
                quote!(-#magnitude)
            }
            (Node::Number(n), _) => number(*n),
            (_, Some(name)) => quote!(self.#name),
            _ => quote!(0.0),
        }
    }

    /// Coefficient `k` of an operand.
    fn at_order(&self, operand: Operand) -> TokenStream {
        match operand {
            Operand::Series(slot) => {
                let x = &self.slots[slot];
                quote!(::dalembert::__private::series::at(&self.#x, k))
            }
            Operand::Constant(e) => {
                let c = self.constant(e);
                quote!(::dalembert::__private::series::constant_at(#c, k))
            }
        }
    }

    /// `sign Σⱼ₌₁ᵏ eⱼ xₖ₋ⱼ` for each entry `e` that moves and its series
    /// `x` of `by`: what the motion of the entries adds to order `k`.
    fn tails<'b>(
        &'b self,
        entries: &'b [Operand],
        by: &'b [Ident],
        sign: TokenStream,
    ) -> impl Iterator<Item = TokenStream> + 'b {
        entries
            .iter()
            .zip(by)
            .filter_map(move |(entry, x)| match entry {
                Operand::Series(slot) => {
                    let m = &self.slots[*slot];
                    Some(quote!(#sign ::dalembert::__private::series::convolution_tail(&self.#m, &self.#x, k)))
                }
                Operand::Constant(_) => None,
            })
    }

    /// Coefficient 0 of an operand.
    fn value(&self, operand: Operand) -> TokenStream {
        match operand {
            Operand::Series(slot) => {
                let x = &self.slots[slot];
                quote!(::dalembert::__private::series::at(&self.#x, 0))
            }
            Operand::Constant(e) => self.constant(e),
        }
    }

    /// The statement computing order `k` of one series.
    fn operation(&self, slot: Slot, operation: &Operation) -> TokenStream {
        let out = &self.slots[slot];
        match operation {
            Operation::State | Operation::Partner => TokenStream::new(),
            Operation::Linear { constant, terms } => {
                let constant = self.constant(*constant);
                let terms = terms.iter().map(|(w, x)| {
                    let (w, x) = (self.constant(*w), &self.slots[*x]);
                    quote!((#w, &self.#x))
                });
                quote!(::dalembert::__private::series::linear(&mut self.#out, k, #constant, [#(#terms),*]);)
            }
            Operation::Call {
                name,
                partner,
                operands,
            } => {
                let name = Ident::new(name, proc_macro2::Span::call_site());
                let partner = partner.map(|p| {
                    let p = &self.slots[p];
                    quote!(&mut self.#p,)
                });
                let operands = operands.iter().map(|&x| &self.slots[x]);
                quote!(::dalembert::__private::series::#name(&mut self.#out, #partner #(&self.#operands,)* k);)
            }
        }
    }
}

/// `pub fn taylor_coefficients<const K: usize>(..)`: order by order with
/// the factorisation of `M₀` that `accelerations` uses, or, for a system
/// with constraints, with the runtime's factorisation of the saddle point
/// ([`emit_constrained`]); nothing for a system without coordinates.
pub fn emit_taylor(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    names: &Names,
    function: &Function,
) -> TokenStream {
    let constrained = !equations.constraint_jacobian.is_empty();
    let solver = elimination(model, pool, equations, None);
    if solver.is_none() && !constrained {
        return TokenStream::new();
    }
    let lowered = lowered(pool, model.nq(), equations);
    let prelude = Prelude::new(names, lowered);
    match solver {
        Some(solver) if !constrained => emit_unconstrained(model, &prelude, solver, function),
        _ => emit_constrained(model, &prelude, function),
    }
}

/// What both forms of `taylor_coefficients` share: the program written
/// out, the declarations of its series and constants, and the work of an
/// order before its solve.
struct Prelude {
    lowered: Lowered,
    /// The name of each slot, then of each bound constant.
    slots: Vec<Ident>,
    constants: Vec<ExprId>,
    constant_names: HashMap<ExprId, Ident>,
    /// The fields of the struct `Series`.
    fields: TokenStream,
    /// The state check, the constants bound, the series declared and
    /// `let mut series = Series::<K> { .. };`.
    setup: TokenStream,
    /// The statements computing order `k` of every node.
    steps: Vec<TokenStream>,
    /// `q`, `v`, `v̇` and `λ` series' names.
    state: [Vec<Ident>; 4],
    /// The series of the coordinates' rates.
    rates: Vec<Ident>,
}

impl Prelude {
    /// The program of `lowered` named after `names`, declared.
    fn new(names: &Names, lowered: Lowered) -> Self {
        let program = &lowered.program;
        let (pool, operations) = (&program.pool, &program.operations);
        // Every constant the program reads, bound once.
        let mut constants: Vec<ExprId> = Vec::new();
        let mut read = |e: ExprId| {
            if !matches!(pool.node(e), Node::Number(_)) && !constants.contains(&e) {
                constants.push(e);
            }
        };
        for operation in operations {
            if let Operation::Linear { constant, terms } = operation {
                read(*constant);
                terms.iter().for_each(|(w, _)| read(*w));
            }
        }
        let entries = lowered.matrix.iter().flatten().chain(&lowered.forcing);
        let constraints = lowered.jacobian.iter().flatten().chain(&lowered.bias);
        for operand in entries.chain(constraints) {
            if let Operand::Constant(e) = operand {
                read(*e);
            }
        }
        let temporary = |i: usize| format_ident!("{}{}", names.temporary, i);
        let slots: Vec<Ident> = (0..operations.len()).map(temporary).collect();
        let constant_names = constants
            .iter()
            .enumerate()
            .map(|(i, &e)| (e, temporary(operations.len() + i)))
            .collect();
        let named =
            |list: &[Slot]| -> Vec<Ident> { list.iter().map(|&s| slots[s].clone()).collect() };
        let state = [
            named(&program.coordinates),
            named(&program.speeds),
            named(&program.accelerations),
            named(&program.multipliers),
        ];
        let rates = named(&lowered.rates);
        let mut prelude = Prelude {
            fields: TokenStream::new(),
            setup: TokenStream::new(),
            steps: Vec::new(),
            slots,
            constants,
            constant_names,
            state,
            rates,
            lowered,
        };
        prelude.declare(names);
        prelude
    }

    /// The names and statements around the program's own.
    fn written(&self) -> Written<'_> {
        Written {
            pool: &self.lowered.program.pool,
            slots: &self.slots,
            constants: &self.constant_names,
        }
    }

    /// Fills in `fields`, `setup` and `steps`.
    fn declare(&mut self, names: &Names) {
        let program = &self.lowered.program;
        let written = self.written();
        let bound: Vec<&Ident> = self
            .constants
            .iter()
            .map(|e| &self.constant_names[e])
            .collect();
        let body = straight_line(&program.pool, names, &self.constants);
        let (statements, outputs) = (&body.statements, &body.outputs);
        let n_constants = Literal::usize_unsuffixed(self.constants.len());
        let time_series = program.time.map(|slot| {
            let x = &self.slots[slot];
            quote!(let mut #x = ::dalembert::__private::series::time::<K>(t);)
        });
        let intermediate: Vec<&Ident> = program
            .operations
            .iter()
            .enumerate()
            .filter(|(_, operation)| !matches!(operation, Operation::State))
            .map(|(slot, _)| &self.slots[slot])
            .collect();
        let steps: Vec<TokenStream> = program
            .operations
            .iter()
            .enumerate()
            .map(|(slot, operation)| written.operation(slot, operation))
            .collect();
        let [q, v, a, lambda] = &self.state;
        let all_series = &self.slots[..program.operations.len()];
        let check = state_check();
        let fields = quote! {
            #(#all_series: &'a mut [f64; K],)*
            #(#bound: f64,)*
            order: usize,
        };
        let setup = quote! {
            #check
            let [#(#bound),*]: [f64; #n_constants] = {
                #statements
                [#(#outputs),*]
            };
            let [#(#q),*] = *q;
            let [#(#v),*] = *qd;
            #(let mut #q = ::dalembert::__private::series::start::<K>(#q);)*
            #(let mut #v = ::dalembert::__private::series::start::<K>(#v);)*
            #(let mut #a = [0.0; K];)*
            #(let mut #lambda = [0.0; K];)*
            #time_series
            #(let mut #intermediate = [0.0; K];)*
            let mut series = Series::<K> {
                #(#all_series: &mut #all_series,)*
                #(#bound,)*
                order: order.min(K.saturating_sub(1)),
            };
        };
        (self.fields, self.setup, self.steps) = (fields, setup, steps);
    }

    /// The integrals of order `k`: `vₖ = v̇ₖ₋₁ / k`, `qₖ = (N(q) v)ₖ₋₁ / k`.
    fn integrals(&self) -> TokenStream {
        let [q, v, a, _] = &self.state;
        let rates = &self.rates;
        quote! {
            #(::dalembert::__private::series::integral(&mut self.#v, &self.#a, k);)*
            #(::dalembert::__private::series::integral(&mut self.#q, &self.#rates, k);)*
        }
    }

    /// The right-hand side of order `k` of row `i` of `M v̇ − Aᵀ λ = f`:
    /// `fₖ − Σⱼ₌₁ᵏ (Mⱼ v̇ₖ₋ⱼ − Aⱼᵀ λₖ₋ⱼ)`, the entries that move only.
    fn forcing_row(&self, i: usize) -> TokenStream {
        let written = self.written();
        let Lowered {
            matrix,
            forcing,
            jacobian,
            ..
        } = &self.lowered;
        let [_, _, a, lambda] = &self.state;
        let f = written.at_order(forcing[i]);
        let inertia = written.tails(&matrix[i], a, quote!(-));
        let column: Vec<Operand> = jacobian.iter().map(|row| row[i]).collect();
        let constraint = written.tails(&column, lambda, quote!(+));
        quote!(#f #(#inertia)* #(#constraint)*)
    }

    /// The right-hand side of order `k` of row `r` of `A v̇ = b`:
    /// `bₖ − Σⱼ₌₁ᵏ Aⱼ v̇ₖ₋ⱼ`.
    fn bias_row(&self, r: usize) -> TokenStream {
        let written = self.written();
        let b = written.at_order(self.lowered.bias[r]);
        let moving = written.tails(&self.lowered.jacobian[r], &self.state[2], quote!(-));
        quote!(#b #(#moving)*)
    }
}

/// The signature shared by both forms of `taylor_coefficients`.
fn signature(model: &Model) -> TokenStream {
    let (nq_lit, nv_lit) = (
        Literal::usize_unsuffixed(model.nq()),
        Literal::usize_unsuffixed(model.nv()),
    );
    let (coordinates_ty, speeds_ty, inputs_ty) = (
        array(model.nq()),
        array(model.nv()),
        array(model.inputs.len()),
    );
    quote! {
        pub fn taylor_coefficients<const K: usize>(
            &self,
            t: f64,
            q: &#coordinates_ty,
            qd: &#speeds_ty,
            u: &#inputs_ty,
            order: usize,
        ) -> ::core::result::Result<([[f64; K]; #nq_lit], [[f64; K]; #nv_lit]), ::dalembert::DynamicsError>
    }
}

/// `taylor_coefficients` of a system without constraints: `M₀ v̇ₖ = fₖ −
/// Σⱼ₌₁ᵏ Mⱼ v̇ₖ₋ⱼ` with the unrolled `L D Lᵀ` solve of `accelerations`.
fn emit_unconstrained(
    model: &Model,
    prelude: &Prelude,
    solver: Elimination,
    function: &Function,
) -> TokenStream {
    let nv = model.nv();
    let written = prelude.written();
    let Elimination {
        entries,
        factor,
        substitutions,
        right_hand_side,
        solution,
        ..
    } = solver;
    let [q, v, a, _] = &prelude.state;
    let steps = &prelude.steps;
    let integrals = prelude.integrals();
    let mass_entries: Vec<TokenStream> = entries
        .iter()
        .map(|&(i, j)| written.value(prelude.lowered.matrix[i][j]))
        .collect();
    let mass_names: Vec<Ident> = entries.iter().map(|&(i, j)| mass(i, j)).collect();
    let rows: Vec<TokenStream> = (0..nv).map(|i| prelude.forcing_row(i)).collect();
    let (nv_lit, ne_lit) = (
        Literal::usize_unsuffixed(nv),
        Literal::usize_unsuffixed(entries.len()),
    );
    let unrolled = (1..=UNROLLED_ORDERS).map(Literal::usize_unsuffixed);
    let beyond = Literal::usize_unsuffixed(UNROLLED_ORDERS + 1);
    let series_docs = "The series of the expansion, borrowed (coordinates, speeds,
accelerations, then every node of `M` and `f` that moves),
the constants they read, and the highest order asked for.";
    let methods = quote! {
                /// Order `k` of every series, after order `k − 1` of the
                /// accelerations (`solved`) and its integrals: the entries
                /// of `M₀` that the factorisation reads and the right-hand
                /// side of order `k` (zeros at `k = order`, which only
                /// integrates). Always inlined, so that each call with a
                /// literal `k` is its own copy and every sum has a
                /// compile-time length.
                #[inline(always)]
                fn advance(&mut self, k: usize, solved: [f64; #nv_lit]) -> ([f64; #ne_lit], [f64; #nv_lit]) {
                    if let ::core::option::Option::Some(below) = k.checked_sub(1) {
                        ::dalembert::__private::series::assign_all([#(&mut self.#a),*], below, solved);
                        #integrals
                        if k == self.order {
                            return ([0.0; #ne_lit], [0.0; #nv_lit]);
                        }
                    }
                    #(#steps)*
                    ([#(#mass_entries),*], [#(#rows),*])
                }
                /// Order `k` of the accelerations solved from the
                /// right-hand side `rhs`, then order `k` of everything
                /// else and the next right-hand side, if the expansion
                /// goes that far.
                #[inline(always)]
                fn next(
                    &mut self,
                    k: usize,
                    rhs: [f64; #nv_lit],
                    solve: impl Fn([f64; #nv_lit]) -> [f64; #nv_lit],
                ) -> [f64; #nv_lit] {
                    if k <= self.order {
                        self.advance(k, solve(rhs)).1
                    } else {
                        rhs
                    }
                }
    };
    let orders = quote! {
            let ([#(#mass_names),*], mut rhs) = series.advance(0, [0.0; #nv_lit]);
            #factor
            let solve = |[#(#right_hand_side),*]: [f64; #nv_lit]| {
                #substitutions
                [#(#solution),*]
            };
            #(rhs = series.next(#unrolled, rhs, solve);)*
            for k in #beyond..=series.order {
                rhs = series.next(k, rhs, solve);
            }
            ::core::result::Result::Ok(([#(#q),*], [#(#v),*]))
    };
    wrapped(model, prelude, function, (series_docs, methods), orders)
}

/// `taylor_coefficients` of a system with constraints: order `k` of
/// `M v̇ − Aᵀ λ = f`, `A v̇ = b` solved with the one factorisation of the
/// saddle point at the expansion point that `constrained_accelerations`
/// makes (`dalembert::__private::constrained_series`), in a loop over the
/// orders.
fn emit_constrained(model: &Model, prelude: &Prelude, function: &Function) -> TokenStream {
    let (nv, nc) = (model.nv(), prelude.state[3].len());
    let written = prelude.written();
    let [q, v, a, lambda] = &prelude.state;
    let steps = &prelude.steps;
    let integrals = prelude.integrals();
    let values = |rows: &[Vec<Operand>]| -> Vec<TokenStream> {
        rows.iter()
            .map(|row| {
                let entries = row.iter().map(|&e| written.value(e));
                quote!([#(#entries),*])
            })
            .collect()
    };
    let (mass_rows, jacobian_rows) = (
        values(&prelude.lowered.matrix),
        values(&prelude.lowered.jacobian),
    );
    let forcing: Vec<TokenStream> = (0..nv).map(|i| prelude.forcing_row(i)).collect();
    let bias: Vec<TokenStream> = (0..nc).map(|r| prelude.bias_row(r)).collect();
    let (nv_lit, nc_lit) = (Literal::usize_unsuffixed(nv), Literal::usize_unsuffixed(nc));
    let series_docs = "The series of the expansion, borrowed (coordinates, speeds,
accelerations, multipliers, then every node of `M`, `f`,
`A`, `b` and the coordinates' rates that moves), the
constants they read, and the highest order asked for.";
    let methods = quote! {
                /// Order `k` of every series, after order `k − 1` of the
                /// accelerations and multipliers (`solved`) and its
                /// integrals: the right-hand sides of order `k` of
                /// `M v̇ − Aᵀ λ = f` and `A v̇ = b` (zeros at `k = order`,
                /// which only integrates).
                #[inline(always)]
                fn advance(
                    &mut self,
                    k: usize,
                    solved: ([f64; #nv_lit], [f64; #nc_lit]),
                ) -> ([f64; #nv_lit], [f64; #nc_lit]) {
                    if let ::core::option::Option::Some(below) = k.checked_sub(1) {
                        ::dalembert::__private::series::assign_all([#(&mut self.#a),*], below, solved.0);
                        ::dalembert::__private::series::assign_all([#(&mut self.#lambda),*], below, solved.1);
                        #integrals
                        if k == self.order {
                            return ([0.0; #nv_lit], [0.0; #nc_lit]);
                        }
                    }
                    #(#steps)*
                    ([#(#forcing),*], [#(#bias),*])
                }
                /// `M₀` and `A₀`, once order 0 is computed.
                #[inline(always)]
                fn saddle_point(&self) -> ([[f64; #nv_lit]; #nv_lit], [[f64; #nv_lit]; #nc_lit]) {
                    ([#(#mass_rows),*], [#(#jacobian_rows),*])
                }
    };
    let orders = quote! {
            let (forcing, bias) = series.advance(0, ([0.0; #nv_lit], [0.0; #nc_lit]));
            let (mass, jacobian) = series.saddle_point();
            let equations = ::dalembert::__private::SaddlePoint {
                mass: &mass,
                forcing,
                jacobian: &jacobian,
                bias,
            };
            ::dalembert::__private::constrained_series(self, t, q, equations, |mut solved, solver| {
                for k in 1..=series.order {
                    let (forcing, bias) = series.advance(k, solved);
                    if k < series.order {
                        solved = solver.solve(forcing, bias)?;
                    }
                }
                ::core::result::Result::Ok(())
            })?;
            ::core::result::Result::Ok(([#(#q),*], [#(#v),*]))
    };
    wrapped(model, prelude, function, (series_docs, methods), orders)
}

/// `taylor_coefficients` itself: its docs and signature, the struct
/// `Series` (documented by `series_docs`, with the methods `methods`), the
/// setup, then `orders`, which expands order by order and returns.
fn wrapped(
    model: &Model,
    prelude: &Prelude,
    function: &Function,
    (series_docs, methods): (&str, TokenStream),
    orders: TokenStream,
) -> TokenStream {
    let docs = function.docs.iter().map(|line| super::raw_string(line));
    let series_docs = series_docs
        .lines()
        .map(|line| super::raw_string(&format!(" {line}")));
    let signature = signature(model);
    let (fields, setup) = (&prelude.fields, &prelude.setup);
    quote! {
        #(#[doc = #docs])*
        #[inline]
        #signature {
            #(#[doc = #series_docs])*
            struct Series<'a, const K: usize> {
                #fields
            }
            impl<const K: usize> Series<'_, K> {
                #methods
            }
            #setup
            #orders
        }
    }
}

/// `impl dalembert::TaylorSystem` forwarding to `taylor_coefficients`.
pub fn emit_trait_impl(name: &Ident, sizes: [usize; 3]) -> TokenStream {
    let [nq, nv, nu] = sizes;
    let (coordinates, speeds, inputs) = (array(nq), array(nv), array(nu));
    let [nq, nv, nu] = sizes.map(Literal::usize_unsuffixed);
    let allowed = allowed_lints();
    quote! {
        #allowed
        impl ::dalembert::TaylorSystem<#nq, #nv, #nu> for #name {
            #[inline]
            fn taylor_coefficients<const K: usize>(
                &self,
                t: f64,
                q: &#coordinates,
                v: &#speeds,
                u: &#inputs,
                order: usize,
            ) -> ::core::result::Result<([[f64; K]; #nq], [[f64; K]; #nv]), ::dalembert::DynamicsError> {
                #name::taylor_coefficients::<K>(self, t, q, v, u, order)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    /// `source`, a system's text, with `outputs taylor;` before its
    /// closing brace, generated: the body of `taylor_coefficients`.
    fn taylor_body(source: &str) -> String {
        let end = source.rfind('}').expect("a closing brace");
        let source = format!("{}    outputs taylor;\n{}", &source[..end], &source[end..]);
        let code = crate::generate(&source).expect("generates");
        code[code.find("pub fn taylor_coefficients").expect("emitted")..].to_owned()
    }

    /// Seed example 3: `M` is constant and `A` moves in its column of
    /// `θ` only, so order `k` adds the tails of `A₀₂ λ₀` and `A₁₂ λ₁` to
    /// the forcing of `θ` and one to each row's bias: four in all, solved
    /// by the runtime's factorisation of the saddle point.
    #[test]
    fn constrained_systems_add_the_tails_of_the_moving_constraint_rows() {
        let body = taylor_body(crate::seeds::CONSTRAINED_PENDULUM);
        assert_eq!(body.matches("convolution_tail(").count(), 4, "{body}");
        assert!(
            body.contains("::dalembert::__private::constrained_series("),
            "{body}"
        );
    }

    /// A ball joint's four quaternion coordinates integrate the series of
    /// `½ q ⊗ (ω, 0)`, not speeds: twelve Cauchy products, each of the
    /// four components by each of the three of `ω` (a uniform ball has no
    /// gyroscopic forcing to add others).
    #[test]
    fn speeds_that_are_not_rates_integrate_the_series_of_the_rates() {
        let body = taylor_body(
            "Ball { parameters m; joint spherical ball { parent: N, child: B, at: O };
               body b { mass: m, center: ball, frame: B, inertia: [m, m, m] }; }",
        );
        assert_eq!(body.matches("series::integral(").count(), 4 + 3, "{body}");
        assert_eq!(body.matches("series::product(").count(), 12, "{body}");
    }

    /// One `sin_cos` per argument, one Cauchy product per distinct
    /// product, `x⁻²` as the reciprocal of `x · x`, constants out of the
    /// recurrences.
    #[test]
    fn the_program_shares_its_series() {
        let source = "S {
            parameters m, k;
            coordinates x;
            particle p { mass: m, at: O + x * N.x };
            potential k * (sin(x) + cos(x) + sin(x) * cos(x) + 1 / x);
            outputs taylor;
        }";
        let code = crate::generate(source).expect("generates");
        let body = &code[code.find("pub fn taylor_coefficients").expect("emitted")..];
        let calls = |name: &str| {
            body.matches(&format!("::dalembert::__private::series::{name}("))
                .count()
        };
        assert_eq!(calls("sin_cos"), 1, "{body}");
        // `−∂V/∂x = k (−cos x + sin x − cos² x + sin² x + x⁻²)`: the squares
        // and `x · x`.
        assert_eq!(calls("product"), 3, "{body}");
        assert_eq!(calls("reciprocal"), 1, "{body}");
        assert!(
            !body.contains("self.k *"),
            "constants are bound once: {body}"
        );
    }
}
