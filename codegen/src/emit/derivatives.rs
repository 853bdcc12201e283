//! The exact derivatives as Rust: `inverse_dynamics_jacobian` (the partials
//! of `τ = M v̇ − f`), `accelerations_jacobian` (`∂v̇/∂q`, `∂v̇/∂v`,
//! `∂v̇/∂u` from `M ∂v̇/∂x = −∂τ/∂x`, every column through the one
//! `L D Lᵀ` factorisation that solved for `v̇`) and `linearize` (the
//! state-space matrices `A`, `B` of `ẋ = (q̇, v̇)` about a state).

use super::body::{Names, Straight, straight_line};
use super::solve::{Factorised, factorised};
use super::{argument, array};
use crate::equations::Equations;
use crate::equations::derivatives::ResidualJacobian;
use crate::expr::{ExprId, Sym};
use crate::model::Model;
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

/// `[[f64; columns]; rows]` as tokens.
fn matrix(rows: usize, columns: usize) -> TokenStream {
    let (row, rows) = (array(columns), Literal::usize_unsuffixed(rows));
    quote!([#row; #rows])
}

/// The entries of `block` column by column (the right-hand sides of the
/// solves).
fn by_columns(block: &[Vec<ExprId>], columns: usize) -> Vec<ExprId> {
    (0..columns)
        .flat_map(|j| block.iter().map(move |row| row[j]))
        .collect()
}

/// `pub fn inverse_dynamics_jacobian(..)`: `∂τ/∂q`, `∂τ/∂v` and
/// `∂τ/∂v̇ = M` at a state and acceleration.
pub fn emit_inverse_dynamics_jacobian(
    model: &Model,
    equations: &Equations,
    jacobian: &ResidualJacobian,
    names: &Names,
) -> TokenStream {
    let nq = model.nq();
    let roots: Vec<ExprId> = jacobian
        .coordinates
        .iter()
        .chain(&jacobian.speeds)
        .chain(&equations.mass_matrix)
        .flatten()
        .copied()
        .collect();
    let body = straight_line(&model.pool, names, &roots);
    let used = |f: fn(&Sym) -> bool| body.used.iter().any(f);
    let t = argument("t", used(|s| matches!(s, Sym::Time)));
    let q = argument("q", used(|s| matches!(s, Sym::Coord(_))));
    let qd = argument("qd", used(|s| matches!(s, Sym::Speed(_))));
    let vdot = argument("vdot", used(|s| matches!(s, Sym::Accel(_))));
    let u = argument("u", used(|s| matches!(s, Sym::Input(_))));
    let (vector, inputs, square) = (array(nq), array(model.inputs.len()), matrix(nq, nq));
    let rows: Vec<TokenStream> = body
        .outputs
        .chunks(nq)
        .map(|row| quote!([#(#row),*]))
        .collect();
    let [by_q, by_v, mass] = [0, 1, 2].map(|k| {
        let block = &rows[k * nq..(k + 1) * nq];
        quote!([#(#block),*])
    });
    let statements = &body.statements;
    quote! {
        /// The derivatives of the inverse dynamics `τ(t, q, v, v̇, u) = M v̇ − f`
        /// at a state and acceleration: `(∂τ/∂q, ∂τ/∂v, ∂τ/∂v̇ = M)`, entry
        /// `[i][j]` the derivative of `τᵢ` by the `j`-th variable. Exact:
        /// the equations differentiated symbolically, their shared
        /// subexpressions computed once.
        #[inline]
        #[must_use]
        pub fn inverse_dynamics_jacobian(
            &self,
            #t: f64,
            #q: &#vector,
            #qd: &#vector,
            #vdot: &#vector,
            #u: &#inputs,
        ) -> (#square, #square, #square) {
            #statements
            (#by_q, #by_v, #mass)
        }
    }
}

/// `pub fn accelerations_jacobian(..)` and `pub fn linearize(..)`, for a
/// system without constraints; nothing for one with.
pub fn emit_accelerations_jacobian(
    model: &Model,
    equations: &Equations,
    jacobian: &ResidualJacobian,
    names: &Names,
) -> TokenStream {
    let Some(Factorised {
        prelude,
        substitutions,
        right_hand_side,
        solution,
    }) = factorised(model, equations)
    else {
        return TokenStream::new();
    };
    let (nq, nu) = (model.nq(), model.inputs.len());
    // ∂τ/∂q, ∂τ/∂v and ∂τ/∂u by columns: solved, then negated as they are
    // transposed into rows.
    let roots: Vec<ExprId> = [
        by_columns(&jacobian.coordinates, nq),
        by_columns(&jacobian.speeds, nq),
        by_columns(&jacobian.inputs, nu),
    ]
    .concat();
    let Straight {
        statements,
        outputs,
        ..
    } = straight_line(&model.pool, names, &roots);
    let columns: Vec<TokenStream> = outputs
        .chunks(nq)
        .map(|column| quote!([#(#column),*]))
        .collect();
    let (q_columns, rest) = columns.split_at(nq);
    let (v_columns, u_columns) = rest.split_at(nq);
    let literal = Literal::usize_unsuffixed;
    let solved = |name: &str, columns: usize| -> TokenStream {
        let name = Ident::new(name, Span::call_site());
        let solves = (0..columns).map(|j| {
            let j = literal(j);
            quote!(solve(#name[#j]))
        });
        quote!([#(#solves),*])
    };
    // `∂v̇/∂x = −M⁻¹ ∂τ/∂x`, row by row.
    let transposed = |name: &str, columns: usize| -> TokenStream {
        let name = Ident::new(name, Span::call_site());
        let rows = (0..nq).map(|i| {
            let i = literal(i);
            let row = (0..columns).map(|j| {
                let j = literal(j);
                quote!(-#name[#j][#i])
            });
            quote!([#(#row),*])
        });
        quote!([#(#rows),*])
    };
    // Without inputs, the input columns are empty arrays nothing reads.
    let (rhs_u, by_u) = match nu {
        0 => ("_rhs_u", "_by_u"),
        _ => ("rhs_u", "by_u"),
    };
    let (solved_q, solved_v, solved_u) =
        (solved("rhs_q", nq), solved("rhs_v", nq), solved(rhs_u, nu));
    let (dq, dv, du) = (
        transposed("by_q", nq),
        transposed("by_v", nq),
        transposed(by_u, nu),
    );
    let (vector, inputs) = (array(nq), array(nu));
    let (square, wide) = (matrix(nq, nq), matrix(nq, nu));
    let (n, nu_lit) = (literal(nq), literal(nu));
    let (rhs_u_name, by_u_name) = (
        Ident::new(rhs_u, Span::call_site()),
        Ident::new(by_u, Span::call_site()),
    );
    let linearize = emit_linearize(nq, nu);
    quote! {
        /// The derivatives of the accelerations `v̇(t, q, v, u)` at a state:
        /// `(∂v̇/∂q, ∂v̇/∂v, ∂v̇/∂u)`, entry `[i][j]` the derivative of `v̇ᵢ` by
        /// the `j`-th variable. Exact: differentiating `M v̇ = f` gives
        /// `M ∂v̇/∂x = −∂(M v̇ − f)/∂x` at the solved `v̇`, whose right-hand
        /// sides are the symbolic partials of the equations and whose
        /// columns all go through the `L D Lᵀ` factorisation of `M` that
        /// solved for `v̇`. The errors of `accelerations`, and
        /// `NonFiniteEquations` for a non-finite partial derivative.
        #[inline]
        pub fn accelerations_jacobian(
            &self,
            t: f64,
            q: &#vector,
            qd: &#vector,
            u: &#inputs,
        ) -> ::core::result::Result<(#square, #square, #wide), ::dalembert::DynamicsError> {
            #prelude
            let solve = |[#(#right_hand_side),*]: #vector| -> #vector {
                #substitutions
                [#(#solution),*]
            };
            let vdot = solve([#(#right_hand_side),*]);
            if !finite(&vdot) {
                return ::core::result::Result::Err(::dalembert::DynamicsError::NonFiniteAccelerations);
            }
            let (rhs_q, rhs_v, #rhs_u_name): ([#vector; #n], [#vector; #n], [#vector; #nu_lit]) = {
                #statements
                ([#(#q_columns),*], [#(#v_columns),*], [#(#u_columns),*])
            };
            let (by_q, by_v, #by_u_name): ([#vector; #n], [#vector; #n], [#vector; #nu_lit]) =
                (#solved_q, #solved_v, #solved_u);
            let jacobian: (#square, #square, #wide) = (#dq, #dv, #du);
            if jacobian.0.iter().chain(&jacobian.1).all(|row| finite(row))
                && jacobian.2.iter().all(|row| finite(row))
            {
                ::core::result::Result::Ok(jacobian)
            } else {
                ::core::result::Result::Err(::dalembert::DynamicsError::NonFiniteEquations)
            }
        }

        #linearize
    }
}

/// `pub fn linearize(..)` from `accelerations_jacobian`, for `q̇ = v`.
fn emit_linearize(nq: usize, nu: usize) -> TokenStream {
    let (vector, inputs) = (array(nq), array(nu));
    let (a, b) = (matrix(2 * nq, 2 * nq), matrix(2 * nq, nu));
    let literal = Literal::usize_unsuffixed;
    let kinematic_rows = (0..nq).map(|i| {
        let row = (0..2 * nq).map(|j| {
            if j == nq + i {
                quote!(1.0)
            } else {
                quote!(0.0)
            }
        });
        quote!([#(#row),*])
    });
    let dynamic_rows = (0..nq).map(|i| {
        let i = literal(i);
        let by_q = (0..nq).map(|j| {
            let j = literal(j);
            quote!(dq[#i][#j])
        });
        let by_v = (0..nq).map(|j| {
            let j = literal(j);
            quote!(dv[#i][#j])
        });
        quote!([#(#by_q,)* #(#by_v),*])
    });
    let input_rows = (0..nq).map(|i| {
        let i = literal(i);
        quote!(du[#i])
    });
    let nu = literal(nu);
    let zero_row = quote!([0.0; #nu]);
    let zero_rows = (0..nq).map(|_| zero_row.clone());
    quote! {
        /// The linearisation `δẋ = A δx + B δu` of the equations of motion
        /// about a state `x = (q, v)` and input `u`: with `q̇ = v`,
        /// `A = [[0, I], [∂v̇/∂q, ∂v̇/∂v]]` and `B = [[0], [∂v̇/∂u]]`, from
        /// `accelerations_jacobian` (and its errors). About an equilibrium
        /// (`v = 0`, `v̇ = 0`) the eigenvalues of `A` are the small-motion
        /// exponents.
        #[inline]
        pub fn linearize(
            &self,
            t: f64,
            q: &#vector,
            qd: &#vector,
            u: &#inputs,
        ) -> ::core::result::Result<(#a, #b), ::dalembert::DynamicsError> {
            let (dq, dv, du) = self.accelerations_jacobian(t, q, qd, u)?;
            ::core::result::Result::Ok((
                [#(#kinematic_rows,)* #(#dynamic_rows),*],
                [#(#zero_rows,)* #(#input_rows),*],
            ))
        }
    }
}
