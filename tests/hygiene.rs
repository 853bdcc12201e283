//! The generated code names everything by absolute path: it compiles under
//! `#![deny(warnings, missing_docs)]` beside user items that shadow the
//! prelude, and with user names that look like its own temporaries.

#![deny(warnings, missing_docs)]
#![allow(dead_code, non_camel_case_types)]

struct Result;
struct Ok;
struct Err;
struct Option;
struct Some;
struct None;
struct Vec;
struct Clone;
struct Copy;
struct Debug;
struct PartialEq;
struct Default;
struct String;
struct sin;
mod core {}

dalembert::dalembert! {
    /// A pendulum on a cart, with user names `x0`, `q`, `u` and `t`-like
    /// names that the generator must not capture.
    pub Hygienic {
        parameters x0, x1, q, u, qd, sin_theta;
        coordinates s, theta;
        inputs self_force;
        frame B = N.rotate_z(theta);
        point C = O + s * N.x;
        particle cart { mass: x0, at: C };
        body rod { mass: x1, center: C - q * B.y, frame: B, inertia: [0, 0, x1 * q^2 / 3] };
        potential sin_theta * cos(theta);
        gravity -u * N.y;
        force self_force * N.x at C;
        dissipation qd * dt(s)^2 / 2;
        constraint s - q * sin(theta) == 0;
        outputs inverse_dynamics, regressor, position(C), velocity(C in B), acceleration(C);
        outputs jacobian(C), rotation(B), angular_velocity(B), angular_jacobian(B in B);
    }
}

#[test]
fn generated_code_is_hygienic() {
    let system = Hygienic {
        x0: 1.0,
        x1: 2.0,
        q: 0.5,
        u: 9.81,
        qd: 0.1,
        sin_theta: 0.0,
    };
    let q = [0.1, 0.2];
    let m = system.mass_matrix(&q);
    assert!(m[0][0] > 0.0 && m[1][1] > 0.0);
    assert_eq!(m[0][1], m[1][0]);
    assert_eq!(
        Hygienic::PARAMETERS,
        ["x0", "x1", "q", "u", "qd", "sin_theta"]
    );
    // `sin_theta` is a parameter (here 0), not the sine of `theta`.
    let with_one = Hygienic {
        sin_theta: 1.0,
        ..system
    };
    let difference = with_one.potential_energy(&q) - system.potential_energy(&q);
    assert!((difference - 0.2f64.cos()).abs() < 1e-12, "{difference}");
    let residual = system.constraint_residual(0.0, &q);
    assert!((residual[0] - (0.1 - 0.5 * 0.2f64.sin())).abs() < 1e-15);
}

dalembert::dalembert! {
    /// The same cart and pendulum, unconstrained, asking for the derivatives,
    /// with user names spelled like the locals of `accelerations_jacobian`.
    pub HygienicDerivatives {
        parameters qdd, solve, rhs_q, by_q, finite, jacobian, m, f, angles, b0;
        coordinates s, theta;
        inputs r0;
        frame B = N.rotate_z(theta);
        point C = O + s * N.x;
        particle cart { mass: qdd, at: C };
        body rod { mass: solve, center: C - rhs_q * B.y, frame: B, inertia: [0, 0, solve * rhs_q^2 / 3] };
        gravity -by_q * N.y;
        force r0 * N.x at C;
        dissipation finite * dt(s)^2 / 2 + (jacobian + angles * b0) * dt(theta)^2 / 2;
        potential m * s^2 / 2 + f * theta^2 / 2;
        outputs linearize, inverse_dynamics_jacobian;
    }
}

#[test]
fn generated_derivatives_are_hygienic() {
    let system = HygienicDerivatives {
        qdd: 1.0,
        solve: 2.0,
        rhs_q: 0.5,
        by_q: 9.81,
        finite: 0.1,
        jacobian: 0.2,
        m: 3.0,
        f: 0.4,
        angles: 0.5,
        b0: 0.2,
    };
    let (a, b) = system
        .linearize(0.0, &[0.0; 2], &[0.0; 2], &[0.0])
        .expect("regular");
    // The force `r0` pushes the cart forwards.
    assert_eq!(a[0], [0.0, 0.0, 1.0, 0.0]);
    assert!(b[2][0] > 0.0, "{b:?}");
    let (by_q, _, mass) =
        system.inverse_dynamics_jacobian(0.0, &[0.1, 0.2], &[0.3, 0.4], &[0.5, 0.6], &[0.7]);
    assert_eq!(mass, system.mass_matrix(&[0.1, 0.2]));
    assert!(by_q[0][0] == 3.0, "the spring m s: {by_q:?}");
}
