//! The outputs that solve through the mass matrix: `accelerations_jacobian`
//! (`∂v̇/∂x = −M⁻¹ ∂τ/∂x` for the partials of the inverse dynamics at the
//! solved `v̇`, every column but those of structural zeros through the one
//! `L D Lᵀ` factorisation that solved for `v̇`) and `linearize` (the state-space matrices `A`, `B` of
//! `ẋ = (q̇, v̇)` about a state).

use super::body::{Names, Straight, straight_line};
use super::solve::{Factorised, factorised};
use super::{array, raw_string};
use crate::equations::Equations;
use crate::expr::{ExprId, Pool, Sym};
use crate::model::Model;
use crate::outputs::Function;
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

/// `[[f64; columns]; rows]` as tokens.
fn matrix(rows: usize, columns: usize) -> TokenStream {
    let (row, rows) = (array(columns), Literal::usize_unsuffixed(rows));
    quote!([#row; #rows])
}

/// The entries of a row-major `rows × columns` block, column by column
/// (the right-hand sides of the solves).
fn by_columns(block: &[ExprId], columns: usize) -> Vec<ExprId> {
    (0..columns)
        .flat_map(|j| block.iter().skip(j).step_by(columns).copied())
        .collect()
}

/// `pub fn accelerations_jacobian(..)` from `function`, whose results are
/// `∂τ/∂q`, `∂τ/∂v`, `∂τ/∂u`; nothing for a system with constraints
/// (which the model rejects).
pub fn emit_accelerations_jacobian(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    names: &Names,
    function: &Function,
) -> TokenStream {
    let Some(Factorised {
        prelude,
        substitutions,
        right_hand_side,
        solution,
        ..
    }) = factorised(model, pool, equations, names)
    else {
        return TokenStream::new();
    };
    let (nv, nu) = (model.nv(), model.inputs.len());
    // ∂τ/∂q, ∂τ/∂v and ∂τ/∂u by columns: solved, then negated as they are
    // transposed into rows.
    let roots: Vec<ExprId> = function
        .results
        .iter()
        .zip([nv, nv, nu])
        .flat_map(|(value, columns)| by_columns(&value.expressions, columns))
        .collect();
    let Straight {
        statements,
        outputs,
        ..
    } = straight_line(pool, names, &roots);
    let columns: Vec<TokenStream> = outputs
        .chunks(nv)
        .map(|column| quote!([#(#column),*]))
        .collect();
    let n = Literal::usize_unsuffixed(nv);
    let (q_columns, rest) = columns.split_at(nv);
    let (v_columns, u_columns) = rest.split_at(nv);
    let (coordinates, vector, inputs) = (array(model.nq()), array(nv), array(nu));
    // Every array is destructured, never indexed: no panic path.
    let names_of = |prefix: &str, count: usize| -> Vec<Ident> {
        (0..count)
            .map(|j| format_ident!("{}{}", prefix, j))
            .collect()
    };
    let (cq, cv, cu) = (names_of("cq", nv), names_of("cv", nv), names_of("cu", nu));
    // A column of structural zeros (`∂τ/∂q₁` of a first joint turning about
    // gravity) is bound to `_` and solved to zeros without the solve.
    let zero_columns: Vec<bool> = roots
        .chunks(nv)
        .map(|column| column.iter().all(|&e| e == pool.zero()))
        .collect();
    let (q_zeros, rest) = zero_columns.split_at(nv);
    let (v_zeros, u_zeros) = rest.split_at(nv);
    let binding = |names: &[Ident], zeros: &[bool]| -> Vec<TokenStream> {
        names
            .iter()
            .zip(zeros)
            .map(|(name, &zero)| match zero {
                true => quote!(_),
                false => quote!(#name),
            })
            .collect()
    };
    let (bq, bv, bu) = (
        binding(&cq, q_zeros),
        binding(&cv, v_zeros),
        binding(&cu, u_zeros),
    );
    // Column `j` of `M⁻¹ ∂τ/∂x`, entry `i`: `{prefix}{j}_{i}`.
    let entry = |prefix: &str, j: usize, i: usize| format_ident!("{}{}_{}", prefix, j, i);
    let solved = |prefix: &str, columns: &[Ident], zeros: &[bool]| -> TokenStream {
        let patterns = (0..columns.len()).map(|j| {
            let entries = (0..nv).map(|i| entry(prefix, j, i));
            quote!([#(#entries),*])
        });
        let values = columns.iter().zip(zeros).map(|(column, &zero)| match zero {
            true => quote!([0.0; #n]),
            false => quote!(solve(#column)),
        });
        let count = Literal::usize_unsuffixed(columns.len());
        quote!(let [#(#patterns),*]: [#vector; #count] = [#(#values),*];)
    };
    // `∂v̇/∂x = −M⁻¹ ∂τ/∂x`, row by row.
    let transposed = |prefix: &str, columns: usize| -> TokenStream {
        let rows = (0..nv).map(|i| {
            let row = (0..columns).map(|j| {
                let name = entry(prefix, j, i);
                quote!(-#name)
            });
            quote!([#(#row),*])
        });
        quote!([#(#rows),*])
    };
    let solves = [
        solved("dq", &cq, q_zeros),
        solved("dv", &cv, v_zeros),
        solved("du", &cu, u_zeros),
    ];
    let (dq, dv, du) = (
        transposed("dq", nv),
        transposed("dv", nv),
        transposed("du", nu),
    );
    let (square, wide) = (matrix(nv, nv), matrix(nv, nu));
    let nu_lit = Literal::usize_unsuffixed(nu);
    let (name, docs) = (
        &function.name,
        function.docs.iter().map(|line| raw_string(line)),
    );
    quote! {
        #(#[doc = #docs])*
        #[inline]
        pub fn #name(
            &self,
            t: f64,
            q: &#coordinates,
            qd: &#vector,
            u: &#inputs,
        ) -> ::core::result::Result<(#square, #square, #wide), ::dalembert::DynamicsError> {
            #prelude
            let solve = |[#(#right_hand_side),*]: #vector| -> #vector {
                #substitutions
                [#(#solution),*]
            };
            let qdd = &solve([#(#right_hand_side),*]);
            if !finite(qdd) {
                return ::core::result::Result::Err(::dalembert::DynamicsError::NonFiniteAccelerations);
            }
            let ([#(#bq),*], [#(#bv),*], [#(#bu),*]): ([#vector; #n], [#vector; #n], [#vector; #nu_lit]) = {
                #statements
                ([#(#q_columns),*], [#(#v_columns),*], [#(#u_columns),*])
            };
            #(#solves)*
            let jacobian: (#square, #square, #wide) = (#dq, #dv, #du);
            if jacobian.0.iter().chain(&jacobian.1).all(|row| finite(row))
                && jacobian.2.iter().all(|row| finite(row))
            {
                ::core::result::Result::Ok(jacobian)
            } else {
                ::core::result::Result::Err(::dalembert::DynamicsError::NonFiniteEquations)
            }
        }
    }
}

/// `n` rows of `columns` names `{prefix}{i}_{j}`: a destructured matrix.
fn entry_names(prefix: &str, n: usize, columns: usize) -> Vec<Vec<Ident>> {
    (0..n)
        .map(|i| {
            (0..columns)
                .map(|j| format_ident!("{}{}_{}", prefix, i, j))
                .collect()
        })
        .collect()
}

/// The pattern `[[a, b], [c, d]]` of a matrix of names.
fn pattern(rows: &[Vec<Ident>]) -> TokenStream {
    let rows = rows.iter().map(|row| quote!([#(#row),*]));
    quote!([#(#rows),*])
}

/// Rows of `2 NV` entries: each row of `left` followed by that of `right`.
fn joined_rows(left: &[Vec<Ident>], right: &[Vec<Ident>]) -> Vec<TokenStream> {
    left.iter()
        .zip(right)
        .map(|(l, r)| quote!([#(#l,)* #(#r),*]))
        .collect()
}

/// `pub fn linearize(..)` with the docs of `function` and `body`, which
/// ends with `Ok((A, B))`.
fn linearize_function(model: &Model, function: &Function, body: TokenStream) -> TokenStream {
    let (nv, nu) = (model.nv(), model.inputs.len());
    let (coordinates, vector, inputs) = (array(model.nq()), array(nv), array(nu));
    let (a, b) = (matrix(2 * nv, 2 * nv), matrix(2 * nv, nu));
    let docs = function.docs.iter().map(|line| raw_string(line));
    quote! {
        #(#[doc = #docs])*
        #[inline]
        pub fn linearize(
            &self,
            t: f64,
            q: &#coordinates,
            qd: &#vector,
            u: &#inputs,
        ) -> ::core::result::Result<(#a, #b), ::dalembert::DynamicsError> {
            #body
        }
    }
}

/// The upper rows of `B`: zeros.
fn zero_rows(model: &Model) -> Vec<TokenStream> {
    let nu = Literal::usize_unsuffixed(model.inputs.len());
    (0..model.nv()).map(|_| quote!([0.0; #nu])).collect()
}

/// The expressions of `function`'s results, in order.
fn roots(function: &Function) -> Vec<ExprId> {
    function
        .results
        .iter()
        .flat_map(|value| value.expressions.iter().copied())
        .collect()
}

/// `pub fn linearize(..)`: the kinematic rows `K_δ`, `K_v` (the results
/// of `function`) by a straight-line body, the dynamic rows from
/// `accelerations_jacobian`, with the docs of `function`.
pub fn emit_linearize(
    model: &Model,
    pool: &Pool,
    names: &Names,
    function: &Function,
) -> TokenStream {
    let nv = model.nv();
    let Straight {
        statements,
        outputs,
        ..
    } = straight_line(pool, names, &roots(function));
    let (kinematic_by_q, kinematic_by_v) = outputs.split_at(nv * nv);
    let kinematic_rows = kinematic_by_q
        .chunks(nv)
        .zip(kinematic_by_v.chunks(nv))
        .map(|(q_row, v_row)| quote!([#(#q_row,)* #(#v_row),*]));
    // `∂v̇/∂q`, `∂v̇/∂v` and `∂v̇/∂u` destructured: entries `dq{i}_{j}`,
    // `dv{i}_{j}`, rows `du{i}`.
    let (by_q, by_v) = (entry_names("dq", nv, nv), entry_names("dv", nv, nv));
    let input_rows: Vec<Ident> = (0..nv).map(|i| format_ident!("du{}", i)).collect();
    let (q_pattern, v_pattern) = (pattern(&by_q), pattern(&by_v));
    let dynamic_rows = joined_rows(&by_q, &by_v);
    let zero_rows = zero_rows(model);
    let kinematic_names: Vec<Ident> = (0..nv).map(|i| format_ident!("k{}", i)).collect();
    let kinematic = match statements.is_empty() {
        true => quote!([#(#kinematic_rows),*]),
        false => quote!({ #statements [#(#kinematic_rows),*] }),
    };
    let (state_row, n) = (array(2 * nv), Literal::usize_unsuffixed(nv));
    let body = quote! {
        let (#q_pattern, #v_pattern, [#(#input_rows),*]) =
            self.accelerations_jacobian(t, q, qd, u)?;
        let [#(#kinematic_names),*]: [#state_row; #n] = #kinematic;
        ::core::result::Result::Ok((
            [#(#kinematic_names,)* #(#dynamic_rows),*],
            [#(#zero_rows,)* #(#input_rows),*],
        ))
    };
    linearize_function(model, function, body)
}

/// `pub fn linearize(..)` of a system with constraints, from `function`,
/// whose results are the partials of `linearize_on_constraints`
/// (`∂r/∂q`, `∂r/∂v`, `∂r/∂u`, `∂c/∂q`, `∂c/∂v`, `∂ψ/∂q`), evaluated at
/// the accelerations and multipliers of `constrained_accelerations`, with
/// the independent coordinates of the model's `linearize(..)`.
pub fn emit_constrained_linearize(
    model: &Model,
    pool: &Pool,
    names: &Names,
    function: &Function,
) -> TokenStream {
    let (nv, nu, nc) = (model.nv(), model.inputs.len(), model.constraints.len());
    let independent: Vec<bool> = (0..nv)
        .map(|j| {
            model
                .outputs
                .iter()
                .flat_map(|o| &o.independent)
                .any(|(i, _)| *i == j)
        })
        .collect();
    let Straight {
        statements,
        outputs,
        used,
    } = straight_line(pool, names, &roots(function));
    let mut outputs = outputs.into_iter();
    let mut block = |rows: usize, columns: usize| -> TokenStream {
        let entries: Vec<TokenStream> = outputs.by_ref().take(rows * columns).collect();
        match columns {
            0 => {
                let rows = (0..rows).map(|_| quote!([]));
                quote!([#(#rows),*])
            }
            _ => {
                let rows = entries.chunks(columns).map(|row| quote!([#(#row),*]));
                quote!([#(#rows),*])
            }
        }
    };
    let (r_q, r_v, r_u) = (block(nv, nv), block(nv, nv), block(nv, nu));
    let (c_q, c_v, psi_q) = (block(nc, nv), block(nc, nv), block(nc, nv));
    let multipliers = (0..nc).map(|j| {
        let name = format_ident!("lambda{}", j);
        match used.contains(&Sym::Multiplier(j as u32)) {
            true => quote!(#name),
            false => quote!(_),
        }
    });
    let [kq, kv, dq, dv] = ["kq", "kv", "dq", "dv"].map(|prefix| entry_names(prefix, nv, nv));
    let du: Vec<Ident> = (0..nv).map(|i| format_ident!("du{}", i)).collect();
    let (kq_pattern, kv_pattern, dq_pattern, dv_pattern) =
        (pattern(&kq), pattern(&kv), pattern(&dq), pattern(&dv));
    let (kinematic_rows, dynamic_rows) = (joined_rows(&kq, &kv), joined_rows(&dq, &dv));
    let zero_rows = zero_rows(model);
    let body = quote! {
        let (accelerations, [#(#multipliers),*]) =
            ::dalembert::constrained::constrained_accelerations(self, t, q, qd, u)?;
        let partials = {
            let qdd = &accelerations;
            #statements
            ::dalembert::constrained::ConstrainedPartials {
                residual_by_q: #r_q,
                residual_by_v: #r_v,
                residual_by_u: #r_u,
                constraint_by_q: #c_q,
                constraint_by_v: #c_v,
                velocity_by_q: #psi_q,
            }
        };
        let ::dalembert::constrained::ConstrainedLinearization {
            kinematic_by_q: #kq_pattern,
            kinematic_by_v: #kv_pattern,
            dynamic_by_q: #dq_pattern,
            dynamic_by_v: #dv_pattern,
            dynamic_by_u: [#(#du),*],
        } = ::dalembert::constrained::linearize_on_constraints(
            &self.mass_matrix(q),
            &self.constraint_jacobian(q),
            &partials,
            &[#(#independent),*],
            &Self::COORDINATES,
        )?;
        ::core::result::Result::Ok((
            [#(#kinematic_rows,)* #(#dynamic_rows),*],
            [#(#zero_rows,)* #(#du),*],
        ))
    };
    linearize_function(model, function, body)
}
