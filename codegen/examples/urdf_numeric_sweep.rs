//! The dalembert half of `scripts/urdf_numeric_sweep.sh`: every case of
//! the reference written by `scripts/urdf_numeric_sweep.py` (a URDF file on
//! a fixed or floating base, with Pinocchio's numbers or its refusal) is
//! imported as `dalembert urdf` imports it, evaluated by the interpreter
//! (d'Alembert's route; Lagrange's too on a fixed base) and compared: one
//! line a case, the totals at the end.
//!
//! ```sh
//! cargo run --release -p dalembert-codegen --example urdf_numeric_sweep -- REFERENCE.json
//! ```
//!
//! A case matches when `M`, `f`, `T` and `V` agree to [`TOLERANCE`] of
//! their largest entry and `q̈` to [`TOLERANCE`] times the condition number
//! of `M` (the most any solver can promise).

#[path = "../tests/pinocchio/mod.rs"]
mod pinocchio;

use dalembert_codegen::Urdf;
use dalembert_codegen::testing::Route;
use pinocchio::{QUANTITIES, worst_errors};
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
