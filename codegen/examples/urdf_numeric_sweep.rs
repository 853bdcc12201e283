//! The dalembert half of `scripts/urdf_numeric_sweep.sh`: every case of
//! the reference written by `scripts/urdf_numeric_sweep.py` (a URDF file on
//! a fixed or floating base, with Pinocchio's numbers or its refusal) is
//! imported as `dalembert urdf` imports it, evaluated by the interpreter
//! (d'Alembert's route; Lagrange's too on a fixed base; and asking for
//! `inverse_dynamics` and `inverse_dynamics_jacobian`) and compared: one
//! line a case, the totals at the end.
//!
//! ```sh
//! cargo run --release -p dalembert-codegen --example urdf_numeric_sweep -- REFERENCE.json
//! ```
//!
//! A case matches when `M`, `f`, `T`, `V`, RNEA and its partials agree to
//! [`TOLERANCE`] of their largest entry and `q̈` to [`TOLERANCE`] times the
//! condition number of `M` (the most any solver can promise).

#[path = "../tests/suite/pinocchio.rs"]
mod pinocchio;

use dalembert_codegen::Urdf;
use dalembert_codegen::testing::{Interpreter, Route};
use pinocchio::{QUANTITIES, for_each_state, keep_worst, relative_error, vector, worst_errors};
use serde_json::Value;

/// Relative agreement required, against the largest entry of a quantity.
const TOLERANCE: f64 = 1e-12;

/// How one case ended.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Outcome {
    Matches,
    Differs,
    BothRefuse,
    PinocchioRefuses,
    DalembertRefuses,
}

/// The model text `dalembert urdf [--floating]` writes for the case's file.
fn import(case: &Value) -> Result<String, String> {
    Urdf::read(case["path"].as_str().unwrap())
        .and_then(|urdf| urdf.floating(case["base"] == "floating").model())
        .map_err(|e| e.to_string().lines().next().unwrap_or_default().to_owned())
}

/// The worst relative errors of the model's `inverse_dynamics` (RNEA, at
/// zero inputs) and `inverse_dynamics_jacobian`'s `∂τ/∂q` (tangent space)
/// and `∂τ/∂v` against Pinocchio's `rnea` and `computeRNEADerivatives` at
/// the entry's states and accelerations (the partials' errors over the
/// larger of their largest entry and `M`'s).
fn inverse_dynamics_errors(model: &str, entry: &Value) -> Result<[f64; 3], String> {
    let close = model.rfind('}').ok_or("no closing brace")?;
    let asking = format!(
        "{}    outputs inverse_dynamics, inverse_dynamics_jacobian;\n{}",
        &model[..close],
        &model[close..]
    );
    let interpreter = Interpreter::new(&asking, Route::Dalembert).map_err(|e| e.to_string())?;
    let mut worst = [0.0_f64; 3];
    let zero_inputs = |_: &Value| vec![0.0; interpreter.nu()];
    for_each_state(entry, zero_inputs, |state, at| {
        let a = vector(&state["a"]);
        let rnea = interpreter.output("inverse_dynamics", at, &a).unwrap();
        let partials = interpreter
            .output("inverse_dynamics_jacobian", at, &a)
            .unwrap();
        let n = a.len();
        let flat = |key: &str| -> Vec<f64> {
            state[key]
                .as_array()
                .unwrap()
                .iter()
                .flat_map(vector)
                .collect()
        };
        // The partials against M's size too: where they vanish Pinocchio
        // leaves rounding (2.7e-20 on the iris' rotors) that sets no scale.
        let mass = flat("M");
        let against_mass = |ours: &[f64], key: &str| {
            relative_error(&[ours, &mass].concat(), &[flat(key), mass.clone()].concat())
        };
        let errors = [
            relative_error(&rnea, &vector(&state["rnea"])),
            against_mass(&partials[..n * n], "rnea_dq"),
            against_mass(&partials[n * n..2 * n * n], "rnea_dv"),
        ];
        keep_worst(&mut worst, errors);
    });
    Ok(worst)
}

/// The case's errors on each route, as text, and whether they are within
/// tolerance.
fn compare(model: &str, case: &Value) -> (String, bool) {
    let entry = &case["entry"];
    let cond = case["cond"].as_f64().unwrap();
    let routes: &[Route] = if case["base"] == "fixed" {
        &[Route::Dalembert, Route::Lagrange]
    } else {
        &[Route::Dalembert]
    };
    let mut text = String::new();
    let mut matches = true;
    for &route in routes {
        text += &format!("{route:?}:");
        match worst_errors(model, entry, route) {
            Ok(worst) => {
                for (what, error) in QUANTITIES.iter().zip(worst) {
                    let allowed = TOLERANCE * if *what == "qdd" { cond.max(1.0) } else { 1.0 };
                    matches &= error <= allowed;
                    text += &format!(" {what} {error:.1e}");
                }
            }
            Err(error) => {
                matches = false;
                text += &format!(" {error}");
            }
        }
        text += "; ";
    }
    match inverse_dynamics_errors(model, entry) {
        Ok(worst) => {
            text += "RNEA:";
            for (what, error) in ["tau", "dq", "dv"].iter().zip(worst) {
                matches &= error <= TOLERANCE;
                text += &format!(" {what} {error:.1e}");
            }
            text += "; ";
        }
        Err(error) => {
            matches = false;
            text += &format!("RNEA: {error}; ");
        }
    }
    (format!("{text}cond(M) {cond:.1e}"), matches)
}

fn run(case: &Value) -> (Outcome, String) {
    match (case.get("error"), import(case)) {
        (Some(theirs), Err(ours)) => (
            Outcome::BothRefuse,
            format!("both refuse: Pinocchio {theirs}; dalembert {ours}"),
        ),
        (Some(theirs), Ok(_)) => (
            Outcome::PinocchioRefuses,
            format!("only Pinocchio refuses: {theirs}"),
        ),
        (None, Err(ours)) => (
            Outcome::DalembertRefuses,
            format!("only dalembert refuses: {ours}"),
        ),
        (None, Ok(model)) => {
            let (text, matches) = compare(&model, case);
            let outcome = if matches {
                Outcome::Matches
            } else {
                Outcome::Differs
            };
            (outcome, format!("{outcome:?}, {text}"))
        }
    }
}

fn main() {
    let path = std::env::args()
        .nth(1)
        .expect("usage: urdf_numeric_sweep REFERENCE.json");
    let text = std::fs::read_to_string(&path).expect("the reference file reads");
    let reference: Value = serde_json::from_str(&text).expect("the reference parses");
    let mut outcomes = Vec::new();
    for case in reference["cases"].as_array().unwrap() {
        let (outcome, line) = run(case);
        println!(
            "{} ({}): {line}",
            case["file"].as_str().unwrap(),
            case["base"].as_str().unwrap()
        );
        outcomes.push(outcome);
    }
    let count = |o: Outcome| outcomes.iter().filter(|&&x| x == o).count();
    println!(
        "{} cases: {} match, {} differ, {} refused by both, {} only by Pinocchio, {} only by dalembert",
        outcomes.len(),
        count(Outcome::Matches),
        count(Outcome::Differs),
        count(Outcome::BothRefuse),
        count(Outcome::PinocchioRefuses),
        count(Outcome::DalembertRefuses),
    );
}
