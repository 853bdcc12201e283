//! Free and spherical joints end to end, through the macro: the emitted
//! equations against Newton–Euler in closed form, the configuration update
//! (a quaternion stays unit), a body thrown under gravity (parabola of the
//! centre, torque-free precession; by DOP853 and by the Taylor series of
//! `q̇ = N(q) v`), the Dzhanibekov effect in quaternions
//! (energy and angular momentum conserved while the body flips) and the
//! same body in Z-Y-X Euler angles stopping at gimbal lock, with the Euler
//! angles' rates as speeds (a singular mass matrix) or the body rates (a
//! singular `q̇ = N(q) v`); in the body rates away from it, the Taylor
//! series of that `q̇ = N(q) v` follow free precession.

use dalembert::integrate::{AdaptiveOptions, ExplicitPair, TaylorOptions, adaptive, taylor};
use dalembert::{DynamicsError, State, Unconstrained, accelerations, energy};
use dalembert_codegen::testing::{cross, mat_vec, quaternion_rotation as rotation};
use dalembert_fixtures::precession::{free_precession, times, turn};
use dalembert_fixtures::reference::{assert_close, flat};

dalembert::dalembert! {
    /// An axisymmetric body thrown under gravity.
    pub Thrown {
        parameters m, I1, I3, g;
        joint free base { parent: N, child: B, at: O };
        body b { mass: m, center: base, frame: B, inertia: [I1, I1, I3] };
        gravity -g * N.z;
        outputs taylor;
    }
}

dalembert::dalembert! {
    /// A rigid body turning freely about its centre.
    pub Tumbler {
        parameters I1, I2, I3;
        joint spherical ball { parent: N, child: B, at: O };
        body b { mass: 1, center: ball, frame: B, inertia: [I1, I2, I3] };
    }
}

dalembert::dalembert! {
    /// The same body in Z-Y-X Euler angles.
    pub EulerTumbler {
        parameters I1, I2, I3;
        coordinates psi, theta, phi;
        frame A = N.rotate_z(psi);
        frame C = A.rotate_y(theta);
        frame B = C.rotate_x(phi);
        body b { mass: 1, center: O, frame: B, inertia: [I1, I2, I3] };
    }
}

dalembert::dalembert! {
    /// A heavy top on a ball joint at `O`, its centre off its symmetry axis.
    pub QuaternionTop {
        parameters m, a, c, I1, I2, I3, g;
        joint spherical ball { parent: N, child: B, at: O };
        body top { mass: m, center: ball + a * B.z + c * B.x, frame: B, inertia: [I1, I2, I3] };
        gravity -g * N.z;
    }
}

dalembert::dalembert! {
    /// A floating base carrying an arm on a hinge, on a ball-jointed tail:
    /// every parameter that enters linearly, for the regressor.
    pub FloatingArm {
        parameters m1, c1, J1, J2, J3, m2, a, K1, K3, L, m3, d, g;
        joint free base { parent: N, child: B, at: O };
        coordinates q1;
        joint revolute hinge { parent: B, child: C, axis: y, coordinate: q1, at: base + L * B.x };
        joint spherical tail { parent: B, child: D, at: base - L * B.x };
        body hull { mass: m1, center: base + c1 * B.z, frame: B, inertia: [J1, J2, J3, 0.1, 0, 0] };
        body arm { mass: m2, center: hinge + a * C.x, frame: C, inertia: [K1, K1, K3] };
        body fin { mass: m3, center: tail - d * D.x, frame: D, inertia: [0.01, 0.02, 0.03] };
        gravity -g * N.z;
        outputs inverse_dynamics, regressor;
    }
}

dalembert::dalembert! {
    /// The same top in Z-Y-X Euler angles.
    pub EulerTop {
        parameters m, a, c, I1, I2, I3, g;
        coordinates psi, theta, phi;
        frame A = N.rotate_z(psi);
        frame C = A.rotate_y(theta);
        frame B = C.rotate_x(phi);
        body top { mass: m, center: O + a * B.z + c * B.x, frame: B, inertia: [I1, I2, I3] };
        gravity -g * N.z;
    }
}

dalembert::dalembert! {
    /// The tumbling body in Z-Y-X Euler angles with its body-axis angular
    /// velocity as speeds.
    pub BodyRates {
        parameters I1, I2, I3;
        coordinates psi, theta, phi;
        speeds wx, wy, wz {
            psi: (sin(phi) * wy + cos(phi) * wz) / cos(theta),
            theta: cos(phi) * wy - sin(phi) * wz,
            phi: wx + tan(theta) * (sin(phi) * wy + cos(phi) * wz)
        };
        frame A = N.rotate_z(psi);
        frame C = A.rotate_y(theta);
        frame B = C.rotate_x(phi);
        body b { mass: 1, center: O, frame: B, inertia: [I1, I2, I3] };
        outputs taylor;
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn quaternion(q: &[f64]) -> [f64; 4] {
    [q[0], q[1], q[2], q[3]]
}

const THROWN: Thrown = Thrown {
    m: 2.0,
    I1: 0.3,
    I3: 0.5,
    g: 9.81,
};

/// Tilted, moving and spinning.
fn thrown_start() -> State<7, 6> {
    let (s, c) = (0.4_f64).sin_cos();
    State {
        t: 0.0,
        q: [0.1, -0.2, 1.0, s * 0.6, s * 0.8, 0.0, c],
        v: [1.0, 0.5, 3.0, 0.7, -0.4, 5.0],
    }
}

#[test]
fn the_api_has_seven_coordinates_and_six_speeds() {
    assert_eq!((Thrown::NQ, Thrown::NV), (7, 6));
    assert_eq!(
        Thrown::COORDINATES,
        [
            "base_x", "base_y", "base_z", "base_qx", "base_qy", "base_qz", "base_qw"
        ]
    );
    assert_eq!(
        Thrown::SPEEDS,
        [
            "base_vx", "base_vy", "base_vz", "base_wx", "base_wy", "base_wz"
        ]
    );
    assert_eq!(Tumbler::SPEEDS, ["ball_wx", "ball_wy", "ball_wz"]);
}

#[test]
fn the_emitted_equations_are_newton_and_euler_in_body_axes() {
    let start = thrown_start();
    let (q, v) = (start.q, start.v);
    let Thrown { m, I1, I3, g } = THROWN;
    let mass = THROWN.mass_matrix(&q);
    let inertia = [I1, I1, I3];
    for (k, row) in mass.iter().enumerate() {
        for (j, entry) in row.iter().enumerate() {
            let expected = match k == j {
                true if k < 3 => m,
                true => inertia[k - 3],
                false => 0.0,
            };
            assert!((entry - expected).abs() < 1e-14, "M[{k}][{j}]");
        }
    }
    // f = (m Rᵀ g − m ω × v, −ω × I ω)
    let r = rotation(quaternion(&q[3..]));
    let weight: [f64; 3] = [0, 1, 2].map(|i| r[2][i] * -m * g);
    let (u, w) = ([v[0], v[1], v[2]], [v[3], v[4], v[5]]);
    let h = [I1 * w[0], I1 * w[1], I3 * w[2]];
    let expected = [
        weight[0] - m * (w[1] * u[2] - w[2] * u[1]),
        weight[1] - m * (w[2] * u[0] - w[0] * u[2]),
        weight[2] - m * (w[0] * u[1] - w[1] * u[0]),
        -(w[1] * h[2] - w[2] * h[1]),
        -(w[2] * h[0] - w[0] * h[2]),
        -(w[0] * h[1] - w[1] * h[0]),
    ];
    let forcing = THROWN.forcing(0.0, &q, &v, &[]);
    for k in 0..6 {
        assert!((forcing[k] - expected[k]).abs() < 1e-13, "f[{k}]");
    }
    // q̇ = N(q) v: the origin moves at R v, the quaternion at ½ q ⊗ ω.
    let rates = THROWN.coordinate_rates(&q, &v);
    let velocity = mat_vec(&r, u);
    for i in 0..3 {
        assert!((rates[i] - velocity[i]).abs() < 1e-15, "ṙ[{i}]");
    }
    let [x, y, z, s] = quaternion(&q[3..]);
    let spin = [
        0.5 * (s * w[0] + y * w[2] - z * w[1]),
        0.5 * (s * w[1] + z * w[0] - x * w[2]),
        0.5 * (s * w[2] + x * w[1] - y * w[0]),
        -0.5 * (x * w[0] + y * w[1] + z * w[2]),
    ];
    for i in 0..4 {
        assert!((rates[3 + i] - spin[i]).abs() < 1e-15, "q̇[{i}]");
    }
}

#[test]
fn the_configuration_update_is_exact_and_keeps_the_quaternion_unit() {
    let start = thrown_start();
    // Constant speeds for 2 s: a screw motion, compared with many small
    // steps of the same update (which compose exactly).
    let once = THROWN.integrate_configuration(&start.q, &start.v, 2.0);
    let mut q = start.q;
    for _ in 0..1000 {
        q = THROWN.integrate_configuration(&q, &start.v, 2e-3);
    }
    for i in 0..7 {
        assert!(
            (once[i] - q[i]).abs() < 1e-12,
            "q[{i}]: {} vs {}",
            once[i],
            q[i]
        );
    }
    assert!((norm(&once[3..]) - 1.0).abs() < 1e-15);
    // A quaternion that is not unit in a call is normalised by the update
    // (the equations take it as given: R(q) is |q|² times a rotation).
    let mut long = start.q;
    long[3..].iter_mut().for_each(|c| *c *= 3.0);
    let still = THROWN.integrate_configuration(&long, &[0.0; 6], 0.1);
    for (i, (got, expected)) in still.iter().zip(start.q).enumerate() {
        assert!((got - expected).abs() < 1e-15, "q[{i}]");
    }
}

/// The adaptive DOP853 at tolerance `1e-12`.
fn tight() -> AdaptiveOptions {
    AdaptiveOptions {
        max_steps: 10_000_000,
        ..AdaptiveOptions::with_tolerance(1e-12)
    }
}

#[test]
fn a_thrown_body_follows_the_parabola_and_precesses_about_its_axis() {
    let start = thrown_start();
    let dynamics = Unconstrained::without_inputs(&THROWN);
    let end = adaptive(&dynamics, start, 2.0, ExplicitPair::Dop853, tight(), |_| {})
        .expect("integrates")
        .end;
    assert_thrown_motion(&start, &end, 1e-9);
}

/// The Taylor integrator's series of `q̇ = N(q) v` (the position's rate
/// `R(q) v` as well as the quaternion's) follow the same closed form,
/// tighter.
#[test]
fn the_taylor_series_of_a_thrown_body_follow_the_parabola_and_the_precession() {
    let start = thrown_start();
    let dynamics = Unconstrained::without_inputs(&THROWN);
    let options = TaylorOptions::with_tolerance(1e-15);
    let end = taylor(&dynamics, start, 2.0, options, |_| {})
        .expect("integrates")
        .end;
    assert_thrown_motion(&start, &end, 1e-11);
}

/// `end` is the thrown body's motion from `start` to within `tolerance`.
fn assert_thrown_motion(start: &State<7, 6>, end: &State<7, 6>, tolerance: f64) {
    let t = end.t - start.t;
    // The centre: r₀ + v₀ t − ½ g t² N.z, with v₀ = R₀ v.
    let v0 = mat_vec(
        &rotation(quaternion(&start.q[3..])),
        [start.v[0], start.v[1], start.v[2]],
    );
    for (i, v0) in v0.into_iter().enumerate() {
        let gravity = if i == 2 { -0.5 * THROWN.g * t * t } else { 0.0 };
        let expected = start.q[i] + v0 * t + gravity;
        assert!(
            (end.q[i] - expected).abs() < tolerance,
            "r[{i}] {} vs {expected}",
            end.q[i]
        );
    }
    // Torque-free and axisymmetric: ω₃ constant, (ω₁, ω₂) turning at
    // λ = (I₃ − I₁) ω₃ / I₁ in body axes.
    let (w1, w2, w3) = (start.v[3], start.v[4], start.v[5]);
    let lambda = (THROWN.I3 - THROWN.I1) * w3 / THROWN.I1;
    let (s, c) = (lambda * t).sin_cos();
    let expected = [w1 * c - w2 * s, w1 * s + w2 * c, w3];
    for (i, expected) in expected.into_iter().enumerate() {
        assert!(
            (end.v[3 + i] - expected).abs() < tolerance,
            "ω[{i}] {} vs {expected}",
            end.v[3 + i]
        );
    }
}

const DZHANIBEKOV: Tumbler = Tumbler {
    I1: 1.0,
    I2: 2.0,
    I3: 3.0,
};

/// The angular momentum `R I ω` in `N`'s axes.
fn momentum(q: &[f64; 4], v: &[f64; 3]) -> [f64; 3] {
    let body = [
        DZHANIBEKOV.I1 * v[0],
        DZHANIBEKOV.I2 * v[1],
        DZHANIBEKOV.I3 * v[2],
    ];
    mat_vec(&rotation(*q), body)
}

#[test]
fn dzhanibekov_flips_while_energy_and_momentum_stay() {
    // Spun about the intermediate axis, with a small wobble.
    let start = State {
        t: 0.0,
        q: [0.0, 0.0, 0.0, 1.0],
        v: [1e-3, 2.0, 1e-3],
    };
    let dynamics = Unconstrained::without_inputs(&DZHANIBEKOV);
    let (e0, l0) = (
        energy(&DZHANIBEKOV, &start.q, &start.v),
        momentum(&start.q, &start.v),
    );
    let (mut worst_energy, mut worst_momentum) = (0.0_f64, 0.0_f64);
    let mut flips = 0;
    let mut sign = 1.0;
    adaptive(
        &dynamics,
        start,
        100.0,
        ExplicitPair::Dop853,
        tight(),
        |s| {
            let e = energy(&DZHANIBEKOV, &s.q, &s.v);
            worst_energy = worst_energy.max((e - e0).abs() / e0);
            let l = momentum(&s.q, &s.v);
            let drift = [0, 1, 2].map(|i| l[i] - l0[i]);
            worst_momentum = worst_momentum.max(norm(&drift) / norm(&l0));
            if s.v[1] * sign < 0.0 {
                flips += 1;
                sign = -sign;
            }
        },
    )
    .expect("integrates");
    println!("relative drift: energy {worst_energy:e}, momentum {worst_momentum:e}; {flips} flips");
    assert!(flips >= 4, "{flips} flips in 100 s");
    assert!(worst_energy < 1e-9, "energy drift {worst_energy:e}");
    assert!(worst_momentum < 1e-9, "momentum drift {worst_momentum:e}");
}

#[test]
fn euler_angles_stop_at_gimbal_lock_naming_the_coordinate() {
    let body = EulerTumbler {
        I1: 1.0,
        I2: 2.0,
        I3: 3.0,
    };
    let locked = [0.3, std::f64::consts::FRAC_PI_2, -0.2];
    match accelerations(&body, 0.0, &locked, &[0.1, 0.2, 0.3], &[]) {
        Err(DynamicsError::SingularMassMatrix { coordinate, .. }) => {
            // At gimbal lock the axes of psi and phi align. The emitted
            // solver meets the vanishing pivot at phi (the last column of
            // L D Lᵀ) or at psi (the root, for the articulated-body
            // recursion), whichever route the engine chose for the model.
            assert!(["psi", "phi"].contains(&coordinate), "{coordinate}");
        }
        other => panic!("expected a singular mass matrix, got {other:?}"),
    }
    // The quaternion body passes through the same attitude.
    let (s, c) = (std::f64::consts::FRAC_PI_4).sin_cos();
    let q = [0.0, s, 0.0, c];
    assert!(accelerations(&DZHANIBEKOV, 0.0, &q, &[0.1, 0.2, 0.3], &[]).is_ok());
}

/// `a ⊗ b` for quaternions `(x, y, z, w)`.
fn product(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[3] * b[0] + b[3] * a[0] + a[1] * b[2] - a[2] * b[1],
        a[3] * b[1] + b[3] * a[1] + a[2] * b[0] - a[0] * b[2],
        a[3] * b[2] + b[3] * a[2] + a[0] * b[1] - a[1] * b[0],
        a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2],
    ]
}

#[test]
fn a_heavy_top_in_quaternions_moves_as_in_euler_angles() {
    let (m, a, c, i1, i2, i3, g) = (1.3, 0.4, 0.15, 0.02, 0.025, 0.012, 9.81);
    let quaternions = QuaternionTop {
        m,
        a,
        c,
        I1: i1,
        I2: i2,
        I3: i3,
        g,
    };
    let euler = EulerTop {
        m,
        a,
        c,
        I1: i1,
        I2: i2,
        I3: i3,
        g,
    };
    for (angles, rates) in [
        ([0.3, 0.5, -0.7], [2.0, -1.0, 15.0]),
        ([-1.2, -0.9, 2.5], [0.5, 3.0, -8.0]),
        ([2.8, 1.2, 0.1], [-4.0, 0.7, 1.0]),
    ] {
        let [psi, theta, phi] = angles;
        let [dpsi, dtheta, dphi] = rates;
        // The attitude R_z(ψ) R_y(θ) R_x(φ) as a quaternion.
        let half = |x: f64| (x / 2.0).sin_cos();
        let ((sz, cz), (sy, cy), (sx, cx)) = (half(psi), half(theta), half(phi));
        let q = product(
            product([0.0, 0.0, sz, cz], [0.0, sy, 0.0, cy]),
            [sx, 0.0, 0.0, cx],
        );
        // Body rates ω = W(θ, φ) (ψ̇, θ̇, φ̇) and their derivative.
        let ((st, ct), (sp, cp)) = (theta.sin_cos(), phi.sin_cos());
        let omega = [
            dphi - dpsi * st,
            dtheta * cp + dpsi * ct * sp,
            -dtheta * sp + dpsi * ct * cp,
        ];
        let e =
            dalembert::accelerations(&euler, 0.0, &angles, &rates, &[]).expect("no gimbal lock");
        let [ddpsi, ddtheta, ddphi] = e;
        let expected = [
            ddphi - ddpsi * st - dpsi * dtheta * ct,
            ddtheta * cp - dtheta * dphi * sp + ddpsi * ct * sp - dpsi * dtheta * st * sp
                + dpsi * dphi * ct * cp,
            -ddtheta * sp - dtheta * dphi * cp + ddpsi * ct * cp
                - dpsi * dtheta * st * cp
                - dpsi * dphi * ct * sp,
        ];
        let got = dalembert::accelerations(&quaternions, 0.0, &q, &omega, &[]).expect("solvable");
        let scale = norm(&expected);
        for i in 0..3 {
            assert!(
                (got[i] - expected[i]).abs() <= 1e-10 * scale,
                "ω̇[{i}]: {} vs {}",
                got[i],
                expected[i]
            );
        }
        let (t1, t2) = (
            quaternions.kinetic_energy(&q, &omega),
            euler.kinetic_energy(&angles, &rates),
        );
        let (v1, v2) = (
            quaternions.potential_energy(&q),
            euler.potential_energy(&angles),
        );
        assert!(
            (t1 - t2).abs() <= 1e-12 * t2.abs() && (v1 - v2).abs() <= 1e-12 * v2.abs().max(1.0)
        );
    }
}

#[test]
fn body_rates_move_as_the_quaternion_body_and_their_rates_blow_up_at_gimbal_lock() {
    let body = BodyRates {
        I1: 1.0,
        I2: 2.0,
        I3: 3.0,
    };
    assert_eq!(BodyRates::SPEEDS, ["wx", "wy", "wz"]);
    let (angles, omega) = ([0.3, 0.5, -0.7], [0.4, -1.1, 2.0]);
    // The same attitude as a quaternion: the same body rates, the same ω̇.
    let half = |x: f64| (x / 2.0).sin_cos();
    let ((sz, cz), (sy, cy), (sx, cx)) = (half(angles[0]), half(angles[1]), half(angles[2]));
    let q = product(
        product([0.0, 0.0, sz, cz], [0.0, sy, 0.0, cy]),
        [sx, 0.0, 0.0, cx],
    );
    // Euler's equations in the body rates: M = I, f = −ω × I ω.
    let mass = body.mass_matrix(&angles);
    let forcing = body.forcing(0.0, &angles, &omega, &[]);
    let inertia = [1.0, 2.0, 3.0];
    let h = [0, 1, 2].map(|i| inertia[i] * omega[i]);
    let gyroscopic = cross(omega, h);
    for (k, row) in mass.iter().enumerate() {
        for (j, entry) in row.iter().enumerate() {
            let expected = if j == k { inertia[k] } else { 0.0 };
            assert!((entry - expected).abs() < 1e-14, "M[{k}][{j}] = {entry}");
        }
        assert!((forcing[k] + gyroscopic[k]).abs() < 1e-13, "f[{k}]");
    }
    let euler = accelerations(&body, 0.0, &angles, &omega, &[]).expect("solvable");
    let quaternion = accelerations(&DZHANIBEKOV, 0.0, &q, &omega, &[]).expect("solvable");
    for i in 0..3 {
        assert!(
            (euler[i] - quaternion[i]).abs() < 1e-12,
            "ω̇[{i}]: {euler:?} vs {quaternion:?}"
        );
    }
    // q̇ = W(q)⁻¹ ω, checked through ω = W q̇.
    let [dpsi, dtheta, dphi] = body.coordinate_rates(&angles, &omega);
    let ((st, ct), (sp, cp)) = (angles[1].sin_cos(), angles[2].sin_cos());
    let back = [
        dphi - dpsi * st,
        dtheta * cp + dpsi * ct * sp,
        -dtheta * sp + dpsi * ct * cp,
    ];
    for i in 0..3 {
        assert!((back[i] - omega[i]).abs() < 1e-14, "ω[{i}]");
    }
    // The update: one RK4 step of q̇ = N(q) ω, fourth order in h.
    let error = |h: f64| {
        let once = body.integrate_configuration(&angles, &omega, h);
        let mut fine = angles;
        for _ in 0..1000 {
            fine = body.integrate_configuration(&fine, &omega, h / 1000.0);
        }
        norm(&[once[0] - fine[0], once[1] - fine[1], once[2] - fine[2]])
    };
    let ratio = error(0.1) / error(0.05);
    assert!(
        (24.0..40.0).contains(&ratio),
        "error ratio {ratio} for h halved"
    );
    // Documented behaviour at gimbal lock (cos θ = 0): the equations in the
    // body rates are regular (M = I), the coordinate rates are not, and the
    // check says so, naming the coordinate whose rate divides by cos θ.
    let locked = [0.3, std::f64::consts::FRAC_PI_2, -0.2];
    assert!(accelerations(&body, 0.0, &locked, &omega, &[]).is_ok());
    let rates = body.coordinate_rates(&locked, &omega);
    assert!(rates[0].abs() > 1e12, "ψ̇ = {} at gimbal lock", rates[0]);
    assert_eq!(body.check_coordinate_rates(&angles), Ok(()));
    match body.check_coordinate_rates(&locked) {
        Err(DynamicsError::SingularCoordinateRates {
            coordinate: "psi",
            divisor: "cos θ",
            value,
        }) => assert!(value.abs() < 1e-15, "cos θ = {value}"),
        other => panic!("expected singular coordinate rates, got {other:?}"),
    }
    // Just outside the tolerance (|cos θ| = 1e-8) the rates are defined.
    let near = [0.3, std::f64::consts::FRAC_PI_2 - 2e-8, -0.2];
    assert_eq!(body.check_coordinate_rates(&near), Ok(()));
}

#[test]
fn body_rates_integrated_into_gimbal_lock_stop_naming_the_coordinate() {
    use dalembert::integrate::{Failure, rk4};
    use std::f64::consts::{FRAC_PI_2, PI};
    let body = BodyRates {
        I1: 1.0,
        I2: 2.0,
        I3: 3.0,
    };
    // Pitching at 1 rad/s about the body's y axis from the upright attitude
    // (a steady spin: ω × I ω = 0), θ = t reaches gimbal lock at t = π/2;
    // there ψ̇ = 0 / cos θ, finite in floating point (cos(π/2) ≈ 6e-17), so
    // without the check the integration would step through silently.
    let start = State {
        t: 0.0,
        q: [0.0; 3],
        v: [0.0, 1.0, 0.0],
    };
    let dynamics = Unconstrained::without_inputs(&body);
    let error = rk4(&dynamics, start, PI, 100, |_| {}).expect_err("stops at gimbal lock");
    assert!(
        (error.t - FRAC_PI_2).abs() < 1e-12,
        "stopped at t = {}",
        error.t
    );
    assert!((error.q[1] - FRAC_PI_2).abs() < 1e-12, "θ = {}", error.q[1]);
    match error.cause {
        Failure::Dynamics(cause @ DynamicsError::SingularCoordinateRates { coordinate, .. }) => {
            assert_eq!(coordinate, "psi");
            let message = cause.to_string();
            assert!(
                message.contains("`psi`") && message.contains("cos θ"),
                "{message}"
            );
        }
        other => panic!("expected singular coordinate rates, got {other:?}"),
    }
    // The same motion up to just before the lock integrates.
    let before = rk4(&dynamics, start, 1.5, 100, |_| {}).expect("no gimbal lock yet");
    assert!((before.end.q[1] - 1.5).abs() < 1e-12);
}

/// The regressor of a system with free and spherical joints: `Y π` is the
/// inverse dynamics at states with unit quaternions, and the base
/// parameters hold every parameter that enters linearly.
#[test]
fn a_floating_regressor_times_its_base_parameters_is_the_inverse_dynamics() {
    let arm = FloatingArm {
        m1: 3.0,
        c1: 0.05,
        J1: 0.4,
        J2: 0.5,
        J3: 0.6,
        m2: 1.2,
        a: 0.3,
        K1: 0.02,
        K3: 0.03,
        L: 0.5,
        m3: 0.4,
        d: 0.2,
        g: 9.81,
    };
    let pi = arm.base_parameters();
    let unit = |x: [f64; 4]| x.map(|c| c / norm(&x));
    for k in 0..5 {
        let s = f64::from(k);
        let (b, d) = (
            unit([0.3 + s, -0.2, 0.5 - 0.1 * s, 0.9]),
            unit([-0.1, 0.4 * s, 0.2, 0.7]),
        );
        let q = [
            0.1 * s,
            -0.3,
            1.0,
            b[0],
            b[1],
            b[2],
            b[3],
            0.7 - 0.2 * s,
            d[0],
            d[1],
            d[2],
            d[3],
        ];
        let v: [f64; 10] = core::array::from_fn(|i| (0.37 * (i as f64 + s)).sin() * 2.0);
        let vdot: [f64; 10] = core::array::from_fn(|i| (0.61 * (i as f64) - s).cos() * 3.0);
        let tau = arm.inverse_dynamics(0.0, &q, &v, &vdot, &[]);
        let y = arm.regressor(&q, &v, &vdot);
        let scale = norm(&tau).max(1.0);
        for (i, (row, tau)) in y.iter().zip(tau).enumerate() {
            let product: f64 = row.iter().zip(&pi).map(|(y, p)| y * p).sum();
            assert!(
                (product - tau).abs() <= 1e-12 * scale,
                "state {k}, row {i}: Y π = {product}, τ = {tau}"
            );
        }
    }
}

/// `Rz(ψ) Ry(θ) Rx(φ)`, the attitude of Z-Y-X Euler angles.
fn euler_attitude([psi, theta, phi]: [f64; 3]) -> [[f64; 3]; 3] {
    let (x, y, z) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
    times(&times(&turn(z, psi), &turn(y, theta)), &turn(x, phi))
}

/// Free precession of a symmetric body (`I₁ = I₂ = 2`, `I₃ = 3`) in Euler
/// angles and body rates, `q̇ = N(q) v` of the `speeds` statement expanded
/// in Taylor series with `tan` and a division by `cos θ`: the
/// momentum vertical, so that the pitch stays within the 0.32 rad of
/// nutation, far from gimbal lock. Taylor at 1e-15 over ten seconds
/// (three turns of the precession) against the closed form, to 1e-13
/// (2e-16 measured).
#[test]
fn free_precession_in_body_rates_is_the_closed_form() {
    let top = BodyRates {
        I1: 2.0,
        I2: 2.0,
        I3: 3.0,
    };
    let angles = [0.3, 0.2, -0.25];
    let r0 = euler_attitude(angles);
    // Body momentum R₀ᵀ (0, 0, 4), so that H = 4 N.z.
    let w0 = [
        4.0 * r0[2][0] / top.I1,
        4.0 * r0[2][1] / top.I1,
        4.0 * r0[2][2] / top.I3,
    ];
    let start = State {
        t: 0.0,
        q: angles,
        v: w0,
    };
    let options = TaylorOptions::with_tolerance(1e-15);
    let end = taylor(
        &Unconstrained::without_inputs(&top),
        start,
        10.0,
        options,
        |_| {},
    )
    .expect("integrates")
    .end;
    let (omega, expected) = free_precession((top.I1, top.I3), &r0, w0, end.t);
    assert_close("ω(10)", &end.v, &omega, 1e-13);
    let reached = euler_attitude(end.q);
    assert_close("R(10)", &flat(&reached), &flat(&expected), 1e-13);
}
