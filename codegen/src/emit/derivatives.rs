//! The outputs that solve through the mass matrix: `accelerations_jacobian`
//! (`∂v̇/∂x = −M⁻¹ ∂τ/∂x` for the partials of the inverse dynamics at the
//! solved `v̇`, every column but those of structural zeros through the one
//! `L D Lᵀ` factorisation that solved for `v̇`; for a large tree `M`, `f`
//! and the world-frame partials computed by loops of the runtime rather
//! than unrolled: `M` and the inertia and gravity terms of `f` by the first
//! pass of `dalembert::__private::TreeRecursion` from the links' states,
//! each link's vectors by its second pass at the solved `v̇`, their pairs
//! by `dalembert::__private::add_tree_pairs`) and
//! `linearize` (the state-space matrices `A`, `B` of `ẋ = (q̇, v̇)` about a
//! state).

use super::body::{Given, Names, Straight, straight_line, straight_line_given};
use super::solve::{
    Elimination, Factorised, deferred_check, elimination, factorised, forward_in_runs, mass,
    negated_row_substitutions, state_check,
};
use super::{array, raw_string};
use crate::equations::derivatives::direction_names;
use crate::equations::{Equations, LinkState, subtree_ends};
use crate::expr::{ExprId, Func, Node, Pool, Sym, SymKinds};
use crate::model::Model;
use crate::outputs::{Function, PairedTree};
use crate::plan::solve::Factorisation;
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use std::collections::HashSet;

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

/// `columns` ordered by speed, each speed's `∂/∂q`, `∂/∂v` and the inputs
/// that first act on it (the first row where their column is not
/// structurally zero) together: on a tree whose speeds are numbered
/// depth-first, the columns where a row of the forward substitution can
/// be nonzero (its ancestors', its own and its subtree's) are then a few
/// long runs.
fn by_speed(
    pool: &Pool,
    blocks: &[&[ExprId]; 3],
    widths: [usize; 3],
    columns: &mut [(usize, usize)],
) {
    let nv = widths[0];
    let speed = |&(block, j): &(usize, usize)| match block {
        2 => (0..nv)
            .find(|&i| !pool.is_zero(blocks[block][i * widths[block] + j]))
            .unwrap_or(nv),
        _ => j,
    };
    columns.sort_by_key(|column| (speed(column), column.0));
}

/// The tree of `paired` as the runtime's table of
/// `dalembert::__private::TreeLink`s, bound to `TREE`: each link's parent,
/// its row in the elimination `order`, its columns among `columns` and
/// where its subtree ends.
fn tree_table(paired: &PairedTree, order: &[usize], columns: &[(usize, usize)]) -> TokenStream {
    let none = || quote!(usize::MAX);
    let index = |i: Option<usize>| {
        i.map_or_else(none, |i| {
            let i = Literal::usize_unsuffixed(i);
            quote!(#i)
        })
    };
    let ends = subtree_ends(&paired.parents);
    let links = paired
        .parents
        .iter()
        .zip(&paired.joints)
        .zip(&paired.speeds)
        .zip(ends);
    let table = links.map(|(((&parent, &joint), &speed), end)| {
        let row = index(order.iter().position(|&s| s == speed));
        let [by_q, by_v] = [0, 1].map(|block| index(columns.iter().position(|&c| c == (block, speed))));
        let parent = index(parent);
        let (joint, end) = (Literal::usize_unsuffixed(joint), Literal::usize_unsuffixed(end));
        quote!(::dalembert::__private::TreeLink { parent: #parent, joint: #joint, row: #row, by_q: #by_q, by_v: #by_v, end: #end })
    });
    let l = Literal::usize_unsuffixed(paired.speeds.len());
    quote!(const TREE: [::dalembert::__private::TreeLink; #l] = [#(#table),*];)
}

/// Whether the link of speed `a` is that of speed `b` or beyond it in the
/// tree of `paired`.
fn descends(paired: &PairedTree, a: usize, b: usize) -> bool {
    let link = |speed: usize| paired.speeds.iter().position(|&s| s == speed);
    let (mut at, target) = (link(a), link(b));
    while let Some(l) = at {
        if Some(l) == target {
            return true;
        }
        at = paired.parents[l];
    }
    false
}

/// `dalembert::__private::LinkState` of the entries `entries`, in the order
/// of the engine's `LinkState::entries`.
fn link_state(entries: &[TokenStream]) -> TokenStream {
    let matrix = |rows: &[TokenStream]| {
        let rows = rows.chunks(3).map(|row| quote!([#(#row),*]));
        quote!([#(#rows),*])
    };
    let (rotation, offset, axis) = (matrix(&entries[..9]), &entries[9..12], &entries[12..18]);
    let [speed, mass] = [&entries[18], &entries[19]];
    let (moment, inertia) = (&entries[20..23], matrix(&entries[23..32]));
    quote! {
        ::dalembert::__private::LinkState {
            rotation: #rotation,
            offset: [#(#offset),*],
            axis: [#(#axis),*],
            speed: #speed,
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

/// The partials of `τ` that the solve takes: the blocks `∂τ/∂q`, `∂τ/∂v`,
/// `∂τ/∂u` (row-major, `widths` columns each) and the columns solved, as
/// `(block, column)`.
struct Partials<'a> {
    blocks: [&'a [ExprId]; 3],
    widths: [usize; 3],
    columns: &'a [(usize, usize)],
}

impl Partials<'_> {
    /// The entries of the rows of the solve, row `i` that of the `i`-th
    /// speed of `order` eliminated.
    fn rows(&self, order: &[usize]) -> Vec<ExprId> {
        order
            .iter()
            .flat_map(|&speed| {
                self.columns
                    .iter()
                    .map(move |&(block, j)| self.blocks[block][speed * self.widths[block] + j])
            })
            .collect()
    }
}

impl Partials<'_> {
    /// Which entries of the rows of the solve can be nonzero (row `i` that
    /// of the `i`-th speed of `order` eliminated, a column each of
    /// `columns`): those that are not structural zeros, and with `paired`
    /// those where the runtime adds a pair, between a speed and one of
    /// its ancestors, itself or one of its descendants.
    fn support(&self, pool: &Pool, order: &[usize], paired: Option<&PairedTree>) -> Vec<Vec<bool>> {
        order
            .iter()
            .map(|&speed| {
                self.columns
                    .iter()
                    .map(|&(block, j)| {
                        let entry = self.blocks[block][speed * self.widths[block] + j];
                        let pair = paired.is_some_and(|paired| {
                            block < 2 && (descends(paired, speed, j) || descends(paired, j, speed))
                        });
                        pair || !pool.is_zero(entry)
                    })
                    .collect()
            })
            .collect()
    }
}

/// The rows `[f64; count]` of `outputs` (all of them, or the first
/// `rows.len() * count`).
fn row_values(outputs: &[TokenStream], rows: usize, count: usize) -> TokenStream {
    let values = (0..rows).map(|i| {
        let row = &outputs[i * count..(i + 1) * count];
        quote!([#(#row),*])
    });
    quote!([#(#values),*])
}

/// The solve of a system whose `M` and `f` are unrolled: `q̈` through the
/// `L D Lᵀ` factorisation (with `accelerations`' checks and errors), then
/// the mutable rows `rows` of `∂τ/∂x` (`[f64; columns.len()]` each) by a
/// straight-line body that takes the sines and cosines computed with `M`
/// and `f`.
fn unrolled_rows(
    model: &Model,
    pool: &Pool,
    (equations, factorisation): (&Equations, &Factorisation),
    names: &Names,
    partials: &Partials<'_>,
    rows: &[Ident],
) -> TokenStream {
    let columns = partials.columns;
    let roots = partials.rows(&factorisation.order);
    let (solved, body) = solved_then(
        model,
        pool,
        (equations, factorisation),
        names,
        &partials.blocks.concat(),
        &roots,
    );
    let (statements, count) = (&body.statements, Literal::usize_unsuffixed(columns.len()));
    let (n, values) = (
        Literal::usize_unsuffixed(rows.len()),
        row_values(&body.outputs, rows.len(), columns.len()),
    );
    quote! {
        #solved
        let [#(mut #rows),*]: [[f64; #count]; #n] = {
            #statements
            #values
        };
    }
}

/// `q̈` through the factorisation, bound to `qdd` and checked finite (with
/// `accelerations`' checks and errors), the sines and cosines of the angles
/// in `angle_roots` computed once beside `M` and `f`; and the straight-line
/// body of `roots`, which takes those sines and cosines.
fn solved_then(
    model: &Model,
    pool: &Pool,
    (equations, factorisation): (&Equations, &Factorisation),
    names: &Names,
    angle_roots: &[ExprId],
    roots: &[ExprId],
) -> (TokenStream, Straight) {
    let angles = angle_functions(pool, angle_roots);
    let given = Given {
        array: format_ident!("angles"),
        expressions: &angles,
    };
    let given = (!angles.is_empty()).then_some(&given);
    let Factorised {
        prelude,
        substitutions,
        solution,
        unsolved,
    } = factorised(model, pool, equations, factorisation, names, given);
    let body = match given {
        Some(given) => straight_line_given(pool, names, roots, given),
        None => straight_line(pool, names, roots),
    };
    let solved = quote! {
        #prelude
        let qdd = &{
            #substitutions
            [#(#solution),*]
        };
        if !finite(qdd) {
            return ::core::result::Result::Err(#unsolved);
        }
    };
    (solved, body)
}

/// The solve of a large tree: one straight-line body computing the rest of
/// the rows `rows` of `∂τ/∂x` (loads, potentials, dissipation), the links'
/// states, gravity and the rest of `τ` (`function`'s results, see
/// [`PairedTree`]); the runtime's recursion at `q̈ = 0` for `M` and the
/// inertia and gravity terms of `f`; `q̈` through the `L D Lᵀ` factorisation
/// (with `accelerations`' checks and errors); then the recursion's second
/// pass at `q̈` and the pairs added to the rows.
fn looped_rows(
    model: &Model,
    pool: &Pool,
    (equations, factorisation): (&Equations, &Factorisation),
    names: &Names,
    partials: &Partials<'_>,
    (function, paired): (&Function, &PairedTree),
    rows: &[Ident],
) -> TokenStream {
    let equations_or = format_ident!("equations_or");
    let elimination = elimination(model, pool, equations, factorisation, Some(&equations_or));
    let deferred = deferred_check(&equations_or, &elimination.bound());
    let Elimination {
        entries,
        factor,
        substitutions,
        right_hand_side,
        ..
    } = elimination;
    let order = &factorisation.order;
    let rest: Vec<ExprId> = function.results[3..]
        .iter()
        .flat_map(|v| v.expressions.iter().copied())
        .collect();
    let columns = partials.columns;
    // The armatures, which the runtime's `M` knows nothing of, last.
    let armature: Vec<ExprId> = model.armature.iter().map(|&(_, a)| a).collect();
    let roots = [partials.rows(order), rest, armature].concat();
    let body = straight_line(pool, names, &roots);
    let (nv, entry_count) = (model.nv(), rows.len() * columns.len());
    let values = row_values(&body.outputs, rows.len(), columns.len());
    let (outputs, armature) = body
        .outputs
        .split_at(body.outputs.len() - model.armature.len());
    let states = &outputs[entry_count..outputs.len() - 3 - nv];
    let gravity = &outputs[outputs.len() - 3 - nv..outputs.len() - nv];
    let residual = &outputs[outputs.len() - nv..];
    let states = states.chunks(LinkState::ENTRIES).map(link_state);
    let l = Literal::usize_unsuffixed(paired.speeds.len());
    let (count, n) = (
        Literal::usize_unsuffixed(columns.len()),
        Literal::usize_unsuffixed(nv),
    );
    let statements = &body.statements;
    let row = |speed: usize| {
        Literal::usize_unsuffixed(order.iter().position(|&s| s == speed).unwrap_or(speed))
    };
    // The runtime writes each entry at the descendant's row; a diagonal
    // entry gets its speed's armatures.
    let mass_entries = entries.iter().map(|&(i, j)| {
        let (name, (r, c)) = (
            mass(i, j),
            match descends(paired, j, i) {
                true => (row(j), row(i)),
                false => (row(i), row(j)),
            },
        );
        let added = model
            .armature
            .iter()
            .zip(armature)
            .filter(|((speed, _), _)| i == j && *speed == i)
            .map(|(_, value)| value);
        quote!(let #name = ::dalembert::__private::matrix_entry(&mass, #r, #c) #(+ #added)*;)
    });
    let forcing = right_hand_side.iter().enumerate().map(|(k, name)| {
        let (r, k) = (row(k), Literal::usize_unsuffixed(k));
        quote!(let #name = -(::dalembert::__private::vector_entry(&bias, #r)
            + ::dalembert::__private::vector_entry(&residual, #k));)
    });
    let solved = (0..nv).map(|i| format_ident!("x{}", i));
    let (check, table) = (state_check(), tree_table(paired, order, columns));
    quote! {
        #check
        let ([#(mut #rows),*], states, gravity, residual): (
            [[f64; #count]; #n],
            [::dalembert::__private::LinkState; #l],
            [f64; 3],
            [f64; #n],
        ) = {
            #statements
            (#values, [#(#states),*], [#(#gravity),*], [#(#residual),*])
        };
        #table
        let mut tree = ::dalembert::__private::TreeRecursion::default();
        tree.sweep(&states, &TREE, &gravity);
        let (mass, bias): ([[f64; #n]; #n], [f64; #n]) = tree.mass_and_bias(&TREE);
        #(#mass_entries)*
        #(#forcing)*
        #deferred
        #factor
        #substitutions
        let accelerations = [#(#solved),*];
        if !finite(&accelerations) {
            return ::core::result::Result::Err(#equations_or(
                ::dalembert::DynamicsError::NonFiniteAccelerations
            ));
        }
        let mut vectors = [[[0.0; 6]; 8]; #l];
        tree.link_vectors(&TREE, &accelerations, &mut vectors);
        ::dalembert::__private::add_tree_pairs([#(&mut #rows),*], &vectors, &TREE);
    }
}

/// `pub fn accelerations_jacobian(..)` from `function`, whose results are
/// `∂τ/∂q`, `∂τ/∂v`, `∂τ/∂u`, through the plan's `factorisation` of `M`;
/// nothing without one (a system with constraints, which the model
/// rejects, or without coordinates). The columns that are not structural zeros
/// are solved together: the rows of `∂τ/∂x` are arrays, substituted in
/// place through `L D Lᵀ` one row operation at a time. With `paired`, the
/// results are the rest of `∂τ/∂q` and `∂τ/∂v`, `∂τ/∂u`, the links' states,
/// gravity and the rest of `τ`, from which loops of the runtime compute
/// `M`, `f` and the inertia and gravity terms of the rows.
pub fn emit_accelerations_jacobian(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    names: &Names,
    function: &Function,
    paired: Option<&PairedTree>,
    factorisation: Option<&Factorisation>,
) -> TokenStream {
    let Some(factorisation) = factorisation else {
        return TokenStream::new();
    };
    let (nv, nu) = (model.nv(), model.inputs.len());
    let widths = [nv, nv, nu];
    let blocks: [&[ExprId]; 3] = [0, 1, 2].map(|k| function.results[k].expressions.as_slice());
    let Factorisation { order, pattern } = factorisation;
    // By speed where the forward substitution then takes rows in runs of
    // columns (which that order makes long), else as they are.
    let mut columns = solved_columns(pool, &blocks, widths, paired);
    let mut by_speeds = columns.clone();
    by_speed(pool, &blocks, widths, &mut by_speeds);
    let reordered = Partials {
        blocks,
        widths,
        columns: &by_speeds,
    };
    if forward_in_runs(pattern, &reordered.support(pool, order, paired)) {
        columns = by_speeds;
    }
    let rows: Vec<Ident> = (0..nv).map(|i| format_ident!("b{}", i)).collect();
    let partials = Partials {
        blocks,
        widths,
        columns: &columns,
    };
    let planned = (equations, factorisation);
    let rows_of_partials = match paired {
        None => unrolled_rows(model, pool, planned, names, &partials, &rows),
        Some(paired) => looped_rows(
            model,
            pool,
            planned,
            names,
            &partials,
            (function, paired),
            &rows,
        ),
    };
    let support = partials.support(pool, order, paired);
    let solve = negated_row_substitutions(pattern, &rows, &support);
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
    let (square, wide) = (matrix(nv, nv), matrix(nv, nu));
    jacobian_function(
        model,
        function,
        quote! {
            // `∂v̇/∂x = −M⁻¹ ∂τ/∂x` for the columns of `∂τ/∂x` that are not
            // structurally zero, row by row in the order of elimination.
            #rows_of_partials
            #solve
            #(#unpacked)*
            let jacobian: (#square, #square, #wide) = (#dq, #dv, #du);
        },
    )
}

/// `pub fn accelerations_jacobian(..)` with the docs of `function`, whose
/// `body` binds `jacobian`, `(∂v̇/∂q, ∂v̇/∂v, ∂v̇/∂u)`: returned if every
/// entry is finite, else `NonFiniteEquations`.
fn jacobian_function(model: &Model, function: &Function, body: TokenStream) -> TokenStream {
    let (nv, nu) = (model.nv(), model.inputs.len());
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
            #body
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
    } = straight_line(pool, names, &function.roots());
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
/// `ConstrainedPartials` that also hold `∂ψ/∂δ`, `∂φ/∂δ` and the kinematic
/// rows `K_δ`, `K_v` (its last results).
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
    } = straight_line(pool, names, &function.roots());
    let mut outputs = outputs.into_iter();
    let mut block = |rows: usize, columns: usize| -> Vec<TokenStream> {
        let entries: Vec<TokenStream> = outputs.by_ref().take(rows * columns).collect();
        match columns {
            0 => (0..rows).map(|_| quote!([])).collect(),
            _ => entries
                .chunks(columns)
                .map(|row| quote!([#(#row),*]))
                .collect(),
        }
    };
    let all = |rows: Vec<TokenStream>| quote!([#(#rows),*]);
    let (r_q, r_v, r_u) = (all(block(nv, nv)), all(block(nv, nv)), all(block(nv, nu)));
    let mut rows = |columns: usize| acting_rows(model, block(nc, columns));
    let (c_q, c_v) = (rows(nv), rows(nv));
    let accelerations = quote! {
        ::dalembert::__private::AccelerationPartials {
            residual_by_q: #r_q,
            residual_by_v: #r_v,
            residual_by_u: #r_u,
            constraint_by_q: #c_q,
            constraint_by_v: #c_v,
        }
    };
    let partials = match velocity {
        true => {
            let (psi_q, phi_q) = (rows(nv), rows(nv));
            let (k_q, k_v) = (all(block(nv, nv)), all(block(nv, nv)));
            quote! {
                ::dalembert::__private::ConstrainedPartials {
                    accelerations: #accelerations,
                    velocity_by_q: #psi_q,
                    position_by_q: #phi_q,
                    kinematic_by_q: #k_q,
                    kinematic_by_v: #k_v,
                }
            }
        }
        false => accelerations,
    };
    let multipliers = (0..nc).map(|j| {
        let name = names.multiplier(j);
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

/// `rows` (one per constraint row) as an array of the rows that do not
/// vanish identically: the runtime's linearisation sees only the rows that
/// constrain.
fn acting_rows(model: &Model, rows: Vec<TokenStream>) -> TokenStream {
    let acting = rows
        .into_iter()
        .zip(&model.constraints)
        .filter(|(_, c)| !c.vanishes)
        .map(|(row, _)| row);
    quote!([#(#acting),*])
}

/// `self.constraint_jacobian(q)`, without the rows that vanish
/// identically (see [`acting_rows`]).
fn acting_jacobian(model: &Model) -> TokenStream {
    if model.vanishing_rows().is_none() {
        return quote!(self.constraint_jacobian(q));
    }
    let names: Vec<Ident> = (0..model.constraints.len())
        .map(|i| format_ident!("row{}", i))
        .collect();
    let patterns = names
        .iter()
        .zip(&model.constraints)
        .map(|(name, c)| match c.vanishes {
            true => quote!(_),
            false => quote!(#name),
        });
    let acting = acting_rows(model, names.iter().map(|n| quote!(#n)).collect());
    quote!({
        let [#(#patterns),*] = self.constraint_jacobian(q);
        #acting
    })
}

/// `pub fn linearize(..)` of a system with constraints, from `function`,
/// whose results are the partials of `linearize_on_constraints`
/// (`∂r/∂q`, `∂r/∂v`, `∂r/∂u`, `∂c/∂q`, `∂c/∂v`, `∂ψ/∂δ`, `∂φ/∂δ`, `K_δ`,
/// `K_v`), evaluated at the accelerations and multipliers of
/// `constrained_accelerations`, with the independent entries of the
/// model's `linearize(..)`.
pub fn emit_constrained_linearize(
    model: &Model,
    pool: &Pool,
    names: &Names,
    function: &Function,
) -> TokenStream {
    let nv = model.nv();
    let chart = model.outputs.iter().find_map(|o| o.chart.as_ref());
    let (coordinates, speeds) = chart.map_or((vec![true; nv], vec![true; nv]), |c| {
        (c.coordinates.clone(), c.speeds.clone())
    });
    let holonomic = model.acting_constraints().map(|c| !c.nonholonomic);
    let jacobian = acting_jacobian(model);
    let direction_names = direction_names(model);
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
        } = ::dalembert::__private::linearize_on_constraints(
            &self.mass_matrix(q),
            &#jacobian,
            &partials,
            &::dalembert::__private::ManifoldChart {
                holonomic: [#(#holonomic),*],
                coordinates: [#(#coordinates),*],
                speeds: [#(#speeds),*],
                coordinate_names: [#(#direction_names),*],
                speed_names: Self::SPEEDS,
            },
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
    let direction_names = direction_names(model);
    let jacobian = acting_jacobian(model);
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
            ::dalembert::__private::constrained_accelerations_jacobian(
                &self.mass_matrix(q),
                &#jacobian,
                &partials,
                &[#(#direction_names),*],
            )
        }
    }
}

/// The nodes that the weighted part of `roots` (the nodes reading the
/// weights `Sym::Multiplier`) reads and that read no weight: the
/// coefficients of a reverse sweep, computed once for every pass of its
/// weights (constants excepted, which are written in place).
fn sweep_coefficients(pool: &Pool, roots: &[ExprId]) -> Vec<ExprId> {
    let weighted = |e: ExprId| pool.kinds(e).intersects(SymKinds::MULTIPLIER);
    let mut seen = HashSet::new();
    pool.topo_order(roots)
        .into_iter()
        .filter(|&e| weighted(e))
        .flat_map(|e| pool.children(e).to_vec())
        .filter(|&c| !weighted(c) && !pool.kinds(c).is_empty() && seen.insert(c))
        .collect()
}

/// `pub fn accelerations_jacobian(..)` from `function`, whose results are
/// `μᵀ ∂τ/∂q`, `μᵀ ∂τ/∂v`, `μᵀ ∂τ/∂u` (those of
/// `inverse_dynamics_adjoint`), by its rows: `v̇` through the plan's
/// `factorisation` of `M` (with `accelerations`' checks and errors), `−M⁻¹`
/// by the same factorisation (its columns four at a time), the sweep's
/// coefficients (what reads no weight) in one straight-line body, then a
/// loop over passes of a few rows (`dalembert::__private::WEIGHT_LANES`,
/// the target's SIMD width), each with its weights `μ = −M⁻¹ eᵢ` in the
/// lanes of a `dalembert::__private::WeightLanes`
/// (`dalembert::__private::weight_lanes`): row `i` of
/// `∂v̇/∂x = −M⁻¹ ∂τ/∂x` is `μᵀ ∂τ/∂x`.
pub fn emit_adjoint_rows(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    names: &Names,
    function: &Function,
    factorisation: Option<&Factorisation>,
) -> TokenStream {
    let Some(factorisation) = factorisation else {
        return TokenStream::new();
    };
    let (nv, nu) = (model.nv(), model.inputs.len());
    let roots = function.roots();
    let coefficients = sweep_coefficients(pool, &roots);
    let (solved, scalar) = solved_then(
        model,
        pool,
        (equations, factorisation),
        names,
        &coefficients,
        &coefficients,
    );
    let given = Given {
        array: format_ident!("coefficients"),
        expressions: &coefficients,
    };
    let lanes_names = Names {
        weights_in_lanes: true,
        ..names.clone()
    };
    let sweep = straight_line_given(pool, &lanes_names, &roots, &given);
    let weighted = |e: ExprId| pool.kinds(e).intersects(SymKinds::MULTIPLIER);
    let outputs: Vec<TokenStream> = roots
        .iter()
        .zip(&sweep.outputs)
        .map(|(&e, output)| match weighted(e) {
            true => output.clone(),
            false => quote!(::dalembert::__private::WeightLanes::splat(#output)),
        })
        .collect();
    let (by_q, rest) = outputs.split_at(nv);
    let (by_v, by_u) = rest.split_at(nv);
    let weights = (0..nv).map(|i| match sweep.used.contains(&Sym::Multiplier(i as u32)) {
        true => {
            let name = names.multiplier(i);
            quote!(#name)
        }
        false => quote!(_),
    });
    // `−M⁻¹`: the columns of the identity through the factorisation, rows
    // in the order of elimination, then by speed.
    let Factorisation { order, pattern } = factorisation;
    let rows: Vec<Ident> = (0..nv).map(|i| format_ident!("b{}", i)).collect();
    let unit_rows = order.iter().map(|&speed| {
        let row = (0..nv).map(|c| match c == speed {
            true => quote!(1.0),
            false => quote!(0.0),
        });
        quote!([#(#row),*])
    });
    // The identity's entries: row `k` (speed `order[k]`) has its one in
    // that speed's column, so `L Y = I` steps only over the columns where
    // `Y` can be nonzero (as the solve of `∂τ/∂x`; the same values).
    let identity: Vec<Vec<bool>> = order
        .iter()
        .map(|&speed| (0..nv).map(|c| c == speed).collect())
        .collect();
    let solve = negated_row_substitutions(pattern, &rows, &identity);
    let by_speed = (0..nv).map(|speed| {
        let k = order.iter().position(|&s| s == speed).unwrap_or(speed);
        &rows[k]
    });
    let (statements, values) = (&scalar.statements, &scalar.outputs);
    let (lane_statements, count) = (
        &sweep.statements,
        Literal::usize_unsuffixed(coefficients.len()),
    );
    let (square, wide) = (matrix(nv, nv), matrix(nv, nu));
    let [n, m] = [nv, nu].map(Literal::usize_unsuffixed);
    let lane = quote!(::dalembert::__private::WeightLanes);
    jacobian_function(
        model,
        function,
        quote! {
            #solved
            let [#(mut #rows),*]: [[f64; #n]; #n] = [#(#unit_rows),*];
            #solve
            let inverse: [[f64; #n]; #n] = [#(#by_speed),*];
            let coefficients: [f64; #count] = {
                #statements
                [#(#values),*]
            };
            let mut jacobian: (#square, #square, #wide) =
                ([[0.0; #n]; #n], [[0.0; #n]; #n], [[0.0; #m]; #n]);
            for pass in 0..::dalembert::__private::weight_passes(#n) {
                let [#(#weights),*] = ::dalembert::__private::weight_lanes(&inverse, pass);
                let (by_q, by_v, by_u): ([#lane; #n], [#lane; #n], [#lane; #m]) = {
                    #lane_statements
                    ([#(#by_q),*], [#(#by_v),*], [#(#by_u),*])
                };
                ::dalembert::__private::put_rows(&mut jacobian.0, pass, &by_q);
                ::dalembert::__private::put_rows(&mut jacobian.1, pass, &by_v);
                ::dalembert::__private::put_rows(&mut jacobian.2, pass, &by_u);
            }
        },
    )
}
