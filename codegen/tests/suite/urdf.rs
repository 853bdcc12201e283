//! URDF import against Pinocchio: the models `dalembert urdf` writes for
//! five real robots of example-robot-data (panda, ur5, solo12, ANYmal C, the
//! double pendulum), evaluated by the interpreter on both routes
//! (d'Alembert's, as the generator derives them, and Lagrange's), match
//! Pinocchio's crba, nle, aba and energies in
//! `tests/reference/urdf/pinocchio.json` (written by
//! `scripts/urdf_reference.py` with Pinocchio's own URDF parser). The
//! comparison itself is `pinocchio/mod.rs`, which
//! `examples/urdf_numeric_sweep.rs` also runs on every robot of
//! example-robot-data.

use crate::pinocchio;
use dalembert_codegen::Urdf;

use dalembert_codegen::testing::{
    Interpreter, Route, Values, cross, quaternion_rotation, transpose_vec,
};
use pinocchio::{QUANTITIES, relative_error, worst_errors};
use serde_json::Value;

fn reference_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/reference/urdf")
}

fn reference() -> Value {
    let text = std::fs::read_to_string(reference_dir().join("pinocchio.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// The worst relative errors over the robot's states: M, f, T, V, q̈.
fn robot_worst_errors(robot: &str, route: Route) -> [f64; 5] {
    let reference = reference();
    let entry = reference["models"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["robot"] == robot)
        .unwrap();
    let model = Urdf::read(reference_dir().join(entry["urdf"].as_str().unwrap()))
        .unwrap()
        .floating(robot.ends_with("_floating"))
        .model()
        .unwrap();
    let worst = worst_errors(&model, entry, route).unwrap();
    eprintln!(
        "{robot} {route:?}: worst relative errors M {:.1e}, f {:.1e}, T {:.1e}, V {:.1e}, qdd {:.1e}",
        worst[0], worst[1], worst[2], worst[3], worst[4]
    );
    worst
}

/// `robot` on both routes, every quantity within `tolerance` of its largest
/// entry (set at about ten times the agreement measured, which each test's
/// comment gives).
fn matches_pinocchio(robot: &str, tolerance: f64) {
    matches_pinocchio_on(robot, &[Route::Dalembert, Route::Lagrange], tolerance);
}

fn matches_pinocchio_on(robot: &str, routes: &[Route], tolerance: f64) {
    for &route in routes {
        let worst = robot_worst_errors(robot, route);
        for (error, what) in worst.iter().zip(QUANTITIES) {
            assert!(
                *error <= tolerance,
                "{robot} ({route:?}): {what} is off by {error:e} relative"
            );
        }
    }
}

#[test]
fn panda_matches_pinocchio() {
    // Measured (worst of both routes): M 5.5e-16, f 7.1e-16, T 7.8e-16,
    // V 4.5e-16, q̈ 2.5e-15.
    matches_pinocchio("panda", 3e-14);
}

#[test]
fn ur5_matches_pinocchio() {
    // Measured: M 7.1e-16, f 4.1e-16, T 6.4e-16, V 7.3e-16, q̈ 4.6e-16.
    matches_pinocchio("ur5_robot", 1e-14);
}

#[test]
fn solo12_matches_pinocchio() {
    // Measured: M 7.2e-16, f 3.7e-16, T 3.4e-16, V 8.3e-15, q̈ 1.5e-15.
    matches_pinocchio("solo12", 1e-13);
}

/// A small robot with what the real ones leave out: a continuous joint,
/// unaligned and negative axes, rotated inertial frames, a rotated fixed
/// joint carrying a moving one, a massless link, siblings out of
/// alphabetical order (imported, as Pinocchio orders them, by name).
#[test]
fn feature_robot_matches_pinocchio() {
    // Measured: M 7.4e-16, f 8.2e-16, T 4.6e-16, V 1.8e-16, q̈ 3.4e-16.
    matches_pinocchio("features", 1e-14);
}

/// ANYmal C, whose file lists links that no mass distribution has (its four
/// depth cameras break the triangle inequality; the hatch's tensor has rank
/// one): welded to the base they make bodies that are
/// physical, and the import matches Pinocchio, on a fixed and on a floating
/// base, without a warning.
#[test]
fn anymal_c_matches_pinocchio() {
    let path = reference_dir().join("anymal_c.urdf");
    for floating in [false, true] {
        let imported = Urdf::read(&path)
            .unwrap()
            .floating(floating)
            .import()
            .unwrap();
        assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
    }
    // Measured: M 1.1e-15, f 6.8e-16, T 1.0e-15, V 1.4e-15, q̈ 1.1e-15; on
    // the floating base M 1.4e-16, f 4.7e-16, T 8.0e-16, V 7.3e-16, q̈ 2.2e-15.
    matches_pinocchio("anymal_c", 2e-14);
    matches_pinocchio_on("anymal_c_floating", &[Route::Dalembert], 3e-14);
}

/// The double pendulum of example-robot-data lists products of inertia of
/// 1e-13 and 1e-16 beside moments of 1e-3: the import keeps them, as
/// Pinocchio does, and matches it to rounding, not just to the others' tolerance
/// (it once wrote them as zero: on a floating base `M` was off by 5e-13 and
/// `T` by 2e-12 of their size). `q̈` is left to the other tests: `M`'s
/// condition number (5e4 floating) makes its agreement 1e-12 at best.
#[test]
fn double_pendulum_keeps_its_small_products_of_inertia() {
    for robot in [
        "regressions/double_pendulum",
        "regressions/double_pendulum_floating",
    ] {
        let worst = robot_worst_errors(robot, Route::Dalembert);
        for (error, what) in worst.iter().zip(QUANTITIES).take(4) {
            assert!(*error <= 1e-14, "{robot}: {what} is off by {error:e}");
        }
    }
}

/// Solo12 on a floating base (`--floating`) against Pinocchio's free flyer:
/// d'Alembert's route only, as Lagrange's needs every speed to be a rate.
#[test]
fn floating_solo12_matches_pinocchio_free_flyer() {
    // Measured: M 1.3e-17, f 5.2e-16, T 6.1e-16, V 5.0e-16, q̈ 6.2e-15.
    matches_pinocchio_on("solo12_floating", &[Route::Dalembert], 1e-13);
}

/// A robot with no joint (a quadrotor's body) is one rigid body on
/// `--floating`: against the closed form of a free body, with speeds
/// `(v, ω)` of its origin in its own axes, centre `c` and central inertia
/// `I_c`: `M = [[m 1, −m [c]×], [m [c]×, I_c − m [c]×²]]`, and at rest the
/// forcing is gravity's wrench about the origin, `(m Rᵀ g, c × m Rᵀ g)`.
#[test]
fn a_robot_without_joints_floats_as_one_rigid_body() {
    let text = r#"<robot name="quad">
  <link name="base">
    <inertial>
      <origin xyz="0.01 -0.02 0.03"/>
      <mass value="1.5"/>
      <inertia ixx="0.02" iyy="0.03" izz="0.04" ixy="0.001" ixz="-0.002" iyz="0.003"/>
    </inertial>
  </link>
</robot>"#;
    let model = Urdf::new("quad.urdf", text).floating(true).model().unwrap();
    let interpreter = Interpreter::new(&model, Route::Dalembert).unwrap();
    assert_eq!((interpreter.nq(), interpreter.nv()), (7, 6));
    let (m, c) = (1.5, [0.01, -0.02, 0.03]);
    let inertia = [
        [0.02, 0.001, -0.002],
        [0.001, 0.03, 0.003],
        [-0.002, 0.003, 0.04],
    ];
    let skew = [[0.0, -c[2], c[1]], [c[2], 0.0, -c[0]], [-c[1], c[0], 0.0]];
    let mut expected = [[0.0; 6]; 6];
    for i in 0..3 {
        expected[i][i] = m;
        for j in 0..3 {
            expected[i][3 + j] = -m * skew[i][j];
            expected[3 + i][j] = m * skew[i][j];
            let cc: f64 = (0..3).map(|k| skew[i][k] * skew[k][j]).sum();
            expected[3 + i][3 + j] = inertia[i][j] - m * cc;
        }
    }
    // A turned body at rest: unit quaternion (x, y, z, w) of half-angles.
    let (x, y, z, w) = (0.2, -0.4, 0.1, (1.0_f64 - 0.04 - 0.16 - 0.01).sqrt());
    let q = [0.3, -0.2, 1.0, x, y, z, w];
    // Gravity in the body's axes, and its moment about the origin.
    let weight = transpose_vec(&quaternion_rotation([x, y, z, w]), [0.0, 0.0, -9.81 * m]);
    let moment = cross(c, weight);
    let at = Values {
        parameters: &[],
        t: 0.0,
        q: &q,
        qd: &[0.0; 6],
        u: &[],
    };
    let mass = interpreter.mass_matrix(&at);
    assert!(
        relative_error(&mass.concat(), &expected.concat()) < 1e-14,
        "{mass:?}"
    );
    let f = interpreter.forcing(&at);
    let gravity: Vec<f64> = weight.into_iter().chain(moment).collect();
    assert!(
        relative_error(&f, &gravity) < 1e-14,
        "{f:?} against {gravity:?}"
    );
}
