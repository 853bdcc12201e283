//! The outputs that solve through the mass matrix: `accelerations_jacobian`
//! (`∂v̇/∂x = −M⁻¹ ∂τ/∂x` for the partials of the inverse dynamics at the
//! solved `v̇`, every column but those of structural zeros through the one
//! `L D Lᵀ` factorisation that solved for `v̇`; for a large tree the
//! world-frame partials computed by loops of the runtime rather than
//! unrolled: each link's vectors by `dalembert::dynamics::tree_link_vectors`
//! from the links' states, their pairs by
//! `dalembert::dynamics::add_tree_pairs`) and
//! `linearize` (the state-space matrices `A`, `B` of `ẋ = (q̇, v̇)` about a
//! state).

use super::body::{Given, Names, Straight, straight_line, straight_line_given};
use super::solve::{Factorised, factorised, negated_row_substitutions};
use super::{array, raw_string};
use crate::equations::{Equations, LinkState};
use crate::expr::{ExprId, Func, Node, Pool, Sym};
use crate::model::Model;
use crate::outputs::{Function, PairedTree};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

/// `[[f64; columns]; rows]` as tokens.
fn matrix(rows: usize, columns: usize) -> TokenStream {
    let (row, rows) = (array(columns), Literal::usize_unsuffixed(rows));
    quote!([#row; #rows])
}

/// The columns of `∂τ/∂x` that the solve takes: those of `∂τ/∂q`, `∂τ/∂v`
/// and `∂τ/∂u` (blocks 0, 1, 2, row-major `nv × widths[block]` in
/// `blocks`) that are not structurally zero (`∂τ/∂q₁` of a first joint
/// turning about gravity is), as `(block, column)`.
/// With `paired`, the columns of `∂τ/∂q` and `∂τ/∂v` are those that can
/// be nonzero with the pairs added.
fn solved_columns(
    pool: &Pool,
    blocks: &[&[ExprId]; 3],
    widths: [usize; 3],
    paired: Option<&PairedTree>,
) -> Vec<(usize, usize)> {
    let nv = widths[0];
    (0..3)
        .flat_map(|block| (0..widths[block]).map(move |j| (block, j)))
        .filter(|&(block, j)| match (paired, block) {
            (Some(paired), 0 | 1) => paired.nonzero[block][j],
            _ => (0..nv).any(|i| !pool.is_zero(blocks[block][i * widths[block] + j])),
        })
        .collect()
}

/// The calls adding the inertia and gravity terms of `paired`'s partials
/// to the rows `rows` (in the elimination `order`, the columns `columns`),
/// from the array `states` of the links' states and `gravity`: the links'
/// vectors by `dalembert::dynamics::tree_link_vectors`, their pairs by
/// `dalembert::dynamics::add_tree_pairs`, with the tree as a table.
fn tree_pairs(
    paired: &PairedTree,
    order: &[usize],
    columns: &[(usize, usize)],
    rows: &[Ident],
) -> TokenStream {
    let none = || quote!(usize::MAX);
    let index = |i: Option<usize>| {
        i.map_or_else(none, |i| {
            let i = Literal::usize_unsuffixed(i);
            quote!(#i)
        })
    };
    let table = paired.parents.iter().zip(&paired.speeds).map(|(&parent, &speed)| {
        let row = index(order.iter().position(|&s| s == speed));
        let [by_q, by_v] = [0, 1].map(|block| index(columns.iter().position(|&c| c == (block, speed))));
        let parent = index(parent);
        quote!(::dalembert::dynamics::TreeLink { parent: #parent, row: #row, by_q: #by_q, by_v: #by_v })
    });
    let l = Literal::usize_unsuffixed(paired.speeds.len());
    quote! {
        const TREE: [::dalembert::dynamics::TreeLink; #l] = [#(#table),*];
        let mut vectors = [[[0.0; 6]; 7]; #l];
        ::dalembert::dynamics::tree_link_vectors(&states, &TREE, &gravity, &mut vectors);
        ::dalembert::dynamics::add_tree_pairs([#(&mut #rows),*], &vectors, &TREE);
    }
}

/// `dalembert::dynamics::LinkState` of the entries `entries`, in the order
/// of the engine's `LinkState::entries`.
fn link_state(entries: &[TokenStream]) -> TokenStream {
    let matrix = |rows: &[TokenStream]| {
        let rows = rows.chunks(3).map(|row| quote!([#(#row),*]));
        quote!([#(#rows),*])
    };
    let (rotation, offset, axis) = (matrix(&entries[..9]), &entries[9..12], &entries[12..18]);
    let [speed, acceleration, mass] = [&entries[18], &entries[19], &entries[20]];
    let (moment, inertia) = (&entries[21..24], matrix(&entries[24..33]));
    quote! {
        ::dalembert::dynamics::LinkState {
            rotation: #rotation,
            offset: [#(#offset),*],
            axis: [#(#axis),*],
            speed: #speed,
            acceleration: #acceleration,
            mass: #mass,
            moment: [#(#moment),*],
            inertia: #inertia,
        }
    }
}

/// The sines and cosines of symbols (the coordinates' angles) that
/// `roots` read, in their order.
fn angle_functions(pool: &Pool, roots: &[ExprId]) -> Vec<ExprId> {
    pool.topo_order(roots)
        .into_iter()
        .filter(|&e| match pool.node(e) {
            Node::Func(Func::Sin | Func::Cos, arg) => matches!(pool.node(*arg), Node::Sym(_)),
            _ => false,
        })
        .collect()
}

/// Binds the mutable rows `rows` of `∂τ/∂x` (`[f64; count]` each) from
/// `body`, whose outputs are the rows' entries and then, with `paired`,
/// the links' states (bound to `states`) and gravity (to `gravity`), from
/// which the calls `pairs` then add the rest.
fn partial_rows(
    body: &Straight,
    rows: &[Ident],
    count: usize,
    paired: Option<(&PairedTree, TokenStream)>,
) -> TokenStream {
    let (statements, outputs) = (&body.statements, &body.outputs);
    let (n, entries) = (Literal::usize_unsuffixed(rows.len()), rows.len() * count);
    let values = (0..rows.len()).map(|i| {
        let row = &outputs[i * count..(i + 1) * count];
        quote!([#(#row),*])
    });
    let values = quote!([#(#values),*]);
    let count = Literal::usize_unsuffixed(count);
    match paired {
        None => quote! {
            let [#(mut #rows),*]: [[f64; #count]; #n] = {
                #statements
                #values
            };
        },
        Some((paired, pairs)) => {
            let (states, gravity) = outputs[entries..].split_at(outputs.len() - entries - 3);
            let states = states.chunks(LinkState::ENTRIES).map(link_state);
            let l = Literal::usize_unsuffixed(paired.speeds.len());
            quote! {
                let ([#(mut #rows),*], states, gravity): (
                    [[f64; #count]; #n],
                    [::dalembert::dynamics::LinkState; #l],
                    [f64; 3],
                ) = {
                    #statements
                    (#values, [#(#states),*], [#(#gravity),*])
                };
                #pairs
            }
        }
    }
}

/// `pub fn accelerations_jacobian(..)` from `function`, whose results are
/// `∂τ/∂q`, `∂τ/∂v`, `∂τ/∂u`; nothing for a system with constraints
/// (which the model rejects). The columns that are not structural zeros
/// are solved together: the rows of `∂τ/∂x` are arrays, substituted in
/// place through `L D Lᵀ` one row operation at a time. With `paired`, the
/// results are the rest of `∂τ/∂q` and `∂τ/∂v`, `∂τ/∂u`, the links' states
/// and gravity, from which loops of the runtime add the inertia and
/// gravity terms to the rows.
pub fn emit_accelerations_jacobian(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    names: &Names,
    function: &Function,
    paired: Option<&PairedTree>,
) -> TokenStream {
    let (nv, nu) = (model.nv(), model.inputs.len());
    let widths = [nv, nv, nu];
    let blocks: [&[ExprId]; 3] = [0, 1, 2].map(|k| function.results[k].expressions.as_slice());
    // With a paired tree, the links' states and gravity.
    let states: Vec<ExprId> = function.results[3..]
        .iter()
        .flat_map(|v| v.expressions.iter().copied())
        .collect();
    // The sines and cosines of the angles are computed once, with `M` and
    // `f`, and the partials' body takes them.
    let angles = angle_functions(pool, &[blocks.concat(), states.clone()].concat());
    let given = Given {
        array: format_ident!("angles"),
        expressions: &angles,
    };
    let given = (!angles.is_empty()).then_some(&given);
    let Some(Factorised {
        prelude,
        substitutions,
        solution,
        unsolved,
        pattern,
        order,
    }) = factorised(model, pool, equations, names, given)
    else {
        return TokenStream::new();
    };
    let columns = solved_columns(pool, &blocks, widths, paired);
    // Row `i` of the solve (the `i`-th speed eliminated): `∂τ/∂x` of that
    // speed's equation in the columns solved.
    let roots: Vec<ExprId> = order
        .iter()
        .flat_map(|&speed| {
            columns
                .iter()
                .map(move |&(block, j)| blocks[block][speed * widths[block] + j])
        })
        .chain(states)
        .collect();
    let body = match given {
        Some(given) => straight_line_given(pool, names, &roots, given),
        None => straight_line(pool, names, &roots),
    };
    let rows: Vec<Ident> = (0..nv).map(|i| format_ident!("b{}", i)).collect();
    let rows_of_partials = match paired {
        None => partial_rows(&body, &rows, columns.len(), None),
        Some(paired) => {
            let pairs = tree_pairs(paired, &order, &columns, &rows);
            partial_rows(&body, &rows, columns.len(), Some((paired, pairs)))
        }
    };
    let solve = negated_row_substitutions(&pattern, &rows);
    // `∂v̇ᵢ/∂x_j`, by the speed `i`: `dq{i}_{j}`, `dv{i}_{j}`, `du{i}_{j}`.
    let entry = |block: usize, i: usize, j: usize| {
        format_ident!("{}{}_{}", ["dq", "dv", "du"][block], i, j)
    };
    let unpacked = order.iter().zip(&rows).map(|(&speed, row)| {
        let entries = columns.iter().map(|&(block, j)| entry(block, speed, j));
        quote!(let [#(#entries),*] = #row;)
    });
    let block = |block: usize| -> TokenStream {
        let rows = (0..nv).map(|i| {
            let row = (0..widths[block]).map(|j| match columns.contains(&(block, j)) {
                true => {
                    let name = entry(block, i, j);
                    quote!(#name)
                }
                false => quote!(0.0),
            });
            quote!([#(#row),*])
        });
        quote!([#(#rows),*])
    };
    let (dq, dv, du) = (block(0), block(1), block(2));
    let (coordinates, vector, inputs) = (array(model.nq()), array(nv), array(nu));
    let (square, wide) = (matrix(nv, nv), matrix(nv, nu));
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
            let qdd = &{
                #substitutions
                [#(#solution),*]
            };
            if !finite(qdd) {
                return ::core::result::Result::Err(#unsolved);
            }
            // `∂v̇/∂x = −M⁻¹ ∂τ/∂x` for the columns of `∂τ/∂x` that are not
            // structurally zero, row by row in the order of elimination.
            #rows_of_partials
            #solve
            #(#unpacked)*
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

/// The statements binding `partials`, the runtime's
/// `AccelerationPartials` (`∂r/∂q`, `∂r/∂v`, `∂r/∂u`, `∂c/∂q`, `∂c/∂v`,
/// the first results of `function`) evaluated at the accelerations and
/// multipliers of `constrained_accelerations`, and with `velocity` the
/// `ConstrainedPartials` that also hold `∂ψ/∂q` (its last result).
fn constrained_partials(
    model: &Model,
    pool: &Pool,
    names: &Names,
    function: &Function,
    velocity: bool,
) -> TokenStream {
    let (nv, nu, nc) = (model.nv(), model.inputs.len(), model.constraints.len());
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
    let (c_q, c_v) = (block(nc, nv), block(nc, nv));
    let accelerations = quote! {
        ::dalembert::constrained::AccelerationPartials {
            residual_by_q: #r_q,
            residual_by_v: #r_v,
            residual_by_u: #r_u,
            constraint_by_q: #c_q,
            constraint_by_v: #c_v,
        }
    };
    let partials = match velocity {
        true => {
            let psi_q = block(nc, nv);
            quote! {
                ::dalembert::constrained::ConstrainedPartials {
                    accelerations: #accelerations,
                    velocity_by_q: #psi_q,
                }
            }
        }
        false => accelerations,
    };
    let multipliers = (0..nc).map(|j| {
        let name = format_ident!("lambda{}", j);
        match used.contains(&Sym::Multiplier(j as u32)) {
            true => quote!(#name),
            false => quote!(_),
        }
    });
    quote! {
        let (accelerations, [#(#multipliers),*]) =
            ::dalembert::constrained::constrained_accelerations(self, t, q, qd, u)?;
        let partials = {
            let qdd = &accelerations;
            #statements
            #partials
        };
    }
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
    let nv = model.nv();
    let independent: Vec<bool> = (0..nv)
        .map(|j| {
            model
                .outputs
                .iter()
                .flat_map(|o| &o.independent)
                .any(|(i, _)| *i == j)
        })
        .collect();
    let partials = constrained_partials(model, pool, names, function, true);
    let [kq, kv, dq, dv] = ["kq", "kv", "dq", "dv"].map(|prefix| entry_names(prefix, nv, nv));
    let du: Vec<Ident> = (0..nv).map(|i| format_ident!("du{}", i)).collect();
    let (kq_pattern, kv_pattern, dq_pattern, dv_pattern) =
        (pattern(&kq), pattern(&kv), pattern(&dq), pattern(&dv));
    let (kinematic_rows, dynamic_rows) = (joined_rows(&kq, &kv), joined_rows(&dq, &dv));
    let zero_rows = zero_rows(model);
    let body = quote! {
        #partials
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

/// `pub fn accelerations_jacobian(..)` of a system with constraints, from
/// `function`, whose results are the runtime's `AccelerationPartials`:
/// `constrained_accelerations_jacobian` solves them.
pub fn emit_constrained_accelerations_jacobian(
    model: &Model,
    pool: &Pool,
    names: &Names,
    function: &Function,
) -> TokenStream {
    let (nv, nu) = (model.nv(), model.inputs.len());
    let (coordinates, vector, inputs) = (array(model.nq()), array(nv), array(nu));
    let (square, wide) = (matrix(nv, nv), matrix(nv, nu));
    let docs = function.docs.iter().map(|line| raw_string(line));
    let partials = constrained_partials(model, pool, names, function, false);
    quote! {
        #(#[doc = #docs])*
        #[inline]
        pub fn accelerations_jacobian(
            &self,
            t: f64,
            q: &#coordinates,
            qd: &#vector,
            u: &#inputs,
        ) -> ::core::result::Result<(#square, #square, #wide), ::dalembert::DynamicsError> {
            #partials
            ::dalembert::constrained::constrained_accelerations_jacobian(
                &self.mass_matrix(q),
                &self.constraint_jacobian(q),
                &partials,
                &Self::COORDINATES,
            )
        }
    }
}
