//! Generated systems carry their model (`NAME::SOURCE`, `dalembert::Model`)
//! from the build script's front door, and a robot's scene drawn from it
//! (`Scene::of`) draws its links between the joint origins and fits the
//! view to the motion.

use dalembert::Model;
use dalembert_fixtures::scene_page::embedded_data;
use dalembert_generated::{DoublePendulum, Ur5};
use dalembert_lab::{Recording, Scene};

#[test]
fn a_built_system_carries_the_file_it_was_built_from() {
    assert_eq!(
        DoublePendulum::SOURCE,
        include_str!("../../models/double_pendulum.dal")
    );
    let ur5 = dalembert_codegen::Urdf::read("../tests/reference/urdf/ur5_robot.urdf")
        .unwrap()
        .outputs("position(tool0_origin), jacobian(tool0_origin), rotation(tool0)")
        .model()
        .unwrap();
    assert_eq!(Ur5::SOURCE, ur5);
    assert_eq!(Ur5 {}.parameter_values(), [0.0; 0]);
}

#[test]
fn the_generated_docs_list_the_functions_and_the_outputs_that_add_others() {
    let api = dalembert_codegen::api(DoublePendulum::SOURCE).unwrap();
    for line in [
        "mass_matrix(q)",
        "forcing(t, q, qd, u)",
        "accelerations(t, q, qd, u)",
        "outputs linearize;  adds linearize",
        "outputs position(P);  adds position_P",
    ] {
        assert!(api.contains(line), "{line} in\n{api}");
    }
    let ur5 = dalembert_codegen::api(Ur5::SOURCE).unwrap();
    assert!(ur5.contains("jacobian_tool0_origin(t, q)"), "{ur5}");
    assert!(!ur5.contains("outputs jacobian(P)"), "asked for: {ur5}");
}

#[test]
fn a_robot_is_drawn_as_links_between_its_joint_origins_in_a_view_that_fits_it() {
    let mut recording = Recording::new();
    for i in 0..=100 {
        let t = i as f64 / 100.0;
        let q = [t, -1.2 + 0.5 * t, 1.5 - t, -0.8 + t, 1.0 + t, t];
        recording.push(t, &q, 0.0);
    }
    let data = embedded_data(&Scene::of(&Ur5 {}).unwrap().html(&recording).unwrap());
    let (points, bodies) = (
        data["points"].as_array().unwrap(),
        data["bodies"].as_array().unwrap(),
    );
    let name = |list: &[serde_json::Value], i: &serde_json::Value| {
        list[i.as_u64().unwrap() as usize]
            .as_str()
            .unwrap()
            .to_string()
    };
    let links: Vec<(String, String, String)> = data["links"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| {
            (
                name(bodies, &l[0]),
                name(points, &l[1]),
                name(points, &l[2]),
            )
        })
        .collect();
    assert!(!links.is_empty());
    // The arm runs link by link from joint origin to joint origin (each bar
    // coloured by a body it is fixed in: a joint offset along the next
    // joint's axis is fixed in both).
    let chain = [
        "base_link_origin",
        "shoulder_link_origin",
        "upper_arm_link_origin",
        "forearm_link_origin",
        "wrist_1_link_origin",
        "wrist_2_link_origin",
        "wrist_3_link_origin",
        "ee_link_origin",
    ];
    for pair in chain.windows(2) {
        assert!(
            links
                .iter()
                .any(|(_, from, to)| (from, to) == (&pair[0].to_string(), &pair[1].to_string())),
            "{pair:?} in {links:?}"
        );
    }
    assert_eq!(links[0].0, "shoulder_link_body");
    // The view is what the arm's joints sweep, not the inertia boxes'.
    let n = points.len();
    let frames = data["frames"].as_array().unwrap();
    assert!(!frames.is_empty());
    let (mut low, mut high) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for frame in frames {
        let numbers = frame.as_array().unwrap();
        for p in 0..n {
            for i in 0..3 {
                let x = numbers[3 * p + i].as_f64().unwrap();
                (low[i], high[i]) = (low[i].min(x), high[i].max(x));
            }
        }
    }
    let swept = (0..3).map(|i| high[i] - low[i]).fold(0.0, f64::max);
    let size = data["size"].as_f64().unwrap();
    assert!(
        size >= swept && size <= 1.15 * swept,
        "view size {size}, joints sweep {swept}"
    );
}
