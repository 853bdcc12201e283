//! The chains in the three spellings (`joint`s with literals, `joint`s with
//! symbolic parameters, the seed's frames and points with torque inputs)
//! give Pinocchio's `M`, `f = τ − nle`, `T` and `V` of
//! `tests/reference/chains.json` (τ = 0) and agree with each other at random
//! states at every size, 30 links included; and the checked-in models are
//! exactly what `dalembert_codegen::chain::chain_spelled` writes.

use dalembert_codegen::chain::{Family, Spelling, chain_spelled};
use dalembert_generated::*;
use serde_json::Value;

/// Relative tolerance (scaled by the largest entry of each quantity).
const TOLERANCE: f64 = 1e-12;

/// `M` (row by row), `f`, `T`, `V` of one system at one state.
type Evaluation = [Vec<f64>; 4];

/// Evaluates a generated system through its inherent methods at `q`, `qd`
/// with every input zero.
macro_rules! evaluate {
    ($system:expr, $q:expr, $qd:expr) => {{
        let system = $system;
        let (q, qd) = ($q, $qd);
        let u = [0.0; _];
        let mass: Vec<f64> = system.mass_matrix(q).concat();
        [
            mass,
            system.forcing(0.0, q, qd, &u).to_vec(),
            vec![system.kinetic_energy(q, qd)],
            vec![system.potential_energy(q)],
        ]
    }};
}

fn assert_agree(what: &str, ours: &Evaluation, theirs: &Evaluation) {
    for (name, (a, b)) in ["M", "f", "T", "V"].iter().zip(ours.iter().zip(theirs)) {
        assert_eq!(a.len(), b.len(), "{what} {name}: length");
        let scale = b.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            assert!(
                (x - y).abs() <= TOLERANCE * scale,
                "{what} {name}[{i}]: {x} vs {y} (scale {scale})"
            );
        }
    }
}

fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(items) => items.iter().flat_map(numbers).collect(),
        other => vec![other.as_f64().expect("a number")],
    }
}

/// Pinocchio's `M`, `−nle`, `T`, `V` and the state, for every state of the
/// `family` chain of `n` links.
fn references(family: Family, n: u64) -> Vec<(Vec<f64>, Vec<f64>, Evaluation)> {
    let text = include_str!("../../../tests/reference/chains.json");
    let reference: Value = serde_json::from_str(text).expect("chains.json parses");
    let model = reference["models"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["family"] == family.name() && m["n"] == n)
        .unwrap_or_else(|| panic!("no {} n={n} in chains.json", family.name()))
        .clone();
    let states = dalembert_fixtures::reference::states(&model);
    let special = model["special_states"].as_array().unwrap();
    states
        .iter()
        .chain(special)
        .map(|state| {
            let minus_nle = numbers(&state["nle"]).iter().map(|x| -x).collect();
            (
                numbers(&state["q"]),
                numbers(&state["qd"]),
                [
                    numbers(&state["M"]),
                    minus_nle,
                    vec![state["T"].as_f64().unwrap()],
                    vec![state["V"].as_f64().unwrap()],
                ],
            )
        })
        .collect()
}

/// Checks the systems against Pinocchio at every reference state.
macro_rules! against_pinocchio {
    ($family:expr, $n:literal, $($system:expr),+) => {{
        for (index, (q, qd, expected)) in references($family, $n).iter().enumerate() {
            let q: [f64; $n] = q.as_slice().try_into().unwrap();
            let qd: [f64; $n] = qd.as_slice().try_into().unwrap();
            $(
                let what = format!("{} at reference state {index}", stringify!($system));
                assert_agree(&what, &evaluate!(&$system, &q, &qd), expected);
            )+
        }
    }};
}

#[test]
fn symbolic_and_seed_spellings_match_pinocchio() {
    against_pinocchio!(
        Family::Planar,
        2,
        SymbolicPlanarChain2::reference(),
        SeedPlanarChain2::reference()
    );
    against_pinocchio!(
        Family::Planar,
        6,
        SymbolicPlanarChain6::reference(),
        SeedPlanarChain6::reference()
    );
    against_pinocchio!(
        Family::Spatial,
        2,
        SymbolicSpatialChain2::reference(),
        SeedSpatialChain2::reference()
    );
    against_pinocchio!(
        Family::Spatial,
        6,
        SymbolicSpatialChain6::reference(),
        SeedSpatialChain6::reference()
    );
}

/// The three spellings agree at random states.
macro_rules! spellings_agree {
    ($n:literal, $joints:expr, $symbolic:expr, $seed:expr) => {{
        let mut random = dalembert_codegen::testing::Random::new($n);
        for s in 0..8 {
            let q: [f64; $n] = std::array::from_fn(|_| random.uniform(-3.0, 3.0));
            let qd: [f64; $n] = std::array::from_fn(|_| random.uniform(-2.0, 2.0));
            let joints = evaluate!(&$joints, &q, &qd);
            let what = format!("{} state {s}", stringify!($joints));
            assert_agree(
                &format!("symbolic vs {what}"),
                &evaluate!(&$symbolic, &q, &qd),
                &joints,
            );
            assert_agree(
                &format!("seed vs {what}"),
                &evaluate!(&$seed, &q, &qd),
                &joints,
            );
        }
    }};
}

#[test]
fn the_three_spellings_agree_at_random_states() {
    spellings_agree!(
        2,
        PlanarChain2 {},
        SymbolicPlanarChain2::reference(),
        SeedPlanarChain2::reference()
    );
    spellings_agree!(
        12,
        PlanarChain12 {},
        SymbolicPlanarChain12::reference(),
        SeedPlanarChain12::reference()
    );
    spellings_agree!(
        30,
        PlanarChain30 {},
        SymbolicPlanarChain30::reference(),
        SeedPlanarChain30::reference()
    );
    spellings_agree!(
        2,
        SpatialChain2 {},
        SymbolicSpatialChain2::reference(),
        SeedSpatialChain2::reference()
    );
    spellings_agree!(
        12,
        SpatialChain12 {},
        SymbolicSpatialChain12::reference(),
        SeedSpatialChain12::reference()
    );
    spellings_agree!(
        30,
        SpatialChain30 {},
        SymbolicSpatialChain30::reference(),
        SeedSpatialChain30::reference()
    );
}

#[test]
fn checked_in_models_are_what_the_generator_writes() {
    for spelling in [Spelling::SymbolicJoints, Spelling::FramesAndPoints] {
        for family in [Family::Planar, Family::Spatial] {
            for n in [2, 6, 12, 30] {
                let path = format!(
                    "{}/models/{}_{}_chain_{n:02}.dal",
                    env!("CARGO_MANIFEST_DIR"),
                    spelling.name(),
                    family.name()
                );
                let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
                assert_eq!(
                    text,
                    chain_spelled(family, n, spelling),
                    "{path}: run `dalembert chain {} {n} {}`",
                    family.name(),
                    spelling.name()
                );
            }
        }
    }
}
