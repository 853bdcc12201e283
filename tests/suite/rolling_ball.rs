//! A uniform solid ball rolling without slipping down an incline, on a free
//! joint: one holonomic row holds its centre at height `r` above the plane,
//! two nonholonomic rows hold its contact point at rest. The expected
//! values are derived by hand below, apart from the code under test.
//!
//! The plane is `z = 0` of `N`, tilted by `α`: gravity is
//! `g_N = (g sin α, 0, −g cos α)`, down the slope along `N.x`. With `n = N.z`
//! the contact point is at `−r n` from the centre, and rolling is
//! `v_N + ω_N × (−r n) = 0`, that is `v_N = r ω_N × n`:
//! `v_x = r ω_y`, `v_y = −r ω_x`, `v_z = 0`.
//!
//! The angular momentum about the contact point (`I = 2/5 m r²`) changes by
//! the moment of gravity there, `r n × m g_N`; for the horizontal part of
//! `ω_N` that is `(I + m r²) ω̇_h = m r n × g_N`, and no torque turns the ball
//! about `n` (`I ω̇_z = 0`: the friction force lies in the plane and passes
//! through the contact point, the normal force through the centre). So
//! `ω̇_N = c = (5 / 7r) n × g_N = (0, 5 g sin α / 7r, 0)`, constant, and the
//! centre accelerates by `a_N = r c × n = (5/7 g sin α, 0, 0)`, whatever the
//! spin: straight down the slope, never across it. Integrated:
//! `ω_N(t) = ω₀ + c t`, `x(t) = x₀ + r ω₀_y t + 5/14 g sin α t²`,
//! `y(t) = y₀ − r ω₀_x t`; and where `ω₀` is along `N.y` (rolling straight
//! down or up) every `ω_N(t)` is, so `R(t) = Rot(N.y, ω₀_y t + c_y t²/2) R₀`.
//!
//! In the joint's speeds (the child's axes, `R` the ball's attitude),
//! `v_B = Rᵀ v_N`, `ω_B = Rᵀ ω_N`, and their rates are
//! `ω̇_B = Rᵀ ω̇_N + (d Rᵀ/dt) ω_N = Rᵀ c − ω_B × ω_B = Rᵀ c` and
//! `v̇_B = Rᵀ a_N − ω_B × v_B`.

use dalembert::constrained::{constrained_accelerations, constraint_drift};
use dalembert::integrate::{Adaptive, AdaptiveOptions, ExplicitPair, Integration, State, Taylor};
use dalembert::{Constrained, Stabilisation};
use dalembert_codegen::testing::{cross, mat_vec, quaternion_rotation as rotation, transpose_vec};
use dalembert_fixtures::differences::central_differences;
use dalembert_fixtures::reference::{assert_close, flat};

dalembert::dalembert! {
    /// A uniform solid ball (mass `m`, radius `r`) rolling without slipping
    /// on the plane `z = 0`, tilted by `alpha` about `N.y` (gravity down the
    /// slope along `N.x`).
    pub RollingBall {
        parameters m, r, g, alpha;
        joint free base { parent: N, child: B, at: O };
        body ball { mass: m, center: base, frame: B, inertia: [2/5*m*r^2, 2/5*m*r^2, 2/5*m*r^2] };
        gravity g * sin(alpha) * N.x - g * cos(alpha) * N.z;
        // The centre at height r.
        constraint dot(base - O, N.z) == r;
        // The contact point at rest: the ball's point at −r n moves at
        // v + ω × (−r n), zero along N.x and N.y.
        constraint dot(velocity(base) + cross(angular_velocity(B), -r * N.z), N.x) == 0;
        constraint dot(velocity(base) + cross(angular_velocity(B), -r * N.z), N.y) == 0;
        outputs taylor, accelerations_jacobian, linearize(base_vx, base_vy, base_wx, base_wy, base_wz; base_wx, base_wy, base_wz);
    }
}

const BALL: RollingBall = RollingBall {
    m: 1.3,
    r: 0.11,
    g: 9.81,
    alpha: 0.3,
};

/// `n = N.z`, the plane's normal.
const NORMAL: [f64; 3] = [0.0, 0.0, 1.0];

/// `ω̇_N = c`, the constant angular acceleration (module docs).
fn angular_acceleration() -> [f64; 3] {
    [0.0, 5.0 * BALL.g * BALL.alpha.sin() / (7.0 * BALL.r), 0.0]
}

/// `a_N = r c × n`, the centre's constant acceleration.
fn centre_acceleration() -> [f64; 3] {
    cross(angular_acceleration(), NORMAL).map(|a| BALL.r * a)
}

/// The unit quaternion `(x, y, z, w)` of the rotation by `angle` about the
/// unit `axis`.
fn quaternion(axis: [f64; 3], angle: f64) -> [f64; 4] {
    let (s, c) = (angle / 2.0).sin_cos();
    [axis[0] * s, axis[1] * s, axis[2] * s, c]
}

/// The ball rolling on the plane at `(x, y)`, turned by `attitude`, turning
/// at `omega` (in `N`'s axes), the centre at `v_N = r ω_N × n`.
fn rolling(x: f64, y: f64, attitude: [f64; 4], omega: [f64; 3]) -> State<7, 6> {
    let attitude_matrix = rotation(attitude);
    let velocity = cross(omega, NORMAL).map(|v| BALL.r * v);
    let ([vx, vy, vz], [wx, wy, wz]) = (
        transpose_vec(&attitude_matrix, velocity),
        transpose_vec(&attitude_matrix, omega),
    );
    let [qx, qy, qz, qw] = attitude;
    State {
        t: 0.0,
        q: [x, y, BALL.r, qx, qy, qz, qw],
        v: [vx, vy, vz, wx, wy, wz],
    }
}

/// The attitude of the states below: off every axis.
fn tilted() -> [f64; 4] {
    let norm = (0.3f64 * 0.3 + 0.5 * 0.5 + 0.8 * 0.8).sqrt();
    quaternion([0.3 / norm, -0.5 / norm, 0.8 / norm], 1.1)
}

/// The quaternion of a state.
fn attitude(state: &State<7, 6>) -> [f64; 4] {
    [state.q[3], state.q[4], state.q[5], state.q[6]]
}

/// The centre's velocity and the angular velocity of a state, in `N`'s
/// axes.
fn in_space(state: &State<7, 6>) -> ([f64; 3], [f64; 3]) {
    let r = rotation(attitude(state));
    let [vx, vy, vz, wx, wy, wz] = state.v;
    (mat_vec(&r, [vx, vy, vz]), mat_vec(&r, [wx, wy, wz]))
}

/// At rest, rolling down, rolling up, rolling straight across the slope
/// and spinning about the normal while it rolls: the accelerations are
/// `ω̇_B = Rᵀ c` and `v̇_B = Rᵀ a_N − ω_B × v_B`, so in space the centre
/// accelerates at `5/7 g sin α` straight down the slope.
#[test]
fn accelerations_are_five_sevenths_of_g_sin_alpha_down_the_slope() {
    let states = [
        rolling(0.0, 0.0, [0.0, 0.0, 0.0, 1.0], [0.0; 3]),
        rolling(0.4, -0.2, tilted(), [0.0, 6.0, 0.0]),
        rolling(0.4, -0.2, tilted(), [0.0, -9.0, 0.0]),
        // Straight across the slope at 0.88 m/s.
        rolling(-1.0, 2.0, tilted(), [8.0, 0.0, 0.0]),
        // Spinning about the normal while rolling obliquely.
        rolling(1.5, 0.3, tilted(), [-3.0, 4.0, 25.0]),
    ];
    for (k, state) in states.iter().enumerate() {
        let (vdot, _) =
            constrained_accelerations(&BALL, 0.0, &state.q, &state.v, &[]).expect("solvable");
        let attitude_matrix = rotation(attitude(state));
        let ([vx, vy, vz], [wx, wy, wz]) = (
            [state.v[0], state.v[1], state.v[2]],
            [state.v[3], state.v[4], state.v[5]],
        );
        let centre: [f64; 3] = std::array::from_fn(|i| {
            transpose_vec(&attitude_matrix, centre_acceleration())[i]
                - cross([wx, wy, wz], [vx, vy, vz])[i]
        });
        let spin = transpose_vec(&attitude_matrix, angular_acceleration());
        let expected: Vec<f64> = centre.iter().chain(&spin).copied().collect();
        assert_close(&format!("state {k}: v̇"), &vdot, &expected, 1e-12);
    }
}

/// Rotation by `angle` about `N.y`.
fn about_y(angle: f64) -> [[f64; 3]; 3] {
    let (s, c) = angle.sin_cos();
    [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
}

/// The closed form at `t` from `start` (module docs): the centre's
/// position and velocity and the angular velocity, in `N`'s axes.
fn closed_form(start: &State<7, 6>, t: f64) -> Vec<f64> {
    let (_, omega0) = in_space(start);
    let c = angular_acceleration();
    let omega: [f64; 3] = std::array::from_fn(|i| omega0[i] + c[i] * t);
    let velocity = cross(omega, NORMAL).map(|v| BALL.r * v);
    let a = centre_acceleration();
    let position: [f64; 3] = std::array::from_fn(|i| {
        let rolled = BALL.r * cross(omega0, NORMAL)[i] * t;
        start.q[i] + rolled + a[i] * t * t / 2.0
    });
    [position, velocity, omega].concat()
}

/// The same quantities of an integrated state.
fn observed(state: &State<7, 6>) -> Vec<f64> {
    let (velocity, omega) = in_space(state);
    [[state.q[0], state.q[1], state.q[2]], velocity, omega].concat()
}

/// Rolling up the slope at 1.65 m/s, stopping at 0.8 s and rolling back:
/// at 2 s the attitude is `R(t) = Rot(N.y, ω₀ t + c t²/2) R₀`.
fn rolling_up() -> State<7, 6> {
    rolling(0.2, -0.1, tilted(), [0.0, -15.0, 0.0])
}

/// Rolling obliquely and spinning about the normal.
fn spinning() -> State<7, 6> {
    rolling(0.2, -0.1, tilted(), [4.0, -10.0, 30.0])
}

const PROJECTION: Stabilisation = Stabilisation::Projection {
    tolerance: 1e-14,
    max_iterations: 5,
};

/// Checks `end`, two seconds after `start`, against the closed form, and
/// that it is on the constraints.
fn assert_closed_form(what: &str, start: &State<7, 6>, end: &State<7, 6>, tol: f64, turns: bool) {
    assert_close(what, &observed(end), &closed_form(start, end.t), tol);
    let drift = constraint_drift(&BALL, end);
    assert!(drift < tol, "{what}: height off by {drift:e}");
    // The velocity form of the rows: the centre's vertical speed and the
    // contact point's slip, against the centre's speed.
    let speed = in_space(end).0.iter().map(|v| v * v).sum::<f64>().sqrt();
    let slip = BALL.constraint_velocity(end.t, &end.q, &end.v);
    assert!(
        slip.iter().all(|s| s.abs() < tol * speed),
        "{what}: {slip:?}"
    );
    if !turns {
        return;
    }
    let c = angular_acceleration()[1];
    let angle = in_space(start).1[1] * end.t + c * end.t * end.t / 2.0;
    // Row i of R(t) R₀ᵀ is (R₀ R(t)ᵀ eᵢ)ᵀ.
    let (initial, reached) = (rotation(attitude(start)), rotation(attitude(end)));
    let relative: [[f64; 3]; 3] = std::array::from_fn(|i| {
        let axis = std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 });
        mat_vec(&initial, transpose_vec(&reached, axis))
    });
    let what = format!("{what}: R(t) R₀ᵀ");
    assert_close(&what, &flat(&relative), &flat(&about_y(angle)), tol);
}

/// DOP853 at 1e-13, projected onto the rows after each step: at 2 s the
/// position, velocities and attitude are the closed form to 1e-11 (8e-13
/// measured, on the attitude), the height `r` to rounding.
#[test]
fn dop853_with_projection_follows_the_closed_form() {
    let dynamics = Constrained::without_inputs(&BALL, PROJECTION);
    let options = AdaptiveOptions::with_tolerance(1e-13);
    for (what, start, turns) in [
        ("rolling up", rolling_up(), true),
        ("spinning", spinning(), false),
    ] {
        let end = Integration::new(
            &dynamics,
            start,
            2.0,
            Adaptive {
                pair: ExplicitPair::Dop853,
                options,
            },
        )
        .run()
        .expect("integrates")
        .end;
        assert_closed_form(&format!("DOP853, {what}"), &start, &end, 1e-11, turns);
    }
}

/// `Taylor` at 1e-15 on the index-1 form and projected: the
/// closed form at 2 s to 1e-13 (2.6e-14 measured).
#[test]
fn taylor_series_follow_the_closed_form() {
    for stabilisation in [Stabilisation::None, PROJECTION] {
        let dynamics = Constrained::without_inputs(&BALL, stabilisation);
        let options = Taylor::with_tolerance(1e-15);
        for (what, start, turns) in [
            ("rolling up", rolling_up(), true),
            ("spinning", spinning(), false),
        ] {
            let end = Integration::new(&dynamics, start, 2.0, options)
                .run()
                .expect("integrates")
                .end;
            assert_closed_form(
                &format!("Taylor {stabilisation:?}, {what}"),
                &start,
                &end,
                1e-13,
                turns,
            );
        }
    }
}

/// Index of `δ_vz` (the dependent tangent coordinate: `n · R δ_v = 0`) and
/// of the speeds `v_B` (dependent: `v_B = r ω_B × n_B`) in `linearize`'s
/// state `(δ, δv)`.
const DEPENDENT: [usize; 4] = [2, 6, 7, 8];

/// `linearize`'s `A` by hand, at a rolling state with `n_B = Rᵀ n`. A
/// perturbation along the manifold is `δ = (δ_v, δ_ω)` with
/// `n_B · δ_v = 0` (the holonomic row: the centre moves by `R δ_v`) and
/// `δv = (δv_B, δω)` with `δv_B = r δω × n_B + r ω̄ × δn_B`,
/// `δn_B = n_B × δ_ω` (`Rᵀ` turns to `(1 − [δ_ω]×) Rᵀ`). Its rates are the
/// kinematic rows `δ̇_v = δv_B − ω̄ × δ_v − v̄ × δ_ω`, `δ̇_ω = δω − ω̄ × δ_ω`
/// and the derivatives of `v̇_B = Rᵀ a_N − ω_B × v_B`, `ω̇_B = Rᵀ c`:
/// `δv̇_B = (Rᵀ a_N) × δ_ω − δω × v̄ − ω̄ × δv_B`, `δω̇_B = (Rᵀ c) × δ_ω`.
/// Column `j` is the rate of the perturbation of independent entry `j`.
fn linearization_by_hand(state: &State<7, 6>) -> [[f64; 12]; 12] {
    let attitude_matrix = rotation(attitude(state));
    let normal = transpose_vec(&attitude_matrix, NORMAL);
    let (centre, spin) = (
        transpose_vec(&attitude_matrix, centre_acceleration()),
        transpose_vec(&attitude_matrix, angular_acceleration()),
    );
    let v = [state.v[0], state.v[1], state.v[2]];
    let w = [state.v[3], state.v[4], state.v[5]];
    let r = BALL.r;
    let unit = |k: usize| -> [f64; 3] { std::array::from_fn(|i| if i == k { 1.0 } else { 0.0 }) };
    let mut a = [[0.0; 12]; 12];
    let mut column = |j: usize, delta_v: [f64; 3], delta_w: [f64; 3], delta_speed_w: [f64; 3]| {
        let turned_normal = cross(normal, delta_w);
        let delta_speed_v: [f64; 3] = std::array::from_fn(|i| {
            r * cross(delta_speed_w, normal)[i] + r * cross(w, turned_normal)[i]
        });
        let rates: [[f64; 3]; 4] = [
            std::array::from_fn(|i| delta_speed_v[i] - cross(w, delta_v)[i] - cross(v, delta_w)[i]),
            std::array::from_fn(|i| delta_speed_w[i] - cross(w, delta_w)[i]),
            std::array::from_fn(|i| {
                cross(centre, delta_w)[i] - cross(delta_speed_w, v)[i] - cross(w, delta_speed_v)[i]
            }),
            cross(spin, delta_w),
        ];
        for (row, rate) in a.iter_mut().zip(rates.iter().flatten()) {
            row[j] = *rate;
        }
    };
    for k in 0..2 {
        // δ_v = e_k, its z entry set by n_B · δ_v = 0.
        let mut delta_v = unit(k);
        delta_v[2] = -normal[k] / normal[2];
        column(k, delta_v, [0.0; 3], [0.0; 3]);
    }
    for k in 0..3 {
        column(3 + k, [0.0; 3], unit(k), [0.0; 3]);
        column(9 + k, [0.0; 3], [0.0; 3], unit(k));
    }
    a
}

/// `linearize` with the tangent directions `δ_vx`, `δ_vy` and the turns
/// independent, and the angular speeds, at states rolling obliquely with
/// spin (the centre's velocity and the angular velocity off every axis):
/// `A` is the hand-derived one, its dependent columns zero, and `B` empty.
#[test]
fn linearization_on_the_rolling_manifold_is_the_hand_derived_one() {
    for state in [
        spinning(),
        rolling_up(),
        rolling(0.0, 0.0, tilted(), [0.0; 3]),
    ] {
        let (a, _) = BALL
            .linearize(0.0, &state.q, &state.v, &[])
            .expect("linearisable");
        assert_close("A", &flat(&a), &flat(&linearization_by_hand(&state)), 1e-12);
        for row in &a {
            for j in DEPENDENT {
                assert_eq!(row[j], 0.0, "a dependent column");
            }
        }
    }
}

/// `accelerations_jacobian` against central differences (step 1e-6) of
/// `constrained_accelerations`, by `q` along `integrate_configuration`
/// (the tangent space `q ⊕ δ`), on the manifold and off it (lifted and
/// slipping: `v̇` is a function of the whole state), to 1e-7 of the
/// largest derivative.
#[test]
fn accelerations_jacobian_matches_differences() {
    let vdot = |q: &[f64; 7], v: &[f64; 6]| {
        constrained_accelerations(&BALL, 0.0, q, v, &[])
            .expect("solvable")
            .0
    };
    let rolling = spinning();
    let mut off = rolling;
    off.q[2] += 0.02;
    off.v[0] += 0.3;
    off.v[4] -= 1.0;
    for state in [rolling, off] {
        let (q, v) = (state.q, state.v);
        let (by_q, by_v, _) = BALL
            .accelerations_jacobian(0.0, &q, &v, &[])
            .expect("regular");
        let step = 1e-6;
        let along = central_differences(&[0.0; 6], step, |delta| {
            vdot(&BALL.integrate_configuration(&q, delta, 1.0), &v)
        });
        let by_speeds = central_differences(&v, step, |v| vdot(&q, v));
        assert_close("∂v̇/∂q", &flat(&by_q), &flat(&along), 1e-7);
        assert_close("∂v̇/∂v", &flat(&by_v), &flat(&by_speeds), 1e-7);
    }
}
