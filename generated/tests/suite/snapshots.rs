//! Snapshots of everything derived from `models/*.dal`: the generated Rust
//! and the rendered equations. Reviewing a change to a model or to the
//! derivation means reading the diff of `tests/suite/snapshots/` (`cargo insta
//! test`); with `CI=true` a changed snapshot fails.
//!
//! The benchmark chains are snapshotted in full only at two links; longer
//! chains (up to 30 links, thousands of lines) as a summary: the operations
//! per call of each function, which is what a review of them needs.

use crate::common;

use dalembert_codegen::Style;

#[test]
fn generated_code() {
    for model in common::models().iter().filter(|m| m.is_small()) {
        insta::assert_snapshot!(format!("code_{}", model.name), model.generated());
    }
}

/// Operations per call of every chain's functions, one line per model
/// (and the run-time loop of a `mass_matrix` that takes its pairs in one).
#[test]
fn chain_operation_counts() {
    let mut table = String::new();
    for model in common::models()
        .iter()
        .filter(|m| m.name.contains("_chain_"))
    {
        let code = model.generated();
        for function in ["mass_matrix", "forcing"] {
            table.push_str(&format!(
                "{:18} {:12} {}\n",
                model.name,
                function,
                common::operations(&code, function)
            ));
        }
        if let Some((pairs, operations)) = mass_pair_operations(&code) {
            table.push_str(&format!(
                "{:18} mass_matrix pairs looped: {pairs} pairs, {operations} operations\n",
                model.name
            ));
        }
    }
    insta::assert_snapshot!("chain_operation_counts", table);
}

/// The pairs of speeds that `mass_matrix` takes in a loop at run time
/// (`dalembert::__private::tree_mass_matrix`, its table of `TreeSpeed`s
/// `{ end, speed }`, speed `i` paired with the entries from `i` to before
/// `end`), if it does, and that loop's operations: a dot product of six
/// (11 operations) a pair.
fn mass_pair_operations(code: &str) -> Option<(usize, usize)> {
    let tokens = flat_tokens(code);
    let text = |t: &proc_macro2::TokenTree| t.to_string();
    let ends: Vec<usize> = tokens
        .windows(5)
        .filter(|w| text(&w[0]) == "TreeSpeed" && text(&w[2]) == "end")
        .map(|w| text(&w[4]).parse().expect("an end"))
        .collect();
    let pairs: usize = ends.iter().enumerate().map(|(i, end)| end - i).sum();
    (!ends.is_empty()).then_some((pairs, 11 * pairs))
}

/// Operations per call of the URDF robots' `mass_matrix`, `forcing` and
/// `accelerations` (their benchmarks' functions), one line each.
#[test]
fn robot_operation_counts() {
    let mut table = String::new();
    for name in ["panda", "ur5_robot", "solo12", "floating_solo12"] {
        let path = std::path::Path::new(env!("OUT_DIR")).join(format!("{name}.rs"));
        let code = std::fs::read_to_string(&path).expect("the generated robot");
        for function in ["mass_matrix", "forcing", "accelerations"] {
            table.push_str(&format!(
                "{name:16} {function:14} {}\n",
                common::operations(&code, function)
            ));
        }
    }
    insta::assert_snapshot!("robot_operation_counts", table);
}

/// Operations per call of `accelerations` and `accelerations_jacobian` of
/// the chains, the branching tree and the robots that ask for the derivatives, and the solve of
/// the jacobian: how many columns of `∂τ/∂x` it takes and its operations at
/// run time (each row operation `scale_and_subtract` loops over the
/// columns, so the body counts leave it out).
#[test]
fn derivative_operation_counts() {
    let mut table = String::new();
    for name in [
        "planar_chain_06",
        "planar_chain_12",
        "spatial_chain_06",
        "spatial_chain_12",
        "panda",
        "ur5_robot",
        "spatial_tree_14",
    ] {
        let path = std::path::Path::new(env!("OUT_DIR")).join(format!("derivatives/{name}.rs"));
        let code = std::fs::read_to_string(&path).expect("the generated copy");
        for function in ["accelerations", "accelerations_jacobian"] {
            table.push_str(&format!(
                "{name:16} {function:22} {}\n",
                common::operations(&code, function)
            ));
        }
        let (columns, operations) = solve_operations(&code);
        table.push_str(&format!(
            "{name:16} solve: {columns} columns, {operations} operations\n"
        ));
        if let Some(parents) = tree_parents(&code) {
            let (links, operations) = link_operations(&parents);
            table.push_str(&format!(
                "{name:16} links looped: {links} links, {operations} operations\n"
            ));
            let (pairs, operations, mass) = pair_operations(&parents);
            table.push_str(&format!(
                "{name:16} pairs looped: {pairs} pairs, {operations} operations\n"
            ));
            table.push_str(&format!(
                "{name:16} mass looped: {pairs} entries, {mass} operations\n"
            ));
        }
    }
    insta::assert_snapshot!("derivative_operation_counts", table);
}

/// The token trees of `code`, flattened through every group.
fn flat_tokens(code: &str) -> Vec<proc_macro2::TokenTree> {
    use proc_macro2::{TokenStream, TokenTree};
    fn flat(stream: TokenStream, out: &mut Vec<TokenTree>) {
        for token in stream {
            out.push(token.clone());
            if let TokenTree::Group(group) = token {
                flat(group.stream(), out);
            }
        }
    }
    let mut tokens = Vec::new();
    flat(code.parse().expect("generated code lexes"), &mut tokens);
    tokens
}

/// The parent of each link of the tree whose partials the jacobian
/// computes in loops at run time (its table of `TreeLink`s), if it does.
fn tree_parents(code: &str) -> Option<Vec<Option<usize>>> {
    let tokens = flat_tokens(code);
    let text = |t: &proc_macro2::TokenTree| t.to_string();
    // `TreeLink { parent: P, … }`, `P` a number or `usize::MAX`.
    let parents: Vec<Option<usize>> = tokens
        .windows(5)
        .filter(|w| text(&w[0]) == "TreeLink" && text(&w[2]) == "parent")
        .map(|w| text(&w[4]).parse().ok())
        .collect();
    (!parents.is_empty()).then_some(parents)
}

/// The links of the loops of `dalembert::__private::TreeRecursion` and
/// their operations, counted in its source (`src/dynamics/tree_vectors.rs`):
/// per link, in the first pass, 189 outwards, 351 for its own inertia in
/// `N` with its rate, momentum and force, 42 for `y` and 11 for its entry
/// of `f`; in the second, 114 for `Ψ̈`'s term `a_λ × S` and what `q̈`
/// changes and 288 for `z, w, u`; 43 to add each subtree into its parent
/// (37 and 6); 3 to negate gravity. The general path of each step: a turn
/// skips 18 of the outward step's (`R b`, `b = 0`), a slide 27, and an
/// inertia tensor diagonal in its link's axes 36 of `R K Rᵀ`.
fn link_operations(parents: &[Option<usize>]) -> (usize, usize) {
    let children = parents.iter().flatten().count();
    let links = parents.len();
    (links, 995 * links + 43 * children + 3)
}

/// The pairs of joints that the jacobian adds in a loop at run time
/// (`dalembert::__private::add_tree_pairs`) and that loop's operations: per
/// link and each of it and its ancestors 4 dot products of six (11
/// operations each) and 4 additions, and with each ancestor 2 more dot
/// products and 2 additions (4 and 4 with an ancestor of the link's own
/// joint, none in these models); and the operations of its mass matrix
/// (`TreeRecursion::mass_and_bias`), one dot product of six a pair.
fn pair_operations(parents: &[Option<usize>]) -> (usize, usize, usize) {
    let depth = |mut link: usize| {
        let mut depth = 0;
        while let Some(parent) = parents[link] {
            (depth, link) = (depth + 1, parent);
        }
        depth
    };
    let ancestors: usize = (0..parents.len()).map(depth).sum();
    let pairs = parents.len() + ancestors;
    (pairs, 48 * pairs + 24 * ancestors, 11 * pairs)
}

/// The columns of the jacobian's solve (`let [mut b0, …]: [[f64; C]; N]`) and
/// its multiplications and subtractions at run time: per call of
/// `scale_and_subtract(row, factor, [(l, other), …])`, `2 C` per term and
/// `C` for a factor other than `1.0`; per call of
/// `subtract_on_runs(row, [(l, other), …], &[(start, end), …])`, two per
/// term and column of its runs.
fn solve_operations(code: &str) -> (usize, usize) {
    use proc_macro2::{Delimiter, TokenTree};
    let tokens = flat_tokens(code);
    let text = |t: &TokenTree| t.to_string();
    let rows = tokens
        .windows(2)
        .position(|w| text(&w[0]) == "mut" && text(&w[1]) == "b0")
        .expect("the rows of the jacobian's solve");
    let columns: usize = tokens[rows..]
        .windows(3)
        .find(|w| text(&w[0]) == "f64" && text(&w[1]) == ";")
        .map(|w| text(&w[2]).parse().expect("a number of columns"))
        .expect("the jacobian's columns");
    // The argument tokens of every call of `name`.
    let calls = |name: &'static str| {
        tokens
            .windows(2)
            .filter(move |w| text(&w[0]) == name)
            .map(move |w| match &w[1] {
                TokenTree::Group(arguments) => arguments.stream(),
                _ => panic!("a call of {name}"),
            })
    };
    let per_column: usize = calls("scale_and_subtract")
        .map(|arguments| {
            let arguments: Vec<TokenTree> = arguments.into_iter().collect();
            let mut parts = arguments.split(|t| text(t) == ",");
            let (_, factor, terms) = (parts.next(), parts.next(), parts.next());
            let scaling = usize::from(factor.map(|f| f.iter().map(text).collect::<String>())
                != Some("1.0".into()));
            let terms = match terms.and_then(|t| t.first()) {
                Some(TokenTree::Group(list)) => list
                    .stream()
                    .into_iter()
                    .filter(|t| matches!(t, TokenTree::Group(g) if g.delimiter() == Delimiter::Parenthesis))
                    .count(),
                _ => panic!("an array of terms"),
            };
            2 * terms + scaling
        })
        .sum();
    let in_runs: usize = calls("subtract_on_runs")
        .map(|arguments| {
            let groups: Vec<TokenTree> = arguments
                .into_iter()
                .filter(|t| matches!(t, TokenTree::Group(g) if g.delimiter() == Delimiter::Bracket))
                .collect();
            let pairs = |list: &TokenTree| -> Vec<Vec<usize>> {
                let TokenTree::Group(list) = list else {
                    panic!("a list")
                };
                list.stream()
                    .into_iter()
                    .filter_map(|t| match t {
                        TokenTree::Group(g) if g.delimiter() == Delimiter::Parenthesis => Some(
                            g.stream()
                                .into_iter()
                                .filter_map(|t| text(&t).parse().ok())
                                .collect(),
                        ),
                        _ => None,
                    })
                    .collect()
            };
            let [terms, runs] = [&groups[0], &groups[1]];
            let width: usize = pairs(runs).iter().map(|run| run[1] - run[0]).sum();
            2 * pairs(terms).len() * width
        })
        .sum();
    (columns, columns * per_column + in_runs)
}

#[test]
fn rendered_equations() {
    for model in common::models().iter().filter(|m| m.is_small()) {
        let text = dalembert_codegen::equations(&model.source, Style::Unicode)
            .unwrap_or_else(|e| panic!("{}: {e}", model.name));
        insta::assert_snapshot!(format!("eom_{}", model.name), text);
    }
}

/// The compiled file is exactly `generate(model)`, and generating twice in
/// one process gives the same bytes (no hash-order dependence).
#[test]
fn build_output_is_the_deterministic_generate() {
    for model in common::models() {
        let first = dalembert_codegen::generate(&model.source).expect("generate");
        let second = dalembert_codegen::generate(&model.source).expect("generate");
        assert_eq!(first, second, "{}: output differs between runs", model.name);
        assert_eq!(model.generated(), first, "{}: OUT_DIR is stale", model.name);
    }
}

/// `src/lib.rs` includes every model, so each one is compiled as well as
/// snapshotted.
#[test]
fn every_model_is_included() {
    let lib = include_str!("../../src/lib.rs");
    for model in common::models() {
        assert!(
            lib.contains(&format!("    {}\n);", model.name)),
            "models/{0}.dal is not included: add `model!({0});` to src/lib.rs",
            model.name
        );
    }
}
