//! The benchmark chains against Pinocchio's numbers in
//! `tests/reference/chains.json` (both families, n = 1..6, 10 random and 2
//! special states each): `M`, `f = τ − nle` (our chains have no inputs, so
//! `forcing = −nle`), `T`, `V` and the accelerations — of the runtime's
//! `dalembert::__private::cholesky_accelerations` and of the generated, unrolled
//! `accelerations` method, which also agree with each other, the latter being
//! what `dalembert::accelerations` calls. And the checked-in
//! `models/*_chain_NN.dal` are exactly what `dalembert_codegen::chain::chain` writes.

use dalembert::{DynamicsError, MultibodySystem};
use dalembert_codegen::chain::Family;
use dalembert_generated::*;
use serde_json::Value;

/// Relative tolerance on `M`, `f`, `T`, `V` (scaled by the largest entry).
const TOLERANCE: f64 = 1e-12;
/// Relative tolerance on `q̈` (README: `M` gets ill-conditioned).
const ACCELERATION_TOLERANCE: f64 = 1e-10;

fn reference() -> Value {
    dalembert_fixtures::reference::reference("chains.json")
}

fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(items) => items.iter().flat_map(numbers).collect(),
        other => vec![other.as_f64().expect("a number")],
    }
}

/// `|got − want| ≤ tolerance · max(1, max|want|)`, entry by entry.
fn assert_close(what: &str, got: &[f64], want: &[f64], tolerance: f64) {
    assert_eq!(got.len(), want.len(), "{what}: length");
    let scale = want.iter().fold(1.0_f64, |m, w| m.max(w.abs()));
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= tolerance * scale,
            "{what}[{i}]: {g} vs {w} (scale {scale})"
        );
    }
}

/// The generated `accelerations` method of a system, at `t = 0`, `u = []`.
type Accelerations<const N: usize> =
    dyn Fn(&[f64; N], &[f64; N]) -> Result<[f64; N], DynamicsError>;

/// Checks `system` (whose generated `accelerations` is `unrolled`) against
/// every state of the reference model `model`.
fn check<S: MultibodySystem<N, N, 0>, const N: usize>(
    system: &S,
    unrolled: &Accelerations<N>,
    model: &Value,
) {
    let name = format!("{} n={}", model["family"], model["n"]);
    let states = model["states"].as_array().unwrap();
    let special = model["special_states"].as_array().unwrap();
    assert_eq!(states.len() + special.len(), 12, "{name}");
    for (index, state) in states.iter().chain(special).enumerate() {
        let what = |field: &str| format!("{name} state {index} {field}");
        let array =
            |field: &str| -> [f64; N] { numbers(&state[field]).try_into().expect("n entries") };
        let (q, qd) = (array("q"), array("qd"));
        let mass = system.mass_matrix(&q);
        assert_close(
            &what("M"),
            mass.as_flattened(),
            &numbers(&state["M"]),
            TOLERANCE,
        );
        let minus_nle: Vec<f64> = numbers(&state["nle"]).iter().map(|x| -x).collect();
        assert_close(
            &what("f"),
            &system.forcing(0.0, &q, &qd, &[]),
            &minus_nle,
            TOLERANCE,
        );
        let t = state["T"].as_f64().unwrap();
        assert_close(
            &what("T"),
            &[system.kinetic_energy(&q, &qd)],
            &[t],
            TOLERANCE,
        );
        let v = state["V"].as_f64().unwrap();
        assert_close(&what("V"), &[system.potential_energy(&q)], &[v], TOLERANCE);
        // With τ = 0 our forcing gives the free motion: q̈ = M⁻¹(−nle).
        let free = dalembert::__private::cholesky_accelerations(system, 0.0, &q, &qd, &[])
            .expect("solvable");
        let mass_reference = numbers(&state["M"]);
        let residual: Vec<f64> = (0..N)
            .map(|i| (0..N).map(|j| mass_reference[i * N + j] * free[j]).sum())
            .collect();
        assert_close(&what("M q̈"), &residual, &minus_nle, ACCELERATION_TOLERANCE);
        let specialised = unrolled(&q, &qd).expect("solvable");
        assert_close(
            &what("q̈ unrolled"),
            &specialised,
            &free,
            ACCELERATION_TOLERANCE,
        );
        // The runtime's entry point uses the system's own unrolled solver.
        assert_eq!(
            dalembert::accelerations(system, 0.0, &q, &qd, &[]),
            Ok(specialised),
            "{}",
            what("dalembert::accelerations")
        );
    }
    let nan = [f64::NAN; N];
    assert_eq!(unrolled(&nan, &nan), Err(DynamicsError::NonFiniteState));
}

/// Checks the generated system `$system` against reference model `$n` of
/// `$family`.
macro_rules! check {
    ($reference:expr, $family:expr, $n:literal, $system:ident) => {
        check(
            &$system {},
            &|q, qd| $system {}.accelerations(0.0, q, qd, &[]),
            model(&$reference, $family, $n),
        )
    };
}

/// The reference model of `family` with `n` links.
fn model(reference: &Value, family: Family, n: u64) -> &Value {
    reference["models"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["family"] == family.name() && m["n"] == n)
        .unwrap_or_else(|| panic!("no {} n={n} in chains.json", family.name()))
}

#[test]
fn planar_chains_match_pinocchio() {
    let r = reference();
    let family = Family::Planar;
    check!(r, family, 1, PlanarChain1);
    check!(r, family, 2, PlanarChain2);
    check!(r, family, 3, PlanarChain3);
    check!(r, family, 4, PlanarChain4);
    check!(r, family, 5, PlanarChain5);
    check!(r, family, 6, PlanarChain6);
}

#[test]
fn spatial_chains_match_pinocchio() {
    let r = reference();
    let family = Family::Spatial;
    check!(r, family, 1, SpatialChain1);
    check!(r, family, 2, SpatialChain2);
    check!(r, family, 3, SpatialChain3);
    check!(r, family, 4, SpatialChain4);
    check!(r, family, 5, SpatialChain5);
    check!(r, family, 6, SpatialChain6);
}

/// `models/FAMILY_chain_NN.dal` is `chain(FAMILY, NN)`, byte for byte.
#[test]
fn chain_models_are_what_the_generator_writes() {
    let mut seen = 0;
    for model in common::models() {
        let Some((family, n)) = model.name.split_once("_chain_") else {
            continue;
        };
        // The other spellings (`symbolic_planar_chain_06`) are checked by
        // tests/spellings.rs.
        let Some(family) = Family::from_name(family) else {
            continue;
        };
        let n: usize = n.parse().expect("a link count");
        assert_eq!(
            model.source,
            dalembert_codegen::chain::chain(family, n),
            "models/{}.dal is stale: rewrite it with `dalembert chain {} {n}`",
            model.name,
            family.name()
        );
        seen += 1;
    }
    assert!(seen >= 12, "only {seen} chain models");
}

use crate::common;
