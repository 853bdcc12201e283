//! `accelerations_x4` (`outputs accelerations_x4;`): the solve of
//! `accelerations` written again over SIMD lanes, four states at once, one
//! in each lane of a `dalembert::__private::lanes::Lanes` (`wide::f64x4`),
//! by the plan's route for the lanes (`Plan::accelerations_x4`: the scalar
//! route, or the articulated-body recursion where that is the faster over
//! lanes, `plan::LANES_ARTICULATED_PERCENT`). The straight-line body is
//! that route's, with its names bound to lanes ([`Names::lanes`]); the
//! unrolled `L D Lᵀ` factorisation and substitutions, or the
//! articulated-body recursion, are the same statements on lanes. Nothing
//! branches on a lane: the pivots are tested at the end, state by state,
//! and a state that fails anything (not finite, a pivot, a non-finite
//! result) is answered by the scalar `accelerations`
//! (`dalembert::__private::lanes::per_state`), so that the errors are the
//! scalar call's.

use super::body::{Angles, Names, straight_line, straight_line_taking};
use super::solve::{mass, unchecked_elimination};
use crate::equations::Equations;
use crate::expr::{ExprId, Pool, Sym};
use crate::model::Model;
use crate::plan::Plan;
use crate::plan::solve::Accelerations;
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};
use std::collections::BTreeSet;

/// `pub fn accelerations_x4(..)` by the plan's route for the lanes;
/// nothing where the plan has no `accelerations` (the checks refuse the
/// output on a system with constraints).
pub fn emit_accelerations_x4(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    names: &Names,
    plan: &Plan,
    docs: &[String],
) -> TokenStream {
    let names = Names {
        lanes: true,
        ..names.clone()
    };
    let body = match (
        plan.accelerations_x4,
        &equations.articulated,
        &plan.factorisation,
    ) {
        (Some(Accelerations::Articulated), Some(articulated), _) => {
            let nv = model.nv();
            let roots = articulated.roots();
            // The forcing (the first `nv`) is tested by the scalar call of
            // a state whose result is not finite.
            let roots = &roots[nv..];
            let body = straight_line_taking(pool, &names, roots, Angles::WhereNeeded);
            let (pivots, solved) = body.outputs.split_at(nv);
            let (load, statements) = (lanes_of_arguments(&body.used), &body.statements);
            quote! {
                let (pivots, solved) = {
                    #load
                    #statements
                    ([#(#pivots),*], [#(#solved),*])
                };
                let hold = ::dalembert::__private::lanes::articulated_pivots_hold(pivots);
            }
        }
        (Some(_), _, Some(factorisation)) => {
            let elimination = unchecked_elimination(model, pool, equations, factorisation);
            let roots: Vec<ExprId> = elimination
                .entries
                .iter()
                .map(|&(i, j)| equations.mass_matrix[i][j])
                .chain(equations.forcing.iter().copied())
                .collect();
            let body = straight_line(pool, &names, &roots);
            let (load, statements) = (lanes_of_arguments(&body.used), &body.statements);
            let (bound, outputs) = (elimination.bound(), &body.outputs);
            let (factor, substitutions) = (&elimination.factor, &elimination.substitutions);
            let nv = model.nv();
            let pivots = (0..nv).map(|j| format_ident!("p{}", j));
            let diagonal = (0..nv).map(|i| mass(i, i));
            let solution = &elimination.solution;
            quote! {
                let [#(#bound),*] = {
                    #load
                    #statements
                    [#(#outputs),*]
                };
                #factor
                #substitutions
                let solved = [#(#solution),*];
                let hold = ::dalembert::__private::lanes::factorised_pivots_hold(
                    [#(#pivots),*],
                    [#(#diagonal),*],
                );
            }
        }
        _ => return TokenStream::new(),
    };
    let [n, nv, nu] = [model.nq(), model.nv(), model.inputs.len()].map(Literal::usize_unsuffixed);
    let docs = docs.iter().map(|line| super::raw_string(line));
    quote! {
        #(#[doc = #docs])*
        #[inline]
        pub fn accelerations_x4(
            &self,
            t: [f64; 4],
            q: &[[f64; #n]; 4],
            qd: &[[f64; #nv]; 4],
            u: &[[f64; #nu]; 4],
        ) -> [::core::result::Result<[f64; #nv], ::dalembert::DynamicsError>; 4] {
            #body
            ::dalembert::__private::lanes::per_state(solved, hold, (t, q, qd, u), |t, q, qd, u| {
                Self::accelerations(self, t, q, qd, u)
            })
        }
    }
}

/// Binds the arguments that the body reads (`t`, `q`, `qd`, `u`) to
/// their lanes, one state a lane, under their own names (the arrays as
/// references, which the body's load reads through).
fn lanes_of_arguments(used: &BTreeSet<Sym>) -> TokenStream {
    let reads = |kind: fn(&Sym) -> bool| used.iter().any(kind);
    let mut out = TokenStream::new();
    if reads(|s| matches!(s, Sym::Time)) {
        out.extend(quote!(let t = ::dalembert::__private::lanes::gather(t);));
    }
    let arrays = [
        (quote!(q), reads(|s| matches!(s, Sym::Coord(_)))),
        (quote!(qd), reads(|s| matches!(s, Sym::Speed(_)))),
        (quote!(u), reads(|s| matches!(s, Sym::Input(_)))),
    ];
    for (array, read) in arrays {
        if read {
            out.extend(quote!(let #array = &::dalembert::__private::lanes::columns(#array);));
        }
    }
    out
}

/// The trait's `accelerations_x4`, forwarding to the inherent one.
pub fn emit_trait_method(name: &proc_macro2::Ident, sizes: [usize; 3]) -> TokenStream {
    let [nq, nv, nu] = sizes.map(Literal::usize_unsuffixed);
    quote! {
        #[inline]
        fn accelerations_x4(
            &self,
            t: [f64; 4],
            q: &[[f64; #nq]; 4],
            v: &[[f64; #nv]; 4],
            u: &[[f64; #nu]; 4],
        ) -> [::core::result::Result<[f64; #nv], ::dalembert::DynamicsError>; 4] {
            #name::accelerations_x4(self, t, q, v, u)
        }
    }
}
