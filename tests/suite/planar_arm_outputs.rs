//! The control outputs of a planar arm with a slide and a payload on a
//! massless wrist, spelled with frames and points and with `joint`s, against
//! their derivatives (the checks of `output_checks`), and the two spellings
//! against each other.

use dalembert_fixtures::reference::{assert_close, flat};

use crate::output_checks::*;

/// The planar arm (a shoulder, a slide along the upper arm, a wrist without
/// mass carrying a payload) in one spelling of its geometry, its loads and
/// outputs common to both, and its constant `$value`.
macro_rules! arm {
    ($(#[$doc:meta])* $name:ident = $value:ident, $($geometry:tt)*) => {
        dalembert::dalembert! {
            $(#[$doc])*
            pub $name {
                parameters m1, m2, mp, l1, l2, I1, I2, g;
                coordinates th, s, ph;
                inputs tau, push, twist;
                $($geometry)*
                point P = S + l2 * W.x;
                point C1 = O + l1 / 2 * A.x;
                body upper { mass: m1, center: C1, frame: A, inertia: [0, 0, I1] };
                body slider { mass: m2, center: S, frame: B, inertia: [0, 0, I2] };
                particle payload { mass: mp, at: P };
                gravity -g * N.y;
                torque tau * N.z on A;
                force push * A.x at S;
                torque twist * N.z on W reacting B;
                outputs inverse_dynamics, inverse_dynamics_jacobian, accelerations_jacobian, linearize, regressor;
                outputs position(P), velocity(P), acceleration(P), jacobian(P);
                outputs position(P in A), velocity(P in A), acceleration(P in A), jacobian(P in A);
                outputs rotation(A), rotation(W), angular_velocity(W), angular_jacobian(W);
                outputs rotation(W in A), angular_velocity(W in A), angular_jacobian(W in A);
            }
        }

        pub(crate) const $value: $name = $name {
            m1: 2.1,
            m2: 0.9,
            mp: 0.45,
            l1: 0.8,
            l2: 0.35,
            I1: 0.11,
            I2: 0.02,
            g: 9.81,
        };
    };
}

arm! {
    /// The arm with frames and points.
    ArmByPoints = ARM_BY_POINTS,
    frame A = N.rotate_z(th);
    frame B = A.rotate_z(0);
    point S = O + s * A.x;
    frame W = B.rotate_z(ph);
}

arm! {
    /// The arm with joints.
    ArmByJoints = ARM_BY_JOINTS,
    joint revolute shoulder { parent: N, child: A, axis: z, coordinate: th, at: O };
    joint prismatic slide { parent: A, child: B, axis: x, coordinate: s, at: O };
    point S = slide;
    joint revolute wrist { parent: B, child: W, axis: z, coordinate: ph, at: S };
}

#[test]
fn arm_outputs_match_their_derivatives() {
    let dynamics = dynamic_outputs!(ARM_BY_POINTS);
    let payload = point_outputs!(
        ARM_BY_POINTS,
        position_P,
        velocity_P,
        acceleration_P,
        jacobian_P
    );
    let payload_in_a = point_outputs!(
        ARM_BY_POINTS,
        position_P_in_A,
        velocity_P_in_A,
        acceleration_P_in_A,
        jacobian_P_in_A
    );
    let wrist = frame_outputs!(
        ARM_BY_POINTS,
        rotation_W,
        angular_velocity_W,
        angular_jacobian_W
    );
    let wrist_in_a = frame_outputs!(
        ARM_BY_POINTS,
        rotation_W_in_A,
        angular_velocity_W_in_A,
        angular_jacobian_W_in_A
    );
    let upper = |t, q: &[f64; 3]| ARM_BY_POINTS.rotation_A(t, q);
    for x in samples::<3, 3, 3>(1) {
        check_dynamics(&ARM_BY_POINTS, &dynamics, &x);
        check_regressor(
            |q, v, a| ARM_BY_POINTS.regressor(q, v, a),
            ARM_BY_POINTS.base_parameters(),
            |q, v, a| ARM_BY_POINTS.inverse_dynamics(x.t, q, v, a, &[0.0; 3]),
            &x,
        );
        check_point_in_n(&ARM_BY_POINTS, &payload, &x);
        check_point_in_frame(&payload, &payload_in_a, upper, &x);
        check_frame_in_n(&ARM_BY_POINTS, &wrist, &x);
        check_frame_in_frame(&wrist, &wrist_in_a, upper, &x);
    }
}

/// Spelled with joints, the arm has the same outputs to rounding.
#[test]
fn arm_by_joints_has_the_outputs_of_arm_by_points() {
    for x in samples::<3, 3, 3>(2) {
        let (t, q, v, a, u) = (x.t, &x.q, &x.v, &x.vdot, &x.u);
        let pairs: [(&str, Vec<f64>, Vec<f64>); 9] = [
            (
                "τ",
                ARM_BY_JOINTS.inverse_dynamics(t, q, v, a, u).to_vec(),
                ARM_BY_POINTS.inverse_dynamics(t, q, v, a, u).to_vec(),
            ),
            (
                "Y",
                flat(&ARM_BY_JOINTS.regressor(q, v, a)),
                flat(&ARM_BY_POINTS.regressor(q, v, a)),
            ),
            (
                "π",
                ARM_BY_JOINTS.base_parameters().to_vec(),
                ARM_BY_POINTS.base_parameters().to_vec(),
            ),
            (
                "A",
                flat(&ARM_BY_JOINTS.linearize(t, q, v, u).expect("regular").0),
                flat(&ARM_BY_POINTS.linearize(t, q, v, u).expect("regular").0),
            ),
            (
                "B",
                flat(&ARM_BY_JOINTS.linearize(t, q, v, u).expect("regular").1),
                flat(&ARM_BY_POINTS.linearize(t, q, v, u).expect("regular").1),
            ),
            (
                "a_P in A",
                ARM_BY_JOINTS.acceleration_P_in_A(t, q, v, a).to_vec(),
                ARM_BY_POINTS.acceleration_P_in_A(t, q, v, a).to_vec(),
            ),
            (
                "J_P",
                flat(&ARM_BY_JOINTS.jacobian_P(t, q)),
                flat(&ARM_BY_POINTS.jacobian_P(t, q)),
            ),
            (
                "R_W in A",
                flat(&ARM_BY_JOINTS.rotation_W_in_A(t, q)),
                flat(&ARM_BY_POINTS.rotation_W_in_A(t, q)),
            ),
            (
                "J_W",
                flat(&ARM_BY_JOINTS.angular_jacobian_W(t, q)),
                flat(&ARM_BY_POINTS.angular_jacobian_W(t, q)),
            ),
        ];
        for (what, joints, points) in pairs {
            assert_close(what, &joints, &points, 1e-13);
        }
    }
    assert_eq!(ArmByJoints::BASE_PARAMETERS, ArmByPoints::BASE_PARAMETERS);
}
