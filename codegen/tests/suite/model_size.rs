//! The size guards: the engine's work is estimated before derivation
//! (`derivation_estimate`) and every generated function's operations
//! before emission (`function_sizes`), both printed by `dalembert check
//! MODEL.dal --stats`, and grow with the links and the outputs asked for;
//! a model over `DERIVATION_LIMIT` is refused before its derivation starts,
//! one over `OPERATION_LIMIT` before emission (the messages: `size.rs`'s
//! unit tests).

use std::path::Path;

use dalembert_codegen::chain::{Family, Spelling, chain_spelled};
use dalembert_codegen::{
    DERIVATION_LIMIT, OPERATION_LIMIT, check, derivation_estimate, function_sizes,
};

/// The seed-spelled spatial chain of `n` links asking for `outputs`.
fn chain_with(n: usize, outputs: &str) -> String {
    let text = chain_spelled(Family::Spatial, n, Spelling::FramesAndPoints);
    let end = text.rfind('}').unwrap();
    format!("{}    outputs {outputs};\n{}", &text[..end], &text[end..])
}

/// The largest function's estimate.
fn largest(source: &str) -> usize {
    let sizes = function_sizes(source).unwrap();
    sizes.iter().map(|s| s.operations).max().unwrap()
}

#[test]
fn every_function_is_estimated_and_grows_with_links_and_outputs() {
    let sizes = function_sizes(&chain_with(3, "accelerations_jacobian, linearize")).unwrap();
    let names: Vec<_> = sizes.iter().map(|s| s.name.as_str()).collect();
    for name in [
        "mass_matrix",
        "forcing",
        "accelerations_jacobian",
        "linearize",
    ] {
        assert!(names.contains(&name), "{name}: {names:?}");
    }
    // `linearize` of a tree without constraints computes nothing itself
    // (it assembles `accelerations_jacobian`'s results).
    let mut computing = sizes.iter().filter(|s| s.name != "linearize");
    assert!(computing.all(|s| s.operations > 0), "{sizes:?}");
    let plain = largest(&chain_spelled(
        Family::Spatial,
        3,
        Spelling::FramesAndPoints,
    ));
    let (three, six) = (
        largest(&chain_with(3, "accelerations_jacobian, linearize")),
        largest(&chain_with(6, "accelerations_jacobian, linearize")),
    );
    println!(
        "largest function: {plain} (3 links, no outputs), {three} (3, derivatives), {six} (6)"
    );
    assert!(plain < three && three < six && six < OPERATION_LIMIT);
}

#[test]
fn check_stats_prints_the_estimates() {
    let model =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../generated/models/double_pendulum.dal");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_dalembert"))
        .args(["check", model.to_str().unwrap(), "--stats"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains(": ok"), "{text}");
    assert!(text.contains(&format!("limit {OPERATION_LIMIT}")), "{text}");
    assert!(text.contains("estimated derivation: "), "{text}");
    let mass = text
        .lines()
        .find(|l| l.trim_end().ends_with("mass_matrix"))
        .unwrap();
    let count: usize = mass.split_whitespace().next().unwrap().parse().unwrap();
    assert!(count > 0, "{text}");
    // `--stats` belongs to `check`.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_dalembert"))
        .args(["generate", model.to_str().unwrap(), "--stats"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
}

#[test]
fn a_chain_too_long_to_derive_is_refused_before_its_derivation() {
    // 200 links with derivatives: over the limit (132 s of the engine's
    // CPU time and 2.7 GB where it was measured), refused at once.
    let long = chain_with(200, "accelerations_jacobian, linearize");
    let estimate = derivation_estimate(&long).unwrap();
    assert_eq!(estimate.speeds, 200);
    assert!(estimate.derivatives && estimate.units > DERIVATION_LIMIT);
    let started = std::time::Instant::now();
    let message = check(&long).unwrap_err().to_string();
    assert!(message.contains("too large to derive"), "{message}");
    assert!(started.elapsed().as_secs() < 30, "{:?}", started.elapsed());
    // The same chain without derivatives is within it.
    let plain = chain_spelled(Family::Spatial, 200, Spelling::FramesAndPoints);
    let estimate = derivation_estimate(&plain).unwrap();
    assert!(!estimate.derivatives && estimate.units < DERIVATION_LIMIT);
}
