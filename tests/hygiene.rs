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
