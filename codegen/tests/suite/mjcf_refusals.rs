//! MJCF input the import refuses, where it cannot write what MuJoCo
//! computes or where MuJoCo itself refuses the file: one error, at the
//! attribute, with its line.
//!
//! * a joint's `springdamper`: MuJoCo derives a stiffness and damping from
//!   the joint's inertia at `qpos0`;
//! * `actuatorgravcomp="true"` beside a `gravcomp` body: the compensation
//!   then goes through the actuators, which the import leaves out;
//! * a tendon's `armature`: inertia `Jᵀ a J` along the tendon (off `M`'s
//!   diagonal too), as its stiffness and damping are refused;
//! * a plane geom in a moving body, which MuJoCo refuses ("plane only
//!   allowed in static bodies").

use dalembert_codegen::Mjcf;

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

#[test]
fn a_tendons_armature_is_refused() {
    let found = refused(
        "<mujoco>\n  <worldbody>\n    <body>\n      <joint name=\"a\"/>\n      <geom size=\".1\"/>\n      \
         <body>\n        <joint name=\"b\"/>\n        <geom size=\".1\" pos=\"0 0 -.3\"/>\n      </body>\n    \
         </body>\n  </worldbody>\n  <tendon>\n    <fixed armature=\"0.3\">\n      \
         <joint joint=\"a\" coef=\"1\"/>\n      <joint joint=\"b\" coef=\"-0.5\"/>\n    </fixed>\n  \
         </tendon>\n</mujoco>\n",
    );
    assert!(
        found.starts_with("13:a tendon with `armature` is not imported"),
        "{found}"
    );
}

#[test]
fn a_plane_in_a_moving_body_is_refused_as_by_mujoco() {
    let found = refused(
        "<mujoco>\n  <worldbody>\n    <body>\n      <joint/>\n      <geom size=\".1\"/>\n      \
         <geom type=\"plane\" size=\"1 1 .1\"/>\n    </body>\n  </worldbody>\n</mujoco>\n",
    );
    assert!(
        found.starts_with("6:a plane geom in a moving body"),
        "{found}"
    );
    // In a body that does not move (the world's, or a body without joints
    // on it), a plane is a static geom without mass, as in MuJoCo.
    let text = "<mujoco>\n  <worldbody>\n    <geom type=\"plane\" size=\"1 1 .1\"/>\n    <body>\n      \
                <geom type=\"plane\" size=\"1 1 .1\"/>\n      <body>\n        <joint/>\n        \
                <geom size=\".1\"/>\n      </body>\n    </body>\n  </worldbody>\n</mujoco>\n";
    Mjcf::new("model.xml", text).model().unwrap();
}
