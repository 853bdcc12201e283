//! The MuJoCo models of `tests/reference/mjcf/` that `build.rs` imports
//! with `Builder::mjcf` (dm_control's cheetah and humanoid), compiled,
//! against MuJoCo's numbers in `tests/reference/mjcf/mujoco.json`
//! (`scripts/mjcf_reference.py`): `M` (armature included), `f`, `T`, `V`
//! and the generated `accelerations` (the articulated-body recursion with
//! the armature on its pivots), in our conventions.

use dalembert_generated::{Cheetah, Humanoid};
use serde_json::Value;

/// Relative agreement required, against the largest entry of the quantity.
const TOLERANCE: f64 = 1e-12;

/// The reference states of `model`.
fn states(model: &str) -> Vec<Value> {
    let text = include_str!("../../../tests/reference/mjcf/mujoco.json");
    let reference: Value = serde_json::from_str(text).expect("mujoco.json parses");
    let entry = reference["models"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["model"] == model)
        .expect("model in mujoco.json");
    let states = entry["states"].as_array().unwrap().clone();
    assert!(!states.is_empty());
    states
}

/// The numbers of `v`, flattened.
fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(items) => items.iter().flat_map(numbers).collect(),
        other => vec![other.as_f64().expect("a number")],
    }
}

fn array<const N: usize>(v: &Value) -> [f64; N] {
    numbers(v)
        .try_into()
        .expect("as many entries as the system has")
}

/// `max |got − want|` over `max |want|`.
fn relative_error(got: &[f64], want: &[f64]) -> f64 {
    assert_eq!(got.len(), want.len());
    let scale = want.iter().fold(f64::MIN_POSITIVE, |m, w| m.max(w.abs()));
    got.iter()
        .zip(want)
        .fold(0.0_f64, |m, (g, w)| m.max((g - w).abs()))
        / scale
}

/// Every quantity of a compiled system at every reference state of
/// `$model`, within [`TOLERANCE`].
macro_rules! matches_mujoco {
    ($system:ident, $model:literal) => {{
        let system = $system {};
        for state in states($model) {
            let (q, v, tau) = (
                array(&state["q"]),
                array(&state["qd"]),
                array(&state["tau"]),
            );
            let got = [
                system.mass_matrix(&q).as_flattened().to_vec(),
                system.forcing(0.0, &q, &v, &tau).to_vec(),
                vec![system.kinetic_energy(&q, &v)],
                vec![system.potential_energy(&q)],
                system
                    .accelerations(0.0, &q, &v, &tau)
                    .expect("solvable")
                    .to_vec(),
            ];
            for (got, field) in got.iter().zip(["M", "f", "T", "V", "qdd"]) {
                let error = relative_error(got, &numbers(&state[field]));
                assert!(error <= TOLERANCE, "{} {field}: off by {error:e}", $model);
            }
        }
    }};
}

#[test]
fn cheetah_matches_mujoco() {
    matches_mujoco!(Cheetah, "cheetah");
}

#[test]
fn humanoid_matches_mujoco() {
    matches_mujoco!(Humanoid, "humanoid");
    assert_eq!(
        Humanoid::COORDINATES[..7],
        [
            "root_x", "root_y", "root_z", "root_qx", "root_qy", "root_qz", "root_qw"
        ]
    );
    assert_eq!(Humanoid::NU, 21);
}
