//! MJCF import against MuJoCo: the models `dalembert mjcf` writes for eleven
//! models of dm_control's suite and a model of every feature the import
//! reads, evaluated by the interpreter (d'Alembert's route, and
//! Lagrange's where every speed is its coordinate's rate), match MuJoCo's
//! `mj_fullM`, `qfrc_applied − qfrc_bias + qfrc_passive`, `qacc` and
//! energies in `tests/reference/mjcf/mujoco.json` (written by
//! `scripts/mjcf_reference.py` with MuJoCo's own compiler, contacts,
//! constraints and actuation disabled), in our conventions.

use crate::pinocchio;

use dalembert_codegen::Mjcf;
use dalembert_codegen::testing::{Interpreter, Route};
use pinocchio::{QUANTITIES, for_each_state, relative_error, vector, worst_errors};
use serde_json::Value;

/// Relative agreement required: against the largest entry of the quantity.
const TOLERANCE: f64 = 1e-12;

fn reference_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/reference/mjcf")
}

/// The reference entry of `model` and the model's text as imported.
fn imported(model: &str) -> (Value, String) {
    let text = std::fs::read_to_string(reference_dir().join("mujoco.json")).unwrap();
    let reference: Value = serde_json::from_str(&text).unwrap();
    let entry = reference["models"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["model"] == model)
        .unwrap_or_else(|| panic!("no reference for {model}"))
        .clone();
    assert!(!entry["states"].as_array().unwrap().is_empty());
    let file = reference_dir().join(entry["file"].as_str().unwrap());
    let text = Mjcf::read(file).unwrap().model().unwrap();
    (entry, text)
}

/// The coordinates' names: MuJoCo's joint names, in MuJoCo's order.
fn check_joint_order(entry: &Value, text: &str) {
    let joints: Vec<&str> = entry["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j.as_str().unwrap())
        .filter(|j| !j.is_empty())
        .collect();
    let mut at = 0;
    for joint in joints {
        let found = text[at..]
            .find(&format!(" {joint} "))
            .or_else(|| text[at..].find(&format!(" {joint};")))
            .unwrap_or_else(|| panic!("joint `{joint}` out of MuJoCo's order"));
        at += found;
    }
}

/// The accelerations of the articulated-body recursion (with the
/// armature on its pivots), which the generated `accelerations` use on a
/// tree, against MuJoCo's `qacc`.
fn check_articulated(model: &str, entry: &Value, text: &str) {
    let interpreter = Interpreter::new(text, Route::Dalembert).unwrap();
    let mut worst = 0.0_f64;
    for_each_state(
        entry,
        |state| vector(&state["tau"]),
        |state, at| {
            let qdd = interpreter
                .articulated_accelerations(at)
                .unwrap_or_else(|| panic!("{model} is a tree"));
            worst = worst.max(relative_error(&qdd, &vector(&state["qdd"])));
        },
    );
    eprintln!("{model}: articulated qdd off by {worst:.1e} relative");
    assert!(
        worst <= TOLERANCE,
        "{model}: articulated qdd off by {worst:e}"
    );
}

fn matches_mujoco(model: &str, routes: &[Route]) {
    let (entry, text) = imported(model);
    check_joint_order(&entry, &text);
    check_articulated(model, &entry, &text);
    for &route in routes {
        let worst = worst_errors(&text, &entry, route).unwrap();
        eprintln!(
            "{model} {route:?}: worst relative errors M {:.1e}, f {:.1e}, T {:.1e}, V {:.1e}, \
             qdd {:.1e}",
            worst[0], worst[1], worst[2], worst[3], worst[4]
        );
        for (error, what) in worst.iter().zip(QUANTITIES) {
            assert!(
                *error <= TOLERANCE,
                "{model} ({route:?}): {what} is off by {error:e} relative"
            );
        }
    }
}

const BOTH: &[Route] = &[Route::Dalembert, Route::Lagrange];
const DALEMBERT: &[Route] = &[Route::Dalembert];

#[test]
fn features_match_mujoco() {
    matches_mujoco("features", DALEMBERT);
}

#[test]
fn pendulum_matches_mujoco() {
    matches_mujoco("pendulum", BOTH);
}

#[test]
fn acrobot_matches_mujoco() {
    matches_mujoco("acrobot", BOTH);
}

#[test]
fn cartpole_matches_mujoco() {
    matches_mujoco("cartpole", BOTH);
}

#[test]
fn reacher_matches_mujoco() {
    matches_mujoco("reacher", BOTH);
}

#[test]
fn point_mass_matches_mujoco() {
    matches_mujoco("point_mass", BOTH);
}

#[test]
fn ball_in_cup_matches_mujoco() {
    matches_mujoco("ball_in_cup", BOTH);
}

#[test]
fn cheetah_matches_mujoco() {
    matches_mujoco("cheetah", BOTH);
}

#[test]
fn hopper_matches_mujoco() {
    matches_mujoco("hopper", BOTH);
}

#[test]
fn walker_matches_mujoco() {
    matches_mujoco("walker", BOTH);
}

#[test]
fn humanoid_matches_mujoco() {
    matches_mujoco("humanoid", DALEMBERT);
}

#[test]
fn finger_matches_mujoco() {
    matches_mujoco("finger", BOTH);
}

#[test]
fn the_command_prints_the_model_with_its_options() {
    let file = reference_dir().join("dm_control/pendulum.xml");
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_dalembert"))
        .args(["mjcf", "--name", "Swing", "--outputs"])
        .arg("position(pole_origin), rotation(pole)")
        .arg(&file)
        .output()
        .unwrap();
    assert!(output.status.success(), "{output:?}");
    let text = String::from_utf8(output.stdout).unwrap();
    let library = Mjcf::read(&file)
        .unwrap()
        .name("Swing")
        .outputs("position(pole_origin), rotation(pole)")
        .model()
        .unwrap();
    assert_eq!(text, library);
    assert!(text.contains("pub Swing {"), "{text}");
    assert!(text.contains("    outputs position(pole_origin), rotation(pole);\n}"));
    dalembert_codegen::check(&text).unwrap();
    let help = std::process::Command::new(env!("CARGO_BIN_EXE_dalembert"))
        .args(["mjcf", "--help"])
        .output()
        .unwrap();
    assert!(
        String::from_utf8(help.stdout)
            .unwrap()
            .contains("--outputs \"LIST\"")
    );
}
