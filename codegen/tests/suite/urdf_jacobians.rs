//! The end-effector outputs of imported robots against Pinocchio's frame
//! jacobians: `position(L_origin)`, `jacobian(L_origin)` (the origin's
//! velocity in `N`'s axes per speed) and `angular_jacobian(L)` (the link's
//! angular velocity in `N`'s axes per speed), asked for on import with
//! `--outputs`, are `oMf`'s translation and the two halves of
//! `getFrameJacobian(.., LOCAL_WORLD_ALIGNED)`, on two quadrupeds' feet on
//! free flyers (speeds in the base's axes on both sides) and two arms'
//! tool links on fixed joints (`tests/reference/robots/jacobians.json`,
//! `scripts/urdf_jacobians_reference.py`).

use crate::urdf_frames::{largest_difference, numbers};

use dalembert_codegen::Urdf;
use dalembert_codegen::testing::{Interpreter, Route, Values};
use serde_json::Value;

/// Agreement required, entry by entry (metres, metres per radian).
const TOLERANCE: f64 = 1e-12;

#[test]
fn link_jacobians_are_pinocchios_frame_jacobians() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/reference");
    let text = std::fs::read_to_string(dir.join("robots/jacobians.json")).unwrap();
    let reference: Value = serde_json::from_str(&text).unwrap();
    let robots = reference["robots"].as_array().unwrap();
    assert_eq!(robots.len(), 4);
    for robot in robots {
        let link = robot["link"].as_str().unwrap();
        let outputs =
            format!("position({link}_origin), jacobian({link}_origin), angular_jacobian({link})");
        let model = Urdf::read(dir.join(robot["urdf"].as_str().unwrap()))
            .unwrap()
            .floating(robot["floating"].as_bool().unwrap())
            .outputs(&outputs)
            .model()
            .unwrap();
        let interpreter = Interpreter::new(&model, Route::Dalembert).unwrap();
        let nv = robot["nv"].as_u64().unwrap() as usize;
        let states = robot["states"].as_array().unwrap();
        assert!(!states.is_empty());
        for state in states {
            let q = numbers(&state["q"]);
            let values = Values {
                parameters: &[],
                t: 0.0,
                q: &q,
                qd: &vec![0.0; nv],
                u: &vec![0.0; nv],
            };
            for (output, expected) in [
                (format!("position_{link}_origin"), "position"),
                (format!("jacobian_{link}_origin"), "jacobian"),
                (format!("angular_jacobian_{link}"), "angular_jacobian"),
            ] {
                let ours = interpreter.output(&output, &values, &[]).unwrap();
                let difference = largest_difference(&ours, &numbers(&state[expected]));
                assert!(
                    difference <= TOLERANCE,
                    "{link}: {output} off by {difference:e}"
                );
            }
        }
    }
}
