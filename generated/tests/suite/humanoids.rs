//! The floating humanoids of the `humanoids` feature (Unitree G1, Talos;
//! `tests/reference/humanoids/`) against Pinocchio on its free flyer:
//! `mass_matrix`, `forcing`, `accelerations` and `accelerations_jacobian`
//! match `crba`, `τ − nonLinearEffects`, `aba` and `computeABADerivatives`
//! (by `q` in the tangent space) to 1e-12 of each quantity's largest entry,
//! at the states of `tests/reference/humanoids/pinocchio.json`
//! (`scripts/humanoids_reference.py`).
//!
//! Run with `cargo test -p dalembert-generated --features humanoids --test
//! suite humanoids::` (add `--release`: the humanoids' code is large).

use crate::derivatives::{AccelerationsJacobian, model_states, numbers, relative_error};
use dalembert::MultibodySystem;
use dalembert_generated::{g1::G1, talos_reduced::Talos};
use serde_json::Value;

/// Relative agreement required, against the quantity's largest entry.
const TOLERANCE: f64 = 1e-12;

/// `max |got − want| ≤ TOLERANCE · max |want|`; the relative error.
fn assert_agrees(what: &str, got: &[f64], want: &[f64]) -> f64 {
    let error = relative_error(what, got, want);
    assert!(error <= TOLERANCE, "{what}: off by {error:e} relative");
    error
}

/// The reference states of `model` in `humanoids/pinocchio.json`.
fn reference_states(model: &str) -> Vec<Value> {
    let text = include_str!("../../../tests/reference/humanoids/pinocchio.json");
    model_states(text, "humanoids/pinocchio.json", model)
}

/// Every quantity of `system` against Pinocchio's at the states of `model`
/// (the inputs are the joints' torques, the last `NU` speeds').
fn check<S, const NQ: usize, const NV: usize, const NU: usize>(
    model: &str,
    system: &S,
    jacobian: AccelerationsJacobian<S, NQ, NV, NU>,
) where
    S: MultibodySystem<NQ, NV, NU>,
{
    fn array<const N: usize>(v: &Value) -> [f64; N] {
        numbers(v).try_into().expect("N numbers")
    }
    let flat = |m: &[[f64; NV]; NV]| -> Vec<f64> { m.iter().flatten().copied().collect() };
    let states = reference_states(model);
    let mut worst = [0.0_f64; 6];
    for state in &states {
        let (q, v, u) = (
            array::<NQ>(&state["q"]),
            array::<NV>(&state["qd"]),
            array::<NU>(&state["tau"]),
        );
        let errors = [
            assert_agrees(
                &format!("{model} M"),
                &flat(&system.mass_matrix(&q)),
                &numbers(&state["dtau_da"]),
            ),
            assert_agrees(
                &format!("{model} f"),
                &system.forcing(0.0, &q, &v, &u),
                &numbers(&state["f"]),
            ),
            assert_agrees(
                &format!("{model} q̈"),
                &dalembert::accelerations(system, 0.0, &q, &v, &u).expect("solvable"),
                &numbers(&state["qdd"]),
            ),
        ];
        let (by_q, by_v, by_u) = jacobian(system, 0.0, &q, &v, &u).expect("solvable");
        // The columns of M⁻¹ of the actuated speeds.
        let inverse = numbers(&state["ddq_dtau"]);
        let actuated: Vec<f64> = inverse
            .chunks(NV)
            .flat_map(|row| row[NV - NU..].iter().copied())
            .collect();
        let by_u: Vec<f64> = by_u.iter().flatten().copied().collect();
        let derivatives = [
            assert_agrees(
                &format!("{model} ∂q̈/∂q"),
                &flat(&by_q),
                &numbers(&state["ddq_dq"]),
            ),
            assert_agrees(
                &format!("{model} ∂q̈/∂v"),
                &flat(&by_v),
                &numbers(&state["ddq_dv"]),
            ),
            assert_agrees(&format!("{model} ∂q̈/∂τ"), &by_u, &actuated),
        ];
        for (w, e) in worst.iter_mut().zip(errors.iter().chain(&derivatives)) {
            *w = w.max(*e);
        }
    }
    eprintln!(
        "{model}: worst relative errors M {:.1e}, f {:.1e}, q̈ {:.1e}, ∂q̈/∂q {:.1e}, ∂q̈/∂v {:.1e}, ∂q̈/∂τ {:.1e}",
        worst[0], worst[1], worst[2], worst[3], worst[4], worst[5]
    );
}

#[test]
fn g1_matches_pinocchio() {
    check("g1_floating", &G1 {}, G1::accelerations_jacobian);
}

#[test]
fn talos_matches_pinocchio() {
    check(
        "talos_reduced_floating",
        &Talos {},
        Talos::accelerations_jacobian,
    );
}
