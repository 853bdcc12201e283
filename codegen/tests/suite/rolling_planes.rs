//! `rolling` on planes whose normal is not `N.z`: the normal `F.x` of a
//! fixed, tilted frame takes the no-slip rows along `F.y` then `F.z`, and
//! `F.y` along `F.z` then `F.x` (DESIGN's cyclic order), with a plane
//! `through:` a point off `O` and a torus `tire:`. The interpreter's
//! residual (the contact row) and constraint jacobian (the two no-slip
//! rows' coefficients of the speeds) match the design's formulas
//! evaluated with numpy (`tests/reference/rolling_planes.json`,
//! `scripts/rolling_planes_reference.py`).

use crate::urdf_frames::numbers;

use dalembert_codegen::testing::{Interpreter, Route, Values};
use serde_json::Value;

const TOLERANCE: f64 = 1e-12;

/// The disc of the reference on the plane with normal `normal` of `frame`.
fn disc(frame: &str, normal: &str) -> String {
    format!(
        "Disc {{
            parameters m, r, rt, g;
            coordinates x, y, z, psi, theta, phi;
            frame A = N.rotate_z(psi);
            frame C = A.rotate_x(theta);
            frame B = C.rotate_y(phi);
            frame {frame};
            point G = O + x * N.x + y * N.y + z * N.z;
            point Q = O + 0.2 * N.x + 0.1 * N.z;
            body disc {{ mass: m, center: G, frame: B, inertia: [m*r^2/4, m*r^2/2, m*r^2/4] }};
            gravity -g * N.z;
            rolling contact {{ wheel: B, axle: B.y, center: G, radius: r, plane: {normal}, tire: rt, through: Q }};
        }}"
    )
}

fn matches_closed_form(case: &str, frame: &str, normal: &str) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/reference/rolling_planes.json");
    let reference: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let interpreter = Interpreter::new(&disc(frame, normal), Route::Dalembert).unwrap();
    assert_eq!(interpreter.nc(), 3);
    let states = reference[case].as_array().unwrap();
    assert!(!states.is_empty());
    for state in states {
        let (q, qd) = (numbers(&state["q"]), numbers(&state["qd"]));
        let values = Values {
            parameters: &[1.0, 0.3, 0.05, 9.81],
            t: 0.0,
            q: &q,
            qd: &qd,
            u: &[],
        };
        let contact = interpreter.constraint_residual(&values)[0];
        let expected = state["contact"].as_f64().unwrap();
        assert!(
            (contact - expected).abs() <= TOLERANCE,
            "{case}: contact {contact} ≠ {expected}"
        );
        let rows = interpreter.constraint_jacobian(&values);
        let expected = numbers(&state["slip_rows"]);
        assert_eq!(rows[1..].concat().len(), expected.len());
        for (ours, theirs) in rows[1..].concat().iter().zip(&expected) {
            assert!(
                (ours - theirs).abs() <= TOLERANCE,
                "{case}: no-slip rows {rows:?} ≠ {expected:?}"
            );
        }
    }
}

#[test]
fn a_plane_of_normal_f_x_slips_along_f_y_then_f_z() {
    matches_closed_form("F.x", "F = N.rotate_y(0.3)", "F.x");
}

#[test]
fn a_plane_of_normal_f_y_slips_along_f_z_then_f_x() {
    matches_closed_form("F.y", "F = N.rotate_x(0.4)", "F.y");
}
