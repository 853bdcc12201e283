//! Emission: the derived equations as Rust items — one public struct of
//! parameters, its inherent functions (DESIGN §4) and the runtime traits.
//! Emitted code names everything by absolute path, so user items called
//! `Result` or `f64` cannot change its meaning. For `#![no_std]` crates
//! ([`Target::NoStd`]) the elementary functions go through `libm` and the
//! items that need the `dalembert` runtime (which needs `std`) are left out.

mod body;
mod configuration;
mod solve;

use crate::equations::Equations;
use crate::model::Model;
use body::{Names, Straight, straight_line};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};

/// The human-readable side of a system: its doc-comment lines (the user's,
/// then the derived equations) and the equations as plain text.
pub struct Documentation {
    /// Lines of the struct's doc comment.
    pub docs: Vec<String>,
    /// The derived equations, for `NAME::EQUATIONS`.
    pub text: String,
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
    equations: &Equations,
    documentation: &Documentation,
    target: Target,
) -> TokenStream {
    let names = names(model, target);
    let name = &model.name;
    let (nq, nv) = (model.nq(), model.nv());
    let nu = model.inputs.len();
    let nc = model.constraints.len();
    let mut items = vec![
        emit_mass_matrix(model, equations, &names),
        emit_forcing(model, equations, &names),
        emit_energies(model, equations, &names),
        emit_constraints(model, equations, &names),
        configuration::emit_configuration(model, &names),
    ];
    let strukt = emit_struct(model, &documentation.docs);
    let constants = emit_constants(model, &documentation.text);
    let traits = match target {
        Target::Std => {
            let solver = solve::emit_accelerations(model, equations);
            let has_solver = !solver.is_empty();
            items.push(solver);
            emit_trait_impls(name, [nq, nv, nu, nc], has_solver)
        }
        Target::NoStd => TokenStream::new(),
    };
    quote! {
        #strukt
        #[allow(non_snake_case, clippy::all)]
        impl #name {
            #constants
            #(#items)*
        }
        #traits
    }
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
    let speeds = model
        .speeds
        .iter()
        .enumerate()
        .map(|(i, speed)| {
            let q = &speed.name;
            let preferred = format!("{q}_dot");
            if !speed.rate_of_coordinate {
                q.clone()
            } else if taken.contains(&preferred) {
                format_ident!("qd_{}", i)
            } else {
                Ident::new(&preferred, q.span())
            }
        })
        .collect();
    let mut temporary = "x".to_string();
    while taken.iter().any(|n| {
        n.strip_prefix(&temporary)
            .is_some_and(|rest| rest.chars().all(|c| c.is_ascii_digit()))
    }) {
        temporary.push('x');
    }
    Names {
        parameters: model.parameters.clone(),
        coordinates: model.coordinates.clone(),
        speeds,
        inputs: model.inputs.clone(),
        temporary,
        libm: target == Target::NoStd,
    }
}

fn emit_struct(model: &Model, docs: &[String]) -> TokenStream {
    let name = &model.name;
    let vis = if model.public { quote!(pub) } else { quote!() };
    let fields = model.parameters.iter().map(|p| {
        let doc = format!(" Parameter `{p}`.");
        quote!(#[doc = #doc] pub #p: f64)
    });
    let docs = docs.iter().map(|line| quote!(#[doc = #line]));
    quote! {
        #(#docs)*
        #[derive(::core::clone::Clone, ::core::marker::Copy, ::core::fmt::Debug, ::core::cmp::PartialEq)]
        #[allow(non_snake_case)]
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

fn emit_constants(model: &Model, equations_text: &str) -> TokenStream {
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
    let nv_doc = if model.pool.rates_are_speeds() {
        " Number of speeds (the coordinates' rates)."
    } else {
        " Number of speeds (`v`, with `q̇ = N(q) v`)."
    };
    let equations = raw_string(equations_text);
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
    }
}

/// `[f64; n]` as tokens.
fn array(n: usize) -> TokenStream {
    let n = Literal::usize_unsuffixed(n);
    quote!([f64; #n])
}

/// An argument name, with a leading underscore when the body ignores it.
fn argument(name: &str, used: bool) -> Ident {
    if used {
        Ident::new(name, Span::call_site())
    } else {
        format_ident!("_{}", name)
    }
}

/// Which of `t, q, qd, u` a body reads.
struct Reads {
    t: Ident,
    q: Ident,
    qd: Ident,
    u: Ident,
}

fn reads(body: &Straight) -> Reads {
    use crate::expr::Sym;
    let any = |f: fn(&Sym) -> bool| body.used.iter().any(f);
    Reads {
        t: argument("t", any(|s| matches!(s, Sym::Time))),
        q: argument("q", any(|s| matches!(s, Sym::Coord(_)))),
        qd: argument("qd", any(|s| matches!(s, Sym::Speed(_)))),
        u: argument("u", any(|s| matches!(s, Sym::Input(_)))),
    }
}

/// Groups flat outputs into rows of `width`.
fn rows(outputs: &[TokenStream], width: usize) -> Vec<TokenStream> {
    outputs
        .chunks(width.max(1))
        .map(|row| quote!([#(#row),*]))
        .collect()
}

fn emit_mass_matrix(model: &Model, equations: &Equations, names: &Names) -> TokenStream {
    let nv = model.nv();
    let roots: Vec<_> = equations.mass_matrix.iter().flatten().copied().collect();
    let body = straight_line(&model.pool, names, &roots);
    let Reads { q, .. } = reads(&body);
    let (coordinates, statements, rows) =
        (array(model.nq()), &body.statements, rows(&body.outputs, nv));
    let (vector, nv) = (array(nv), Literal::usize_unsuffixed(nv));
    quote! {
        /// The mass matrix `M(q)` (symmetric, positive definite where the
        /// coordinates are independent).
        #[inline]
        #[must_use]
        pub fn mass_matrix(&self, #q: &#coordinates) -> [#vector; #nv] {
            #statements
            [#(#rows),*]
        }
    }
}

fn emit_forcing(model: &Model, equations: &Equations, names: &Names) -> TokenStream {
    let body = straight_line(&model.pool, names, &equations.forcing);
    let Reads { t, q, qd, u } = reads(&body);
    let (coordinates, inputs) = (array(model.nq()), array(model.inputs.len()));
    let vector = array(model.nv());
    let (statements, outputs) = (&body.statements, &body.outputs);
    quote! {
        /// The forcing `f(t, q, q̇, u)` of `M(q) q̈ = f`: applied and
        /// gravity forces, minus the velocity-dependent inertia terms.
        #[inline]
        #[must_use]
        pub fn forcing(&self, #t: f64, #q: &#coordinates, #qd: &#vector, #u: &#inputs) -> #vector {
            #statements
            [#(#outputs),*]
        }
    }
}

fn emit_energies(model: &Model, equations: &Equations, names: &Names) -> TokenStream {
    let (vector, speeds) = (array(model.nq()), array(model.nv()));
    let kinetic = straight_line(&model.pool, names, &[equations.kinetic_energy]);
    let potential = straight_line(&model.pool, names, &[equations.potential_energy]);
    let Reads { q: kq, qd: kqd, .. } = reads(&kinetic);
    let Reads { q: vq, .. } = reads(&potential);
    let (ks, kv) = (&kinetic.statements, &kinetic.outputs[0]);
    let (vs, vv) = (&potential.statements, &potential.outputs[0]);
    quote! {
        /// The kinetic energy `T(q, q̇)`.
        #[inline]
        #[must_use]
        pub fn kinetic_energy(&self, #kq: &#vector, #kqd: &#speeds) -> f64 {
            #ks
            #kv
        }

        /// The potential energy `V(q)`: gravity (from `O`) and the
        /// `potential` statements.
        #[inline]
        #[must_use]
        pub fn potential_energy(&self, #vq: &#vector) -> f64 {
            #vs
            #vv
        }
    }
}

fn emit_constraints(model: &Model, equations: &Equations, names: &Names) -> TokenStream {
    let nc = model.constraints.len();
    if nc == 0 {
        return TokenStream::new();
    }
    let nv = model.nv();
    let (vector, speeds) = (array(model.nq()), array(nv));
    let rows_out = array(nc);
    let roots: Vec<_> = equations
        .constraint_jacobian
        .iter()
        .flatten()
        .copied()
        .collect();
    let jacobian = straight_line(&model.pool, names, &roots);
    let Reads { q: jq, .. } = reads(&jacobian);
    let (js, jr) = (&jacobian.statements, rows(&jacobian.outputs, nv));
    let nc = Literal::usize_unsuffixed(nc);
    let bias = straight_line(&model.pool, names, &equations.constraint_bias);
    let Reads {
        t: bt,
        q: bq,
        qd: bqd,
        ..
    } = reads(&bias);
    let (bs, bo) = (&bias.statements, &bias.outputs);
    let residual = straight_line(&model.pool, names, &equations.constraint_residual);
    let Reads { t: rt, q: rq, .. } = reads(&residual);
    let (rs, ro) = (&residual.statements, &residual.outputs);
    let velocity = straight_line(&model.pool, names, &equations.constraint_velocity);
    let Reads {
        t: vt,
        q: vq,
        qd: vqd,
        ..
    } = reads(&velocity);
    let (vs, vo) = (&velocity.statements, &velocity.outputs);
    quote! {
        /// The constraint Jacobian `A(q)` of `M q̈ = f + Aᵀλ`, `A q̈ = b`;
        /// rows in declaration order.
        #[inline]
        #[must_use]
        pub fn constraint_jacobian(&self, #jq: &#vector) -> [#speeds; #nc] {
            #js
            [#(#jr),*]
        }

        /// The constraint bias `b(t, q, q̇)` of `A q̈ = b`.
        #[inline]
        #[must_use]
        pub fn constraint_bias(&self, #bt: f64, #bq: &#vector, #bqd: &#speeds) -> #rows_out {
            #bs
            [#(#bo),*]
        }

        /// The residual `lhs − rhs` of each holonomic constraint (0 for
        /// nonholonomic rows).
        #[inline]
        #[must_use]
        pub fn constraint_residual(&self, #rt: f64, #rq: &#vector) -> #rows_out {
            #rs
            [#(#ro),*]
        }

        /// The velocity form of each constraint, `A q̇ + ψ₀(t, q)`: the time
        /// derivative of a holonomic row's residual, a nonholonomic row
        /// itself. Zero on the constraint manifold.
        #[inline]
        #[must_use]
        pub fn constraint_velocity(&self, #vt: f64, #vq: &#vector, #vqd: &#speeds) -> #rows_out {
            #vs
            [#(#vo),*]
        }
    }
}

/// The runtime's traits, forwarding to the inherent functions (and to the
/// emitted `accelerations` when the system has one).
fn emit_trait_impls(name: &Ident, sizes: [usize; 4], has_solver: bool) -> TokenStream {
    let [nq, nv, nu, nc] = sizes;
    let (coordinates, vector) = (array(nq), array(nv));
    let (inputs, rows_out) = (array(nu), array(nc));
    let [nq, nv, nu, nc_lit] = [nq, nv, nu, nc].map(Literal::usize_unsuffixed);
    let accelerations = if has_solver {
        quote! {
            #[inline]
            fn accelerations(
                &self,
                t: f64,
                q: &#coordinates,
                v: &#vector,
                u: &#inputs,
            ) -> ::core::result::Result<#vector, ::dalembert::DynamicsError> {
                #name::accelerations(self, t, q, v, u)
            }
        }
    } else {
        TokenStream::new()
    };
    let system = quote! {
        impl ::dalembert::MultibodySystem<#nq, #nv, #nu> for #name {
            const COORDINATES: [&'static str; #nq] = #name::COORDINATES;
            const SPEEDS: [&'static str; #nv] = #name::SPEEDS;
            const INPUTS: [&'static str; #nu] = #name::INPUTS;
            #[inline]
            fn mass_matrix(&self, q: &#coordinates) -> [#vector; #nv] {
                #name::mass_matrix(self, q)
            }
            #[inline]
            fn forcing(&self, t: f64, q: &#coordinates, v: &#vector, u: &#inputs) -> #vector {
                #name::forcing(self, t, q, v, u)
            }
            #[inline]
            fn kinetic_energy(&self, q: &#coordinates, v: &#vector) -> f64 {
                #name::kinetic_energy(self, q, v)
            }
            #[inline]
            fn potential_energy(&self, q: &#coordinates) -> f64 {
                #name::potential_energy(self, q)
            }
            #[inline]
            fn coordinate_rates(&self, q: &#coordinates, v: &#vector) -> #coordinates {
                #name::coordinate_rates(self, q, v)
            }
            #[inline]
            fn integrate_configuration(&self, q: &#coordinates, v: &#vector, h: f64) -> #coordinates {
                #name::integrate_configuration(self, q, v, h)
            }
            #accelerations
        }
    };
    if nc == 0 {
        return system;
    }
    quote! {
        #system
        impl ::dalembert::ConstrainedSystem<#nq, #nv, #nu, #nc_lit> for #name {
            #[inline]
            fn constraint_jacobian(&self, q: &#coordinates) -> [#vector; #nc_lit] {
                #name::constraint_jacobian(self, q)
            }
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

#[cfg(test)]
mod tests {
    use super::raw_string;

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
