//! The specialised forward dynamics of an unconstrained system: an
//! `accelerations` method solving `M q̈ = f` by a square-root-free Cholesky
//! factorisation `M = L D Lᵀ` unrolled for the system's size, which skips
//! every entry of `L` that the structural zeros of `M` make zero (a tree's
//! branches), with the same checks and errors as the runtime's
//! `dalembert::accelerations` (the pivots `Dⱼ` are the `Lⱼⱼ²` of `L Lᵀ`).

use crate::equations::Equations;
use crate::model::Model;
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{ToTokens, format_ident, quote};

/// `pub fn accelerations(..)`, for systems without constraints.
pub fn emit_accelerations(model: &Model, equations: &Equations) -> TokenStream {
    let nq = model.nv();
    if !model.constraints.is_empty() || nq == 0 {
        return TokenStream::new();
    }
    let pattern = fill_pattern(model, equations);
    let factor = factorisation(model, &pattern);
    let forward = forward_substitution(&pattern);
    let backward = backward_substitution(&pattern);
    let solution: Vec<Ident> = (0..nq).map(|i| format_ident!("x{}", i)).collect();
    let (n_lit, nu) = (index(nq), index(model.inputs.len()));
    let coordinates = index(model.nq());
    let diagonal = (0..nq).map(|i| mass(i, i));
    let rows = (0..nq).map(|i| {
        let row = (0..nq).map(|j| match j == i || (j < i && pattern[i][j]) {
            true => mass(i, j).into_token_stream(),
            false => quote!(_),
        });
        quote!([#(#row),*])
    });
    let forcing = (0..nq).map(|i| format_ident!("f{}", i));
    quote! {
        /// The accelerations `q̈` solving `M(q) q̈ = f(t, q, q̇, u)`, by a
        /// square-root-free Cholesky factorisation `L D Lᵀ` unrolled for this
        /// system (structural zeros of `M` skipped). Same checks and errors as
        /// `dalembert::accelerations`: a non-finite state, equation or result,
        /// or a pivot not above `dalembert::dynamics::RELATIVE_PIVOT_TOLERANCE`
        /// times the largest diagonal entry of `M`, is an error.
        #[inline]
        pub fn accelerations(
            &self,
            t: f64,
            q: &[f64; #coordinates],
            qd: &[f64; #n_lit],
            u: &[f64; #nu],
        ) -> ::core::result::Result<[f64; #n_lit], ::dalembert::DynamicsError> {
            let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
            if !(t.is_finite() && finite(q) && finite(qd) && finite(u)) {
                return ::core::result::Result::Err(::dalembert::DynamicsError::NonFiniteState);
            }
            let m = self.mass_matrix(q);
            let f = self.forcing(t, q, qd, u);
            if !(m.iter().all(|row| finite(row)) && finite(&f)) {
                return ::core::result::Result::Err(::dalembert::DynamicsError::NonFiniteEquations);
            }
            let [#(#rows),*] = m;
            let [#(#forcing),*] = f;
            let tolerance =
                ::dalembert::dynamics::RELATIVE_PIVOT_TOLERANCE * [#(#diagonal),*].into_iter().fold(0.0, ::core::primitive::f64::max);
            #factor
            #forward
            #backward
            let qdd = [#(#solution),*];
            if finite(&qdd) {
                ::core::result::Result::Ok(qdd)
            } else {
                ::core::result::Result::Err(::dalembert::DynamicsError::NonFiniteAccelerations)
            }
        }
    }
}

/// `pattern[i][j]` (`j ≤ i`): whether `Lᵢⱼ` can be nonzero — `Mᵢⱼ` is not
/// structurally zero, or fill-in through an earlier column.
fn fill_pattern(model: &Model, equations: &Equations) -> Vec<Vec<bool>> {
    let nq = model.nv();
    let mut pattern: Vec<Vec<bool>> = (0..nq)
        .map(|i| {
            (0..=i)
                .map(|j| !model.pool.is_zero(equations.mass_matrix[i][j]))
                .collect()
        })
        .collect();
    for j in 0..nq {
        for i in j + 1..nq {
            let fill = (0..j).any(|k| pattern[i][k] && pattern[j][k]);
            pattern[i][j] |= fill;
        }
    }
    pattern
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
fn mass(i: usize, j: usize) -> Ident {
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
/// the pivot `Dⱼ` and its test, its reciprocal, then `Lᵢⱼ`.
fn factorisation(model: &Model, pattern: &[Vec<bool>]) -> TokenStream {
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
    for (j, coordinate) in names.iter().enumerate().take(nq) {
        let jj = index(j);
        let diagonal = mass(j, j);
        let pivot = minus_products(
            quote!(#diagonal),
            shared(j, j).map(|k| {
                let (w, l) = (unscaled(j, k), entry(j, k));
                (quote!(#w), quote!(#l))
            }),
        );
        let (p, r) = (format_ident!("p{}", j), format_ident!("r{}", j));
        out.extend(quote! {
            let #p = #pivot;
            if !(#p > tolerance) {
                return ::core::result::Result::Err(::dalembert::DynamicsError::SingularMassMatrix {
                    index: #jj,
                    coordinate: #coordinate,
                    pivot: #p,
                });
            }
            let #r = 1.0 / #p;
        });
        for i in (j + 1..nq).filter(|&i| pattern[i][j]) {
            let start = mass(i, j);
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

/// `L y = f` (`L` has a unit diagonal).
fn forward_substitution(pattern: &[Vec<bool>]) -> TokenStream {
    let mut out = TokenStream::new();
    for (i, row) in pattern.iter().enumerate() {
        let start = format_ident!("f{}", i);
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

/// `D Lᵀ x = y`: `xᵢ = yᵢ / Dᵢ − Σₖ Lₖᵢ xₖ`.
fn backward_substitution(pattern: &[Vec<bool>]) -> TokenStream {
    let nq = pattern.len();
    let mut out = TokenStream::new();
    for i in (0..nq).rev() {
        let (y, r) = (format_ident!("y{}", i), format_ident!("r{}", i));
        let value = minus_products(
            quote!(#y * #r),
            (i + 1..nq).filter(|&k| pattern[k][i]).map(|k| {
                let (l, x) = (entry(k, i), format_ident!("x{}", k));
                (quote!(#l), quote!(#x))
            }),
        );
        let x = format_ident!("x{}", i);
        out.extend(quote!(let #x = #value;));
    }
    out
}
