//! The specialised forward dynamics of an unconstrained system: an
//! `accelerations` method solving `M q̈ = f` by the route the plan chose
//! (`plan::solve`): the square-root-free Cholesky factorisation
//! `M = L D Lᵀ` unrolled for the system's size in the planned order of
//! elimination, skipping every entry of `L` that the structural zeros of
//! `M` make zero, or the articulated-body recursion derived with the
//! equations (see `equations::articulated`), which never forms `M`.
//!
//! Both have the same checks and errors as the runtime's
//! `dalembert::accelerations` (the pivots `Dⱼ` are the `Lⱼⱼ²` of `L Lᵀ`).

use super::body::{Angles, Given, Names, straight_line, straight_line_taking};
use crate::equations::{Articulated, Equations};
use crate::expr::{ExprId, Pool};
use crate::model::Model;
use crate::plan::solve::{Accelerations, Factorisation};
use crate::plan::{FILLED_GAP, Plan};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

/// `pub fn accelerations(..)`, for systems without constraints, by the
/// plan's route; nothing where the plan has no `accelerations`.
pub fn emit_accelerations(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    names: &Names,
    plan: &Plan,
) -> TokenStream {
    let nv = model.nv();
    let (doc, body, unsolved) = match (
        plan.accelerations,
        &equations.articulated,
        &plan.factorisation,
    ) {
        (Some(Accelerations::Articulated), Some(articulated), _) => (
            [
                " The accelerations `q̈` solving `M(q) q̈ = f(t, q, q̇, u)`, by the",
                " articulated-body recursion over the kinematic tree (`M` is never",
                " formed). Same checks and errors as `dalembert::accelerations`: a",
                " non-finite state, equation or result, or a pivot `Sᵀ Iᴬ S` not",
                " above `dalembert::dynamics::RELATIVE_PIVOT_TOLERANCE` times the",
                " largest pivot, is an error.",
            ],
            articulated_body(model, pool, equations, articulated, names),
            quote!(::dalembert::DynamicsError::NonFiniteAccelerations),
        ),
        (Some(_), _, Some(factorisation)) => {
            let Factorised {
                prelude,
                substitutions,
                solution,
                unsolved,
            } = factorised(model, pool, equations, factorisation, names, None);
            (
                [
                    " The accelerations `q̈` solving `M(q) q̈ = f(t, q, q̇, u)`, by a",
                    " square-root-free Cholesky factorisation `L D Lᵀ` unrolled for this",
                    " system (structural zeros of `M` skipped). Same checks and errors as",
                    " `dalembert::accelerations`: a non-finite state, equation or result,",
                    " or a pivot not above `dalembert::dynamics::RELATIVE_PIVOT_TOLERANCE`",
                    " times the largest diagonal entry of `M`, is an error.",
                ],
                quote!(#prelude #substitutions let qdd = [#(#solution),*];),
                unsolved,
            )
        }
        _ => return TokenStream::new(),
    };
    let (n_lit, nu) = (index(nv), index(model.inputs.len()));
    let coordinates = index(model.nq());
    quote! {
        #(#[doc = #doc])*
        #[inline]
        pub fn accelerations(
            &self,
            t: f64,
            q: &[f64; #coordinates],
            qd: &[f64; #n_lit],
            u: &[f64; #nu],
        ) -> ::core::result::Result<[f64; #n_lit], ::dalembert::DynamicsError> {
            #body
            if finite(&qdd) {
                ::core::result::Result::Ok(qdd)
            } else {
                ::core::result::Result::Err(#unsolved)
            }
        }
    }
}

/// Binds the closure `finite(&[f64]) -> bool` and returns the runtime's
/// error for a non-finite `t`, `q`, `qd` or `u`.
pub fn state_check() -> TokenStream {
    quote! {
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        if !(t.is_finite() && finite(q) && finite(qd) && finite(u)) {
            return ::core::result::Result::Err(::dalembert::DynamicsError::NonFiniteState);
        }
    }
}

/// The pieces of a solve of `M x = f` for an unconstrained system.
pub struct Factorised {
    /// The checks of the state (`t`, `q`, `qd`, `u`), the entries of `M`
    /// that the factorisation reads and `f` evaluated in one straight-line
    /// body, bound to `m{i}_{j}` and `f{i}`, and factorised (`l{i}_{j}`,
    /// the reciprocal pivots `r{j}`), returning the runtime's errors; binds
    /// the closures `finite(&[f64]) -> bool` and `equations_or`, which tests
    /// `M` and `f` only on the error paths (see [`deferred_check`]).
    pub prelude: TokenStream,
    /// Forward and backward substitution from `f{i}` to `x{i}`.
    pub substitutions: TokenStream,
    /// The names `x{i}` of the solution.
    pub solution: Vec<Ident>,
    /// The error for a solution that is not finite: `NonFiniteEquations`
    /// if `M` or `f` is not finite, else `NonFiniteAccelerations`.
    pub unsolved: TokenStream,
}

/// The order in which the factorisation eliminates the speeds:
/// `speeds[i]` is the `i`-th eliminated.
struct Order {
    speeds: Vec<usize>,
}

impl Order {
    /// The name of `M`'s entry at rows `i` and `j` of the elimination
    /// order: `m{a}_{b}` with `a ≥ b` the speeds' indices.
    fn mass(&self, i: usize, j: usize) -> Ident {
        let (a, b) = (self.speeds[i], self.speeds[j]);
        mass(a.max(b), a.min(b))
    }
}

/// The unrolled `L D Lᵀ` solve of `M x = f`, whatever computes `M`'s
/// entries and `f`.
pub struct Elimination {
    /// The entries `(i, j)` (`i ≥ j`) of `M` that the factorisation reads,
    /// by the speeds' indices, bound to `m{i}_{j}` before it.
    pub entries: Vec<(usize, usize)>,
    /// Binds `tolerance` and factorises (`l{i}_{j}`, the reciprocal pivots
    /// `r{j}`), returning the runtime's error at a pivot not above the
    /// tolerance.
    pub factor: TokenStream,
    /// Forward and backward substitution from `f{i}` to `x{i}`.
    pub substitutions: TokenStream,
    /// The names `f{i}` of the right-hand side.
    pub right_hand_side: Vec<Ident>,
    /// The names `x{i}` of the solution.
    pub solution: Vec<Ident>,
}

impl Elimination {
    /// The names that the factorisation and substitutions read: `M`'s
    /// entries `m{i}_{j}` and `f`'s `f{i}`.
    pub fn bound(&self) -> Vec<Ident> {
        self.entries
            .iter()
            .map(|&(i, j)| mass(i, j))
            .chain(self.right_hand_side.iter().cloned())
            .collect()
    }
}

/// How the unrolled factorisation tests its pivots.
#[derive(Clone, Copy)]
enum Pivots<'a> {
    /// Each as it is formed, against `tolerance`: a pivot that fails
    /// returns `SingularMassMatrix`, passed through the closure, if any
    /// (`Err(checked(error))`).
    Checked(Option<&'a Ident>),
    /// Not at all: the caller tests the pivots `p{j}` (the solve over
    /// lanes, whose states fail apart).
    Unchecked,
}

/// The planned elimination of `M x = f` written out. A pivot that fails
/// returns `SingularMassMatrix`, passed through the closure `checked` if
/// any (`Err(checked(error))`).
pub fn elimination(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    factorisation: &Factorisation,
    checked: Option<&Ident>,
) -> Elimination {
    eliminate(
        model,
        pool,
        equations,
        factorisation,
        Pivots::Checked(checked),
    )
}

/// The planned elimination of `M x = f` written out without a test of
/// its pivots, which are named `p{j}` (`j` in the elimination order) for
/// the caller to test, and without `tolerance`.
pub fn unchecked_elimination(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    factorisation: &Factorisation,
) -> Elimination {
    eliminate(model, pool, equations, factorisation, Pivots::Unchecked)
}

/// [`elimination`], its pivots tested as `pivots` says.
fn eliminate(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    factorisation: &Factorisation,
    pivots: Pivots<'_>,
) -> Elimination {
    let nq = model.nv();
    let Factorisation { order, pattern } = factorisation;
    let order = Order {
        speeds: order.clone(),
    };
    let mass_at_state = mass_at_state(model, pool, equations);
    let factor = factorisation_code(model, pattern, &order, pivots, &mass_at_state);
    let forward = forward_substitution(pattern, &order);
    let backward = backward_substitution(pattern);
    let mut solution: Vec<Ident> = vec![format_ident!("x0"); nq];
    for (i, &speed) in order.speeds.iter().enumerate() {
        solution[speed] = format_ident!("x{}", i);
    }
    let diagonal = (0..nq).map(|i| mass(i, i));
    // The entries the factorisation reads, by the speeds' indices.
    let mut read = vec![vec![false; nq]; nq];
    for (i, row) in pattern.iter().enumerate() {
        for (j, _) in row
            .iter()
            .enumerate()
            .filter(|(j, nonzero)| **nonzero || *j == i)
        {
            let (a, b) = (order.speeds[i], order.speeds[j]);
            read[a.max(b)][a.min(b)] = true;
        }
    }
    let entries: Vec<(usize, usize)> = (0..nq)
        .flat_map(|i| (0..=i).map(move |j| (i, j)))
        .filter(|&(i, j)| read[i][j])
        .collect();
    Elimination {
        entries,
        factor: match pivots {
            Pivots::Checked(_) => quote! {
                let tolerance = ::dalembert::__private::pivot_tolerance([#(#diagonal),*]);
                #factor
            },
            Pivots::Unchecked => factor,
        },
        substitutions: quote!(#forward #backward),
        right_hand_side: (0..nq).map(|i| format_ident!("f{}", i)).collect(),
        solution,
    }
}

/// The planned factorisation and substitutions of `M x = f`. The body
/// computing `M` and `f` also computes the values of `also`, if any, into
/// its array, for a later body to take.
pub fn factorised(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    factorisation: &Factorisation,
    names: &Names,
    also: Option<&Given<'_>>,
) -> Factorised {
    // The closure that the error paths call (see [`deferred_check`]).
    let equations_or = format_ident!("equations_or");
    let elimination = elimination(model, pool, equations, factorisation, Some(&equations_or));
    let bound = elimination.bound();
    let Elimination {
        entries,
        factor,
        substitutions,
        solution,
        ..
    } = elimination;
    // `M`'s entries the factorisation reads and `f`, computed together so
    // that they share their subexpressions (sines and cosines above all),
    // in a block that keeps the model's names out of the solver's.
    let given: &[ExprId] = also.map_or(&[], |also| also.expressions);
    let roots: Vec<ExprId> = entries
        .iter()
        .map(|&(i, j)| equations.mass_matrix[i][j])
        .chain(equations.forcing.iter().copied())
        .chain(given.iter().copied())
        .collect();
    let body = straight_line(pool, names, &roots);
    let statements = &body.statements;
    let (outputs, given_outputs) = body.outputs.split_at(roots.len() - given.len());
    let check = state_check();
    let binding = match also {
        None => quote! {
            let [#(#bound),*] = {
                #statements
                [#(#outputs),*]
            };
        },
        Some(Given { array, .. }) => quote! {
            let ([#(#bound),*], #array) = {
                #statements
                ([#(#outputs),*], [#(#given_outputs),*])
            };
        },
    };
    let deferred = deferred_check(&equations_or, &bound);
    let prelude = quote! {
        #check
        #binding
        #deferred
        #factor
    };
    Factorised {
        prelude,
        substitutions,
        solution,
        unsolved: quote!(#equations_or(
            ::dalembert::DynamicsError::NonFiniteAccelerations
        )),
    }
}

/// Binds the closure `equations_or(error)`: `NonFiniteEquations` if one of
/// `bound` (`M`'s entries that the factorisation reads, and `f`) is not
/// finite, else `error`. The runtime checks `M` and `f` before it
/// factorises; the emitted solve tests them only where it fails, with the
/// same outcome: a non-finite entry of `M` makes a pivot fail (an infinite
/// diagonal makes the tolerance infinite; a NaN pivot fails its test; a
/// non-finite `wᵢⱼ` below the diagonal subtracts the non-finite `wᵢⱼ Lᵢⱼ =
/// wᵢⱼ² rⱼ ≥ 0` from the pivot `Dᵢ`), and with every pivot positive a
/// non-finite `fᵢ` leaves `yᵢ`, then `xᵢ = yᵢ rᵢ − …`, not finite.
pub fn deferred_check(equations_or: &Ident, bound: &[Ident]) -> TokenStream {
    quote! {
        let #equations_or = |error: ::dalembert::DynamicsError| {
            if finite(&[#(#bound),*]) {
                error
            } else {
                ::dalembert::DynamicsError::NonFiniteEquations
            }
        };
    }
}

/// The articulated-body route, up to `let qdd = [..];`: one straight-line
/// body computing `f`, the pivots and `q̈`, then the checks.
fn articulated_body(
    model: &Model,
    pool: &Pool,
    equations: &Equations,
    articulated: &Articulated,
    names: &Names,
) -> TokenStream {
    let mass_at_state = mass_at_state(model, pool, equations);
    let body = straight_line_taking(pool, names, &articulated.roots(), Angles::WhereNeeded);
    let nq = model.nv();
    let statements = &body.statements;
    let forcing = &body.outputs[..nq];
    let pivots = &body.outputs[nq..2 * nq];
    let accelerations = &body.outputs[2 * nq..];
    let check = state_check();
    // The pivots are named as the factorisation names them.
    let names = pivot_names(model);
    quote! {
        #check
        #statements
        if !finite(&[#(#forcing),*]) {
            return ::core::result::Result::Err(::dalembert::DynamicsError::NonFiniteEquations);
        }
        ::dalembert::__private::check_pivots([#(#pivots),*], #names)
            .map_err(|e| ::dalembert::__private::with_null_motion(e, #mass_at_state))?;
        let qdd = [#(#accelerations),*];
    }
}

/// The arguments of `dalembert::__private::with_null_motion` after the
/// error, in an emitted function of `(t, q, ..)`: the mass matrix at the
/// state (computed on the error path only, to name the speeds whose
/// columns became dependent) and the names of its rows, by coordinate
/// when every speed is its coordinate's rate, else by speed.
fn mass_at_state(model: &Model, pool: &Pool, equations: &Equations) -> TokenStream {
    let mass = match equations.time_dependent(pool) {
        true => quote!(Self::mass_matrix_at(self, t, q)),
        false => quote!(Self::mass_matrix(self, q)),
    };
    let names = pivot_names(model);
    quote!(&#mass, &#names)
}

/// The names of `M`'s rows as the runtime's errors give them: by
/// coordinate when every speed is its coordinate's rate, else by speed.
fn pivot_names(model: &Model) -> TokenStream {
    match model.nq() == model.nv() {
        true => quote!(Self::COORDINATES),
        false => quote!(Self::SPEEDS),
    }
}

/// `start − Σ a·b` over `pairs`.
fn minus_products(
    start: TokenStream,
    pairs: impl Iterator<Item = (TokenStream, TokenStream)>,
) -> TokenStream {
    let mut out = start;
    for (a, b) in pairs {
        out = quote!(#out - #a * #b);
    }
    out
}

/// The name of `Mᵢⱼ`.
pub fn mass(i: usize, j: usize) -> Ident {
    format_ident!("m{}_{}", i, j)
}

/// An unsuffixed index literal.
fn index(i: usize) -> Literal {
    Literal::usize_unsuffixed(i)
}

/// The name of `Lᵢⱼ` (unit lower triangular factor).
fn entry(i: usize, j: usize) -> Ident {
    format_ident!("l{}_{}", i, j)
}

/// The name of `Lᵢⱼ Dⱼ`, the entry before its division by the pivot.
fn unscaled(i: usize, j: usize) -> Ident {
    format_ident!("w{}_{}", i, j)
}

/// The columns of `M = L D Lᵀ` (no square roots): the entries `Lᵢⱼ Dⱼ`,
/// the pivot `Dⱼ` and its test (if `pivots` says so), its reciprocal,
/// then `Lᵢⱼ`. A failed pivot's error goes through the closure of
/// [`Pivots::Checked`], if any, with the speeds that move no mass there
/// (see [`mass_at_state`]).
fn factorisation_code(
    model: &Model,
    pattern: &[Vec<bool>],
    order: &Order,
    pivots: Pivots<'_>,
    mass_at_state: &TokenStream,
) -> TokenStream {
    let nq = pattern.len();
    let mut out = TokenStream::new();
    let shared = |i: usize, j: usize| (0..j).filter(move |&k| pattern[i][k] && pattern[j][k]);
    // The pivot's name, as the runtime's solver reports it: the coordinate
    // when every speed is its coordinate's rate, else the speed.
    let names: Vec<String> = if model.nq() == model.nv() {
        model.coordinates.iter().map(|c| c.to_string()).collect()
    } else {
        model.speeds.iter().map(|s| s.written()).collect()
    };
    for (j, &speed) in order.speeds.iter().enumerate().take(nq) {
        let (jj, coordinate) = (index(speed), &names[speed]);
        let diagonal = order.mass(j, j);
        let pivot = minus_products(
            quote!(#diagonal),
            shared(j, j).map(|k| {
                let (w, l) = (unscaled(j, k), entry(j, k));
                (quote!(#w), quote!(#l))
            }),
        );
        let (p, r) = (format_ident!("p{}", j), format_ident!("r{}", j));
        let singular = quote! {
            ::dalembert::__private::with_null_motion(
                ::dalembert::DynamicsError::SingularMassMatrix {
                    index: #jj,
                    coordinate: #coordinate,
                    pivot: #p,
                    null_motion: ::dalembert::dynamics::NullMotion::default(),
                },
                #mass_at_state,
            )
        };
        let test = match pivots {
            Pivots::Checked(Some(checked)) => Some(quote!(#checked(#singular))),
            Pivots::Checked(None) => Some(singular),
            Pivots::Unchecked => None,
        }
        .map(|error| {
            quote! {
                if !(#p > tolerance) {
                    return ::core::result::Result::Err(#error);
                }
            }
        });
        out.extend(quote! {
            let #p = #pivot;
            #test
            let #r = 1.0 / #p;
        });
        for i in (j + 1..nq).filter(|&i| pattern[i][j]) {
            let start = order.mass(i, j);
            let value = minus_products(
                quote!(#start),
                shared(i, j).map(|k| {
                    let (w, l) = (unscaled(i, k), entry(j, k));
                    (quote!(#w), quote!(#l))
                }),
            );
            let (w, l) = (unscaled(i, j), entry(i, j));
            out.extend(quote!(let #w = #value; let #l = #w * #r;));
        }
    }
    out
}

/// `L y = f` (`L` has a unit diagonal), `f` taken in the elimination
/// order.
fn forward_substitution(pattern: &[Vec<bool>], order: &Order) -> TokenStream {
    let mut out = TokenStream::new();
    for (i, row) in pattern.iter().enumerate() {
        let start = format_ident!("f{}", order.speeds[i]);
        let value = minus_products(
            quote!(#start),
            (0..i).filter(|&k| row[k]).map(|k| {
                let (l, y) = (entry(i, k), format_ident!("y{}", k));
                (quote!(#l), quote!(#y))
            }),
        );
        let y = format_ident!("y{}", i);
        out.extend(quote!(let #y = #value;));
    }
    out
}

/// `D Lᵀ x = y`: `xᵢ = yᵢ / Dᵢ − Σₖ Lₖᵢ xₖ`, the `xₖ` subtracted in the
/// order they were solved, the one just solved last: each `xᵢ` then waits
/// on the one before by a product and a subtraction (subtracted first, it
/// waited on the whole chain of the others' subtractions).
fn backward_substitution(pattern: &[Vec<bool>]) -> TokenStream {
    let nq = pattern.len();
    let mut out = TokenStream::new();
    for i in (0..nq).rev() {
        let (y, r) = (format_ident!("y{}", i), format_ident!("r{}", i));
        let value = minus_products(
            quote!(#y * #r),
            (i + 1..nq).rev().filter(|&k| pattern[k][i]).map(|k| {
                let (l, x) = (entry(k, i), format_ident!("x{}", k));
                (quote!(#l), quote!(#x))
            }),
        );
        let x = format_ident!("x{}", i);
        out.extend(quote!(let #x = #value;));
    }
    out
}

/// `M X = −B` for the many columns of `B` at once, in place: `rows[i]`
/// names the mutable array holding row `i` (in the elimination order) of
/// `B`, and holds that of `X` after `L Y = B` and `D Lᵀ X = −Y` (the
/// negation folded into the reciprocal pivots). Each step is one
/// `dalembert::__private::scale_and_subtract` over the columns, or in `L Y
/// = B`, where `support[i][c]` says which entries of `B` can be nonzero,
/// `dalembert::__private::subtract_on_runs` over the columns where the
/// rows subtracted can be (on a tree, a row of `Y` is nonzero only in the
/// columns of its speed's ancestors, itself and its subtree).
pub fn negated_row_substitutions(
    pattern: &[Vec<bool>],
    rows: &[Ident],
    support: &[Vec<bool>],
) -> TokenStream {
    let nq = pattern.len();
    let terms_of = |terms: &[(Ident, usize)]| -> Vec<TokenStream> {
        terms
            .iter()
            .map(|(l, k)| {
                let other = &rows[*k];
                quote!((#l, &#other))
            })
            .collect()
    };
    let step = |i: usize, factor: TokenStream, terms: &[(Ident, usize)]| -> TokenStream {
        let (row, terms) = (&rows[i], terms_of(terms));
        quote!(::dalembert::__private::scale_and_subtract(&mut #row, #factor, [#(#terms),*]);)
    };
    let mut out = TokenStream::new();
    let forward = forward_support(pattern, support);
    for (i, row) in pattern.iter().enumerate() {
        let terms: Vec<(Ident, usize)> = (0..i)
            .filter(|&k| row[k])
            .map(|k| (entry(i, k), k))
            .collect();
        // Consecutive terms nonzero on the same runs of columns, together.
        for group in terms.chunk_by(|(_, a), (_, b)| runs(&forward[*a]) == runs(&forward[*b])) {
            let runs = runs(&forward[group[0].1]);
            match runs[..] {
                [] => {}
                [(0, end)] if end == forward[i].len() => out.extend(step(i, quote!(1.0), group)),
                _ => {
                    let (row, terms) = (&rows[i], terms_of(group));
                    let runs = runs.iter().map(|&(a, b)| {
                        let (a, b) = (Literal::usize_unsuffixed(a), Literal::usize_unsuffixed(b));
                        quote!((#a, #b))
                    });
                    out.extend(quote! {
                        ::dalembert::__private::subtract_on_runs(&mut #row, [#(#terms),*], &[#(#runs),*]);
                    });
                }
            }
        }
    }
    for i in (0..nq).rev() {
        let r = format_ident!("r{}", i);
        let terms: Vec<(Ident, usize)> = (i + 1..nq)
            .filter(|&k| pattern[k][i])
            .map(|k| (entry(k, i), k))
            .collect();
        out.extend(step(i, quote!(-#r), &terms));
    }
    out
}

/// Which entries of `Y` in `L Y = B` can be nonzero, row by row in the
/// elimination order: those of `B` (`support`) and every column of a row
/// that row `i` subtracts (`pattern[i][k]`).
fn forward_support(pattern: &[Vec<bool>], support: &[Vec<bool>]) -> Vec<Vec<bool>> {
    let mut forward: Vec<Vec<bool>> = support.to_vec();
    for (i, row) in pattern.iter().enumerate() {
        for k in (0..i).filter(|&k| row[k]) {
            let below = forward[k].clone();
            for (entry, nonzero) in forward[i].iter_mut().zip(below) {
                *entry |= nonzero;
            }
        }
    }
    forward
}

/// Whether [`negated_row_substitutions`] takes a step of `L Y = B` in runs
/// of columns (short of every column) for the entries of `B` that
/// `support` says can be nonzero.
pub fn forward_in_runs(pattern: &[Vec<bool>], support: &[Vec<bool>]) -> bool {
    let forward = forward_support(pattern, support);
    let subtracted = |k: usize| pattern.iter().skip(k + 1).any(|row| row[k]);
    forward
        .iter()
        .enumerate()
        .any(|(k, nonzero)| subtracted(k) && runs(nonzero) != [(0, nonzero.len())])
}

/// The runs `(start, end)` of consecutive `true` entries of `nonzero`, two
/// runs apart by at most [`FILLED_GAP`] columns taken as one (their
/// products by zeros cost less than a pass of their own), and as many
/// columns at either end taken into the first and last run.
fn runs(nonzero: &[bool]) -> Vec<(usize, usize)> {
    let mut runs: Vec<(usize, usize)> = Vec::new();
    for (c, _) in nonzero.iter().enumerate().filter(|&(_, &n)| n) {
        let start = match runs.is_empty() && c <= FILLED_GAP {
            true => 0,
            false => c,
        };
        match runs.last_mut() {
            Some((_, end)) if c <= *end + FILLED_GAP => *end = c + 1,
            _ => runs.push((start, c + 1)),
        }
    }
    if let Some((_, end)) = runs
        .last_mut()
        .filter(|(_, end)| *end + FILLED_GAP >= nonzero.len())
    {
        *end = nonzero.len();
    }
    runs
}
