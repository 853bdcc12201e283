//! The engine of `dalembert`: parse and check the system-description
//! language, derive the equations of motion with d'Alembert's principle on a
//! symbolic DAG, and emit flat Rust.
//!
//! Data flows one way: language (tokens → syntax tree) → model (names
//! resolved, rules checked) → expressions → kinematics → equations →
//! outputs → plan (every route choice, by one cost model) → emission. Two front doors share it: [`expand`] for the `dalembert!`
//! macro and [`generate`] for build scripts, wrapped by [`Builder`] and
//! [`generate_file`], which read `.dal` files and report errors with file,
//! line and column. [`Urdf`] imports a robot description (URDF) as a
//! model in the same language. [`Geometry`] evaluates a model's named
//! points and frames numerically, for drawing it. Beside the generator, an interpreter evaluates the
//! derived equations numerically (by d'Alembert's route or, independently,
//! Lagrange's) for differential tests of the emitted code; it lives in
//! `testing`, behind the non-default feature `testing`, with the other test
//! fixtures. [`chain`] writes the benchmark chains as model text (what
//! `dalembert chain` prints).

#![deny(missing_docs)]
#![warn(rust_2018_idioms, unused_qualifications)]

mod api;
mod build;
pub mod chain;
mod checks;
#[cfg(test)]
mod duplicates;
mod emit;
mod equations;
mod expr;
mod geometry;
#[cfg(any(test, feature = "testing"))]
mod interpret;
mod kinematics;
mod language;
mod mjcf;
mod model;
mod outputs;
mod plan;
mod random;
mod readable;
mod render;
mod rigid;
#[cfg(test)]
mod seeds;
mod series;
mod size;
#[cfg(any(test, feature = "testing"))]
mod trees;
mod urdf;

pub use build::{
    BuildError, Builder, Diagnostic, ImportOptions, ModelFile, Severity, generate_file,
};
pub use emit::Target;
pub use geometry::{Geometry, Values};
pub use mjcf::Mjcf;
pub use render::Style;
pub use size::{DERIVATION_LIMIT, DerivationEstimate, FunctionSize, OPERATION_LIMIT};
pub use urdf::{Imported, Urdf};

/// Tools for testing and benchmarking generated systems, not needed to
/// generate code: compiled with the non-default feature `testing` only
/// (the workspace's tests, benchmarks and lab turn it on).
///
/// * [`Interpreter`](testing::Interpreter) evaluates a system's derived
///   equations numerically, by d'Alembert's route (as the generator derives
///   them, before optimisation) or Lagrange's (`M` and `f` derived from `T`
///   and `V` instead): differential tests compare the emitted code (the
///   optimised equations) with the first, which checks the optimiser and
///   the emitter, and the two routes with each other, which checks the
///   d'Alembert assembly.
/// * [`testing::Values`]: the values of every symbol, as the
///   interpreter and [`Geometry`] read them (the same type as the crate's
///   root [`Values`]).
/// * [`Random`](testing::Random) is the one deterministic generator of the
///   project's random states.
/// * [`quaternion_rotation`](testing::quaternion_rotation), [`cross`](testing::cross),
///   [`mat_vec`](testing::mat_vec) and [`transpose_vec`](testing::transpose_vec):
///   numeric rigid-body closed forms for free and spherical joints, written
///   apart from the symbolic engine.
/// * [`Shape`](testing::Shape): the benchmark trees as URDF text.
#[cfg(feature = "testing")]
pub mod testing {
    pub use crate::geometry::Values;
    pub use crate::interpret::{Interpreter, Route, Sample};
    pub use crate::random::Random;
    pub use crate::rigid::{cross, mat_vec, quaternion_rotation, transpose_vec};
    pub use crate::trees::Shape;
}

use proc_macro2::TokenStream;

/// Expands the body of `dalembert! { ... }` into the generated items, or
/// into `compile_error!`s pointing at every problem found.
pub fn expand(input: TokenStream) -> TokenStream {
    let source = written_text(&input);
    derive_items(input, &source, Target::Std).unwrap_or_else(syn::Error::into_compile_error)
}

/// The macro's input as the user wrote it (comments and layout kept, the
/// common indentation removed), from the text of the macro call when the
/// compiler gives it and it reads as the same tokens (not when another
/// macro wrote the call); else the tokens printed.
fn written_text(input: &TokenStream) -> String {
    let tokens = input.to_string();
    proc_macro2::Span::call_site()
        .source_text()
        .and_then(|call| {
            let call = call.trim_end();
            let open = call.find(['{', '(', '['])?;
            call.get(open + 1..call.len() - 1).map(dedented)
        })
        .filter(|text| lex(text).is_ok_and(|t| t.to_string() == tokens))
        .unwrap_or(tokens)
}

/// `text` without its leading blank lines, its trailing whitespace and
/// the indentation common to its lines.
fn dedented(text: &str) -> String {
    let lines: Vec<&str> = text
        .trim_end()
        .lines()
        .skip_while(|l| l.trim().is_empty())
        .collect();
    let indent = lines
        .iter()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.len() - l.trim_start().len())
        .min()
        .unwrap_or(0);
    let lines: Vec<&str> = lines
        .iter()
        .map(|l| l.get(indent..).unwrap_or(""))
        .collect();
    lines.join("\n") + "\n"
}

/// Generates formatted Rust source for the system in `source` (the text of
/// a `.dal` file: the macro's language).
pub fn generate(source: &str) -> syn::Result<String> {
    generate_for(source, Target::Std)
}

/// Like [`generate`], for a kind of crate: [`Target::NoStd`] writes code
/// for `#![no_std]` crates (elementary functions from `libm`).
pub fn generate_for(source: &str, target: Target) -> syn::Result<String> {
    let items = derive_items(lex(source)?, source, target)?;
    let file = syn::parse2::<syn::File>(items)?;
    Ok(format!(
        "// @generated by dalembert-codegen. Do not edit by hand.\n\n{}",
        prettyplease::unparse(&file)
    ))
}

/// Checks the system in `source` (the text of a `.dal` file) as the macro
/// does: every error the macro would report, without emitting code.
pub fn check(source: &str) -> syn::Result<()> {
    derive(lex(source)?).map(drop)
}

/// The derived equations of the system in `source` (the text of a `.dal`
/// file), rendered in the seed document's style: `M(q)`, `f`, and with
/// constraints `A` and `b`, as Unicode text or LaTeX.
pub fn equations(source: &str, style: Style) -> syn::Result<String> {
    let Derivation {
        model,
        mut pool,
        equations,
        mut forms,
    } = derive(lex(source)?)?;
    Ok(render::equations_text(
        &model, &equations, &mut pool, &mut forms, style,
    ))
}

/// How big the derivation of a system is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Statistics {
    /// Expression nodes interned while deriving and optimising (the pool's
    /// size: everything the engine built, dead ends included).
    pub pool_nodes: usize,
    /// Distinct nodes reachable from the emitted outputs (`M`, `f`, `T`,
    /// `V` and the constraint rows): the size of the DAG the code computes.
    pub output_nodes: usize,
}

/// The size of the derivation of the system in `source` (the text of a
/// `.dal` file), as [`generate`] derives and optimises it.
pub fn statistics(source: &str) -> syn::Result<Statistics> {
    let Derivation {
        pool,
        mut equations,
        ..
    } = derive(lex(source)?)?;
    let outputs: Vec<expr::ExprId> = equations.expressions_mut().map(|e| *e).collect();
    Ok(Statistics {
        pool_nodes: pool.len(),
        output_nodes: pool.topo_order(&outputs).len(),
    })
}

/// The tokens of `source`, or the lexer's error at its position (where
/// the compiler would have rejected the macro's input).
fn lex(source: &str) -> syn::Result<TokenStream> {
    source.parse().map_err(|e: proc_macro2::LexError| {
        syn::Error::new(
            e.span(),
            "cannot read the tokens here: expected balanced `()`, `[]` and `{}` \
             and Rust tokens (names, numbers, punctuation, comments)",
        )
    })
}

/// The estimated size of each function generated for the system in
/// `source` (the text of a `.dal` file), in the order emitted, as
/// `dalembert check MODEL.dal --stats` prints them; a model whose largest
/// function exceeds [`OPERATION_LIMIT`] is refused by every other front
/// door.
pub fn function_sizes(source: &str) -> syn::Result<Vec<FunctionSize>> {
    let Derivation {
        model,
        mut pool,
        equations,
        mut forms,
    } = derive(lex(source)?)?;
    let plan = plan::plan(&model, &equations, &mut pool, &mut forms, Target::Std);
    Ok(size::sizes(&pool, &plan.functions))
}

/// The estimate of the engine's work on the system in `source` (the text
/// of a `.dal` file), from its speeds and outputs, before anything is
/// derived; a model over [`DERIVATION_LIMIT`] is refused by every front
/// door before its derivation starts.
pub fn derivation_estimate(source: &str) -> syn::Result<DerivationEstimate> {
    let system = language::parse_system(lex(source)?)?;
    let (model, _) = model::resolve(&system)?;
    Ok(DerivationEstimate::of(&model))
}

/// The functions generated for the system in `source` (the text of a
/// `.dal` file), one a line with its arguments and the first line of its
/// docs, then the `outputs` that would add the others: what
/// `dalembert check MODEL.dal --api` prints and the struct's docs end with.
pub fn api(source: &str) -> syn::Result<String> {
    let tokens = lex(source)?;
    let model = model::resolve(&language::parse_system(tokens.clone())?)?.0;
    let items = derive_items(tokens, source, Target::Std)?;
    Ok(api::Api::of(&model, &items).text())
}

/// The whole pipeline, from tokens to items; a model too large to compile
/// is refused before emission. `source` is the model's text, for
/// `NAME::SOURCE`.
fn derive_items(input: TokenStream, source: &str, target: Target) -> syn::Result<TokenStream> {
    let Derivation {
        model,
        mut pool,
        equations,
        mut forms,
    } = derive(input)?;
    let mut plan = plan::plan(&model, &equations, &mut pool, &mut forms, target);
    size::check_size(&model, &size::sizes(&pool, &plan.functions))?;
    let mut docs = model.docs.clone();
    if !docs.is_empty() {
        docs.push(String::new());
    }
    let (equation_lines, text) = render::equations_doc(&model, &equations, &mut pool, &mut forms);
    docs.extend(equation_lines);
    plan.plan_taylor(&model, &mut pool, &mut forms, &equations, target);
    Ok(emit::emit(
        &model,
        &pool,
        &equations,
        &plan,
        &emit::Documentation {
            docs,
            text,
            source: source.to_string(),
        },
        target,
    ))
}

/// One system's derivation: the checked model, the pool every expression
/// of it lives in, its equations, and the readable forms computed so far,
/// which the optimiser and the renderer share so that each is computed
/// once.
struct Derivation {
    model: model::Model,
    pool: expr::Pool,
    equations: equations::Equations,
    forms: readable::ReadableForms,
}

/// Parses, checks, derives and optimises.
fn derive(input: TokenStream) -> syn::Result<Derivation> {
    let mut derivation = derive_unoptimised(input)?;
    let Derivation {
        model,
        pool,
        equations,
        forms,
    } = &mut derivation;
    plan::optimize::optimize(equations, pool, forms);
    checks::after_derivation(model, pool, equations)?;
    Ok(derivation)
}

/// Parses, checks and derives: the equations as derived, before
/// optimisation (no readable form computed yet). The checks of the derived
/// equations ([`checks::after_derivation`]) need the optimised ones.
fn derive_unoptimised(input: TokenStream) -> syn::Result<Derivation> {
    let system = language::parse_system(input)?;
    let (model, mut pool) = model::resolve(&system)?;
    size::check_derivation(&model)?;
    let equations = equations::derive(&model, &mut pool);
    Ok(Derivation {
        model,
        pool,
        equations,
        forms: readable::ReadableForms::default(),
    })
}
