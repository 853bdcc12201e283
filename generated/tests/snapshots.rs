//! Snapshots of everything derived from `models/*.dal`: the generated Rust
//! and the rendered equations. Reviewing a change to a model or to the
//! derivation means reading the diff of `tests/snapshots/` (`cargo insta
//! test`); with `CI=true` a changed snapshot fails.
//!
//! The benchmark chains are snapshotted in full only at two links; longer
//! chains (up to 30 links, thousands of lines) as a summary: the operations
//! per call of each function, which is what a review of them needs.

mod common;

use dalembert_codegen::Style;

#[test]
fn generated_code() {
    for model in common::models().iter().filter(|m| m.is_small()) {
        insta::assert_snapshot!(format!("code_{}", model.name), model.generated());
    }
}

/// Operations per call of every chain's functions, one line per model.
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
    }
    insta::assert_snapshot!("chain_operation_counts", table);
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
/// the chains and robots that ask for the derivatives, and how many
/// columns the jacobian sends through the solve (whose body is counted
/// once: each call costs about `n²` more).
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
    ] {
        let path = std::path::Path::new(env!("OUT_DIR")).join(format!("derivatives/{name}.rs"));
        let code = std::fs::read_to_string(&path).expect("the generated copy");
        for function in ["accelerations", "accelerations_jacobian"] {
            table.push_str(&format!(
                "{name:16} {function:22} {}\n",
                common::operations(&code, function)
            ));
        }
        // `solve(` once for `v̇`, once per column solved.
        let columns = code.matches("solve(").count() - 1;
        table.push_str(&format!("{name:16} columns solved {columns}\n"));
    }
    insta::assert_snapshot!("derivative_operation_counts", table);
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
    let lib = include_str!("../src/lib.rs");
    for model in common::models() {
        assert!(
            lib.contains(&format!("    {}\n);", model.name)),
            "models/{0}.dal is not included: add `model!({0});` to src/lib.rs",
            model.name
        );
    }
}
