//! A diagnostic of the derivations (tests only): the quantities an output's
//! DAG computes twice under two forms. Hash-consing merges equal
//! *expressions*, not equal *values*: a subtree's `ċ = m v + ω × c` and its
//! linear momentum `m v − c × ω` were two nodes, both summed up the tree
//! (`0f35c8c`). Every node of the DAG is evaluated at a few random states
//! and the nodes whose values agree (up to sign) to ten significant digits
//! at every state are grouped; the groups that only inherit a smaller
//! group's duplication (same operation on children of the same groups) are
//! left out, so each reported group is where two forms first part.
//!
//! `cargo test --release -p dalembert-codegen duplicates -- --ignored
//! --nocapture` prints the report on the benched systems.

use std::collections::{HashMap, HashSet};

use crate::expr::{Env, ExprId, Node, Pool, Sym, SymKinds};
use crate::plan::cost::{node_operations, operations};

/// Nodes of one DAG whose values agree, up to sign, at every state.
#[derive(Debug)]
pub struct Group {
    /// The nodes, each with `+1` or `−1`: its value over the group's.
    pub members: Vec<(ExprId, f64)>,
    /// The operations that only the members need (no other node of the
    /// DAG reads them), all members but the one that needs fewest: what
    /// computing the value once would save, about.
    pub excess: usize,
}

/// The groups of equal-valued distinct nodes among those computing
/// `roots`, valued at each of `states`, largest excess first. Constants,
/// [`Node::Group`] wrappers and negations `−1·x` (the same computation as
/// `x`) are skipped; nodes that vanish at every state form a group of
/// their own (value 0).
pub fn duplicates(pool: &Pool, roots: &[ExprId], states: &[&dyn Env]) -> Vec<Group> {
    let order = pool.topo_order(roots);
    let values: Vec<Vec<f64>> = states.iter().map(|s| pool.eval_many(&order, *s)).collect();
    let mut by_value: HashMap<Vec<i64>, Vec<(ExprId, f64)>> = HashMap::new();
    for (i, &e) in order.iter().enumerate() {
        if is_trivial(pool, e) {
            continue;
        }
        let at: Vec<f64> = values.iter().map(|v| v[i]).collect();
        if let Some((key, sign)) = rounded(&at) {
            by_value.entry(key).or_default().push((e, sign));
        }
    }
    let mut groups: Vec<Vec<(ExprId, f64)>> =
        by_value.into_values().filter(|g| g.len() > 1).collect();
    groups.sort_by_key(|g| g[0].0);
    let class: HashMap<ExprId, usize> = groups
        .iter()
        .enumerate()
        .flat_map(|(k, g)| g.iter().map(move |&(e, _)| (e, k)))
        .collect();
    let mut origins: Vec<Group> = groups
        .into_iter()
        .filter(|g| !inherited(pool, g, &class))
        .map(|members| {
            let own: Vec<usize> = members
                .iter()
                .map(|&(e, _)| exclusive_operations(pool, roots, e))
                .collect();
            let fewest = own.iter().min().copied().unwrap_or(0);
            Group {
                excess: own.iter().sum::<usize>() - fewest,
                members,
            }
        })
        .collect();
    origins.sort_by_key(|g| std::cmp::Reverse(g.excess));
    origins
}

/// The operations of `e`'s cone that the rest of the DAG of `roots` does
/// not read: what dropping `e` would save.
pub fn exclusive_operations(pool: &Pool, roots: &[ExprId], e: ExprId) -> usize {
    let mut others: HashSet<ExprId> = HashSet::new();
    let mut stack: Vec<ExprId> = roots.iter().copied().filter(|&r| r != e).collect();
    while let Some(n) = stack.pop() {
        if others.insert(n) {
            stack.extend(pool.children(n).iter().filter(|&&c| c != e));
        }
    }
    pool.topo_order(&[e])
        .into_iter()
        .filter(|n| !others.contains(n))
        .map(|n| node_operations(pool, n))
        .sum()
}

/// A node whose value is trivially another's or a constant.
fn is_trivial(pool: &Pool, e: ExprId) -> bool {
    if pool.kinds(e) == SymKinds::EMPTY {
        return true;
    }
    match pool.node(e) {
        Node::Group(_) => true,
        Node::Mul(factors) => {
            factors.len() == 2 && pool.constant_value(factors[0]).is_some_and(|c| c == -1.0)
        }
        _ => false,
    }
}

/// The values at every state to ten significant digits, with the sign that
/// makes the first non-zero one positive; all zeros (below `1e-12`) key
/// as zero. `None` for a non-finite value.
fn rounded(at: &[f64]) -> Option<(Vec<i64>, f64)> {
    if at.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let sign = at
        .iter()
        .find(|v| v.abs() > 1e-12)
        .map_or(1.0, |v| v.signum());
    let key = at
        .iter()
        .flat_map(|&v| {
            let v = sign * v;
            if v.abs() <= 1e-12 {
                return [0, 0];
            }
            let exponent = v.abs().log10().floor();
            let mantissa = (v / 10f64.powf(exponent - 9.0)).round();
            [exponent as i64, mantissa as i64]
        })
        .collect();
    Some((key, sign))
}

/// Whether every member is the same operation on children of the same
/// groups: the duplication comes from a smaller group.
fn inherited(pool: &Pool, group: &[(ExprId, f64)], class: &HashMap<ExprId, usize>) -> bool {
    let shape = |e: ExprId| {
        let operands = pool.children(e);
        if operands.is_empty() {
            return None;
        }
        let mut classes: Vec<String> = operands
            .iter()
            .map(|c| {
                class
                    .get(c)
                    .map_or(format!("#{}", c.0), |k| format!("g{k}"))
            })
            .collect();
        classes.sort();
        Some((std::mem::discriminant(pool.node(e)), classes))
    };
    let first = shape(group[0].0);
    first.is_some() && group.iter().all(|&(e, _)| shape(e) == first)
}

/// `e` printed to `depth` levels, deeper nodes as `#id`.
pub fn shallow(pool: &Pool, e: ExprId, depth: usize) -> String {
    let join = |children: &[ExprId], separator: &str| {
        let parts: Vec<String> = children
            .iter()
            .map(|&c| shallow(pool, c, depth.saturating_sub(1)))
            .collect();
        format!("({})", parts.join(separator))
    };
    match pool.node(e) {
        Node::Number(n) => n.to_string(),
        Node::Sym(s) => symbol(*s),
        _ if depth == 0 => format!("#{}", e.0),
        Node::Add(terms) => join(terms, " + "),
        Node::Mul(factors) => join(factors, "·"),
        Node::Pow(base, exponent) => format!("{}^{exponent}", join(&[*base], "")),
        Node::Func(f, arg) => format!("{}{}", f.name(), join(&[*arg], "")),
        Node::Group(sum) => format!("group{}", join(&[*sum], "")),
    }
}

/// A symbol as the models name it (`q3`, `u1`, parameters by index).
fn symbol(s: Sym) -> String {
    match s {
        Sym::Time => "t".into(),
        Sym::Param(i) => format!("p{i}"),
        Sym::Coord(i) => format!("q{}", i + 1),
        Sym::Speed(i) => format!("v{}", i + 1),
        Sym::Accel(i) => format!("a{}", i + 1),
        Sym::Input(i) => format!("u{}", i + 1),
        Sym::Multiplier(i) => format!("λ{}", i + 1),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::{Family, chain};
    use crate::expr::test_util::Scratch;
    use crate::geometry::Values;
    use crate::outputs::Function;
    use crate::random::Random;

    /// Random states for a system of these sizes.
    struct States {
        parameters: Vec<f64>,
        rows: Vec<[Vec<f64>; 3]>,
    }

    impl States {
        fn new(np: usize, nq: usize, nv: usize, nu: usize) -> States {
            let mut random = Random::new(17);
            let mut draw = |n: usize, r: f64| (0..n).map(|_| random.uniform(-r, r)).collect();
            States {
                parameters: (0..np).map(|_| 1.0).collect(),
                rows: (0..3)
                    .map(|_| [draw(nq, 3.0), draw(nv, 2.0), draw(nu, 5.0)])
                    .collect(),
            }
        }

        fn values(&self) -> Vec<Values<'_>> {
            self.rows
                .iter()
                .map(|[q, qd, u]| Values {
                    parameters: &self.parameters,
                    t: 0.5,
                    q,
                    qd,
                    u,
                })
                .collect()
        }
    }

    #[test]
    fn finds_two_forms_of_one_value_and_their_negation() {
        let mut s = Scratch::default();
        let sum = s.e("sin(q0)*cos(q1) + cos(q0)*sin(q1)");
        let sine = s.e("sin(q0 + q1)");
        let negated = s.e("-sin(q0 + q1) + 0*q0 - q1 + q1");
        let other = s.e("sin(q0 - q1)");
        let roots = [sum, sine, other, negated];
        let point = |a: f64, b: f64| {
            crate::expr::test_util::Point([(Sym::Coord(0), a), (Sym::Coord(1), b)].into())
        };
        let (first, second) = (point(0.3, 1.1), point(-2.0, 0.4));
        let groups = duplicates(&s.pool, &roots, &[&first, &second]);
        assert_eq!(groups.len(), 1, "{groups:?}");
        let members: Vec<ExprId> = groups[0].members.iter().map(|m| m.0).collect();
        assert_eq!(members, vec![sum, sine], "the negation is trivially `sine`");
        // The sum of products is the dearer form, and no other node reads
        // its four halves of `sin_cos` and three operations.
        assert_eq!(groups[0].excess, 4 * 20 + 3, "{groups:?}");
    }

    /// The roots of the output `name` of `source` (`accelerations` and
    /// `mass_forcing` from the equations, others asked for) as generated.
    fn output(source: &str, name: &str) -> (Pool, Vec<ExprId>, States) {
        let close = source.rfind('}').unwrap();
        let asking = format!("{} outputs {name};\n}}", &source[..close]);
        let source = match name {
            "accelerations" | "mass_forcing" => source,
            _ => &asking,
        };
        let crate::Derivation {
            model,
            mut pool,
            equations,
            mut forms,
        } = crate::derive(crate::lex(source).unwrap()).unwrap();
        let roots = match name {
            "accelerations" => equations.articulated.as_ref().unwrap().roots(),
            "mass_forcing" => [equations.mass_matrix.concat(), equations.forcing.clone()].concat(),
            _ => {
                let mut requested =
                    crate::outputs::requested(&model, &equations, &mut pool).functions;
                crate::plan::optimize::optimize_functions(&mut requested, &mut pool, &mut forms);
                let function: &Function = requested.iter().find(|f| f.name == name).unwrap();
                function.roots()
            }
        };
        let states = States::new(
            model.parameters.len(),
            model.nq(),
            model.nv(),
            model.inputs.len(),
        );
        (pool, roots, states)
    }

    /// Prints the groups of one output, the costliest first; returns their
    /// total excess.
    fn report(label: &str, source: &str, name: &str) -> usize {
        let (pool, roots, states) = output(source, name);
        let values = states.values();
        let envs: Vec<&dyn Env> = values.iter().map(|v| v as &dyn Env).collect();
        let groups = duplicates(&pool, &roots, &envs);
        let total: usize = groups.iter().map(|g| g.excess).sum();
        println!(
            "== {label} {name}: {} operations, {} groups, excess {total}",
            operations(&pool, &roots),
            groups.len()
        );
        for group in groups.iter().take(12) {
            println!("  excess {}:", group.excess);
            for &(e, sign) in group.members.iter().take(4) {
                let (cone, own) = (
                    operations(&pool, &[e]),
                    exclusive_operations(&pool, &roots, e),
                );
                let text: String = shallow(&pool, e, 2).chars().take(150).collect();
                println!("    {sign:+} #{} ({cone} ops, {own} its own) {text}", e.0);
            }
        }
        total
    }

    #[test]
    #[ignore = "a report: prints the duplicated values of the benched systems"]
    fn report_benched_systems() {
        let spatial_12 = chain(Family::Spatial, 12);
        report("spatial 12", &spatial_12, "accelerations");
        report("spatial 12", &spatial_12, "mass_forcing");
        let planar = report(
            "planar 12",
            &chain(Family::Planar, 12),
            "accelerations_jacobian",
        );
        // The subtree's `ċ` and linear momentum, two nodes before `0f35c8c`,
        // showed as 81 groups of excess 838 (of 4051 operations).
        assert!(
            planar < 100,
            "planar 12's jacobian computes {planar} operations twice"
        );
        report(
            "spatial 6",
            &chain(Family::Spatial, 6),
            "accelerations_jacobian",
        );
        let urdf = |file: &str, floating: bool| {
            crate::Urdf::read(format!("../tests/reference/urdf/{file}"))
                .and_then(|u| u.floating(floating).model())
                .unwrap()
        };
        report("panda", &urdf("panda.urdf", false), "accelerations");
        report("solo12", &urdf("solo12.urdf", true), "mass_forcing");
        report(
            "panda",
            &urdf("panda.urdf", false),
            "accelerations_jacobian",
        );
        report("spatial 12", &spatial_12, "accelerations_jacobian");
    }
}
