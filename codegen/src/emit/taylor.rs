//! `taylor_coefficients` (`outputs taylor;`): the Taylor coefficients of
//! the motion through a state, to any order, written from the plan's
//! program on series (`crate::series`, `plan::Taylor`).
//!
//! Order `k` of every series is computed from the lower orders by the
//! runtime's recurrences (`dalembert::__private::series`), which read and write the
//! series without indexing; then order `k` of the accelerations from
//! `M₀ q̈ₖ = fₖ − Σⱼ₌₁ᵏ Mⱼ q̈ₖ₋ⱼ` with the one `L D Lᵀ` factorisation of
//! `M₀` (only the entries of `M` that move contribute to the sum), and
//! order `k + 1` of the speeds and coordinates by integration. The work of
//! one order is `advance`, a method of a local struct (`Series`) that
//! borrows the series, always inlined and called once per order up to the
//! plan's unrolled orders with the order a literal, so that every
//! recurrence's sum has a compile-time length and unrolls; higher orders
//! run in a loop. The series stay local arrays, one each, which the struct
//! only borrows: owned by one struct, they measured twice as slow (the
//! sums of the inlined copies no longer vectorised), and so did one
//! out-of-line function per order.

use std::collections::HashMap;

use super::body::{Names, number, straight_line};
use super::solve::{Elimination, elimination, mass, state_check};
use super::{allowed_lints, array};
use crate::equations::Equations;
use crate::expr::{ExprId, Node, Pool};
use crate::model::Model;
use crate::outputs::Function;
use crate::plan::Taylor;
use crate::plan::solve::Factorisation;
use crate::series::{Lowered, Operand, Operation, Slot};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

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

/// `pub fn taylor_coefficients<const K: usize>(..)` from the plan's
/// `taylor` program: order by order with the `factorisation` of `M₀` that
/// `accelerations` uses, or, for a system with constraints, with the
/// runtime's factorisation of the saddle point ([`emit_constrained`]).
pub fn emit_taylor(
    (model, pool, equations): (&Model, &Pool, &Equations),
    names: &Names,
    function: &Function,
    taylor: &Taylor,
    factorisation: Option<&Factorisation>,
) -> TokenStream {
    let constrained = !equations.constraint_jacobian.is_empty();
    let prelude = Prelude::new(pool, names, &taylor.lowered);
    match factorisation {
        Some(factorisation) if !constrained => {
            let solver = elimination(model, pool, equations, factorisation, None);
            emit_unconstrained(model, &prelude, solver, function, taylor.unrolled_orders)
        }
        _ => emit_constrained(model, &prelude, function),
    }
}

/// What both forms of `taylor_coefficients` share: the program written
/// out, the declarations of its series and constants, and the work of an
/// order before its solve.
struct Prelude<'a> {
    /// The derivation's pool, which holds the program's constants.
    pool: &'a Pool,
    lowered: &'a Lowered,
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
    /// The const generic `K` of `taylor_coefficients`, the series' length
    /// (`KK` beside a user name `K`, which a `let` could not bind).
    length: Ident,
}

impl<'a> Prelude<'a> {
    /// The program of `lowered` named after `names`, declared.
    fn new(pool: &'a Pool, names: &Names, lowered: &'a Lowered) -> Self {
        let program = &lowered.program;
        let operations = &program.operations;
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
            length: names.unused("K"),
            fields: TokenStream::new(),
            setup: TokenStream::new(),
            steps: Vec::new(),
            slots,
            constants,
            constant_names,
            state,
            rates,
            pool,
            lowered,
        };
        prelude.declare(names);
        prelude
    }

    /// The names and statements around the program's own.
    fn written(&self) -> Written<'_> {
        Written {
            pool: self.pool,
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
        let body = straight_line(self.pool, names, &self.constants);
        let (statements, outputs) = (&body.statements, &body.outputs);
        let n_constants = Literal::usize_unsuffixed(self.constants.len());
        let k = &self.length;
        let time_series = program.time.map(|slot| {
            let x = &self.slots[slot];
            quote!(let mut #x = ::dalembert::__private::series::time::<#k>(t);)
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
            #(let mut #q = ::dalembert::__private::series::start::<#k>(#q);)*
            #(let mut #v = ::dalembert::__private::series::start::<#k>(#v);)*
            #(let mut #a = [0.0; #k];)*
            #(let mut #lambda = [0.0; #k];)*
            #time_series
            #(let mut #intermediate = [0.0; #k];)*
            let mut series = Series::<#k> {
                #(#all_series: &mut #all_series,)*
                #(#bound,)*
                order: order.min(#k.saturating_sub(1)),
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

/// The signature shared by both forms of `taylor_coefficients`, its const
/// generic named `k`.
fn signature(model: &Model, k: &Ident) -> TokenStream {
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
        pub fn taylor_coefficients<const #k: usize>(
            &self,
            t: f64,
            q: &#coordinates_ty,
            qd: &#speeds_ty,
            u: &#inputs_ty,
            order: usize,
        ) -> ::core::result::Result<([[f64; #k]; #nq_lit], [[f64; #k]; #nv_lit]), ::dalembert::DynamicsError>
    }
}

/// `taylor_coefficients` of a system without constraints: `M₀ v̇ₖ = fₖ −
/// Σⱼ₌₁ᵏ Mⱼ v̇ₖ₋ⱼ` with the unrolled `L D Lᵀ` solve of `accelerations`.
fn emit_unconstrained(
    model: &Model,
    prelude: &Prelude<'_>,
    solver: Elimination,
    function: &Function,
    unrolled_orders: usize,
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
    let unrolled = (1..=unrolled_orders).map(Literal::usize_unsuffixed);
    let beyond = Literal::usize_unsuffixed(unrolled_orders + 1);
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
fn emit_constrained(model: &Model, prelude: &Prelude<'_>, function: &Function) -> TokenStream {
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
    prelude: &Prelude<'_>,
    function: &Function,
    (series_docs, methods): (&str, TokenStream),
    orders: TokenStream,
) -> TokenStream {
    let docs = function.docs.iter().map(|line| super::raw_string(line));
    let series_docs = series_docs
        .lines()
        .map(|line| super::raw_string(&format!(" {line}")));
    let signature = signature(model, &prelude.length);
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
