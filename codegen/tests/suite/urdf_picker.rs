//! A robot no other test uses, against Pinocchio: `picker.urdf`, a mobile
//! picker on a free flyer written for this test (`tests/reference/robots/`),
//! with siblings listed out of the byte order of their joint names, two
//! continuous wheels (one about a negative axis), a prismatic lift along an
//! unaligned axis, rotated joint and inertial origins, a camera welded to
//! the chassis and an end effector `tool-tip` welded to the hand beside a
//! finger. Imported with `--floating` and the outputs of DESIGN §8's end
//! effector (`position(tool_tip_origin), jacobian(tool_tip_origin),
//! rotation(tool_tip)`), evaluated by the interpreter, against
//! `tests/reference/robots/picker.json` (`scripts/picker_reference.py`):
//! `M`, `f = τ − nle`, the energies, the tool's placement and the linear
//! rows of its frame jacobian.

use crate::robots::reference_dir;
use crate::urdf_frames::{largest_difference, numbers};

use dalembert_codegen::Urdf;
use dalembert_codegen::testing::{Interpreter, Route, Values};
use serde_json::Value;

/// Agreement required, relative to the quantity's largest entry (1 for the
/// placement, in metres).
const TOLERANCE: f64 = 1e-12;

/// The worst difference of `ours` from `theirs`, relative to the largest
/// entry of `theirs` (at least 1).
fn relative(ours: &[f64], theirs: &[f64]) -> f64 {
    let scale = theirs.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    largest_difference(ours, theirs) / scale
}

#[test]
fn the_picker_matches_pinocchio_and_its_tool_is_an_output() {
    let path = reference_dir().join("robots/picker.json");
    let document: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let outputs = "position(tool_tip_origin), jacobian(tool_tip_origin), rotation(tool_tip)";
    let model = Urdf::read(reference_dir().join("robots/picker.urdf"))
        .unwrap()
        .floating(true)
        .outputs(outputs)
        .model()
        .unwrap();
    let coordinates: Vec<&str> = document["coordinates"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap())
        .collect();
    let declared = format!("coordinates {};", coordinates.join(", "));
    assert!(model.contains(&declared), "Pinocchio's order: {model}");
    let interpreter = Interpreter::new(&model, Route::Dalembert).unwrap();
    assert_eq!((interpreter.nq(), interpreter.nv()), (13, 12));
    let states = document["states"].as_array().unwrap();
    assert!(!states.is_empty());
    for (i, state) in states.iter().enumerate() {
        let [q, v, tau] = ["q", "v", "tau"].map(|k| numbers(&state[k]));
        let at = Values {
            parameters: &[],
            t: 0.0,
            q: &q,
            qd: &v,
            u: &tau,
        };
        let output = |name: &str| interpreter.output(name, &at, &[]).unwrap();
        let checks = [
            (
                "M",
                interpreter.mass_matrix(&at).concat(),
                numbers(&state["M"]),
            ),
            ("f", interpreter.forcing(&at), numbers(&state["f"])),
            (
                "T",
                vec![interpreter.kinetic_energy(&at)],
                numbers(&state["kinetic"]),
            ),
            (
                "V",
                vec![interpreter.potential_energy(&at)],
                numbers(&state["potential"]),
            ),
            (
                "tool position",
                output("position_tool_tip_origin"),
                numbers(&state["tool_position"]),
            ),
            (
                "tool rotation",
                output("rotation_tool_tip"),
                numbers(&state["tool_rotation"]),
            ),
            (
                "tool jacobian",
                output("jacobian_tool_tip_origin"),
                numbers(&state["tool_jacobian"]),
            ),
        ];
        for (what, ours, theirs) in checks {
            let error = relative(&ours, &theirs);
            assert!(error <= TOLERANCE, "state {i}: {what} off by {error:e}");
        }
    }
}
