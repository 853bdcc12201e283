//! The form of each result: optimisation of the derived equations and of
//! the outputs before emission.
//!
//! d'Alembert's principle assembles each entry as dot products of vectors
//! in `N`'s axes, so an entry such as `M₁₁` of the double pendulum arrives as
//! `m L² (¼ cos²θ₁ + ¼ sin²θ₁) + …` where a constant would do. Each output is
//! therefore offered its compact form: expanded, like terms collected,
//! `sin² + cos²` and angle-sum pairs recombined (the readable form of the
//! docs), then every `sin`/`cos` of a sum of angles written back as products
//! of the sines and cosines of its parts, which the code computes anyway.
//! The compact form replaces the entry when it costs fewer operations; an
//! entry too large to expand within the budget keeps its DAG form. A
//! function computes each shared node once, so either form is charged only
//! the nodes that its function's results chosen before it do not compute
//! already: a DAG entry whose subexpressions its neighbours share is
//! cheap, though costly alone. Chosen one result at a time, the forms can
//! still cost more together than the derived DAG forms (compact forms
//! cheaper alone that share nothing with the results after them), so a
//! function whose derived forms cost less in total keeps them. The
//! readable forms come from the derivation's
//! [`ReadableForms`](crate::readable::ReadableForms), which the renderer
//! reads again for the docs.

use super::COMPACT_FORM_BUDGET;
use super::cost::{cost_past, function_cost};
use crate::equations::Equations;
use crate::expr::{ExprId, Func, Node, Pool};
use crate::outputs::Function;
use crate::readable::ReadableForms;
use std::collections::{HashMap, HashSet};

/// Replaces each output of `equations` by its compact form where cheaper,
/// from the derivation's readable `forms`; each of `M`, `f`, `T`, `V`, `A`,
/// `b`, the residuals and the velocity forms is one function's results.
pub fn optimize(equations: &mut Equations, pool: &mut Pool, forms: &mut ReadableForms) {
    optimize_all(equations.functions_mut().into_iter(), pool, forms);
}

/// Replaces each result of `functions` by its compact form where cheaper,
/// from the derivation's readable `forms`.
pub fn optimize_functions(functions: &mut [Function], pool: &mut Pool, forms: &mut ReadableForms) {
    optimize_all(
        functions.iter_mut().map(|f| f.expressions_mut().collect()),
        pool,
        forms,
    );
}

/// Replaces each of `expressions` by its compact form where cheaper: each
/// group is one function's results, which compute every shared node once,
/// so a form costs only the nodes that the forms chosen before it in its
/// group do not already compute.
fn optimize_all<'a>(
    groups: impl Iterator<Item = Vec<&'a mut ExprId>>,
    pool: &mut Pool,
    forms: &mut ReadableForms,
) {
    let mut chosen: HashMap<ExprId, ExprId> = HashMap::new();
    let mut split = AngleSums::new();
    for mut group in groups {
        let derived: Vec<ExprId> = group.iter().map(|e| **e).collect();
        let mut computed = HashSet::new();
        for e in group.iter_mut() {
            **e = *chosen
                .entry(**e)
                .or_insert_with(|| cheaper_form(pool, forms, &mut split, **e, &computed));
            pool.post_order(&[**e], |n| computed.insert(n));
        }
        let picked: Vec<ExprId> = group.iter().map(|e| **e).collect();
        if function_cost(pool, &derived) < function_cost(pool, &picked) {
            keep_derived(&mut group, &derived, &mut chosen);
        }
    }
}

/// Puts back the `derived` forms of a function's results, whose shared
/// nodes made them cheaper together than the forms chosen one result at a
/// time (each compact form cheaper than its DAG form alone, but sharing
/// nothing with the results after it: the planar chains written with
/// literals).
fn keep_derived(
    group: &mut [&mut ExprId],
    derived: &[ExprId],
    chosen: &mut HashMap<ExprId, ExprId>,
) {
    for (e, &d) in group.iter_mut().zip(derived) {
        **e = d;
        chosen.insert(d, d);
    }
}

/// `e`, or its compact form if that costs fewer operations besides the
/// nodes already `computed`; `split` holds the nodes whose angle sums are
/// already split.
fn cheaper_form(
    pool: &mut Pool,
    forms: &mut ReadableForms,
    split: &mut AngleSums,
    e: ExprId,
    computed: &HashSet<ExprId>,
) -> ExprId {
    let Some(compact) = forms.get(pool, e, COMPACT_FORM_BUDGET) else {
        return e;
    };
    let compact = expand_angle_sums(pool, split, compact);
    // `−s` costs what `s` does: the emitter writes it as the terms of `s`
    // negated where `s` is not shared, as the sum it reads.
    let written = pool.negated_sum(compact).unwrap_or(compact);
    let compact_cost = cost_past(pool, written, computed, usize::MAX);
    if compact_cost < cost_past(pool, e, computed, compact_cost) {
        compact
    } else {
        e
    }
}

/// The image of every node met by [`expand_angle_sums`], kept across the
/// entries (which share most of their nodes).
type AngleSums = HashMap<ExprId, Option<ExprId>>;

/// `e` with every `sin(a + b)`, `cos(a + b)` rewritten by the addition
/// formulas, recursively, down to sines and cosines of single terms.
fn expand_angle_sums(pool: &mut Pool, split: &mut AngleSums, e: ExprId) -> ExprId {
    let images = pool.try_rebuild_remembering(&[e], split, |pool, node, images| {
        Some(match *pool.node(node) {
            Node::Func(f @ (Func::Sin | Func::Cos), _) => {
                let (sin, cos) = sin_cos_of_sum(pool, images[0]);
                if f == Func::Sin { sin } else { cos }
            }
            _ => pool.with_children(node, images),
        })
    });
    images.map_or(e, |images| images[0])
}

/// `(sin x, cos x)` with `x` a sum split term by term:
/// `sin(a + r) = sin a cos r + cos a sin r`, `cos(a + r) = cos a cos r − sin a sin r`.
fn sin_cos_of_sum(pool: &mut Pool, x: ExprId) -> (ExprId, ExprId) {
    let Node::Add(terms) = pool.node(x).clone() else {
        return (pool.sin(x), pool.cos(x));
    };
    let (first, rest) = (terms[0], pool.sum(terms[1..].iter().copied()));
    let (sin_a, cos_a) = (pool.sin(first), pool.cos(first));
    let (sin_r, cos_r) = sin_cos_of_sum(pool, rest);
    let sin_terms = [pool.mul(sin_a, cos_r), pool.mul(cos_a, sin_r)];
    let cos_first = pool.mul(cos_a, cos_r);
    let sin_product = pool.mul(sin_a, sin_r);
    (pool.sum(sin_terms), pool.sub(cos_first, sin_product))
}

#[cfg(test)]
mod tests {
    use crate::interpret::{Interpreter, Route, Sample};
    use crate::seeds::{DOUBLE_PENDULUM, ROTATING_BAR};

    /// The interpreter evaluates the equations as derived and the emitted
    /// code computes the optimised ones, so their agreement checks this
    /// pass only if it rewrites something: on seed examples 1 and 2 it does
    /// (`sin² + cos²` in `M`), and the rewritten equations keep their values.
    #[test]
    fn the_optimiser_rewrites_the_seed_examples_and_keeps_their_values() {
        for source in [DOUBLE_PENDULUM, ROTATING_BAR] {
            let interpreter = Interpreter::new(source, Route::Dalembert).unwrap();
            let crate::Derivation {
                mut pool,
                equations: mut derived,
                mut forms,
                ..
            } = crate::derive_unoptimised(crate::lex(source).unwrap()).unwrap();
            let mut optimised = derived.clone();
            super::optimize(&mut optimised, &mut pool, &mut forms);
            let before: Vec<_> = derived.expressions_mut().map(|e| *e).collect();
            let after: Vec<_> = optimised.expressions_mut().map(|e| *e).collect();
            assert_ne!(before, after, "nothing rewritten in\n{source}");
            for seed in 0..4 {
                let sample = Sample::random(&interpreter, seed);
                let at = sample.values();
                let (before, after) = (pool.eval_many(&before, &at), pool.eval_many(&after, &at));
                for (b, a) in before.iter().zip(&after) {
                    assert!(
                        (b - a).abs() <= 1e-12 * (1.0 + b.abs()),
                        "{b} ≠ {a}\n{source}"
                    );
                }
            }
        }
    }
}
