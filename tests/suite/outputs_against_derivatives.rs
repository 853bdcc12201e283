//! The control outputs of `docs/language.md` ("Outputs") against their
//! derivatives (the checks of `output_checks`) on inputs in a turning frame,
//! springs, dampers and a support shaken with time, a body with symbolic
//! products of inertia and parameters inside functions, and speeds of one's
//! own; their base parameters independent; and `inverse_dynamics` against the
//! `M v̇ − f` of the SymPy reading `dal_sympy.py` (stored in
//! `tests/reference/dal_sympy_states.json`).

use crate::planar_arm_outputs::ARM_BY_POINTS;
use dalembert::Model;
use dalembert_fixtures::reference::{SympyState, assert_close, flat, sympy_states};

use crate::output_checks::*;

dalembert::dalembert! {
    /// A turntable carrying a tilting arm; a force along the arm and a motor
    /// between arm and table, so the inputs enter through the turning axes.
    pub TurningInputs {
        parameters m, d, l, g;
        coordinates phi, theta;
        inputs pull, motor;
        frame F = N.rotate_z(phi);
        frame B = F.rotate_y(theta);
        point H = O + d * F.y;
        point G = H + l * B.z;
        body arm { mass: m, center: G, frame: B, inertia: [m*l^2/3, m*l^2/3, 0.01*m] };
        gravity -g * N.z;
        force pull * B.x at G;
        torque motor * F.y on B reacting F;
        outputs inverse_dynamics, inverse_dynamics_jacobian, accelerations_jacobian, linearize, regressor;
        outputs position(G in F), velocity(G in F), acceleration(G in F), jacobian(G in F);
        outputs rotation(F), angular_velocity(B in F), angular_jacobian(B in F), rotation(B in F);
    }
}

const TURNING_INPUTS: TurningInputs = TurningInputs {
    m: 1.4,
    d: 0.3,
    l: 0.6,
    g: 9.81,
};

dalembert::dalembert! {
    /// A cart on a spring carrying a pendulum, springs and dampers both (the
    /// damping depending on the coordinates), a load that varies with time
    /// and a marker without mass sliding along the pendulum with time.
    pub ShakenSprings {
        parameters m, M, l, k, kt, c, ct, a, w, g;
        coordinates x, th;
        inputs u;
        frame B = N.rotate_z(th);
        point Cart = O + x * N.x;
        point Bob = Cart - l * B.y;
        point Marker = Bob + a * sin(w * t) * B.x;
        particle cart { mass: M, at: Cart };
        particle bob { mass: m, at: Bob };
        gravity -g * N.y;
        potential k / 2 * x^2 + kt * (1 - cos(th));
        dissipation c / 2 * dt(x)^2 + ct / 2 * (cos(th) * dt(th))^2 + c / 2 * x^2 * dt(th)^2;
        force (u + a * cos(w * t)) * N.x at Cart;
        outputs inverse_dynamics, inverse_dynamics_jacobian, accelerations_jacobian, linearize;
        outputs position(Marker), velocity(Marker), acceleration(Marker), jacobian(Marker);
        outputs position(Marker in B), velocity(Marker in B), acceleration(Marker in B), jacobian(Marker in B), rotation(B);
    }
}

const SHAKEN: ShakenSprings = ShakenSprings {
    m: 0.6,
    M: 1.9,
    l: 0.7,
    k: 12.0,
    kt: 0.8,
    c: 0.4,
    ct: 0.3,
    a: 0.05,
    w: 7.0,
    g: 9.81,
};

dalembert::dalembert! {
    /// A body on a tilted axis (`alpha` inside functions), turning and
    /// nodding, with all six entries of its inertia symbolic and its center
    /// off both axes.
    pub FullInertia {
        parameters m, c, e, alpha, Ixx, Iyy, Izz, Ixy, Iyz, Izx, g;
        coordinates q1, q2;
        inputs u1;
        frame A = N.rotate_x(alpha);
        frame B = A.rotate_z(q1);
        frame C = B.rotate_x(q2);
        point G = O + e^2 * B.x + c * C.y;
        body b { mass: m, center: G, frame: C, inertia: [Ixx, Iyy, Izz, Ixy, Iyz, Izx] };
        gravity -g * N.z;
        torque u1 * B.x on C reacting B;
        outputs inverse_dynamics, inverse_dynamics_jacobian, accelerations_jacobian, linearize, regressor;
        outputs velocity(G in C), acceleration(G in C), angular_velocity(C in A), angular_jacobian(C in A);
        outputs rotation(C), rotation(A), position(G), velocity(G), acceleration(G), jacobian(G);
        outputs angular_velocity(C), angular_jacobian(C), position(G in C), jacobian(G in C), rotation(C in A);
    }
}

const FULL_INERTIA: FullInertia = FullInertia {
    m: 1.3,
    c: 0.25,
    e: 0.6,
    alpha: 0.4,
    Ixx: 0.05,
    Iyy: 0.07,
    Izz: 0.09,
    Ixy: 0.004,
    Iyz: -0.006,
    Izx: 0.003,
    g: 9.81,
};

dalembert::dalembert! {
    /// A heavy top in X-Y-Z Cardan angles with its body rates as speeds.
    pub RatesTop {
        parameters m, h, I1, I2, I3, g;
        coordinates a, b, c;
        inputs spin;
        speeds wx, wy, wz {
            a: (cos(c) * wx - sin(c) * wy) / cos(b),
            b: sin(c) * wx + cos(c) * wy,
            c: wz - tan(b) * (cos(c) * wx - sin(c) * wy)
        };
        frame A = N.rotate_x(a);
        frame C = A.rotate_y(b);
        frame B = C.rotate_z(c);
        point G = O + h * B.x;
        body top { mass: m, center: G, frame: B, inertia: [I1, I2, I3] };
        gravity -g * N.z;
        torque spin * B.z on B;
        outputs inverse_dynamics, inverse_dynamics_jacobian, accelerations_jacobian, linearize, regressor;
        outputs position(G), velocity(G), acceleration(G), jacobian(G);
        outputs rotation(B), angular_velocity(B), angular_jacobian(B);
        outputs position(G in C), velocity(G in C), acceleration(G in C), jacobian(G in C);
        outputs rotation(B in C), angular_velocity(B in C), angular_jacobian(B in C);
    }
}

const RATES_TOP: RatesTop = RatesTop {
    m: 0.8,
    h: 0.12,
    I1: 0.011,
    I2: 0.013,
    I3: 0.02,
    g: 9.81,
};

#[test]
fn inputs_in_turning_axes_match_their_derivatives() {
    let dynamics = dynamic_outputs!(TURNING_INPUTS);
    let table = |t, q: &[f64; 2]| TURNING_INPUTS.rotation_F(t, q);
    for x in samples::<2, 2, 2>(3) {
        check_dynamics(&TURNING_INPUTS, &dynamics, &x);
        check_regressor(
            |q, v, a| TURNING_INPUTS.regressor(q, v, a),
            TURNING_INPUTS.base_parameters(),
            |q, v, a| TURNING_INPUTS.inverse_dynamics(x.t, q, v, a, &[0.0; 2]),
            &x,
        );
        // The rotation of F is about N.z by phi; G in F's axes is the
        // closed form d F.y + l B.z with B.z = (sin θ, 0, cos θ) in F.
        let (s, c) = x.q[1].sin_cos();
        let expected = [TURNING_INPUTS.l * s, TURNING_INPUTS.d, TURNING_INPUTS.l * c];
        assert_close(
            "G in F",
            &TURNING_INPUTS.position_G_in_F(x.t, &x.q),
            &expected,
            1e-14,
        );
        let g_in_f = PointOutputs {
            position: Box::new(|t, q: &[f64; 2]| {
                let r = TURNING_INPUTS.rotation_F(t, q);
                matrix_times(&r, &TURNING_INPUTS.position_G_in_F(t, q))
            }),
            velocity: Box::new(|t, q, v| {
                matrix_times(
                    &TURNING_INPUTS.rotation_F(t, q),
                    &TURNING_INPUTS.velocity_G_in_F(t, q, v),
                )
            }),
            acceleration: Box::new(|t, q, v, a| {
                matrix_times(
                    &TURNING_INPUTS.rotation_F(t, q),
                    &TURNING_INPUTS.acceleration_G_in_F(t, q, v, a),
                )
            }),
            jacobian: Box::new(|t, q| {
                product(
                    &TURNING_INPUTS.rotation_F(t, q),
                    &TURNING_INPUTS.jacobian_G_in_F(t, q),
                )
            }),
        };
        check_point_in_n(&TURNING_INPUTS, &g_in_f, &x);
        // B relative to F turns about F.y at θ̇: its ω in F's axes is that
        // plus φ̇ N.z = φ̇ F.z.
        let omega = TURNING_INPUTS.angular_velocity_B_in_F(x.t, &x.q, &x.v);
        assert_close("ω_B in F", &omega, &[0.0, x.v[1], x.v[0]], 1e-14);
        let jacobian = TURNING_INPUTS.angular_jacobian_B_in_F(x.t, &x.q);
        assert_close(
            "J_B in F",
            &flat(&jacobian),
            &[0.0, 0.0, 0.0, 1.0, 1.0, 0.0],
            1e-14,
        );
        let r_b = product(
            &table(x.t, &x.q),
            &TURNING_INPUTS.rotation_B_in_F(x.t, &x.q),
        );
        let expected_b = [[c, -0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]];
        assert_close(
            "R_B in F",
            &flat(&TURNING_INPUTS.rotation_B_in_F(x.t, &x.q)),
            &flat(&expected_b),
            1e-14,
        );
        assert_close(
            "R_F R_B/F",
            &flat(&r_b),
            &flat(&product(&table(x.t, &x.q), &expected_b)),
            1e-14,
        );
    }
}

#[test]
fn springs_dampers_and_time_match_their_derivatives() {
    let dynamics = dynamic_outputs!(SHAKEN);
    let marker = point_outputs!(
        SHAKEN,
        position_Marker,
        velocity_Marker,
        acceleration_Marker,
        jacobian_Marker
    );
    let marker_in_b = point_outputs!(
        SHAKEN,
        position_Marker_in_B,
        velocity_Marker_in_B,
        acceleration_Marker_in_B,
        jacobian_Marker_in_B
    );
    let pendulum = |t, q: &[f64; 2]| SHAKEN.rotation_B(t, q);
    for x in samples::<2, 2, 1>(4) {
        check_dynamics(&SHAKEN, &dynamics, &x);
        check_point_in_n(&SHAKEN, &marker, &x);
        check_point_in_frame(&marker, &marker_in_b, pendulum, &x);
    }
}

#[test]
fn symbolic_products_of_inertia_match_their_derivatives() {
    let dynamics = dynamic_outputs!(FULL_INERTIA);
    let center = point_outputs!(
        FULL_INERTIA,
        position_G,
        velocity_G,
        acceleration_G,
        jacobian_G
    );
    let center_in_c = point_outputs!(
        FULL_INERTIA,
        position_G_in_C,
        velocity_G_in_C,
        acceleration_G_in_C,
        jacobian_G_in_C
    );
    let body = frame_outputs!(
        FULL_INERTIA,
        rotation_C,
        angular_velocity_C,
        angular_jacobian_C
    );
    let body_in_a = FrameOutputs {
        rotation: Box::new(|t, q: &[f64; 2]| FULL_INERTIA.rotation_C_in_A(t, q)),
        angular_velocity: Box::new(|t, q, v| FULL_INERTIA.angular_velocity_C_in_A(t, q, v)),
        angular_jacobian: Box::new(|t, q| FULL_INERTIA.angular_jacobian_C_in_A(t, q)),
    };
    let tilted = |t, q: &[f64; 2]| FULL_INERTIA.rotation_A(t, q);
    let own = |t, q: &[f64; 2]| FULL_INERTIA.rotation_C(t, q);
    for x in samples::<2, 2, 1>(5) {
        check_dynamics(&FULL_INERTIA, &dynamics, &x);
        check_regressor(
            |q, v, a| FULL_INERTIA.regressor(q, v, a),
            FULL_INERTIA.base_parameters(),
            |q, v, a| FULL_INERTIA.inverse_dynamics(x.t, q, v, a, &[0.0]),
            &x,
        );
        check_point_in_n(&FULL_INERTIA, &center, &x);
        check_point_in_frame(&center, &center_in_c, own, &x);
        check_frame_in_n(&FULL_INERTIA, &body, &x);
        check_frame_in_frame(&body, &body_in_a, tilted, &x);
    }
}

#[test]
fn speeds_of_ones_own_match_their_derivatives() {
    let dynamics = dynamic_outputs!(RATES_TOP);
    let center = point_outputs!(
        RATES_TOP,
        position_G,
        velocity_G,
        acceleration_G,
        jacobian_G
    );
    let center_in_c = point_outputs!(
        RATES_TOP,
        position_G_in_C,
        velocity_G_in_C,
        acceleration_G_in_C,
        jacobian_G_in_C
    );
    let body = frame_outputs!(
        RATES_TOP,
        rotation_B,
        angular_velocity_B,
        angular_jacobian_B
    );
    let body_in_c = frame_outputs!(
        RATES_TOP,
        rotation_B_in_C,
        angular_velocity_B_in_C,
        angular_jacobian_B_in_C
    );
    let gimbal = |t, q: &[f64; 3]| {
        let turned_back = transpose(&RATES_TOP.rotation_B_in_C(t, q));
        product(&RATES_TOP.rotation_B(t, q), &turned_back)
    };
    for x in samples::<3, 3, 1>(6) {
        check_dynamics(&RATES_TOP, &dynamics, &x);
        check_regressor(
            |q, v, a| RATES_TOP.regressor(q, v, a),
            RATES_TOP.base_parameters(),
            |q, v, a| RATES_TOP.inverse_dynamics(x.t, q, v, a, &[0.0]),
            &x,
        );
        check_point_in_n(&RATES_TOP, &center, &x);
        check_point_in_frame(&center, &center_in_c, gimbal, &x);
        check_frame_in_n(&RATES_TOP, &body, &x);
        check_frame_in_frame(&body, &body_in_c, gimbal, &x);
        // The speeds are B's angular velocity in B's axes.
        let in_b = transposed_times(
            &RATES_TOP.rotation_B(x.t, &x.q),
            &RATES_TOP.angular_velocity_B(x.t, &x.q, &x.v),
        );
        assert_close("ω_B in B", &in_b, &x.v, 1e-14);
    }
}

/// The smallest singular value of `Y` stacked over 12 random motions,
/// relative to the largest: positive where no combination of the base
/// parameters leaves `M v̇ − f` unchanged.
fn independence<const NQ: usize, const NV: usize, const NP: usize>(
    regressor: impl Fn(&[f64; NQ], &[f64; NV], &[f64; NV]) -> [[f64; NP]; NV],
) -> f64 {
    let mut seed = 11;
    let rows: Vec<[f64; NP]> = (0..12)
        .flat_map(|_| regressor(&draws(&mut seed), &draws(&mut seed), &draws(&mut seed)))
        .collect();
    let stacked = nalgebra::DMatrix::from_fn(rows.len(), NP, |i, j| rows[i][j]);
    let singular = stacked.singular_values();
    singular.min() / singular.max()
}

/// The base parameters are independent: none can be merged into the
/// others (with `Y π = τ` above, they are a basis of what motions tell);
/// the smallest relative singular values are 2e-3 to 0.3.
#[test]
fn base_parameters_are_independent() {
    assert!(independence(|q, v, a| ARM_BY_POINTS.regressor(q, v, a)) > 1e-5);
    assert!(independence(|q, v, a| TURNING_INPUTS.regressor(q, v, a)) > 1e-5);
    assert!(independence(|q, v, a| FULL_INERTIA.regressor(q, v, a)) > 1e-5);
    assert!(independence(|q, v, a| RATES_TOP.regressor(q, v, a)) > 1e-5);
}

/// `inverse_dynamics` is SymPy's `M v̇ − f`: the six-entry symbolic inertia
/// on a tilted axis, and the springs, the angle-dependent dampers and the
/// load that varies with time.
#[test]
fn inverse_dynamics_is_sympys_reading() {
    let vdot = [0.9, -1.4];
    let expected = |state: &SympyState<2, 1>| -> [f64; 2] {
        std::array::from_fn(|i| matrix_times(&state.mass, &vdot)[i] - state.forcing[i])
    };
    let parameters = FULL_INERTIA.parameter_values();
    for state in &sympy_states::<2, 1>("FullInertia", &parameters) {
        let SympyState { t, q, v, u, .. } = *state;
        let tau = FULL_INERTIA.inverse_dynamics(t, &q, &v, &vdot, &u);
        assert_close("tilted body", &tau, &expected(state), 1e-13);
    }
    for state in &sympy_states::<2, 1>("ShakenSprings", &SHAKEN.parameter_values()) {
        let SympyState { t, q, v, u, .. } = *state;
        let tau = SHAKEN.inverse_dynamics(t, &q, &v, &vdot, &u);
        assert_close("springs and dampers", &tau, &expected(state), 1e-13);
    }
}
