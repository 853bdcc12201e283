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

/// Systems whose names clash with the generated code's locals and methods,
/// with `std` names, with the runtime's traits, in a user's module that
/// denies clippy's pedantic and nursery lints: the expansion must compile
/// here as it is and compute with the user's names.
#[deny(clippy::pedantic, clippy::nursery)]
mod clashes {
    dalembert::dalembert! {
        /// Absolute-angle double pendulum of point masses, its parameters
        /// named like locals of the generated functions (`sin_q1` and
        /// `q1_dot` beside a coordinate `q1`).
        pub Locals {
            parameters v, vdot, tau, m0_0, f0, l1_0, xx0, tolerance, equations_or, sin_q1, q1_dot, L;
            coordinates q1, q2;
            inputs result;
            frame B1 = N.rotate_z(q1);
            frame B2 = N.rotate_z(q2);
            point P1 = O - L * B1.y;
            point G2 = P1 - l1_0 * B2.y;
            particle first { mass: v, at: P1 };
            particle second { mass: vdot, at: G2 };
            gravity -tau * N.y;
            torque result * N.z on B1;
            potential m0_0 * q1^2 / 2 + f0 * q2^2 / 2 + sin_q1 * q1 + q1_dot * q2;
            dissipation (tolerance + xx0) * dt(q1)^2 / 2 + equations_or * dt(q2)^2 / 2;
            outputs inverse_dynamics, regressor, accelerations_jacobian, linearize;
            outputs position(P1), velocity(G2), jacobian(G2), rotation(B2);
        }
    }

    dalembert::dalembert! {
        /// A pendulum hanging from a slider, its names those of the
        /// generated methods, constants and arguments.
        pub Methods {
            parameters mass_matrix, forcing, NQ, COORDINATES, kinetic_energy;
            coordinates q, qd;
            inputs u;
            frame B = N.rotate_z(q);
            point S = O + qd * N.x;
            point P = S - NQ * B.y;
            body b { mass: mass_matrix, center: P, frame: B, inertia: [0, 0, forcing] };
            particle slider { mass: kinetic_energy, at: S };
            gravity -COORDINATES * N.y;
            force u * N.x at S;
            outputs inverse_dynamics, regressor, accelerations_jacobian, linearize, position(P);
        }
    }

    // No doc comment: the generated docs satisfy `missing_docs`.
    dalembert::dalembert! {
        pub Std {
            parameters f64, core, std, Result, Option, Vec;
            coordinates x;
            particle p { mass: f64, at: O + x * N.x };
            potential core * x^2 / 2 + std * Result * Option * Vec * x;
        }
    }

    dalembert::dalembert! {
        /// A struct named like the runtime's trait.
        pub MultibodySystem {
            parameters m;
            coordinates x;
            particle p { mass: m, at: O + x * N.x };
        }
    }

    /// The mass of a system declared inside a function body.
    pub fn local_mass(m: f64) -> f64 {
        dalembert::dalembert! {
            Local {
                parameters m;
                coordinates x;
                particle p { mass: m, at: O + x * N.x };
            }
        }
        Local { m }.mass_matrix(&[0.0])[0][0]
    }
}

#[test]
fn names_of_locals_stay_the_user_s() {
    let system = clashes::Locals {
        v: 1.5,
        vdot: 0.5,
        tau: 9.81,
        m0_0: 0.3,
        f0: 0.7,
        l1_0: 0.8,
        xx0: 0.1,
        tolerance: 0.2,
        equations_or: 0.4,
        sin_q1: 0.25,
        q1_dot: -0.6,
        L: 1.2,
    };
    let (q1, q2) = (0.3, -0.4);
    let m = system.mass_matrix(&[q1, q2]);
    // Closed forms of the double pendulum of point masses.
    let expected = [
        [2.0 * 1.2 * 1.2, 0.5 * 1.2 * 0.8 * (q1 - q2).cos()],
        [0.5 * 1.2 * 0.8 * (q1 - q2).cos(), 0.5 * 0.8 * 0.8],
    ];
    for (row, expected) in m.iter().zip(expected) {
        for (entry, expected) in row.iter().zip(expected) {
            assert!((entry - expected).abs() < 1e-14, "{m:?}");
        }
    }
    let height =
        |q1: f64, q2: f64| -9.81 * (1.5 * 1.2 * q1.cos() + 0.5 * (1.2 * q1.cos() + 0.8 * q2.cos()));
    let potential = height(q1, q2) + 0.15 * q1 * q1 + 0.35 * q2 * q2 + 0.25 * q1 - 0.6 * q2;
    assert!((system.potential_energy(&[q1, q2]) - potential).abs() < 1e-13);
    assert!(
        system
            .linearize(0.0, &[q1, q2], &[0.1, 0.2], &[0.0])
            .is_ok()
    );
}

#[test]
fn names_of_methods_and_std_items_stay_the_user_s() {
    let system = clashes::Methods {
        mass_matrix: 2.0,
        forcing: 0.1,
        NQ: 0.5,
        COORDINATES: 9.81,
        kinetic_energy: 3.0,
    };
    let q = 0.7;
    let m = system.mass_matrix(&[q, 0.2]);
    // The pendulum's mass 2 at 0.5 from the slider of mass 3.
    let expected = [
        [2.0 * 0.25 + 0.1, 2.0 * 0.5 * q.cos()],
        [2.0 * 0.5 * q.cos(), 5.0],
    ];
    assert_eq!(m.len(), clashes::Methods::NQ);
    for (row, expected) in m.iter().zip(expected) {
        for (entry, expected) in row.iter().zip(expected) {
            assert!((entry - expected).abs() < 1e-15, "{m:?}");
        }
    }
    let potential = -2.0 * 9.81 * 0.5 * q.cos();
    assert!((system.potential_energy(&[q, 0.2]) - potential).abs() < 1e-15);
    assert_eq!(clashes::Methods::COORDINATES, ["q", "qd"]);

    let std = clashes::Std {
        f64: 2.0,
        core: 3.0,
        std: 0.5,
        Result: 2.0,
        Option: 1.0,
        Vec: 4.0,
    };
    assert!((std.mass_matrix(&[0.4])[0][0] - 2.0).abs() < 1e-15);
    assert!((std.potential_energy(&[0.4]) - (1.5 * 0.16 + 4.0 * 0.4)).abs() < 1e-15);
}

#[test]
fn a_struct_named_like_a_trait_still_implements_it() {
    let system = clashes::MultibodySystem { m: 2.5 };
    let mass = <clashes::MultibodySystem as dalembert::MultibodySystem<1, 1, 0>>::mass_matrix(
        &system,
        &[0.0],
    );
    assert!((mass[0][0] - 2.5).abs() < 1e-15);
    assert!((clashes::local_mass(1.5) - 1.5).abs() < 1e-15);
}
