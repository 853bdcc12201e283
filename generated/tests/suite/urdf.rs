//! The URDF robots of `tests/reference/urdf/`, imported by `Builder::urdf`
//! in `build.rs` and compiled, against Pinocchio's numbers in
//! `tests/reference/urdf/pinocchio.json` (`scripts/urdf_reference.py`, with
//! Pinocchio's own URDF parser): `M`, `f = τ − nle`, `T`, `V` and the
//! accelerations of the generated `accelerations` method (ABA's `q̈`).
//! And the imported model text, for review, as insta snapshots.

use dalembert_generated::{Anymal, FeatureTree, FloatingSolo, Panda, Solo, Ur5};
use serde_json::Value;

fn reference() -> Value {
    let text = include_str!("../../../tests/reference/urdf/pinocchio.json");
    serde_json::from_str(text).expect("pinocchio.json parses")
}

fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(items) => items.iter().flat_map(numbers).collect(),
        other => vec![other.as_f64().expect("a number")],
    }
}

/// The numbers of `v` as an array of the length the caller needs.
fn array<const N: usize>(v: &Value) -> [f64; N] {
    numbers(v)
        .try_into()
        .expect("as many entries as the system has")
}

/// Checks `max |got − want| ≤ tolerance · max |want|`; returns the ratio.
fn assert_close(what: &str, got: &[f64], want: &[f64], tolerance: f64) -> f64 {
    assert_eq!(got.len(), want.len(), "{what}: length");
    let scale = want.iter().fold(f64::MIN_POSITIVE, |m, w| m.max(w.abs()));
    let error = got
        .iter()
        .zip(want)
        .fold(0.0_f64, |m, (g, w)| m.max((g - w).abs()));
    assert!(
        error <= tolerance * scale,
        "{what}: off by {:e} relative",
        error / scale
    );
    error / scale
}

/// Checks a generated robot against the reference model `robot`: every
/// quantity within `tolerance` of its largest entry (set at about ten times
/// the agreement measured, which each test's comment gives).
macro_rules! check {
    ($system:ident, $robot:literal, $tolerance:expr) => {{
        let system = $system {};
        let reference = reference();
        let model = reference["models"]
            .as_array()
            .unwrap()
            .iter()
            .find(|m| m["robot"] == $robot)
            .expect("robot in pinocchio.json");
        let names: Vec<&str> = model["coordinates"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c.as_str().unwrap())
            .collect();
        assert_eq!(names, $system::COORDINATES, "{}", $robot);
        let mut worst = [0.0_f64; 5];
        for (index, state) in dalembert_fixtures::reference::states(model)
            .iter()
            .enumerate()
        {
            let what = |field: &str| format!("{} state {index} {field}", $robot);
            let (q, qd, tau) = (
                array(&state["q"]),
                array(&state["qd"]),
                array(&state["tau"]),
            );
            let mass = system.mass_matrix(&q);
            let f = system.forcing(0.0, &q, &qd, &tau);
            let t = system.kinetic_energy(&q, &qd);
            let v = system.potential_energy(&q);
            let qdd = system.accelerations(0.0, &q, &qd, &tau).expect("solvable");
            let errors = [
                assert_close(
                    &what("M"),
                    mass.as_flattened(),
                    &numbers(&state["M"]),
                    $tolerance,
                ),
                assert_close(&what("f"), &f, &numbers(&state["f"]), $tolerance),
                assert_close(&what("T"), &[t], &numbers(&state["T"]), $tolerance),
                assert_close(&what("V"), &[v], &numbers(&state["V"]), $tolerance),
                assert_close(&what("qdd"), &qdd, &numbers(&state["qdd"]), $tolerance),
            ];
            for (w, e) in worst.iter_mut().zip(errors) {
                *w = w.max(e);
            }
        }
        eprintln!(
            "{}: worst relative errors M {:.1e}, f {:.1e}, T {:.1e}, V {:.1e}, qdd {:.1e}",
            $robot, worst[0], worst[1], worst[2], worst[3], worst[4]
        );
    }};
}

#[test]
fn panda_matches_pinocchio() {
    // Measured: M 5.4e-16, f 4.7e-16, T 7.8e-16, V 6.0e-16, q̈ 5.1e-15.
    check!(Panda, "panda", 5e-14);
}

#[test]
fn ur5_matches_pinocchio() {
    // Measured: M 3.9e-16, f 3.4e-16, T 5.7e-16, V 4.5e-16, q̈ 2.3e-16.
    check!(Ur5, "ur5_robot", 1e-14);
}

#[test]
fn solo12_matches_pinocchio() {
    // Measured: M 8.4e-16, f 3.6e-16, T 3.4e-16, V 7.8e-15, q̈ 1.6e-15.
    check!(Solo, "solo12", 1e-13);
}

#[test]
fn anymal_c_matches_pinocchio() {
    // Measured: M 9.4e-16, f 5.0e-16, T 8.0e-16, V 6.2e-16, q̈ 1.9e-15.
    check!(Anymal, "anymal_c", 2e-14);
}

#[test]
fn floating_solo12_matches_pinocchio_free_flyer() {
    // Measured: M 1.5e-17, f 5.2e-16, T 6.1e-16, V 5.0e-16, q̈ 6.2e-15.
    check!(FloatingSolo, "solo12_floating", 1e-13);
}

/// The checked-in floating model is what the importer writes today.
#[test]
fn floating_solo12_is_the_imported_model() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let model = dalembert_codegen::Urdf::read(root.join("../tests/reference/urdf/solo12.urdf"))
        .map(|urdf| urdf.floating(true).name("FloatingSolo"))
        .and_then(|urdf| urdf.model())
        .expect("imports");
    let checked_in = std::fs::read_to_string(root.join("models/floating_solo12.dal"))
        .expect("models/floating_solo12.dal");
    assert_eq!(
        model, checked_in,
        "regenerate with `dalembert urdf tests/reference/urdf/solo12.urdf --floating --name FloatingSolo`"
    );
}

#[test]
fn feature_robot_matches_pinocchio() {
    // Measured: M 2.5e-16, f 3.9e-16, T 5.2e-16, V 2.9e-16, q̈ 1.6e-15.
    check!(FeatureTree, "features", 2e-14);
}

/// The model text `Builder::urdf` derives the code from, for review.
#[test]
fn imported_models() {
    for robot in ["panda", "features"] {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join(format!("../tests/reference/urdf/{robot}.urdf"));
        let model = dalembert_codegen::Urdf::read(path)
            .and_then(|urdf| urdf.model())
            .expect("imports");
        insta::assert_snapshot!(format!("urdf_model_{robot}"), model);
    }
}
