//! MJCF bodies with `gravcomp`: MuJoCo holds up that fraction of each
//! body's weight by a passive force at its centre of mass
//! (`qfrc_gravcomp`, part of `qfrc_passive` and not of the potential
//! energy). The import used to drop it, and `f` differed from MuJoCo's
//! by the weight compensated; it writes the force now. Against MuJoCo
//! 4.0's values in `tests/reference/mjcf/gravcomp.json`
//! (`scripts/mjcf_reference.py --files features/gravcomp.xml`), on
//! d'Alembert's route and Lagrange's. The joint attributes the import cannot
//! write are refused: `springdamper` (MuJoCo derives a stiffness and
//! damping from the joint's inertia at `qpos0`) and `actuatorgravcomp`
//! beside a `gravcomp` body (the compensation then goes through the
//! actuators, which the import leaves out).

use crate::pinocchio::{QUANTITIES, worst_errors};

use dalembert_codegen::Mjcf;
use dalembert_codegen::testing::Route;
use serde_json::Value;

#[test]
fn gravity_compensation_matches_mujoco() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/reference/mjcf");
    let text = std::fs::read_to_string(dir.join("gravcomp.json")).unwrap();
    let reference: Value = serde_json::from_str(&text).unwrap();
    let entry = &reference["models"][0];
    assert!(!entry["states"].as_array().unwrap().is_empty());
    let model = Mjcf::read(dir.join(entry["file"].as_str().unwrap()))
        .unwrap()
        .model()
        .unwrap();
    assert_eq!(
        model.matches("// Gravity compensation").count(),
        2,
        "{model}"
    );
    for route in [Route::Dalembert, Route::Lagrange] {
        let worst = worst_errors(&model, entry, route).unwrap();
        for (error, what) in worst.iter().zip(QUANTITIES) {
            assert!(
                *error <= 1e-12,
                "{what} ({route:?}) off by {error:e} relative"
            );
        }
    }
}

/// The error of importing `text`: its one line of message and where.
fn refused(text: &str) -> String {
    let error = Mjcf::new("model.xml", text)
        .model()
        .expect_err("the import fails");
    let diagnostics = error.diagnostics();
    assert_eq!(diagnostics.len(), 1, "{error}");
    let d = &diagnostics[0];
    format!("{}:{}", d.line().unwrap_or(0), d.message())
}

#[test]
fn a_spring_damper_from_the_inertia_is_refused() {
    let found = refused(
        "<mujoco>\n  <worldbody>\n    <body>\n      <joint type=\"slide\" springdamper=\"0.5 0.8\"/>\n      \
         <geom size=\".1\"/>\n    </body>\n  </worldbody>\n</mujoco>\n",
    );
    assert!(
        found.starts_with("4:`springdamper` is not supported"),
        "{found}"
    );
}

#[test]
fn compensation_through_the_actuators_is_refused() {
    let body = "<body gravcomp=\"1\">\n      <joint actuatorgravcomp=\"true\"/>\n      \
                <geom size=\".1\" pos=\"0 0 -.5\"/>\n    </body>";
    let found = refused(&format!(
        "<mujoco>\n  <worldbody>\n    {body}\n  </worldbody>\n</mujoco>\n"
    ));
    assert!(
        found.starts_with("4:`actuatorgravcomp=\"true\"` is not supported"),
        "{found}"
    );
    // Without a `gravcomp` body the attribute changes nothing: imported.
    let plain = body.replace(" gravcomp=\"1\"", "");
    let text = format!("<mujoco>\n  <worldbody>\n    {plain}\n  </worldbody>\n</mujoco>\n");
    Mjcf::new("model.xml", &text).model().unwrap();
}
