//! Animated scenes: the drawn positions against closed forms derived by
//! hand, the page's structure and embedded data, decimation and file sizes.

use dalembert_codegen::chain::{Family, chain};
use dalembert_lab::{Pose, Recording, Scene, decimate};

/// Seed example 1, as the language reference writes it.
const DOUBLE_PENDULUM: &str = include_str!("../../../generated/models/double_pendulum.dal");

/// A smooth, wide made-up motion of `nq` coordinates over `[0, end]` with
/// `samples` samples: what the scene draws depends on the configurations,
/// not on how they were reached.
fn recording(nq: usize, end: f64, samples: usize) -> Recording {
    let mut recording = Recording::new();
    for i in 0..samples {
        let t = end * i as f64 / (samples - 1) as f64;
        recording.push(t, &configuration(nq, t), 1.0 + 1e-6 * (3.0 * t).sin());
    }
    recording
}

/// The made-up configuration at time `t`.
fn configuration(nq: usize, t: f64) -> Vec<f64> {
    (0..nq)
        .map(|k| {
            let k = k as f64;
            2.0 * (0.7 * t + 0.9 * k).sin() + 0.3 * (2.3 * t * (k + 1.0)).cos()
        })
        .collect()
}

fn assert_close(what: &str, got: &[f64; 3], expected: &[f64; 3]) {
    for i in 0..3 {
        assert!(
            (got[i] - expected[i]).abs() <= 1e-12,
            "{what}: got {got:?}, expected {expected:?}"
        );
    }
}

fn rotation_z(angle: f64) -> [[f64; 3]; 3] {
    let (s, c) = angle.sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}

fn rotation_y(angle: f64) -> [[f64; 3]; 3] {
    let (s, c) = angle.sin_cos();
    [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
}

fn mat_mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    r
}

fn assert_rotation(what: &str, got: &[[f64; 3]; 3], expected: &[[f64; 3]; 3]) {
    for i in 0..3 {
        assert_close(what, &got[i], &expected[i]);
    }
}

/// P1 = (L sin θ₁, −L cos θ₁, 0), G1 halfway, G2 = P1 + L/2 (sin θ₂, −cos θ₂, 0),
/// the links turned by θ₁ and θ₂ about N.z.
#[test]
fn double_pendulum_positions_match_the_closed_form() {
    let (m, l, g) = (1.3, 0.8, 9.81);
    let scene = Scene::new(DOUBLE_PENDULUM, &[m, l, g]).unwrap();
    let recording = recording(2, 3.0, 301);
    let poses = scene.poses(&recording).unwrap();
    assert_eq!(poses.len(), 301);
    for (i, (t, pose)) in poses.iter().enumerate() {
        assert_eq!(*t, recording.times()[i]);
        let q = configuration(2, *t);
        let (s1, c1) = q[0].sin_cos();
        let (s2, c2) = q[1].sin_cos();
        let p1 = [l * s1, -l * c1, 0.0];
        let g1 = [l / 2.0 * s1, -l / 2.0 * c1, 0.0];
        let g2 = [p1[0] + l / 2.0 * s2, p1[1] - l / 2.0 * c2, 0.0];
        let Pose {
            points,
            centres,
            rotations,
            particles,
        } = pose;
        assert_eq!(points.len(), 4, "O, P1, G1, G2");
        assert_close("O", &points[0], &[0.0; 3]);
        assert_close("P1", &points[1], &p1);
        assert_close("G1", &points[2], &g1);
        assert_close("G2", &points[3], &g2);
        assert_close("link1's centre", &centres[0], &g1);
        assert_close("link2's centre", &centres[1], &g2);
        assert_rotation("link1", &rotations[0], &rotation_z(q[0]));
        assert_rotation("link2", &rotations[1], &rotation_z(q[1]));
        assert!(particles.is_empty());
    }
}

/// The drawn poses of 2 s of the made-up motion of the `family` chain of
/// `n` links, every sample kept.
fn chain_poses(family: Family, n: usize) -> Vec<(f64, Pose)> {
    let scene = Scene::new(&chain(family, n), &[]).unwrap();
    scene.poses(&recording(n, 2.0, 41)).unwrap()
}

/// The planar chain: joint `J1` at `O`, `J(k+1) = Jk − L_k Bk.y` with
/// `Bk` at the absolute angle `q1 + … + qk` about N.z and
/// `L_k = 1/2 + k/20`; link `k`'s centre halfway.
#[test]
fn planar_chain_positions_match_the_hand_kinematics() {
    let n = 6;
    for (t, pose) in chain_poses(Family::Planar, n) {
        let q = configuration(n, t);
        let (mut joint, mut angle) = ([0.0; 3], 0.0);
        assert_close("O", &pose.points[0], &[0.0; 3]);
        for k in 1..=n {
            angle += q[k - 1];
            let length = 0.5 + k as f64 / 20.0;
            let (s, c) = f64::sin_cos(angle);
            assert_close(&format!("J{k}"), &pose.points[k], &joint);
            let centre = [
                joint[0] + length / 2.0 * s,
                joint[1] - length / 2.0 * c,
                0.0,
            ];
            assert_close(&format!("link{k}"), &pose.centres[k - 1], &centre);
            assert_rotation(&format!("B{k}"), &pose.rotations[k - 1], &rotation_z(angle));
            joint = [joint[0] + length * s, joint[1] - length * c, 0.0];
        }
    }
}

/// The spatial chain: joint axes z, y, z, … of the parent link, rods
/// along each link's +x: `R_k = R_(k−1) A_k(q_k)`, `J(k+1) = Jk + L_k R_k e_x`.
#[test]
fn spatial_chain_positions_match_the_hand_kinematics() {
    let n = 5;
    for (t, pose) in chain_poses(Family::Spatial, n) {
        let q = configuration(n, t);
        let (mut joint, mut r) = ([0.0; 3], rotation_z(0.0));
        for k in 1..=n {
            let turn = if k % 2 == 1 {
                rotation_z(q[k - 1])
            } else {
                rotation_y(q[k - 1])
            };
            r = mat_mul(&r, &turn);
            let length = 0.5 + k as f64 / 20.0;
            let x_axis = [r[0][0], r[1][0], r[2][0]];
            assert_close(&format!("J{k}"), &pose.points[k], &joint);
            let centre = [0, 1, 2].map(|i| joint[i] + length / 2.0 * x_axis[i]);
            assert_close(&format!("link{k}"), &pose.centres[k - 1], &centre);
            assert_rotation(&format!("B{k}"), &pose.rotations[k - 1], &r);
            joint = [0, 1, 2].map(|i| joint[i] + length * x_axis[i]);
        }
    }
}

/// The page's single script's embedded data, parsed.
fn embedded_data(html: &str) -> serde_json::Value {
    assert_eq!(html.matches("<script").count(), 1, "one script");
    assert_eq!(html.matches("</script>").count(), 1);
    assert_eq!(html.matches("<canvas").count(), 1, "one canvas");
    assert!(html.starts_with("<!DOCTYPE html>") && html.trim_end().ends_with("</html>"));
    for external in ["src=", "href=\"http", "https://", "http://"] {
        assert!(
            !html.contains(external),
            "the page loads nothing: {external}"
        );
    }
    dalembert_fixtures::scene_page::embedded_data(html)
}

#[test]
fn the_page_embeds_every_kept_frame_as_json() {
    let scene = Scene::new(DOUBLE_PENDULUM, &[1.0, 1.0, 9.81])
        .unwrap()
        .equations("M(q) q̈ = f")
        .max_frames(100);
    let recording = recording(2, 10.0, 1001);
    let html = scene.html(&recording).unwrap();
    let data = embedded_data(&html);
    let frames = data["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 100);
    assert_eq!(data["t"].as_array().unwrap().len(), 100);
    assert_eq!(data["energy"].as_array().unwrap().len(), 100);
    assert_eq!(data["points"], serde_json::json!(["O", "P1", "G1", "G2"]));
    assert_eq!(data["bodies"], serde_json::json!(["link1", "link2"]));
    // O → P1, O → G1, P1 → G2.
    assert_eq!(
        data["segments"],
        serde_json::json!([[0, 1], [0, 2], [1, 3]])
    );
    assert_eq!(
        data["normal"], 2,
        "a double pendulum moves in the plane z = 0"
    );
    assert_eq!(data["equations"], "M(q) q̈ = f");
    for frame in frames {
        assert_eq!(frame.as_array().unwrap().len(), 4 * 3 + 2 * 7);
    }
    assert_eq!(data["t"][0], 0.0);
    assert_eq!(data["t"][99], 10.0);
    // The rods are as long as the links, from the points fixed in them.
    let length = data["sizes"][0][1].as_f64().unwrap();
    assert!((length - 1.0).abs() < 1e-3, "{}", data["sizes"]);
}

#[test]
fn a_spatial_system_gets_the_3d_view() {
    let scene = Scene::new(&chain(Family::Spatial, 3), &[]).unwrap();
    let data = embedded_data(&scene.html(&recording(3, 1.0, 11)).unwrap());
    assert_eq!(data["normal"], serde_json::Value::Null);
    // Rods along x, as long as the links (from their inertia: 0.55 m first).
    let first = data["sizes"][0].as_array().unwrap();
    assert!(
        (first[0].as_f64().unwrap() - 0.55).abs() < 1e-3,
        "{first:?}"
    );
}

#[test]
fn decimation_keeps_the_first_and_last_samples_evenly_in_time() {
    let times: Vec<f64> = (0..=100_000).map(|i| i as f64 * 6e-4).collect();
    let kept = decimate(&times, 1500);
    assert!(kept.len() <= 1500 && kept.len() >= 1490, "{}", kept.len());
    assert_eq!(kept[0], 0);
    assert_eq!(*kept.last().unwrap(), 100_000);
    assert!(kept.windows(2).all(|w| w[0] < w[1]));
    let spacing = 60.0 / 1499.0;
    for w in kept.windows(2) {
        let gap = times[w[1]] - times[w[0]];
        assert!(gap <= spacing + 6e-4 + 1e-9, "gap {gap}");
    }
    // Few samples are all kept; an uneven last step is kept too.
    assert_eq!(decimate(&[0.0, 1.0, 2.0], 10), vec![0, 1, 2]);
    assert_eq!(*decimate(&[0.0, 0.1, 0.2, 0.3, 0.35], 3).last().unwrap(), 4);
}

#[test]
fn sixty_seconds_of_a_thirty_link_chain_make_a_page_under_5_mb() {
    for family in [Family::Planar, Family::Spatial] {
        let scene = Scene::new(&chain(family, 30), &[]).unwrap();
        // 60 s at a 1 ms step.
        let recording = recording(30, 60.0, 60_001);
        let html = scene.html(&recording).unwrap();
        let data = embedded_data(&html);
        let frames = data["frames"].as_array().unwrap();
        assert!(frames.len() >= 1000, "{} frames", frames.len());
        assert_eq!(data["t"][frames.len() - 1], 60.0, "the last sample is kept");
        assert_eq!(frames[0].as_array().unwrap().len(), 31 * 3 + 30 * 7);
        assert!(html.len() < 5_000_000, "{family:?}: {} bytes", html.len());
        eprintln!(
            "{family:?} chain of 30, 60 s: {} frames, {} bytes",
            frames.len(),
            html.len()
        );
    }
}

/// The model texts the examples animate derive the same equations as the
/// systems they simulate.
#[test]
fn the_animated_model_texts_are_the_simulated_systems() {
    use dalembert_fixtures::seeds::{ConstrainedPendulum, RotatingBar};
    use dalembert_fixtures::slider_crank::SliderCrank;
    let unicode = dalembert_codegen::Style::Unicode;
    for (text, equations) in [
        (
            include_str!("../../../examples/slider_crank/slider_crank.dal"),
            SliderCrank::EQUATIONS,
        ),
        (
            DOUBLE_PENDULUM,
            dalembert_fixtures::seeds::DoublePendulum::EQUATIONS,
        ),
        (
            include_str!("../../../generated/models/rotating_bar.dal"),
            RotatingBar::EQUATIONS,
        ),
        (
            include_str!("../../../generated/models/constrained_pendulum.dal"),
            ConstrainedPendulum::EQUATIONS,
        ),
    ] {
        assert_eq!(
            dalembert_codegen::equations(text, unicode).unwrap(),
            equations
        );
    }
}

/// A brick thrown on a free joint, its centre off the joint's origin.
const FREE_BRICK: &str = "pub FreeBrick {
    parameters m;
    joint free base { parent: N, child: B, at: O };
    body brick { mass: m, center: base + 0.3 * B.x - 0.1 * B.z, frame: B, inertia: [1, 2, 3] };
}";

/// The rotation matrix of the unit quaternion `(x, y, z, w)` (columns: the
/// turned frame's unit vectors), in the textbook form.
fn rotation_of([x, y, z, w]: [f64; 4]) -> [[f64; 3]; 3] {
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - z * w),
            2.0 * (x * z + y * w),
        ],
        [
            2.0 * (x * y + z * w),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - x * w),
        ],
        [
            2.0 * (x * z - y * w),
            2.0 * (y * z + x * w),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

/// A made-up tumbling throw: the joint's origin on a parabola, the
/// attitude a unit quaternion turning about a tilted axis.
fn thrown(t: f64) -> Vec<f64> {
    let (s, c) = (0.9 * t).sin_cos();
    let axis = [0.48, 0.6, 0.64];
    vec![
        0.5 * t,
        -0.2 * t,
        1.0 + 3.0 * t - 4.905 * t * t,
        s * axis[0],
        s * axis[1],
        s * axis[2],
        c,
    ]
}

#[test]
fn a_free_body_is_drawn_where_its_joint_puts_it_and_turned_by_its_quaternion() {
    let scene = Scene::new(FREE_BRICK, &[2.0]).unwrap();
    let mut recording = Recording::new();
    for i in 0..=40 {
        let t = i as f64 * 0.05;
        recording.push(t, &thrown(t), 1.0);
    }
    let poses = scene.poses(&recording).unwrap();
    let data = embedded_data(&scene.html(&recording).unwrap());
    assert_eq!(data["bodies"], serde_json::json!(["brick"]));
    assert_eq!(data["normal"], serde_json::Value::Null);
    let base = data["points"]
        .as_array()
        .unwrap()
        .iter()
        .position(|p| p == "base")
        .expect("the joint's point is drawn");
    let points = data["points"].as_array().unwrap().len();
    for (k, (t, pose)) in poses.iter().enumerate() {
        let q = thrown(*t);
        let rotation = rotation_of([q[3], q[4], q[5], q[6]]);
        assert_rotation("brick", &pose.rotations[0], &rotation);
        let offset = [0.3, 0.0, -0.1];
        let centre: [f64; 3] =
            std::array::from_fn(|i| q[i] + (0..3).map(|j| rotation[i][j] * offset[j]).sum::<f64>());
        assert_close("centre", &pose.centres[0], &centre);
        assert_close("base", &pose.points[base], &[q[0], q[1], q[2]]);
        // The page's frame: the body's centre, then its quaternion (w, x,
        // y, z), rounded for display, the same turn up to its sign.
        let frame: Vec<f64> = data["frames"][k]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let drawn = &frame[3 * points..3 * points + 7];
        for i in 0..3 {
            assert!(
                (drawn[i] - centre[i]).abs() < 1e-3,
                "{drawn:?} vs {centre:?}"
            );
        }
        let expected = [q[6], q[3], q[4], q[5]];
        let off = |sign: f64| {
            (0..4)
                .map(|i| (sign * drawn[3 + i] - expected[i]).abs())
                .fold(0.0, f64::max)
        };
        assert!(off(1.0).min(off(-1.0)) < 1e-4, "{drawn:?} vs {expected:?}");
    }
}
