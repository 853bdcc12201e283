//! Every link of a URDF file, moving or welded to its parent by a fixed
//! joint (tool flanges, feet, cameras), has a frame named after it and a
//! point `<link>_origin` in the imported model, placed where Pinocchio
//! places the link's frame: `oMf` of its BODY frame after
//! `updateFramePlacements` (`tests/reference/robots/pinocchio.json`,
//! `scripts/robots_reference.py`), on five robots: `branches.urdf`, the A1
//! quadruped and the simple humanoid on free flyers, the UR5 and the Panda
//! on fixed bases. The frames and points are read with the engine's
//! geometry (what the outputs `position(L_origin)` and `rotation(L)`
//! compute), and asked for as outputs through [`Urdf::outputs`].

use crate::robots;

use dalembert_codegen::Urdf;
use dalembert_codegen::testing::{Interpreter, Values};
use robots::{entry, reference_dir};
use serde_json::Value;

/// Agreement required: positions in metres (the robots are about a metre
/// across), rotations entry by entry.
const TOLERANCE: f64 = 1e-12;

pub(crate) fn numbers(value: &Value) -> Vec<f64> {
    match value {
        Value::Array(items) => items.iter().flat_map(numbers).collect(),
        other => vec![other.as_f64().expect("a number")],
    }
}

pub(crate) fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Checks every link of Pinocchio's `robot` entry at every state; returns
/// the number of links checked.
fn links_match_pinocchio(robot: &str) -> usize {
    let entry = entry("frames", robot);
    let links: Vec<&str> = entry["links"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l.as_str().unwrap())
        .collect();
    assert!(!links.is_empty());
    let model = Urdf::read(reference_dir().join(entry["urdf"].as_str().unwrap()))
        .unwrap()
        .floating(entry["floating"].as_bool().unwrap())
        .model()
        .unwrap();
    let geometry = dalembert_codegen::Geometry::new(&model).unwrap();
    let states = entry["states"].as_array().unwrap();
    assert!(!states.is_empty());
    for state in states {
        let q = numbers(&state["q"]);
        let at = Values {
            parameters: &[],
            t: 0.0,
            q: &q,
            qd: &[],
            u: &[],
        };
        let (positions, rotations) = (geometry.positions(&at), geometry.rotations(&at));
        for link in &links {
            let placement = &state["links"][*link];
            let origin = format!("{link}_origin");
            let point = geometry.points().iter().position(|p| *p == origin);
            let frame = geometry.frames().iter().position(|f| f == link);
            let (Some(point), Some(frame)) = (point, frame) else {
                panic!("{robot}: link `{link}` has no frame or no point `{origin}`");
            };
            let position = largest_difference(&positions[point], &numbers(&placement["position"]));
            let rotation =
                largest_difference(&rotations[frame].concat(), &numbers(&placement["rotation"]));
            assert!(
                position <= TOLERANCE && rotation <= TOLERANCE,
                "{robot}: link `{link}` off by {position:e} m and {rotation:e} in rotation"
            );
        }
    }
    links.len()
}

#[test]
fn every_link_of_five_robots_is_where_pinocchio_places_it() {
    for (robot, at_least) in [
        ("branches", 15),
        ("a1_floating", 20),
        ("simple_humanoid_floating", 30),
        ("ur5_robot", 10),
        ("panda", 12),
    ] {
        let links = links_match_pinocchio(robot);
        assert!(links >= at_least, "{robot}: {links} links");
    }
}

/// The end effector of an arm, a link on a fixed joint, as outputs:
/// `position(tool0_origin)`, `jacobian(tool0_origin)` and `rotation(tool0)`
/// of the imported UR5, asked for on import, agree with its geometry, and
/// the jacobian with the point's motion along each speed.
#[test]
fn the_tool_frame_of_an_arm_is_an_output() {
    let model = Urdf::read(reference_dir().join("urdf/ur5_robot.urdf"))
        .unwrap()
        .outputs("position(tool0_origin), jacobian(tool0_origin), rotation(tool0)")
        .model()
        .unwrap();
    assert!(
        model.contains("outputs position(tool0_origin), jacobian(tool0_origin), rotation(tool0);")
    );
    let interpreter =
        Interpreter::new(&model, dalembert_codegen::testing::Route::Dalembert).unwrap();
    let geometry = dalembert_codegen::Geometry::new(&model).unwrap();
    let q = [0.3, -1.1, 1.4, -0.2, 0.9, 2.0];
    let at = |q: &[f64; 6]| -> [f64; 3] {
        let values = Values {
            parameters: &[],
            t: 0.0,
            q,
            qd: &[0.0; 6],
            u: &[0.0; 6],
        };
        interpreter
            .output("position_tool0_origin", &values, &[])
            .unwrap()
            .try_into()
            .unwrap()
    };
    let values = Values {
        parameters: &[],
        t: 0.0,
        q: &q,
        qd: &[0.0; 6],
        u: &[0.0; 6],
    };
    let point = geometry
        .points()
        .iter()
        .position(|p| p == "tool0_origin")
        .unwrap();
    let frame = geometry.frames().iter().position(|f| f == "tool0").unwrap();
    assert!(largest_difference(&at(&q), &geometry.positions(&values)[point]) <= 1e-15);
    let rotation = interpreter.output("rotation_tool0", &values, &[]).unwrap();
    assert!(largest_difference(&rotation, &geometry.rotations(&values)[frame].concat()) <= 1e-15);
    let jacobian = interpreter
        .output("jacobian_tool0_origin", &values, &[])
        .unwrap();
    let h = 1e-6;
    for k in 0..6 {
        let (mut plus, mut minus) = (q, q);
        plus[k] += h;
        minus[k] -= h;
        for i in 0..3 {
            let difference = (at(&plus)[i] - at(&minus)[i]) / (2.0 * h);
            assert!(
                (jacobian[6 * i + k] - difference).abs() <= 1e-8,
                "J[{i}][{k}]"
            );
        }
    }
}

/// A link named as a joint (ANYmal's `LF_HAA`, the benchmark trees')
/// cannot name its frame, which is the joint's coordinate: the frame gets a
/// fresh name, the point keeps `L_origin`, and the joint's comment in the
/// model says so (a convention this common is not worth a warning).
#[test]
fn a_link_named_as_a_joint_gets_a_fresh_frame_name_said_in_the_model() {
    let text = r#"<robot name="leg">
  <link name="base"/>
  <joint name="hip" type="revolute">
    <parent link="base"/><child link="hip"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <link name="hip">
    <inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
</robot>"#;
    let imported = Urdf::new("leg.urdf", text).import().unwrap();
    let model = &imported.model;
    assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
    assert!(model.contains("child: hip_2,"), "{model}");
    assert!(model.contains("joint revolute hip_origin "), "{model}");
    assert!(
        model.contains(
            "// Joint `hip` (revolute): link `base` carries link `hip`. Its frame is `hip_2` \
             and its origin `hip_origin`, as the link's name is taken."
        ),
        "{model}"
    );
}
