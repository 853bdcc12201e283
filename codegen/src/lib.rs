//! The engine of `dalembert`: parse and check the system-description
//! language, derive the equations of motion with d'Alembert's principle on a
//! symbolic DAG, and emit flat Rust.
//!
//! Data flows one way: language (tokens → syntax tree) → model (names
//! resolved, rules checked) → expressions → kinematics → equations →
//! emission. Two front doors share it: [`expand`] for the `dalembert!`
//! macro and [`generate`] for build scripts, wrapped by [`Builder`] and
//! [`generate_file`], which read `.dal` files and report errors with file,
//! line and column. [`Urdf`] imports a robot description (URDF) as a
//! model in the same language. Beside the generator, an interpreter evaluates the
//! derived equations numerically (by d'Alembert's route or, independently,
//! Lagrange's) for differential tests of the emitted code; it lives in
//! [`testing`] with the benchmark chain generator.

#![warn(missing_docs, rust_2018_idioms, unused_qualifications)]

mod api;
mod build;
mod chain;
mod cost;
#[cfg(test)]
mod duplicates;
mod emit;
mod equations;
mod expr;
mod interpret;
mod kinematics;
mod language;
mod mjcf;
mod model;
mod optimize;
mod outputs;
mod random;
mod readable;
mod render;
mod rigid;
#[cfg(test)]
mod seeds;
mod size;
mod trees;
mod urdf;

pub use build::{
    BuildError, Builder, Diagnostic, ImportOptions, ModelFile, Severity, generate_file,
};
pub use emit::Target;
pub use mjcf::Mjcf;
pub use render::Style;
pub use size::{FunctionSize, OPERATION_LIMIT};
pub use urdf::{Imported, Urdf};

/// Tools for testing and benchmarking generated systems, not needed to
/// generate code.
///
/// * [`Interpreter`](testing::Interpreter) evaluates a system's derived
///   equations numerically, by d'Alembert's route (as the generator derives
///   them, before optimisation) or Lagrange's (`M` and `f` derived from `T`
///   and `V` instead): differential tests compare the emitted code (the
///   optimised equations) with the first, which checks the optimiser and
///   the emitter, and the two routes with each other, which checks the
///   d'Alembert assembly.
/// * [`chain`](testing::chain) and [`chain_spelled`](testing::chain_spelled)
///   write the n-link benchmark chains of the reference data
///   ([`Family`](testing::Family)) as model text, in three
///   [`Spelling`](testing::Spelling)s; the `dalembert chain` command prints
///   them.
/// * [`Geometry`](testing::Geometry) gives the positions of a model's points
///   and the rotations of its frames from the engine's kinematics (what the
///   animations draw).
/// * [`Random`](testing::Random) is the one deterministic generator of the
///   project's random states.
/// * [`quaternion_rotation`](testing::quaternion_rotation), [`cross`](testing::cross),
///   [`mat_vec`](testing::mat_vec) and [`transpose_vec`](testing::transpose_vec):
///   numeric rigid-body closed forms for free and spherical joints, written
///   apart from the symbolic engine.
pub mod testing {
    pub use crate::chain::{Family, Spelling, chain, chain_parameters, chain_spelled};
    pub use crate::interpret::{Geometry, Interpreter, Route, Sample, Values};
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
    let (functions, _) = functions(&model, &equations, &mut pool, &mut forms, Target::Std)?;
    Ok(size::sizes(&pool, &functions))
}

/// The functions to emit for `target` (the standard ones, then those the
/// model's `outputs` ask for), optimised, with the constants asked for.
fn functions(
    model: &model::Model,
    equations: &equations::Equations,
    pool: &mut expr::Pool,
    forms: &mut readable::ReadableForms,
    target: Target,
) -> syn::Result<(Vec<outputs::Function>, Vec<outputs::NameList>)> {
    let looped = target == Target::Std;
    let mut functions = outputs::standard(model, equations, pool, looped);
    // A looped `M`'s vectors are new expressions, optimised as the outputs are.
    if let Some(mass) = functions
        .first_mut()
        .filter(|f| matches!(f.body, outputs::Body::MassPairs(_)))
    {
        optimize::optimize_functions(std::slice::from_mut(mass), pool, forms);
    }
    let mut requested = outputs::requested(model, equations, pool)?;
    optimize::optimize_functions(&mut requested.functions, pool, forms);
    functions.extend(requested.functions);
    Ok((functions, requested.constants))
}

/// The functions generated for the system in `source` (the text of a
/// `.dal` file), one a line with its arguments and the first line of its
/// docs, then the `outputs` that would add the others: what
/// `dalembert check MODEL.dal --api` prints and the struct's docs end with.
pub fn api(source: &str) -> syn::Result<String> {
    let Derivation {
        model,
        mut pool,
        equations,
        mut forms,
    } = derive(lex(source)?)?;
    let documentation = emit::Documentation {
        docs: Vec::new(),
        text: String::new(),
        source: String::new(),
    };
    let (functions, constants) = functions(&model, &equations, &mut pool, &mut forms, Target::Std)?;
    let items = emit::emit(
        &model,
        &pool,
        &equations,
        &functions,
        &constants,
        &documentation,
        Target::Std,
    );
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
    let (functions, constants) = functions(&model, &equations, &mut pool, &mut forms, target)?;
    size::check_size(&model, &size::sizes(&pool, &functions))?;
    let mut docs = model.docs.clone();
    if !docs.is_empty() {
        docs.push(String::new());
    }
    let (equation_lines, text) = render::equations_doc(&model, &equations, &mut pool, &mut forms);
    docs.extend(equation_lines);
    Ok(emit::emit(
        &model,
        &pool,
        &equations,
        &functions,
        &constants,
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
    optimize::optimize(equations, pool, forms);
    check_equations(model, pool, equations)?;
    Ok(derivation)
}

/// Parses, checks and derives: the equations as derived, before
/// optimisation (no readable form computed yet). The checks of the derived
/// equations ([`check_equations`]) need the optimised ones.
fn derive_unoptimised(input: TokenStream) -> syn::Result<Derivation> {
    let system = language::parse_system(input)?;
    let (model, mut pool) = model::resolve(&system)?;
    let equations = equations::derive(&model, &mut pool);
    Ok(Derivation {
        model,
        pool,
        equations,
        forms: readable::ReadableForms::default(),
    })
}

/// The checks that need the derived (and optimised) equations.
fn check_equations(
    model: &model::Model,
    pool: &expr::Pool,
    equations: &equations::Equations,
) -> syn::Result<()> {
    check_inertia(model, pool, equations)
}

/// Every speed must move some mass: a coordinate (or speed) whose diagonal entry
/// of `M` is zero (and that no constraint ties) makes `M` singular
/// everywhere. Reported at the coordinate's declaration.
fn check_inertia(
    model: &model::Model,
    pool: &expr::Pool,
    equations: &equations::Equations,
) -> syn::Result<()> {
    let mut errors = (0..model.nv()).filter_map(|k| {
        let massless = pool.is_zero(equations.mass_matrix[k][k]);
        let constrained = equations
            .constraint_jacobian
            .iter()
            .any(|row| !pool.is_zero(row[k]));
        (massless && !constrained).then(|| {
            let speed = &model.speeds[k];
            let name = &speed.name;
            let what = if speed.rate_of_coordinate {
                "coordinate"
            } else {
                "speed"
            };
            syn::Error::new(
                name.span(),
                format!(
                    "the {what} `{name}` moves no mass, so the mass matrix is singular \
                     everywhere: make a body or particle depend on it, or remove it"
                ),
            )
        })
    });
    match errors.next() {
        None => Ok(()),
        Some(mut first) => {
            errors.for_each(|e| first.combine(e));
            Err(first)
        }
    }
}
