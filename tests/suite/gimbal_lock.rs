//! Attitudes in Z-Y-X Euler angles against quaternions: the Dzhanibekov body
//! stopping at gimbal lock, with the Euler angles' rates as speeds (a
//! singular mass matrix) or the body rates (a singular `q̇ = N(q) v`); a heavy
//! top in quaternions moving as in Euler angles; in the body rates away from
//! gimbal lock, the Taylor series of that `q̇ = N(q) v` follow free
//! precession.

use crate::free_body::{DZHANIBEKOV, norm};

use dalembert::integrate::{Integration, Taylor};
use dalembert::{DynamicsError, State, Unconstrained, accelerations};
use dalembert_codegen::testing::cross;
use dalembert_fixtures::precession::{free_precession, times, turn};
use dalembert_fixtures::reference::{assert_close, flat};

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
    use dalembert::integrate::{Failure, Integration, Rk4};
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
    let error = Integration::new(&dynamics, start, PI, Rk4 { steps: 100 })
        .run()
        .expect_err("stops at gimbal lock");
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
    let before = Integration::new(&dynamics, start, 1.5, Rk4 { steps: 100 })
        .run()
        .expect("no gimbal lock yet");
    assert!((before.end.q[1] - 1.5).abs() < 1e-12);
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
    let options = Taylor::with_tolerance(1e-15);
    let end = Integration::new(&Unconstrained::without_inputs(&top), start, 10.0, options)
        .run()
        .expect("integrates")
        .end;
    let (omega, expected) = free_precession((top.I1, top.I3), &r0, w0, end.t);
    assert_close("ω(10)", &end.v, &omega, 1e-13);
    let reached = euler_attitude(end.q);
    assert_close("R(10)", &flat(&reached), &flat(&expected), 1e-13);
}
