//! The emitted control outputs of `models/two_link_arm.dal` against closed
//! forms of a planar two-link arm (tip position, velocity, Jacobian, frame
//! rotation and angular velocity), against the interpreter's evaluation of
//! every output (which checks the optimiser and the emitter), against
//! `M v̇ − f` from the emitted `mass_matrix` and `forcing`, against the
//! scene's positions (`dalembert_codegen::Geometry`), and `Y π = inverse_dynamics` at
//! zero inputs.

use dalembert_codegen::testing::{Interpreter, Random, Route, Values};
use dalembert_generated::two_link_arm::TwoLinkArm;

const SOURCE: &str = include_str!("../../models/two_link_arm.dal");

fn arm(random: &mut Random) -> TwoLinkArm {
    let mut draw = || random.uniform(0.5, 1.5);
    TwoLinkArm {
        m1: draw(),
        m2: draw(),
        l1: draw(),
        l2: draw(),
        c1: draw(),
        c2: draw(),
        I1: draw(),
        I2: draw(),
        g: 9.81,
    }
}

fn parameters(arm: &TwoLinkArm) -> [f64; 9] {
    [
        arm.m1, arm.m2, arm.l1, arm.l2, arm.c1, arm.c2, arm.I1, arm.I2, arm.g,
    ]
}

/// The interpreter's values of `arm`'s parameters `p` at `(q, v, u)`.
fn values<'a>(p: &'a [f64; 9], q: &'a [f64; 2], v: &'a [f64; 2], u: &'a [f64; 2]) -> Values<'a> {
    Values {
        parameters: p,
        t: 0.0,
        q,
        qd: v,
        u,
    }
}

/// A random state `(q, v, v̇, u)`.
fn state(random: &mut Random) -> [[f64; 2]; 4] {
    let mut pair = |low: f64, high: f64| [random.uniform(low, high), random.uniform(low, high)];
    [
        pair(-3.0, 3.0),
        pair(-2.0, 2.0),
        pair(-3.0, 3.0),
        pair(-5.0, 5.0),
    ]
}

fn assert_close(what: &str, a: &[f64], b: &[f64], tolerance: f64) {
    assert_eq!(a.len(), b.len(), "{what}: length");
    let scale = b.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() <= tolerance * scale, "{what}: {a:?} vs {b:?}");
    }
}

#[test]
fn tip_and_forearm_kinematics_match_the_closed_forms() {
    let mut random = Random::new(17);
    for _ in 0..20 {
        let arm = arm(&mut random);
        let [q, v, vdot, _] = state(&mut random);
        let (s1, c1) = q[0].sin_cos();
        let (s12, c12) = (q[0] + q[1]).sin_cos();
        let (l1, l2) = (arm.l1, arm.l2);
        let w = v[0] + v[1];
        let wdot = vdot[0] + vdot[1];
        let position = [l1 * c1 + l2 * c12, l1 * s1 + l2 * s12, 0.0];
        assert_close("position", &arm.position_tip(0.0, &q), &position, 1e-14);
        let jacobian = [
            [-l1 * s1 - l2 * s12, -l2 * s12],
            [l1 * c1 + l2 * c12, l2 * c12],
            [0.0, 0.0],
        ];
        assert_close(
            "jacobian",
            &arm.jacobian_tip(0.0, &q).concat(),
            &jacobian.concat(),
            1e-14,
        );
        let velocity = [
            -l1 * s1 * v[0] - l2 * s12 * w,
            l1 * c1 * v[0] + l2 * c12 * w,
            0.0,
        ];
        assert_close("velocity", &arm.velocity_tip(0.0, &q, &v), &velocity, 1e-14);
        let acceleration = [
            -l1 * (s1 * vdot[0] + c1 * v[0] * v[0]) - l2 * (s12 * wdot + c12 * w * w),
            l1 * (c1 * vdot[0] - s1 * v[0] * v[0]) + l2 * (c12 * wdot - s12 * w * w),
            0.0,
        ];
        assert_close(
            "acceleration",
            &arm.acceleration_tip(0.0, &q, &v, &vdot),
            &acceleration,
            1e-13,
        );
        let rotation = [[c12, -s12, 0.0], [s12, c12, 0.0], [0.0, 0.0, 1.0]];
        assert_close(
            "rotation",
            &arm.rotation_B2(0.0, &q).concat(),
            &rotation.concat(),
            1e-14,
        );
        assert_close(
            "angular velocity",
            &arm.angular_velocity_B2(0.0, &q, &v),
            &[0.0, 0.0, w],
            1e-14,
        );
        assert_close(
            "angular jacobian",
            &arm.angular_jacobian_B2(0.0, &q).concat(),
            &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0],
            0.0,
        );
        // In the forearm's axes: Rᵀ v.
        let in_forearm = [
            c12 * velocity[0] + s12 * velocity[1],
            -s12 * velocity[0] + c12 * velocity[1],
            0.0,
        ];
        assert_close(
            "velocity in B2",
            &arm.velocity_tip_in_B2(0.0, &q, &v),
            &in_forearm,
            1e-14,
        );
    }
}

#[test]
fn inverse_dynamics_is_m_vdot_minus_f_of_the_emitted_functions() {
    let mut random = Random::new(18);
    for _ in 0..50 {
        let arm = arm(&mut random);
        let [q, v, vdot, u] = state(&mut random);
        let m = arm.mass_matrix(&q);
        let f = arm.forcing(0.0, &q, &v, &u);
        let expected: Vec<f64> = (0..2)
            .map(|i| m[i][0] * vdot[0] + m[i][1] * vdot[1] - f[i])
            .collect();
        let id = arm.inverse_dynamics(0.0, &q, &v, &vdot, &u);
        assert_close("inverse dynamics", &id, &expected, 1e-13);
        // And the accelerations it is the inverse of.
        let accelerations = arm.accelerations(0.0, &q, &v, &u).unwrap();
        let residual = arm.inverse_dynamics(0.0, &q, &v, &accelerations, &u);
        assert_close(
            "M v̇ − f at v̇ = accelerations",
            &residual,
            &[0.0, 0.0],
            1e-13,
        );
    }
}

#[test]
fn regressor_times_base_parameters_is_the_inverse_dynamics() {
    let mut random = Random::new(19);
    for _ in 0..50 {
        let arm = arm(&mut random);
        let [q, v, vdot, _] = state(&mut random);
        let y = arm.regressor(&q, &v, &vdot);
        let pi = arm.base_parameters();
        let y_pi: Vec<f64> = y
            .iter()
            .map(|row| row.iter().zip(&pi).map(|(a, b)| a * b).sum())
            .collect();
        let id = arm.inverse_dynamics(0.0, &q, &v, &vdot, &[0.0; 2]);
        assert_close("Y π", &y_pi, &id, 1e-12);
    }
    assert_eq!(
        TwoLinkArm::BASE_PARAMETERS,
        [
            "m1*c1*g + m2*l1*g",
            "m1*c1^2 + m2*l1^2 + I1",
            "m2*l1*c2",
            "m2*c2*g",
            "m2*c2^2 + I2",
        ]
    );
}

#[test]
fn emitted_outputs_equal_the_interpreted_ones() {
    let interpreter = Interpreter::new(SOURCE, Route::Dalembert).unwrap();
    let mut random = Random::new(20);
    for _ in 0..20 {
        let arm = arm(&mut random);
        let [q, v, vdot, u] = state(&mut random);
        let p = parameters(&arm);
        let at = values(&p, &q, &v, &u);
        let interpreted = |name: &str| interpreter.output(name, &at, &vdot).unwrap();
        let emitted: [(&str, Vec<f64>); 10] = [
            (
                "inverse_dynamics",
                arm.inverse_dynamics(0.0, &q, &v, &vdot, &u).to_vec(),
            ),
            ("position_tip", arm.position_tip(0.0, &q).to_vec()),
            ("velocity_tip", arm.velocity_tip(0.0, &q, &v).to_vec()),
            (
                "acceleration_tip",
                arm.acceleration_tip(0.0, &q, &v, &vdot).to_vec(),
            ),
            ("jacobian_tip", arm.jacobian_tip(0.0, &q).concat()),
            ("rotation_B2", arm.rotation_B2(0.0, &q).concat()),
            (
                "angular_velocity_B2",
                arm.angular_velocity_B2(0.0, &q, &v).to_vec(),
            ),
            (
                "angular_jacobian_B2",
                arm.angular_jacobian_B2(0.0, &q).concat(),
            ),
            (
                "velocity_tip_in_B2",
                arm.velocity_tip_in_B2(0.0, &q, &v).to_vec(),
            ),
            ("base_parameters", arm.base_parameters().to_vec()),
        ];
        for (name, value) in emitted {
            assert_close(name, &value, &interpreted(name), 1e-13);
        }
        assert_close(
            "regressor",
            &arm.regressor(&q, &v, &vdot).concat(),
            &interpreted("regressor"),
            1e-13,
        );
    }
}

#[test]
fn the_scene_draws_the_tip_where_position_puts_it() {
    let geometry = dalembert_codegen::Geometry::new(SOURCE).unwrap();
    let tip = geometry.points().iter().position(|p| p == "tip").unwrap();
    let mut random = Random::new(21);
    for _ in 0..20 {
        let arm = arm(&mut random);
        let [q, v, _, u] = state(&mut random);
        let p = parameters(&arm);
        let at = values(&p, &q, &v, &u);
        let drawn = geometry.positions(&at)[tip];
        assert_close("tip", &arm.position_tip(0.0, &q), &drawn, 1e-12);
    }
}
