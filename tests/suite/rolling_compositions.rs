//! Rolling composed with joints and speeds of one's own, against the
//! SymPy references of `tests/suite/rolling_wheels.rs`.
//!
//! **A free joint.** The `rolling` statement on a free joint: the thin disc of
//! `tests/suite/rolling_wheels.rs`, its attitude a quaternion and its speeds the
//! joint's (the centre's velocity and the angular velocity, in the disc's
//! axes), rolls as SymPy's disc in Euler angles. At the states on the
//! constraint manifold of `tests/reference/rolling_wheels.json` (`disc`:
//! centre `(x, y, z)`, yaw `ψ`, lean `θ`, spin `φ`, speeds the rates),
//! turned into the joint's coordinates and speeds, the centre's
//! acceleration and the angular acceleration in `N` are `KanesMethod`'s.
//!
//! From Euler angles: `R = R_z(ψ) R_x(θ) R_y(φ)`, the quaternion
//! `q_z(ψ) ⊗ q_x(θ) ⊗ q_y(φ)`, `ω_N = ψ̇ N.z + θ̇ A.x + φ̇ C.y`
//! (`A.x = R_z(ψ) e_x`, `C.y = R_z(ψ) R_x(θ) e_y`) and
//! `ω̇_N = ψ̈ N.z + θ̈ A.x + θ̇ ψ̇ N.z × A.x + φ̈ C.y + φ̇ ω_C × C.y`
//! (`ω_C = ψ̇ N.z + θ̇ A.x`); for the joint, `ω_B = Rᵀ ω_N`,
//! `v_B = Rᵀ v_N`, and back `a_N = R (v̇_B + ω_B × v_B)`, `ω̇_N = R ω̇_B`.
//!
//! **A `speeds` statement.** The Chaplygin sleigh with the blade's velocity
//! in its own axes as speeds, `u1 = v_P · B.x`, `u2 = v_P · B.y`,
//! `u3 = θ̇`, held by `dot(velocity(P), B.y) == 0` (that is `u2 = 0`): at
//! SymPy's states (speeds the rates; its spring's potential written with
//! `norm`), `u̇1 = ẍ cos θ + ÿ sin θ + θ̇ u2`,
//! `u̇2 = −ẍ sin θ + ÿ cos θ − θ̇ u1`, `u̇3 = θ̈`.

use dalembert::constrained::constrained_accelerations;
use dalembert_codegen::testing::{cross, mat_vec, quaternion_rotation, transpose_vec};
use dalembert_fixtures::reference::{array, assert_close, reference};

dalembert::dalembert! {
    /// The thin disc rolling on `z = 0`, on a free joint, driven by a torque
    /// `T` about its axle.
    pub FreeDisc {
        parameters m, r, g;
        inputs T;
        joint free base { parent: N, child: B, at: O };
        body disc { mass: m, center: base, frame: B, inertia: [m*r^2/4, m*r^2/2, m*r^2/4] };
        gravity -g * N.z;
        torque T * B.y on B;
        rolling contact { wheel: B, axle: B.y, center: base, radius: r, plane: N.z };
    }
}

dalembert::dalembert! {
    /// The Chaplygin sleigh of `tests/suite/rolling_wheels.rs` in the blade's
    /// body-axis speeds.
    pub BodyRateSleigh {
        parameters m, I, a, k;
        coordinates x, y, theta;
        speeds u1, u2, u3 {
            x: cos(theta) * u1 - sin(theta) * u2,
            y: sin(theta) * u1 + cos(theta) * u2,
            theta: u3
        };
        inputs F, T;
        frame B = N.rotate_z(theta);
        point P = O + x * N.x + y * N.y;
        body sleigh { mass: m, center: P + a * B.x, frame: B, inertia: [0, 0, I] };
        potential k / 2 * norm(P + a * B.x - O)^2;
        force F * B.x at P;
        torque T * N.z on B;
        constraint dot(velocity(P), B.y) == 0;
    }
}

const SLEIGH: BodyRateSleigh = BodyRateSleigh {
    m: 2.5,
    I: 0.3,
    a: 0.4,
    k: 1.7,
};

const DISC: FreeDisc = FreeDisc {
    m: 0.8,
    r: 0.3,
    g: 9.81,
};

/// `a ⊗ b` of quaternions `(x, y, z, w)`.
fn product([ax, ay, az, aw]: [f64; 4], [bx, by, bz, bw]: [f64; 4]) -> [f64; 4] {
    [
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    ]
}

/// The quaternion of the turn by `angle` about the `axis`-th axis.
fn about(axis: usize, angle: f64) -> [f64; 4] {
    let (s, c) = (angle / 2.0).sin_cos();
    let mut q = [0.0, 0.0, 0.0, c];
    q[axis] = s;
    q
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(s: f64, a: [f64; 3]) -> [f64; 3] {
    a.map(|x| s * x)
}

#[test]
fn a_disc_on_a_free_joint_rolls_as_sympys_in_euler_angles() {
    assert_eq!(FreeDisc::NC, 3);
    let entry = &reference("rolling_wheels.json")["systems"]["disc"];
    for (name, value) in [("m", DISC.m), ("r", DISC.r), ("g", DISC.g)] {
        assert_eq!(entry["parameters"][name].as_f64(), Some(value), "{name}");
    }
    let states = entry["constrained"].as_array().expect("states");
    assert!(!states.is_empty(), "no states on the manifold");
    for state in states {
        let [x, y, z, psi, theta, phi] = array::<6>(&state["q"]);
        let [vx, vy, vz, psi_rate, theta_rate, phi_rate] = array::<6>(&state["v"]);
        let [ax, ay, az, psi_acc, theta_acc, phi_acc] = array::<6>(&state["vdot"]);
        let attitude = product(product(about(2, psi), about(0, theta)), about(1, phi));
        let turn = quaternion_rotation(attitude);
        let yawed = quaternion_rotation(about(2, psi));
        let leaned = quaternion_rotation(product(about(2, psi), about(0, theta)));
        let (up, a_x, c_y) = (
            [0.0, 0.0, 1.0],
            mat_vec(&yawed, [1.0, 0.0, 0.0]),
            mat_vec(&leaned, [0.0, 1.0, 0.0]),
        );
        let omega_c = add(scale(psi_rate, up), scale(theta_rate, a_x));
        let omega = add(omega_c, scale(phi_rate, c_y));
        let [qx, qy, qz, qw] = attitude;
        let [bvx, bvy, bvz] = transpose_vec(&turn, [vx, vy, vz]);
        let [bwx, bwy, bwz] = transpose_vec(&turn, omega);
        let q = [x, y, z, qx, qy, qz, qw];
        let v = [bvx, bvy, bvz, bwx, bwy, bwz];
        let drift = DISC.constraint_velocity(0.0, &q, &v);
        assert!(
            drift.iter().all(|d| d.abs() < 1e-12),
            "off the manifold: {drift:?}"
        );
        let u = array::<1>(&state["u"]);
        let (vdot, _) = constrained_accelerations(&DISC, 0.0, &q, &v, &u).expect("solvable");
        let centre = mat_vec(
            &turn,
            add(
                [vdot[0], vdot[1], vdot[2]],
                cross([bwx, bwy, bwz], [bvx, bvy, bvz]),
            ),
        );
        let angular = mat_vec(&turn, [vdot[3], vdot[4], vdot[5]]);
        let expected_angular = [
            scale(psi_acc, up),
            scale(theta_acc, a_x),
            scale(theta_rate * psi_rate, cross(up, a_x)),
            scale(phi_acc, c_y),
            scale(phi_rate, cross(omega_c, c_y)),
        ]
        .into_iter()
        .fold([0.0; 3], add);
        assert_close(
            "centre's and angular accelerations",
            &[centre, angular].concat(),
            &[[ax, ay, az], expected_angular].concat(),
            1e-11,
        );
    }
}

#[test]
fn a_sleigh_in_body_axis_speeds_slides_as_sympys() {
    let entry = &reference("rolling_wheels.json")["systems"]["sleigh"];
    let parameters = [
        ("m", SLEIGH.m),
        ("I", SLEIGH.I),
        ("a", SLEIGH.a),
        ("k", SLEIGH.k),
    ];
    for (name, value) in parameters {
        assert_eq!(entry["parameters"][name].as_f64(), Some(value), "{name}");
    }
    let states = entry["constrained"].as_array().expect("states");
    assert!(!states.is_empty(), "no states on the manifold");
    for state in states {
        let q = array::<3>(&state["q"]);
        let [vx, vy, rate] = array::<3>(&state["v"]);
        let [ax, ay, angular] = array::<3>(&state["vdot"]);
        let (s, c) = q[2].sin_cos();
        let (u1, u2) = (vx * c + vy * s, -vx * s + vy * c);
        let v = [u1, u2, rate];
        let (vdot, _) = constrained_accelerations(&SLEIGH, 0.0, &q, &v, &array::<2>(&state["u"]))
            .expect("solvable");
        let expected = [
            ax * c + ay * s + rate * u2,
            -ax * s + ay * c - rate * u1,
            angular,
        ];
        assert_close("u̇", &vdot, &expected, 1e-11);
    }
}
