//! The control outputs of a flyer (a free joint) and a swing (a spherical
//! joint) against the checks of `lie_group_output_checks`, `linearize` at rest
//! and moving with the documented kinematic rows `δ̇ = δν − ad(ν̄) δ`.

use crate::lie_group_output_checks::*;

#[test]
fn the_coordinates_and_speeds_are_in_the_documented_order() {
    assert_eq!(
        Flyer::COORDINATES,
        [
            "base_x", "base_y", "base_z", "base_qx", "base_qy", "base_qz", "base_qw", "a"
        ]
    );
    assert_eq!(
        Flyer::SPEEDS,
        [
            "base_vx", "base_vy", "base_vz", "base_wx", "base_wy", "base_wz", "dt(a)"
        ]
    );
    assert_eq!(
        Swing::COORDINATES,
        ["phi", "ball_qx", "ball_qy", "ball_qz", "ball_qw"]
    );
    assert_eq!(Swing::SPEEDS, ["dt(phi)", "ball_wx", "ball_wy", "ball_wz"]);
}

#[test]
fn a_point_beyond_a_free_joint_moves_as_its_position_says() {
    check_point(&FLYER, &flyer_tip(), flyer_state());
}

#[test]
fn a_point_beyond_a_spherical_joint_moves_as_its_position_says() {
    check_point(&SWING, &swing_bob(), swing_state());
}

#[test]
fn a_frame_beyond_a_free_joint_turns_as_its_rotation_says() {
    let (q, v, _) = flyer_state();
    check_frame(&FLYER, &flyer_c(), q, v);
}

#[test]
fn the_frame_of_a_spherical_joint_turns_as_its_rotation_says() {
    let (q, v, _) = swing_state();
    check_frame(&SWING, &swing_b(), q, v);
}

/// The free joint's own frame: its rotation is the quaternion's
/// (docs/language.md: `R(q) = (w² − x² − y² − z²) 1 + 2 x xᵀ + 2 w [x]×`)
/// and its angular velocity is `(wx, wy, wz)` in its own axes.
#[test]
fn the_free_joints_frame_is_its_quaternion_and_body_rates() {
    let (q, v, _) = flyer_state();
    let [x, y, z, w] = [q[3], q[4], q[5], q[6]];
    let expected = [
        [
            w * w + x * x - y * y - z * z,
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            w * w - x * x + y * y - z * z,
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            w * w - x * x - y * y + z * z,
        ],
    ];
    let rotation = FLYER.rotation_B(0.0, &q);
    assert_vec("rotation(B)", &flat(&rotation), &flat(&expected), 1e-15);
    // C turns about B's y axis by a: ω_C = R_B (wx, wy + ȧ, wz).
    let body = [v[3], v[4] + v[6], v[5]];
    let in_n: Vec3 = std::array::from_fn(|i| (0..3).map(|k| rotation[i][k] * body[k]).sum());
    assert_vec("ω_C", &FLYER.angular_velocity_C(0.0, &q, &v), &in_n, 1e-14);
    assert_vec(
        "ω_C in B",
        &FLYER.angular_velocity_C_in_B(0.0, &q, &v),
        &body,
        1e-14,
    );
}

#[test]
fn outputs_in_a_frame_beyond_a_free_joint_are_the_same_vectors_in_its_axes() {
    check_in_frame(
        flyer_state(),
        |q| FLYER.rotation_B(0.0, q),
        (&flyer_tip(), &flyer_tip_in_b()),
        (&flyer_c(), &flyer_c_in_b()),
    );
}

#[test]
fn outputs_in_the_frame_of_a_spherical_joint_are_the_same_vectors_in_its_axes() {
    check_in_frame(
        swing_state(),
        |q| SWING.rotation_B(0.0, q),
        (&swing_bob(), &swing_bob_in_b()),
        (&swing_a(), &swing_a_in_b()),
    );
}

#[test]
fn inverse_dynamics_is_m_vdot_minus_f_on_lie_group_joints() {
    check_inverse_dynamics(
        &FLYER,
        |q, v, vdot, u| FLYER.inverse_dynamics(0.0, q, v, vdot, u),
        flyer_state(),
        [0.7],
    );
    check_inverse_dynamics(
        &SWING,
        |q, v, vdot, u| SWING.inverse_dynamics(0.0, q, v, vdot, u),
        swing_state(),
        [-0.4],
    );
}

#[test]
fn linearize_at_rest_is_the_tangent_space_state_equation() {
    let (q, _, _) = flyer_state();
    let u = [0.7];
    let linear = FLYER.linearize(0.0, &q, &[0.0; 7], &u).expect("regular");
    check_linearize(&FLYER, linear, (q, [0.0; 7], u), [[0.0; 7]; 7]);
    let (q, _, _) = swing_state();
    let u = [-0.4];
    let linear = SWING.linearize(0.0, &q, &[0.0; 4], &u).expect("regular");
    check_linearize(&SWING, linear, (q, [0.0; 4], u), [[0.0; 4]; 4]);
}

/// Moving, the free joint's kinematic rows are (docs/language.md)
/// `δ̇_v = δv − ω̄ × δ_v − v̄ × δ_ω` and `δ̇_ω = δω − ω̄ × δ_ω`, in the
/// child's axes; the hinge's is `δ̇_a = δȧ`.
#[test]
fn linearize_while_moving_has_the_documented_kinematic_rows() {
    let (q, v, _) = flyer_state();
    let u = [0.7];
    let mut kinematic = [[0.0; 7]; 7];
    minus_cross(&mut kinematic, (0, 0), &v[3..6]);
    minus_cross(&mut kinematic, (0, 3), &v[0..3]);
    minus_cross(&mut kinematic, (3, 3), &v[3..6]);
    let linear = FLYER.linearize(0.0, &q, &v, &u).expect("regular");
    check_linearize(&FLYER, linear, (q, v, u), kinematic);
}
