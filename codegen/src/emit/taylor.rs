//! `taylor_coefficients` (`outputs taylor;`): the Taylor coefficients of
//! the motion through a state, to any order.
//!
//! The expression DAG of `M` and `f` is lowered to a program on series
//! (`[f64; K]`, one per node that moves: constants stay scalars): a sum is a
//! linear combination, a product a Cauchy product, a division a quotient,
//! `x^n` products of squares (a reciprocal for `n < 0`), and each elementary
//! function its recurrence (`sin` and `cos` of one argument as one pair).
//! Every operation calls the runtime's recurrence (`dalembert::series`),
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
    time: Option<Slot>,
}

/// The symbols whose series move within a step (inputs are held).
const MOVING: SymKinds = SymKinds::COORD.union(SymKinds::SPEED).union(SymKinds::TIME);

impl Program {
    /// The series of the state: `q`, `q̇` and `q̈`.
    fn new(pool: Pool, n: usize) -> Self {
        let mut program = Program {
            pool,
            operations: Vec::new(),
            nodes: HashMap::new(),
            calls: HashMap::new(),
            coordinates: Vec::new(),
            speeds: Vec::new(),
            accelerations: Vec::new(),
            time: None,
        };
        program.coordinates = (0..n).map(|_| program.push(Operation::State)).collect();
        program.speeds = (0..n).map(|_| program.push(Operation::State)).collect();
        program.accelerations = (0..n).map(|_| program.push(Operation::State)).collect();
        program
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

/// The program of `M` and `f`, and the operands of their entries.
struct Lowered {
    program: Program,
    matrix: Vec<Vec<Operand>>,
    forcing: Vec<Operand>,
}

impl Lowered {
    /// The entries of `M` and `f` lowered in `pool`.
    fn new(pool: Pool, nv: usize, (mass_matrix, forcing): (&[Vec<ExprId>], &[ExprId])) -> Self {
        let mut program = Program::new(pool, nv);
        let matrix = mass_matrix
            .iter()
            .map(|row| row.iter().map(|&e| program.lower(e)).collect())
            .collect();
        let forcing = forcing.iter().map(|&e| program.lower(e)).collect();
        Lowered {
            program,
            matrix,
            forcing,
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

/// `M` and `f` lowered as derived, or with their angle sums recombined
/// (within [`RECOMBINATION_BUDGET`]) when that takes fewer recurrences.
fn lowered(pool: &Pool, nv: usize, equations: &Equations) -> Lowered {
    let derived = Lowered::new(
        pool.clone(),
        nv,
        (&equations.mass_matrix, &equations.forcing),
    );
    let mut pool = pool.clone();
    let mut forms = ReadableForms::default();
    let mut recombine = |e: ExprId| forms.get(&mut pool, e, RECOMBINATION_BUDGET).unwrap_or(e);
    let mass_matrix: Vec<Vec<ExprId>> = equations
        .mass_matrix
        .iter()
        .map(|row| row.iter().map(|&e| recombine(e)).collect())
        .collect();
    let forcing: Vec<ExprId> = equations.forcing.iter().map(|&e| recombine(e)).collect();
    let recombined = Lowered::new(pool, nv, (&mass_matrix, &forcing));
    if recombined.recurrences() < derived.recurrences() {
        recombined
    } else {
        derived
    }
}

/// Names of the program's series and constants in the emitted code.
struct Written<'a> {
    pool: &'a Pool,
    slots: Vec<Ident>,
    constants: HashMap<ExprId, Ident>,
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
                quote!(::dalembert::series::at(&self.#x, k))
            }
            Operand::Constant(e) => {
                let c = self.constant(e);
                quote!(::dalembert::series::constant_at(#c, k))
            }
        }
    }

    /// Coefficient 0 of an operand.
    fn value(&self, operand: Operand) -> TokenStream {
        match operand {
            Operand::Series(slot) => {
                let x = &self.slots[slot];
                quote!(::dalembert::series::at(&self.#x, 0))
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
                quote!(::dalembert::series::linear(&mut self.#out, k, #constant, [#(#terms),*]);)
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
                quote!(::dalembert::series::#name(&mut self.#out, #partner #(&self.#operands,)* k);)
            }
        }
    }
}

/// `pub fn taylor_coefficients<const K: usize>(..)`; nothing for a system
/// the model rejects (constraints, speeds that are not rates).
pub fn emit_taylor(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    names: &Names,
    function: &Function,
) -> TokenStream {
    let Some(solver) = elimination(model, pool, equations, None) else {
        return TokenStream::new();
    };
    let nv = model.nv();
    let Lowered {
        program:
            Program {
                pool,
                operations,
                coordinates,
                speeds,
                accelerations,
                time,
                ..
            },
        matrix,
        forcing,
    } = lowered(pool, nv, equations);
    // Every constant the program reads, bound once.
    let mut constants: Vec<ExprId> = Vec::new();
    let mut read = |e: ExprId| {
        if !matches!(pool.node(e), Node::Number(_)) && !constants.contains(&e) {
            constants.push(e);
        }
    };
    for operation in &operations {
        if let Operation::Linear { constant, terms } = operation {
            read(*constant);
            terms.iter().for_each(|(w, _)| read(*w));
        }
    }
    for operand in matrix.iter().flatten().chain(&forcing) {
        if let Operand::Constant(e) = operand {
            read(*e);
        }
    }
    let temporary = |i: usize| format_ident!("{}{}", names.temporary, i);
    let written = Written {
        pool: &pool,
        slots: (0..operations.len()).map(temporary).collect(),
        constants: constants
            .iter()
            .enumerate()
            .map(|(i, &e)| (e, temporary(operations.len() + i)))
            .collect(),
    };
    let Elimination {
        entries,
        factor,
        substitutions,
        right_hand_side,
        solution,
        ..
    } = solver;
    let slots =
        |list: &[Slot]| -> Vec<Ident> { list.iter().map(|&s| written.slots[s].clone()).collect() };
    let (q, v, a) = (slots(&coordinates), slots(&speeds), slots(&accelerations));
    let bound: Vec<&Ident> = constants.iter().map(|e| &written.constants[e]).collect();
    let body = straight_line(&pool, names, &constants);
    let (statements, outputs) = (&body.statements, &body.outputs);
    let n_constants = Literal::usize_unsuffixed(constants.len());
    let time_series = time.map(|slot| {
        let x = &written.slots[slot];
        quote!(let mut #x = ::dalembert::series::time::<K>(t);)
    });
    let intermediate: Vec<&Ident> = operations
        .iter()
        .enumerate()
        .filter(|(_, operation)| !matches!(operation, Operation::State))
        .map(|(slot, _)| &written.slots[slot])
        .collect();
    let steps: Vec<TokenStream> = operations
        .iter()
        .enumerate()
        .map(|(slot, operation)| written.operation(slot, operation))
        .collect();
    let mass_entries: Vec<TokenStream> = entries
        .iter()
        .map(|&(i, j)| written.value(matrix[i][j]))
        .collect();
    let mass_names: Vec<Ident> = entries.iter().map(|&(i, j)| mass(i, j)).collect();
    let rows: Vec<TokenStream> = (0..nv)
        .map(|i| {
            let f = written.at_order(forcing[i]);
            let moving = matrix[i]
                .iter()
                .zip(&a)
                .filter_map(|(entry, acceleration)| match entry {
                    Operand::Series(slot) => {
                        let m = &written.slots[*slot];
                        Some(
                            quote!(- ::dalembert::series::convolution_tail(&self.#m, &self.#acceleration, k)),
                        )
                    }
                    Operand::Constant(_) => None,
                });
            quote!(#f #(#moving)*)
        })
        .collect();
    let (nq_lit, nv_lit, ne_lit) = (
        Literal::usize_unsuffixed(model.nq()),
        Literal::usize_unsuffixed(nv),
        Literal::usize_unsuffixed(entries.len()),
    );
    let (coordinates_ty, speeds_ty, inputs_ty) =
        (array(model.nq()), array(nv), array(model.inputs.len()));
    let check = state_check();
    let unrolled = (1..=UNROLLED_ORDERS).map(Literal::usize_unsuffixed);
    let beyond = Literal::usize_unsuffixed(UNROLLED_ORDERS + 1);
    let all_series = &written.slots;
    let docs = function.docs.iter().map(|line| super::raw_string(line));
    quote! {
        #(#[doc = #docs])*
        #[inline]
        pub fn taylor_coefficients<const K: usize>(
            &self,
            t: f64,
            q: &#coordinates_ty,
            qd: &#speeds_ty,
            u: &#inputs_ty,
            order: usize,
        ) -> ::core::result::Result<([[f64; K]; #nq_lit], [[f64; K]; #nv_lit]), ::dalembert::DynamicsError> {
            /// The series of the expansion, borrowed (coordinates, speeds,
            /// accelerations, then every node of `M` and `f` that moves),
            /// the constants they read, and the highest order asked for.
            struct Series<'a, const K: usize> {
                #(#all_series: &'a mut [f64; K],)*
                #(#bound: f64,)*
                order: usize,
            }
            impl<const K: usize> Series<'_, K> {
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
                        ::dalembert::series::assign_all([#(&mut self.#a),*], below, solved);
                        #(::dalembert::series::integral(&mut self.#v, &self.#a, k);)*
                        #(::dalembert::series::integral(&mut self.#q, &self.#v, k);)*
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
            }
            #check
            let [#(#bound),*]: [f64; #n_constants] = {
                #statements
                [#(#outputs),*]
            };
            let [#(#q),*] = *q;
            let [#(#v),*] = *qd;
            #(let mut #q = ::dalembert::series::start::<K>(#q);)*
            #(let mut #v = ::dalembert::series::start::<K>(#v);)*
            #(let mut #a = [0.0; K];)*
            #time_series
            #(let mut #intermediate = [0.0; K];)*
            let mut series = Series::<K> {
                #(#all_series: &mut #all_series,)*
                #(#bound,)*
                order: order.min(K.saturating_sub(1)),
            };
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
    /// closing brace.
    fn asking_for_taylor(source: &str) -> String {
        let end = source.rfind('}').expect("a closing brace");
        format!("{}    outputs taylor;\n{}", &source[..end], &source[end..])
    }

    /// The error `check` reports, at the line and column of `taylor`.
    fn error_at_taylor(source: &str) -> String {
        let error = crate::check(source).expect_err("rejected");
        let line = source
            .lines()
            .position(|l| l.contains("outputs taylor"))
            .expect("the line");
        let start = error.span().start();
        assert_eq!(start.line, line + 1, "{error}");
        let column = source.lines().nth(line).and_then(|l| l.find("taylor"));
        assert_eq!(Some(start.column), column, "{error}");
        error.to_string()
    }

    #[test]
    fn constrained_systems_have_no_taylor_output_and_the_error_says_where() {
        let source = asking_for_taylor(crate::seeds::CONSTRAINED_PENDULUM);
        let message = error_at_taylor(&source);
        assert!(
            message.contains("`taylor` is not available for a system with constraints"),
            "{message}"
        );
    }

    #[test]
    fn speeds_that_are_not_rates_have_no_taylor_output() {
        let source = asking_for_taylor(
            "Ball { parameters m; joint spherical ball { parent: N, child: B, at: O };
               body b { mass: m, center: ball, frame: B, inertia: [m, m, m] }; }",
        );
        let message = error_at_taylor(&source);
        assert!(
            message.contains("whose speeds are not its coordinates' rates"),
            "{message}"
        );
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
            body.matches(&format!("::dalembert::series::{name}("))
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
