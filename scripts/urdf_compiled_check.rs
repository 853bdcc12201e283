//! The compiled half of `scripts/urdf_numeric_sweep.sh` with `COMPILED=...`:
//! the script writes `dalembert urdf [--floating]` then `dalembert generate`
//! of each chosen file into `case_<i>.rs` beside this file in a scratch
//! crate, and this main compares each compiled model's `mass_matrix`,
//! `forcing`, `kinetic_energy` and `accelerations` (its emitted solver)
//! with Pinocchio's numbers in the reference (`urdf_numeric_sweep.py`).
//! Not part of the workspace; the script puts the modules and `compare_all`
//! in place of the line that marks the cases.

// The generated models have more functions than this compares, and the
// shared module more helpers than it uses.
#![allow(dead_code)]

#[path = "../../../codegen/tests/suite/pinocchio.rs"]
mod pinocchio;

use dalembert::MultibodySystem;
use pinocchio::{keep_worst, matrix, relative_error, vector};
use serde_json::Value;

// CASES

/// One line: the worst relative errors of the compiled model over the
/// states of the reference case of `file` on `base`.
fn compare<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    (file, base): (&str, &str),
    cases: &[Value],
) where
    S: MultibodySystem<NQ, NV, NU>,
{
    let case = cases
        .iter()
        .find(|c| c["file"] == file && c["base"] == base)
        .expect("the case is in the reference");
    let mut worst = [0.0_f64; 4];
    for state in case["entry"]["states"].as_array().unwrap() {
        let q: [f64; NQ] = vector(&state["q"]).try_into().unwrap();
        let v: [f64; NV] = vector(&state["qd"]).try_into().unwrap();
        let u: [f64; NU] = vector(&state["tau"]).try_into().unwrap();
        let accelerations = system.accelerations(0.0, &q, &v, &u).unwrap();
        let kinetic = system.kinetic_energy(&q, &v);
        let errors = [
            relative_error(
                system.mass_matrix(&q).as_flattened(),
                &matrix(&state["M"]).concat(),
            ),
            relative_error(&system.forcing(0.0, &q, &v, &u), &vector(&state["f"])),
            relative_error(&[kinetic], &[state["T"].as_f64().unwrap()]),
            relative_error(&accelerations, &vector(&state["qdd"])),
        ];
        keep_worst(&mut worst, errors);
    }
    println!(
        "{file} ({base}) compiled: M {:.1e} f {:.1e} T {:.1e} qdd {:.1e}; cond(M) {:.1e}",
        worst[0],
        worst[1],
        worst[2],
        worst[3],
        case["cond"].as_f64().unwrap()
    );
}

fn main() {
    let path = std::env::args()
        .nth(1)
        .expect("usage: compiled REFERENCE.json");
    let text = std::fs::read_to_string(path).expect("the reference reads");
    let reference: Value = serde_json::from_str(&text).expect("the reference parses");
    let cases = reference["cases"].as_array().unwrap();
    compare_all(cases);
}
