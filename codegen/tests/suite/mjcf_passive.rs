//! MJCF passive forces the import used to get wrong, against MuJoCo 4.0's
//! values in `tests/reference/mjcf/passive.json`
//! (`scripts/mjcf_reference.py --files features/gravcomp.xml
//! features/free_armature.xml --out tests/reference/mjcf/passive.json`),
//! on d'Alembert's route (and Lagrange's where every speed is its
//! coordinate's rate):
//!
//! * bodies with `gravcomp`: MuJoCo holds up that fraction of each body's
//!   weight by a passive force at its centre of mass (`qfrc_gravcomp`,
//!   not in the potential energy); the import dropped it, and `f` differed
//!   by the weight held up;
//! * a free joint's `armature`: MuJoCo adds it on the linear speeds in
//!   world axes, which in the body's axes (ours) also turns with the body
//!   (`a ω × v`); the import added only `M`'s diagonal, and `f` differed.
//!
//! What the import cannot write is refused (`mjcf_refusals.rs`).

use crate::pinocchio::{QUANTITIES, worst_errors};

use dalembert_codegen::Mjcf;
use dalembert_codegen::testing::Route;
use serde_json::Value;

/// The imported model of `name` matches MuJoCo's values on `routes`;
/// returns its text.
fn matches_mujoco(name: &str, routes: &[Route]) -> String {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/reference/mjcf");
    let text = std::fs::read_to_string(dir.join("passive.json")).unwrap();
    let reference: Value = serde_json::from_str(&text).unwrap();
    let entry = reference["models"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["model"] == name)
        .unwrap_or_else(|| panic!("no reference for {name}"));
    assert!(!entry["states"].as_array().unwrap().is_empty());
    let model = Mjcf::read(dir.join(entry["file"].as_str().unwrap()))
        .unwrap()
        .model()
        .unwrap();
    for &route in routes {
        let worst = worst_errors(&model, entry, route).unwrap();
        for (error, what) in worst.iter().zip(QUANTITIES) {
            assert!(
                *error <= 1e-12,
                "{name}: {what} ({route:?}) off by {error:e} relative"
            );
        }
    }
    model
}

#[test]
fn gravity_compensation_matches_mujoco() {
    let model = matches_mujoco("gravcomp", &[Route::Dalembert, Route::Lagrange]);
    assert_eq!(
        model.matches("// Gravity compensation").count(),
        2,
        "{model}"
    );
}

#[test]
fn a_free_joints_armature_matches_mujoco() {
    let model = matches_mujoco("free_armature", &[Route::Dalembert]);
    assert!(model.contains("armature 0.1 on f_vx;"), "{model}");
}
