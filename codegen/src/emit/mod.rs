//! Emission: the planned functions as Rust items — one public struct of
//! parameters, its inherent functions (docs/architecture.md §4) and the
//! runtime traits. Every choice of route is the plan's (`crate::plan`);
//! emission only writes code from it.
//! Emitted code names everything by absolute path, so user items called
//! `Result` or `f64` cannot change its meaning. For `#![no_std]` crates
//! ([`Target::NoStd`]) the elementary functions go through `libm` and the
//! items that need the `dalembert` runtime (which needs `std`) are left out.

mod body;
mod configuration;
mod derivatives;
mod lanes;
mod solve;
mod taylor;

use crate::api::Api;
use crate::equations::Equations;
use crate::expr::{Pool, Sym};
use crate::model::Model;
use crate::outputs::{Argument, Body, Function, NameList, Shape, SpeedTree};
use crate::plan::Plan;
use body::{Names, straight_line};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};

/// The human-readable side of a system: its doc-comment lines (the user's,
/// then the derived equations; the list of generated functions follows
/// them), the equations as plain text and the model's own text.
pub struct Documentation {
    /// Lines of the struct's doc comment.
    pub docs: Vec<String>,
    /// The derived equations, for `NAME::EQUATIONS`.
    pub text: String,
    /// The model's text, for `NAME::SOURCE`.
    pub source: String,
}

/// The kind of crate the code is for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Target {
    /// A crate with `std` and the `dalembert` runtime: `f64`'s methods for
    /// the functions, the runtime's traits, the `accelerations` method.
    #[default]
    Std,
    /// A `#![no_std]` crate depending on `libm`: the equations only.
    NoStd,
}

/// All items for one system.
pub fn emit(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    plan: &Plan,
    documentation: &Documentation,
    target: Target,
) -> TokenStream {
    let names = names(model, target);
    let factorisation = plan.factorisation.as_ref();
    let name = &model.name;
    let (nq, nv) = (model.nq(), model.nv());
    let nu = model.inputs.len();
    let nc = model.constraints.len();
    let mut items: Vec<TokenStream> = plan
        .functions
        .iter()
        .map(|function| match (&function.body, target) {
            (Body::Explicit | Body::MassPairs(_), _) => {
                emit_function(model, pool, &names, function)
            }
            // They return the runtime's errors.
            (_, Target::NoStd) => TokenStream::new(),
            (Body::AccelerationsJacobian(paired), Target::Std) => {
                derivatives::emit_accelerations_jacobian(
                    model,
                    pool,
                    equations,
                    &names,
                    function,
                    paired.as_ref(),
                    factorisation,
                )
            }
            (Body::AdjointRows, Target::Std) => derivatives::emit_adjoint_rows(
                model,
                pool,
                equations,
                &names,
                function,
                factorisation,
            ),
            (Body::Linearize, Target::Std) => {
                derivatives::emit_linearize(model, pool, &names, function)
            }
            (Body::ConstrainedLinearize, Target::Std) => {
                derivatives::emit_constrained_linearize(model, pool, &names, function)
            }
            (Body::ConstrainedAccelerationsJacobian, Target::Std) => {
                derivatives::emit_constrained_accelerations_jacobian(model, pool, &names, function)
            }
            (Body::AccelerationsX4, Target::Std) => {
                lanes::emit_accelerations_x4(model, pool, equations, &names, plan, &function.docs)
            }
            (Body::Taylor, Target::Std) => match &plan.taylor {
                Some(program) => taylor::emit_taylor(
                    (model, pool, equations),
                    &names,
                    function,
                    program,
                    factorisation,
                ),
                None => TokenStream::new(),
            },
        })
        .collect();
    items.push(configuration::emit_configuration(model, pool, &names));
    let mut constants = emit_constants(model, pool, documentation);
    constants.extend(plan.constants.iter().map(emit_name_list));
    if equations.time_dependent(pool) {
        constants.extend(quote! {
            /// Time `t` enters the mass matrix, the energies or the
            /// constraint Jacobian: they are `mass_matrix_at(t, q)`,
            /// `kinetic_energy_at(t, q, qd)`, `potential_energy_at(t, q)`
            /// (and `constraint_jacobian_at(t, q)`).
            pub const TIME_DEPENDENT: bool = true;
        });
    }
    let traits = match target {
        Target::Std => {
            let solver = solve::emit_accelerations(model, pool, equations, &names, plan);
            let has_solver = !solver.is_empty();
            items.push(solver);
            let check = configuration::emit_rate_check(model, pool, &names);
            let has_check = !check.is_empty();
            items.push(check);
            let has_lanes = plan
                .functions
                .iter()
                .any(|f| f.body == Body::AccelerationsX4);
            let emitted = [
                has_solver,
                has_check,
                equations.time_dependent(pool),
                has_solver && has_lanes,
            ];
            let vanishing = model.vanishing_rows();
            let mut traits =
                emit_trait_impls(name, [nq, nv, nu, nc], emitted, vanishing.as_deref());
            traits.extend(emit_model_impl(model));
            if plan.functions.iter().any(|f| f.body == Body::Taylor) {
                traits.extend(taylor::emit_trait_impl(name, [nq, nv, nu]));
            }
            traits
        }
        Target::NoStd => TokenStream::new(),
    };
    let allowed = allowed_lints();
    let inherent = quote! {
        impl #name {
            #constants
            #(#items)*
        }
    };
    let mut docs = documentation.docs.clone();
    docs.extend(Api::of(model, &inherent).doc_lines());
    let strukt = emit_struct(model, &docs);
    quote! {
        #strukt
        #allowed
        #inherent
        #traits
    }
}

/// `impl dalembert::Model`: the model's text and the parameters' values,
/// for tools that read the model (the lab's scenes).
fn emit_model_impl(model: &Model) -> TokenStream {
    let name = &model.name;
    let parameters = &model.parameters;
    let np = Literal::usize_unsuffixed(parameters.len());
    let allowed = allowed_lints();
    quote! {
        #allowed
        impl ::dalembert::Model<#np> for #name {
            const SOURCE: &'static str = #name::SOURCE;
            const PARAMETERS: [&'static str; #np] = #name::PARAMETERS;
            #[inline]
            fn parameter_values(&self) -> [f64; #np] {
                [#(self.#parameters),*]
            }
        }
    }
}

/// The lints every generated item allows: parameters are named as written
/// (`L`), and straight-line code for a model is long, dense in names and
/// literals, and not written for a human, so that a user's crate with
/// `#![deny(clippy::pedantic)]` (or `nursery`) compiles the build step's
/// `include!`d file as it compiles the macro's expansion.
fn allowed_lints() -> TokenStream {
    quote!(#[allow(non_snake_case, clippy::all, clippy::pedantic, clippy::nursery)])
}

fn names(model: &Model, target: Target) -> Names {
    let own_speeds = model.speeds.iter().filter(|s| !s.rate_of_coordinate);
    let taken: Vec<String> = model
        .parameters
        .iter()
        .chain(&model.coordinates)
        .chain(&model.inputs)
        .chain(own_speeds.map(|s| &s.name))
        .map(|i| i.to_string())
        .collect();
    // A speed that is its coordinate's rate is `q_dot` (its rate `q_ddot`);
    // a speed of the user's own keeps its name (its rate `w_dot`).
    let rates = |suffix: &str, own: &str, fallback: &str| -> Vec<Ident> {
        model
            .speeds
            .iter()
            .enumerate()
            .map(|(i, speed)| {
                let name = &speed.name;
                let preferred = match speed.rate_of_coordinate {
                    true => format!("{name}_{suffix}"),
                    false if own.is_empty() => return name.clone(),
                    false => format!("{name}_{own}"),
                };
                if taken.contains(&preferred) {
                    format_ident!("{}_{}", fallback, i)
                } else {
                    Ident::new(&preferred, name.span())
                }
            })
            .collect()
    };
    let speeds = rates("dot", "", "qd");
    let accelerations = rates("ddot", "dot", "qdd");
    Names {
        parameters: model.parameters.clone(),
        coordinates: model.coordinates.clone(),
        speeds,
        accelerations,
        inputs: model.inputs.clone(),
        temporary: unused_prefix(&taken, "x", 'x'),
        multiplier: unused_prefix(&taken, "lambda", '_'),
        libm: target == Target::NoStd,
        lanes: false,
        weights_in_lanes: false,
    }
}

/// `base`, lengthened by `pad` until no name of `taken` is it followed by
/// digits, so that the names it numbers (`x0`, `lambda3`) are free.
fn unused_prefix(taken: &[String], base: &str, pad: char) -> String {
    let mut prefix = base.to_string();
    while taken.iter().any(|n| {
        n.strip_prefix(&prefix)
            .is_some_and(|rest| rest.chars().all(|c| c.is_ascii_digit()))
    }) {
        prefix.push(pad);
    }
    prefix
}

fn emit_struct(model: &Model, docs: &[String]) -> TokenStream {
    let name = &model.name;
    let vis = if model.public { quote!(pub) } else { quote!() };
    let fields = model.parameters.iter().map(|p| {
        let doc = format!(" Parameter `{p}`.");
        quote!(#[doc = #doc] pub #p: f64)
    });
    let docs = docs.iter().map(|line| quote!(#[doc = #line]));
    let allowed = allowed_lints();
    quote! {
        #(#docs)*
        #[derive(::core::clone::Clone, ::core::marker::Copy, ::core::fmt::Debug, ::core::cmp::PartialEq)]
        #allowed
        #vis struct #name {
            #(#fields,)*
        }
    }
}

/// `text` as a raw string literal, so that its characters (`q̈`'s combining
/// diaeresis among them) read as themselves in the source and in rustdoc,
/// not as `\u{308}` escapes.
fn raw_string(text: &str) -> Literal {
    let longest = text
        .split('"')
        .skip(1)
        .map(|after| after.chars().take_while(|&c| c == '#').count())
        .max()
        .unwrap_or(0);
    let hashes = "#".repeat(longest + 1);
    format!("r{hashes}\"{text}\"{hashes}")
        .parse()
        .unwrap_or_else(|_| Literal::string(text))
}

fn emit_constants(model: &Model, pool: &Pool, documentation: &Documentation) -> TokenStream {
    let [nq, nv, np, nu, nc] = [
        model.nq(),
        model.nv(),
        model.parameters.len(),
        model.inputs.len(),
        model.constraints.len(),
    ]
    .map(Literal::usize_unsuffixed);
    let strings = |list: &[Ident]| -> Vec<String> { list.iter().map(|i| i.to_string()).collect() };
    let coordinates = strings(&model.coordinates);
    let parameters = strings(&model.parameters);
    let inputs = strings(&model.inputs);
    let speeds = model.speeds.iter().map(|s| s.written());
    let nv_doc = if pool.rates_are_speeds() {
        " Number of speeds (the coordinates' rates)."
    } else {
        " Number of speeds (`v`, with `q̇ = N(q) v`)."
    };
    let equations = raw_string(&documentation.text);
    let source = raw_string(&documentation.source);
    quote! {
        /// Number of generalized coordinates.
        pub const NQ: usize = #nq;
        #[doc = #nv_doc]
        pub const NV: usize = #nv;
        /// Number of inputs.
        pub const NU: usize = #nu;
        /// Number of constraints.
        pub const NC: usize = #nc;
        /// Names of the generalized coordinates, in index order.
        pub const COORDINATES: [&'static str; #nq] = [#(#coordinates),*];
        /// Names of the speeds, in index order.
        pub const SPEEDS: [&'static str; #nv] = [#(#speeds),*];
        /// Names of the parameters, in field order.
        pub const PARAMETERS: [&'static str; #np] = [#(#parameters),*];
        /// Names of the inputs, in index order.
        pub const INPUTS: [&'static str; #nu] = [#(#inputs),*];
        /// The derived equations of motion, in the seed document's style.
        pub const EQUATIONS: &'static str = #equations;
        /// The model's text, as the build script read it (a `.dal` file or
        /// an imported robot's model) or as the macro read its tokens: what
        /// tools that read the model take (`dalembert_lab::Scene::of`).
        pub const SOURCE: &'static str = #source;
    }
}

/// `pub const NAME: [&'static str; n]`, with its docs.
fn emit_name_list(list: &NameList) -> TokenStream {
    let docs = list.docs.iter().map(|line| raw_string(line));
    let (name, names) = (&list.name, &list.names);
    let n = Literal::usize_unsuffixed(names.len());
    quote! {
        #(#[doc = #docs])*
        pub const #name: [&'static str; #n] = [#(#names),*];
    }
}

/// `[f64; n]` as tokens.
fn array(n: usize) -> TokenStream {
    let n = Literal::usize_unsuffixed(n);
    quote!([f64; #n])
}

/// An argument name, with a leading underscore when the body ignores it.
fn argument_name(name: &str, used: bool) -> Ident {
    if used {
        Ident::new(name, Span::call_site())
    } else {
        format_ident!("_{}", name)
    }
}

/// Groups flat outputs into rows of `width`.
fn rows(outputs: &[TokenStream], width: usize) -> Vec<TokenStream> {
    outputs
        .chunks(width.max(1))
        .map(|row| quote!([#(#row),*]))
        .collect()
}

/// One function: its docs, its signature (an argument it does not read is
/// named with a leading `_`) and a straight-line body computing all its
/// results, which share their subexpressions.
fn emit_function(model: &Model, pool: &Pool, names: &Names, function: &Function) -> TokenStream {
    let body = straight_line(pool, names, &function.roots());
    let reads = |kind: fn(&Sym) -> bool| body.used.iter().any(kind);
    let (nq, nv, nu) = (
        array(model.nq()),
        array(model.nv()),
        array(model.inputs.len()),
    );
    let arguments = function.arguments.iter().map(|argument| {
        let (name, ty, used) = match argument {
            Argument::Time => ("t", quote!(f64), reads(|s| matches!(s, Sym::Time))),
            Argument::Coordinates => ("q", quote!(&#nq), reads(|s| matches!(s, Sym::Coord(_)))),
            Argument::Speeds => ("qd", quote!(&#nv), reads(|s| matches!(s, Sym::Speed(_)))),
            Argument::Accelerations => ("qdd", quote!(&#nv), reads(|s| matches!(s, Sym::Accel(_)))),
            Argument::Inputs => ("u", quote!(&#nu), reads(|s| matches!(s, Sym::Input(_)))),
            Argument::Weights => (
                "mu",
                quote!(&#nv),
                reads(|s| matches!(s, Sym::Multiplier(_))),
            ),
        };
        let name = argument_name(name, used);
        quote!(#name: #ty)
    });
    let entries = body.outputs;
    let mut outputs = entries.iter().cloned();
    let (mut types, mut values) = (Vec::new(), Vec::new());
    for result in &function.results {
        let n = result.expressions.len();
        let entries: Vec<TokenStream> = outputs.by_ref().take(n).collect();
        let (ty, value) = match result.shape {
            Shape::Scalar => (quote!(f64), quote!(#(#entries)*)),
            Shape::Vector => (array(n), quote!([#(#entries),*])),
            Shape::Matrix { columns } => {
                let height = Literal::usize_unsuffixed(n / columns.max(1));
                let (row, rows) = (array(columns), rows(&entries, columns));
                (quote!([#row; #height]), quote!([#(#rows),*]))
            }
        };
        types.push(ty);
        values.push(value);
    }
    let (ty, value) = match (types.as_slice(), values.as_slice(), &function.body) {
        (_, _, Body::MassPairs(tree)) => tree_mass_matrix(model.nv(), tree, &entries),
        ([ty], [value], _) => (ty.clone(), value.clone()),
        _ => (quote!((#(#types),*)), quote!((#(#values),*))),
    };
    let docs = function.docs.iter().map(|line| raw_string(line));
    let (name, statements) = (&function.name, &body.statements);
    let weights = match function.arguments.contains(&Argument::Weights) {
        true => load_weights(model.nv(), names, &body.used),
        false => TokenStream::new(),
    };
    quote! {
        #(#[doc = #docs])*
        #[inline]
        #[must_use]
        pub fn #name(&self, #(#arguments),*) -> #ty {
            #weights
            #statements
            #value
        }
    }
}

/// `let [lambda0, _, ..] = *mu;`: the weights of a vector–jacobian
/// product (the symbols `Sym::Multiplier`, which the body names
/// [`Names::multiplier`]), `_` for those it does not read; nothing if it
/// reads none.
fn load_weights(nv: usize, names: &Names, used: &std::collections::BTreeSet<Sym>) -> TokenStream {
    let patterns = (0..nv).map(|i| match used.contains(&Sym::Multiplier(i as u32)) {
        true => {
            let name = names.multiplier(i);
            quote!(#name)
        }
        false => quote!(_),
    });
    match (0..nv).any(|i| used.contains(&Sym::Multiplier(i as u32))) {
        true => quote!(let [#(#patterns),*] = *mu;),
        false => TokenStream::new(),
    }
}

/// The return type and value of a `mass_matrix` whose pairs the
/// runtime's loop takes (`dalembert::__private::tree_mass_matrix`), from
/// the entries `outputs` of each speed's `Sⱼ` and `Fⱼ` and the table of
/// `tree`, then the armatures (the rest of `outputs`) added to its
/// diagonal (`dalembert::__private::add_to_diagonal`).
fn tree_mass_matrix(
    nv: usize,
    tree: &SpeedTree,
    outputs: &[TokenStream],
) -> (TokenStream, TokenStream) {
    let (outputs, armature) = outputs.split_at(12 * tree.speeds.len());
    let vectors = outputs.chunks(12).map(|speed| {
        let [s, f] = [&speed[..6], &speed[6..]];
        quote!([[#(#s),*], [#(#f),*]])
    });
    let table = tree.ends.iter().zip(&tree.speeds).map(|(&end, &speed)| {
        let [end, speed] = [end, speed].map(Literal::usize_unsuffixed);
        quote!(::dalembert::__private::TreeSpeed { end: #end, speed: #speed })
    });
    let (row, nv) = (array(nv), Literal::usize_unsuffixed(nv));
    let pairs = quote!(::dalembert::__private::tree_mass_matrix(&[#(#vectors),*], &[#(#table),*]));
    let value = match armature.is_empty() {
        true => pairs,
        false => {
            let terms = tree.armature.iter().zip(armature).map(|(&speed, value)| {
                let speed = Literal::usize_unsuffixed(speed);
                quote!((#speed, #value))
            });
            quote! {{
                let mut m = #pairs;
                ::dalembert::__private::add_to_diagonal(&mut m, [#(#terms),*]);
                m
            }}
        }
    };
    (quote!([#row; #nv]), value)
}

/// The runtime's traits, forwarding to the inherent functions (and to the
/// emitted `accelerations` and `check_coordinate_rates` when the system has
/// them). A system with constraints answers `accelerations` with the
/// constrained `v̇` of `M v̇ = f + Aᵀ λ`, `A v̇ = b` (the runtime's
/// `constrained_accelerations`, multipliers dropped), so that
/// `dalembert::accelerations` gives the motion the constraints allow. A
/// time-dependent system (the third of `emitted`) forwards the traits'
/// `_at` functions and has no value for the time-free ones (see
/// [`TraitFunction::undefined`]). The rows that vanish identically, if
/// any, are its `VANISHING_ROWS`. A system with `accelerations_x4` (the
/// fourth of `emitted`) forwards the trait's to it.
fn emit_trait_impls(
    name: &Ident,
    sizes: [usize; 4],
    emitted: [bool; 4],
    vanishing: Option<&[bool]>,
) -> TokenStream {
    let [has_solver, has_check, timed, has_lanes] = emitted;
    let lanes = has_lanes.then(|| lanes::emit_trait_method(name, [sizes[0], sizes[1], sizes[2]]));
    let [nq, nv, nu, nc] = sizes;
    let (coordinates, vector) = (array(nq), array(nv));
    let (inputs, rows_out) = (array(nu), array(nc));
    let [nq, nv, nu, nc_lit] = [nq, nv, nu, nc].map(Literal::usize_unsuffixed);
    let bools = quote!([bool; #nc_lit]);
    let solve = if nc > 0 {
        Some(quote! {
            ::dalembert::constrained::constrained_accelerations(self, t, q, v, u)
                .map(|(vdot, _)| vdot)
        })
    } else {
        has_solver.then(|| quote!(#name::accelerations(self, t, q, v, u)))
    };
    let accelerations = solve.map(|solve| {
        quote! {
            #[inline]
            fn accelerations(
                &self,
                t: f64,
                q: &#coordinates,
                v: &#vector,
                u: &#inputs,
            ) -> ::core::result::Result<#vector, ::dalembert::DynamicsError> {
                #solve
            }
        }
    });
    let check = has_check.then(|| {
        quote! {
            #[inline]
            fn check_coordinate_rates(
                &self,
                q: &#coordinates,
            ) -> ::core::result::Result<(), ::dalembert::DynamicsError> {
                #name::check_coordinate_rates(self, q)
            }
        }
    });
    let nan = quote!(::core::primitive::f64::NAN);
    let energies = [
        TraitFunction {
            function: quote!(mass_matrix),
            arguments: quote!(q: &#coordinates),
            passed: quote!(q),
            ty: quote!([#vector; #nv]),
            undefined: quote!([[#nan; #nv]; #nv]),
        },
        TraitFunction {
            function: quote!(kinetic_energy),
            arguments: quote!(q: &#coordinates, v: &#vector),
            passed: quote!(q, v),
            ty: quote!(f64),
            undefined: nan.clone(),
        },
        TraitFunction {
            function: quote!(potential_energy),
            arguments: quote!(q: &#coordinates),
            passed: quote!(q),
            ty: quote!(f64),
            undefined: nan.clone(),
        },
    ]
    .map(|function| function.forward(name, timed));
    let [mass, kinetic, potential] = &energies;
    let time_dependent = timed.then(|| {
        quote!(
            const TIME_DEPENDENT: bool = true;
        )
    });
    let allowed = allowed_lints();
    let system = quote! {
        #allowed
        impl ::dalembert::MultibodySystem<#nq, #nv, #nu> for #name {
            const COORDINATES: [&'static str; #nq] = #name::COORDINATES;
            const SPEEDS: [&'static str; #nv] = #name::SPEEDS;
            const INPUTS: [&'static str; #nu] = #name::INPUTS;
            #time_dependent
            #mass
            #[inline]
            fn forcing(&self, t: f64, q: &#coordinates, v: &#vector, u: &#inputs) -> #vector {
                #name::forcing(self, t, q, v, u)
            }
            #kinetic
            #potential
            #[inline]
            fn coordinate_rates(&self, q: &#coordinates, v: &#vector) -> #coordinates {
                #name::coordinate_rates(self, q, v)
            }
            #[inline]
            fn integrate_configuration(&self, q: &#coordinates, v: &#vector, h: f64) -> #coordinates {
                #name::integrate_configuration(self, q, v, h)
            }
            #accelerations
            #lanes
            #check
        }
    };
    if nc == 0 {
        return system;
    }
    let vanishing = vanishing.map(|rows| {
        quote! {
            const VANISHING_ROWS: #bools = [#(#rows),*];
        }
    });
    let jacobian = TraitFunction {
        function: quote!(constraint_jacobian),
        arguments: quote!(q: &#coordinates),
        passed: quote!(q),
        ty: quote!([#vector; #nc_lit]),
        undefined: quote!([[#nan; #nv]; #nc_lit]),
    }
    .forward(name, timed);
    quote! {
        #system
        #allowed
        impl ::dalembert::ConstrainedSystem<#nq, #nv, #nu, #nc_lit> for #name {
            #vanishing
            #jacobian
            #[inline]
            fn constraint_bias(&self, t: f64, q: &#coordinates, v: &#vector) -> #rows_out {
                #name::constraint_bias(self, t, q, v)
            }
            #[inline]
            fn constraint_residual(&self, t: f64, q: &#coordinates) -> #rows_out {
                #name::constraint_residual(self, t, q)
            }
            #[inline]
            fn constraint_velocity(&self, t: f64, q: &#coordinates, v: &#vector) -> #rows_out {
                #name::constraint_velocity(self, t, q, v)
            }
        }
    }
}

/// A function of the traits that a time-dependent system has only at a
/// time: `M`, `T`, `V` or `A`.
struct TraitFunction {
    function: TokenStream,
    arguments: TokenStream,
    passed: TokenStream,
    ty: TokenStream,
    /// Its time-free value for a time-dependent system: NaN in every
    /// entry, since it depends on a `t` the call does not give. The
    /// runtime calls the `_at` forms; a caller of the time-free one meets
    /// a non-finite value, never a value at some time.
    undefined: TokenStream,
}

impl TraitFunction {
    /// The function forwarded to the inherent one: for a time-free system,
    /// the time-free function (the trait's `_at` form calls it); for a
    /// `timed` one, the `_at` form, and the time-free one
    /// [undefined](TraitFunction::undefined).
    fn forward(self, name: &Ident, timed: bool) -> TokenStream {
        let TraitFunction {
            function,
            arguments,
            passed,
            ty,
            undefined,
        } = self;
        if !timed {
            return quote! {
                #[inline]
                fn #function(&self, #arguments) -> #ty {
                    #name::#function(self, #passed)
                }
            };
        }
        let at = format_ident!("{}_at", function.to_string());
        quote! {
            #[inline]
            fn #function(&self, #arguments) -> #ty {
                let _ = (#passed,);
                #undefined
            }
            #[inline]
            fn #at(&self, t: f64, #arguments) -> #ty {
                #name::#at(self, t, #passed)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Target, emit_function, names, raw_string};
    use crate::expr::Sym;
    use crate::outputs::{Argument, Body, Function, Value, doc_lines};
    use quote::quote;

    #[test]
    fn one_function_returns_its_results_as_a_tuple_sharing_subexpressions() {
        let source = "S { parameters m; coordinates q; particle p { mass: m, at: O + q * N.x }; }";
        let system = crate::language::parse_system(source.parse().unwrap()).unwrap();
        let (model, mut pool) = crate::model::resolve(&system).unwrap();
        let (m, q) = (pool.sym(Sym::Param(0)), pool.sym(Sym::Coord(0)));
        let sine = pool.sin(q);
        let product = pool.mul(m, sine);
        let function = Function {
            name: quote::format_ident!("both"),
            docs: doc_lines("Both."),
            arguments: vec![Argument::Coordinates, Argument::Speeds],
            results: vec![Value::vector(vec![product]), Value::scalar(sine)],
            body: Body::Explicit,
        };
        let emitted = emit_function(&model, &pool, &names(&model, Target::Std), &function);
        let expected = quote! {
            #[doc = r#" Both."#]
            #[inline]
            #[must_use]
            pub fn both(&self, q: &[f64; 1], _qd: &[f64; 1]) -> ([f64; 1], f64) {
                let (m, [q]) = (self.m, *q);
                let sin_q = q.sin();
                ([m * sin_q], sin_q)
            }
        };
        assert_eq!(emitted.to_string(), expected.to_string());
    }

    /// `a / x²` is `a / (x * x)`, not `a / x * x` (which is `a`).
    #[test]
    fn a_square_below_a_division_is_parenthesised() {
        let source = "pub S {
            parameters m, k;
            coordinates x;
            particle p { mass: m, at: O + x * N.x };
            potential k * x / (2 + sin(x))^2;
        }";
        let code = crate::generate(source).expect("generates");
        let words: Vec<&str> = code.split_whitespace().collect();
        for w in words.windows(4) {
            assert!(
                !(w[0] == "/" && w[2] == "*" && w[1] == w[3].trim_end_matches([';', ')', ','])),
                "unparenthesised square below a division: {}",
                w.join(" ")
            );
        }
        assert!(code.contains("/ ("), "{code}");
    }

    #[test]
    fn raw_strings_keep_their_characters_and_survive_quotes() {
        assert_eq!(raw_string("q̈₁ = 0").to_string(), "r#\"q̈₁ = 0\"#");
        assert_eq!(
            raw_string("a \"# b").to_string(),
            "r##\"a \"# b\"##",
            "a quote followed by a hash needs two hashes"
        );
    }
}
