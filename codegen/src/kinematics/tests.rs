//! Rotations about constant axes against the same frames built from
//! coordinate-axis rotations, which the seed's examples check: a rotation by
//! `θ` about `[1, 1, 0]` is `rotate_z(π/4)`, then `rotate_x(θ)`, then
//! `rotate_z(−π/4)`; one about `−z` is `rotate_z(−θ)`.

use crate::interpret::{Interpreter, Route, Sample};

/// A system whose body hangs in frame `B`, made by `frames`.
fn system(frames: &str) -> String {
    format!(
        "pub Tilted {{
            parameters m, a, b, g;
            coordinates q1, q2;
            inputs u;
            frame A = N.rotate_y(q1);
            {frames}
            point G = O + a * A.x + b * B.y - a * B.z;
            body rotor {{ mass: m, center: G, frame: B, inertia: [m, 2 * m, 3 * m, m/10, m/20, -m/30] }};
            particle tip {{ mass: m / 2, at: G + b * B.x }};
            gravity -g * N.z;
            torque u * B.x on B reacting A;
            force u * B.z at G;
        }}"
    )
}

/// `M`, `f`, `T`, `V` of two spellings agree at random states, on both
/// routes of the interpreter.
fn assert_same_system(ours: &str, expected: &str) {
    for route in [Route::Dalembert, Route::Lagrange] {
        let a = Interpreter::new(&system(ours), route).unwrap_or_else(|e| panic!("{e}"));
        let b = Interpreter::new(&system(expected), route).unwrap_or_else(|e| panic!("{e}"));
        for seed in 0..4 {
            let sample = Sample::random(&a, seed);
            let at = sample.values();
            let pairs = [
                (a.mass_matrix(&at).concat(), b.mass_matrix(&at).concat()),
                (a.forcing(&at), b.forcing(&at)),
                (vec![a.kinetic_energy(&at)], vec![b.kinetic_energy(&at)]),
                (vec![a.potential_energy(&at)], vec![b.potential_energy(&at)]),
            ];
            for (x, y) in pairs {
                for (p, r) in x.iter().zip(&y) {
                    assert!(
                        (p - r).abs() <= 1e-12 * r.abs().max(1.0),
                        "{ours} vs {expected}: {p:e} vs {r:e} at state {seed}"
                    );
                }
            }
        }
    }
}

const QUARTER_PI: &str = "0.78539816339744830962";

#[test]
fn a_rotation_about_a_diagonal_is_a_conjugated_coordinate_rotation() {
    assert_same_system(
        "frame B = A.rotate([1, 1, 0], q2);",
        &format!(
            "frame C = A.rotate_z({QUARTER_PI}); frame D = C.rotate_x(q2); frame B = D.rotate_z(-{QUARTER_PI});"
        ),
    );
}

#[test]
fn a_rotation_about_a_negative_axis_turns_the_other_way() {
    assert_same_system(
        "frame B = A.rotate([0, 0, -2], q2);",
        "frame B = A.rotate_z(-q2);",
    );
}

#[test]
fn a_unit_axis_and_a_parameter_axis_are_coordinate_rotations() {
    assert_same_system(
        "frame B = A.rotate([0, 3, 0], q2);",
        "frame B = A.rotate_y(q2);",
    );
    assert_same_system(
        "frame B = A.rotate([a, 0, 0], q2);",
        "frame B = A.rotate_x(q2);",
    );
}

#[test]
fn constant_rotations_of_both_signs_compose() {
    assert_same_system(
        "frame C = A.rotate_x(-1.8); frame D = C.rotate_z(q2); frame B = D.rotate([0, 1, 0], 0.4);",
        "frame C = A.rotate([-1, 0, 0], 1.8); frame D = C.rotate_z(q2); frame B = D.rotate_y(0.4);",
    );
}
