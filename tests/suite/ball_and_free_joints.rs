//! Spherical and free joints (docs/architecture.md §4) against independent routes: a
//! bob on a ball joint at the tip of a turning arm against the same system
//! in Z-Y-X angles (whose `M`, `f`, `T`, `V` are checked against
//! dal_sympy.py's numbers first, `tests/reference/dal_sympy_states.json`), with the angles' rates and accelerations
//! mapped to the body-axis angular velocity and its rate by hand; the
//! quaternion kinematics `q̇ = ½ q ⊗ (ω, 0)`; and a free body whose joint
//! point is neither `O` nor its centre of mass, against Newton–Euler in
//! closed form.

use dalembert::Model;
use dalembert_codegen::testing::{cross, quaternion_rotation, transpose_vec};
use dalembert_fixtures::reference::{SympyState, assert_near, assert_near_all, sympy_states};

dalembert::dalembert! {
    /// A bob on a ball joint at the tip of a turning arm, in Z-Y-X angles.
    pub SwingEuler {
        parameters m, M, l, d, g, I1, I2, I3;
        coordinates phi, a, b, c;
        inputs u;
        frame A = N.rotate_z(phi);
        point P = O + l * A.x;
        point H = O + l / 2 * A.x;
        body arm { mass: M, center: H, frame: A, inertia: [M*l^2/100, M*l^2/12, M*l^2/12] };
        frame Ba = A.rotate_z(a);
        frame Bb = Ba.rotate_y(b);
        frame B = Bb.rotate_x(c);
        point G = P - d * B.z + 0.1 * B.x;
        body bob { mass: m, center: G, frame: B, inertia: [I1, I2, I3] };
        gravity -g * N.z;
        torque u * N.z on A;
    }
}

dalembert::dalembert! {
    /// The same bob on a spherical joint.
    pub SwingBall {
        parameters m, M, l, d, g, I1, I2, I3;
        coordinates phi;
        inputs u;
        frame A = N.rotate_z(phi);
        point P = O + l * A.x;
        joint spherical ball { parent: A, child: B, at: P };
        body arm { mass: M, center: O + l / 2 * A.x, frame: A, inertia: [M*l^2/100, M*l^2/12, M*l^2/12] };
        body bob { mass: m, center: ball - d * B.z + 0.1 * B.x, frame: B, inertia: [I1, I2, I3] };
        gravity -g * N.z;
        torque u * N.z on A;
    }
}

dalembert::dalembert! {
    /// A body on a free joint placed away from `O`, its centre away from
    /// the joint's point.
    pub Offset {
        parameters m, I1, I2, I3, g, cx, cy, cz;
        point P = O + 0.3 * N.x - 0.2 * N.y + 0.5 * N.z;
        joint free base { parent: N, child: B, at: P };
        body b { mass: m, center: base + cx * B.x + cy * B.y + cz * B.z, frame: B, inertia: [I1, I2, I3] };
        gravity -g * N.z;
    }
}

const EULER: SwingEuler = SwingEuler {
    m: 0.9,
    M: 1.4,
    l: 0.8,
    d: 0.5,
    g: 9.81,
    I1: 0.03,
    I2: 0.05,
    I3: 0.02,
};

/// The ball-joint swing with the parameters of [`EULER`].
#[allow(non_snake_case)]
fn ball_swing() -> SwingBall {
    let SwingEuler {
        m,
        M,
        l,
        d,
        g,
        I1,
        I2,
        I3,
    } = EULER;
    SwingBall {
        m,
        M,
        l,
        d,
        g,
        I1,
        I2,
        I3,
    }
}

/// dal_sympy's `M`, `f`, `T`, `V` of `SwingEuler` at its stored states.
fn swing_states() -> Vec<SympyState<4, 1>> {
    sympy_states("SwingEuler", &EULER.parameter_values())
}

/// The Hamilton product `p ⊗ r` of quaternions `(x, y, z, w)`.
fn product([px, py, pz, pw]: [f64; 4], [rx, ry, rz, rw]: [f64; 4]) -> [f64; 4] {
    [
        pw * rx + px * rw + py * rz - pz * ry,
        pw * ry - px * rz + py * rw + pz * rx,
        pw * rz + px * ry - py * rx + pz * rw,
        pw * rw - px * rx - py * ry - pz * rz,
    ]
}

/// The quaternion of `Rz(a) Ry(b) Rx(c)`.
fn quaternion_of_angles([a, b, c]: [f64; 3]) -> [f64; 4] {
    let z = [0.0, 0.0, (a / 2.0).sin(), (a / 2.0).cos()];
    let y = [0.0, (b / 2.0).sin(), 0.0, (b / 2.0).cos()];
    let x = [(c / 2.0).sin(), 0.0, 0.0, (c / 2.0).cos()];
    product(product(z, y), x)
}

/// The angular velocity in the child's axes and its rate, from the Z-Y-X
/// angles, their rates and their accelerations (differentiated by hand).
fn body_rates(
    [_, b, c]: [f64; 3],
    [da, db, dc]: [f64; 3],
    [dda, ddb, ddc]: [f64; 3],
) -> ([f64; 3], [f64; 3]) {
    let (sb, cb, sc, cc) = (b.sin(), b.cos(), c.sin(), c.cos());
    let omega = [
        dc - da * sb,
        db * cc + da * cb * sc,
        -db * sc + da * cb * cc,
    ];
    let rate = [
        ddc - dda * sb - da * db * cb,
        ddb * cc - db * dc * sc + dda * cb * sc - da * db * sb * sc + da * dc * cb * cc,
        -ddb * sc - db * dc * cc + dda * cb * cc - da * db * sb * cc - da * dc * cb * sc,
    ];
    (omega, rate)
}

#[test]
fn the_euler_angle_swing_matches_dal_sympy() {
    for r in &swing_states() {
        for (k, row) in EULER.mass_matrix(&r.q).iter().enumerate() {
            assert_near_all(&format!("M[{k}]"), row, &r.mass[k], 1e-11);
        }
        assert_near_all(
            "f",
            &EULER.forcing(r.t, &r.q, &r.v, &r.u),
            &r.forcing,
            1e-11,
        );
        assert_near("T", EULER.kinetic_energy(&r.q, &r.v), r.kinetic, 1e-11);
        assert_near("V", EULER.potential_energy(&r.q), r.potential, 1e-11);
    }
}

#[test]
fn a_ball_joint_on_a_turning_arm_moves_as_its_euler_angles() {
    assert_eq!(
        SwingBall::COORDINATES,
        ["phi", "ball_qx", "ball_qy", "ball_qz", "ball_qw"]
    );
    assert_eq!(
        SwingBall::SPEEDS,
        ["dt(phi)", "ball_wx", "ball_wy", "ball_wz"]
    );
    let swing = ball_swing();
    for r in &swing_states() {
        let accelerations =
            dalembert::accelerations(&EULER, r.t, &r.q, &r.v, &r.u).expect("regular");
        let angles = [r.q[1], r.q[2], r.q[3]];
        let (omega, omega_rate) = body_rates(
            angles,
            [r.v[1], r.v[2], r.v[3]],
            [accelerations[1], accelerations[2], accelerations[3]],
        );
        let [x, y, z, w] = quaternion_of_angles(angles);
        let q = [r.q[0], x, y, z, w];
        let v = [r.v[0], omega[0], omega[1], omega[2]];
        assert_near("T", swing.kinetic_energy(&q, &v), r.kinetic, 1e-11);
        assert_near("V", swing.potential_energy(&q), r.potential, 1e-11);
        let ball = dalembert::accelerations(&swing, r.t, &q, &v, &r.u).expect("regular");
        let expected = [
            accelerations[0],
            omega_rate[0],
            omega_rate[1],
            omega_rate[2],
        ];
        assert_near_all("v̇", &ball, &expected, 1e-10);
        let half = product([x, y, z, w], [omega[0], omega[1], omega[2], 0.0]).map(|c| c / 2.0);
        let rates = swing.coordinate_rates(&q, &v);
        assert_near_all(
            "q̇",
            &rates,
            &[r.v[0], half[0], half[1], half[2], half[3]],
            1e-14,
        );
    }
}

#[test]
fn a_free_body_off_its_joint_point_falls_by_newton_and_euler() {
    let body = Offset {
        m: 1.7,
        I1: 0.2,
        I2: 0.35,
        I3: 0.5,
        g: 9.81,
        cx: 0.3,
        cy: -0.1,
        cz: 0.25,
    };
    let quaternion = [0.3, -0.5, 0.2, 0.8];
    let norm = quaternion.iter().map(|c| c * c).sum::<f64>().sqrt();
    let [qx, qy, qz, qw] = quaternion.map(|c| c / norm);
    let q = [0.4, -1.1, 0.9, qx, qy, qz, qw];
    let (v_joint, omega) = ([0.6, -0.3, 1.2], [1.5, -0.8, 2.1]);
    let v = [
        v_joint[0], v_joint[1], v_joint[2], omega[0], omega[1], omega[2],
    ];
    let vdot = dalembert::accelerations(&body, 0.0, &q, &v, &[]).expect("regular");
    let inertia = [body.I1, body.I2, body.I3];
    let momentum = [0, 1, 2].map(|i| inertia[i] * omega[i]);
    let gyroscopic = cross(omega, momentum);
    let alpha = [0, 1, 2].map(|i| -gyroscopic[i] / inertia[i]);
    let rotation = quaternion_rotation([qx, qy, qz, qw]);
    let gravity = transpose_vec(&rotation, [0.0, 0.0, -body.g]);
    let c = [body.cx, body.cy, body.cz];
    let (spin, whirl, transport) = (
        cross(alpha, c),
        cross(omega, cross(omega, c)),
        cross(omega, v_joint),
    );
    let linear = [0, 1, 2].map(|i| gravity[i] - spin[i] - whirl[i] - transport[i]);
    assert_near_all(
        "v̇",
        &vdot,
        &[
            linear[0], linear[1], linear[2], alpha[0], alpha[1], alpha[2],
        ],
        1e-12,
    );
    let centre = [0, 1, 2]
        .map(|i| q[i] + [0.3, -0.2, 0.5][i] + (0..3).map(|j| rotation[i][j] * c[j]).sum::<f64>());
    assert_near(
        "V",
        body.potential_energy(&q),
        body.m * body.g * centre[2],
        1e-12,
    );
}
