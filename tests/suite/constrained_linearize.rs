//! `linearize` of systems with constraints, on the constraint manifold with
//! the independent coordinates the model names: seed example 3 with `θ`
//! independent against the closed form of the same pendulum in one
//! coordinate (its small oscillations `±i √(3g / 2l)` at the hanging
//! position) and with `ẋ` its independent speed against the closed form of
//! its exponents at rest off the equilibrium, the slider-crank with the
//! crank angle independent against
//! central differences of the constrained accelerations along the
//! manifold, and the error where the chosen coordinates do not determine
//! the others; the nonholonomic knife-edge sled against SymPy's own
//! `KanesMethod.linearize`; seed example 3 in body-axis speeds (a `speeds`
//! statement) and a spherical joint held to a plane by two rows on its
//! quaternion against the closed forms of their one-coordinate pendulums.
//! And `accelerations_jacobian` of constrained systems (seed example 3, the
//! sled, the held spherical joint) against central differences of
//! `dalembert::accelerations` (along `integrate_configuration` for the
//! spherical joint), on and off the manifold.

use dalembert::constrained::constrained_accelerations;
use dalembert::{DynamicsError, MultibodySystem};
use dalembert_fixtures::differences::central_differences;
use dalembert_fixtures::reference::assert_near_all;
use dalembert_fixtures::slider_crank::{SLIDER_CRANK, SliderCrank};
use nalgebra::SMatrix;

/// Seed example 3 as `$name`, linearised with `$independent` independent
/// (or with what `[..]` holds: `[theta; dt(x)]`), with the statements
/// `$speeds` (a `speeds` statement) if given.
macro_rules! seed_example_3 {
    ($name:ident, $independent:ident $(, $($speeds:tt)+)?) => {
        seed_example_3!($name, [$independent] $(, $($speeds)+)?);
    };
    ($name:ident, [$($independent:tt)+] $(, $($speeds:tt)+)?) => {
        dalembert::dalembert! {
            /// Seed example 3, linearised with one coordinate independent.
            pub $name {
                parameters m, l, g;
                coordinates x, y, theta;
                $($($speeds)+)?
                inputs M;
                frame B = N.rotate_z(theta);
                point G = O + x * N.x + y * N.y;
                body bar { mass: m, center: G, frame: B, inertia: [0, 0, m*l^2/12] };
                gravity -g * N.y;
                torque M * N.z on B;
                constraint x - l/2 * sin(theta) == 0;
                constraint y + l/2 * cos(theta) == 0;
                outputs linearize($($independent)+), accelerations_jacobian;
            }
        }
    };
}

seed_example_3!(ByAngle, theta);
// `x` and `theta` follow from `y` except where `sin θ = 0`.
seed_example_3!(ByHeight, y);
// `theta` and `y` follow from `x`, and their speeds from that of `x`,
// except where `cos θ = 0`.
seed_example_3!(BySlide, [theta; dt(x)]);

dalembert::dalembert! {
    /// A knife-edge sled: it slides only along its own axis `B.x`, pushed
    /// along it and turned by the inputs, on a slope.
    pub Sled {
        parameters m, I, c, g;
        coordinates x, y, theta;
        inputs push, turn;
        frame B = N.rotate_z(theta);
        point G = O + x * N.x + y * N.y + c * B.x;
        body sled { mass: m, center: G, frame: B, inertia: [0, 0, I] };
        gravity -g * N.y;
        force push * B.x at G;
        torque turn * N.z on B;
        constraint -sin(theta) * dt(x) + cos(theta) * dt(y) == 0;
        outputs accelerations_jacobian, linearize(x, y, theta; dt(x), dt(theta));
    }
}

const BAR: ByAngle = ByAngle {
    m: 1.7,
    l: 1.1,
    g: 9.81,
};

/// The state on the manifold with the bar at `theta`, turning at `rate`.
fn assembled(l: f64, theta: f64, rate: f64) -> ([f64; 3], [f64; 3]) {
    let (s, c) = theta.sin_cos();
    let half = l / 2.0;
    (
        [half * s, -half * c, theta],
        [half * c * rate, half * s * rate, rate],
    )
}

#[test]
fn hanging_bar_oscillates_at_the_closed_form_frequency() {
    let (q, v) = assembled(BAR.l, 0.0, 0.0);
    let (a, b) = BAR.linearize(0.0, &q, &v, &[0.0]).expect("linearisable");
    // About the pivot: I_O = m l² / 3, restoring torque m g (l/2) θ.
    let omega = (3.0 * BAR.g / (2.0 * BAR.l)).sqrt();
    let eigenvalues = SMatrix::<f64, 6, 6>::from_fn(|i, j| a[i][j]).complex_eigenvalues();
    let mut imaginary: Vec<f64> = eigenvalues.iter().map(|z| z.im).collect();
    imaginary.sort_by(f64::total_cmp);
    for z in &eigenvalues {
        assert!(z.re.abs() < 1e-12 * omega, "real part {}", z.re);
    }
    let expected = [-omega, 0.0, 0.0, 0.0, 0.0, omega];
    for (got, want) in imaginary.iter().zip(expected) {
        assert!(
            (got - want).abs() < 1e-12 * omega,
            "{imaginary:?} against ±{omega}"
        );
    }
    // The torque turns the bar by M / I_O.
    let inertia = BAR.m * BAR.l * BAR.l / 3.0;
    assert!((b[5][0] - 1.0 / inertia).abs() < 1e-12 / inertia, "{b:?}");
}

/// Everywhere on the manifold the rows and columns of `(θ, θ̇)` are the
/// one-coordinate pendulum's `[[0, 1], [−3g cos θ / 2l, 0]]`, `x`'s row is
/// the derivative of `ẋ = (l/2) cos θ θ̇` along the manifold, and the
/// columns of the dependent `x`, `y`, `ẋ`, `ẏ` are zero.
#[test]
fn reduced_matrix_is_the_one_coordinate_pendulum_s() {
    for (theta, rate) in [(0.4, -1.3), (2.0, 0.7), (-2.9, 2.2)] {
        let (q, v) = assembled(BAR.l, theta, rate);
        let (a, _) = BAR.linearize(0.0, &q, &v, &[0.3]).expect("linearisable");
        let stiffness = -3.0 * BAR.g * theta.cos() / (2.0 * BAR.l);
        let close = |got: f64, want: f64| (got - want).abs() < 1e-12 * (1.0 + want.abs());
        assert!(close(a[2][2], 0.0) && close(a[2][5], 1.0), "{:?}", a[2]);
        assert!(
            close(a[5][2], stiffness) && close(a[5][5], 0.0),
            "{:?}",
            a[5]
        );
        let half = BAR.l / 2.0;
        assert!(close(a[0][2], -half * theta.sin() * rate), "{:?}", a[0]);
        assert!(close(a[0][5], half * theta.cos()), "{:?}", a[0]);
        for row in &a {
            for j in [0, 1, 3, 4] {
                assert_eq!(row[j], 0.0, "a dependent column");
            }
        }
    }
}

#[test]
fn a_choice_that_does_not_determine_the_others_is_an_error_naming_one() {
    let bar = ByHeight {
        m: BAR.m,
        l: BAR.l,
        g: BAR.g,
    };
    // Hanging, `y` is at its lowest: it does not determine `θ`.
    let (q, v) = assembled(bar.l, 0.0, 0.0);
    match bar.linearize(0.0, &q, &v, &[0.0]) {
        Err(DynamicsError::SingularDependentCoordinates { coordinate, .. }) => {
            assert_eq!(coordinate, "theta")
        }
        other => panic!("expected SingularDependentCoordinates, got {other:?}"),
    }
    // Away from it, the same choice linearises, and agrees with `θ`'s on
    // the accelerations' derivative by the torque.
    let (q, v) = assembled(bar.l, 0.8, 0.5);
    let (_, by_height) = bar.linearize(0.0, &q, &v, &[0.0]).expect("linearisable");
    let (_, by_angle) = BAR.linearize(0.0, &q, &v, &[0.0]).expect("linearisable");
    assert_eq!(by_height.len(), by_angle.len());
    for (x, y) in by_height.iter().zip(&by_angle) {
        assert!((x[0] - y[0]).abs() < 1e-12 * (1.0 + y[0].abs()));
    }
}

/// The slider-crank's `A` applied to a perturbation along the manifold
/// (the crank angle or its rate) against central differences of the state's
/// rate `(v, v̇)` between assembled states, `v̇` from the runtime's
/// saddle-point solve: `A` is exact to the differences' accuracy.
#[test]
fn slider_crank_matches_differences_along_the_manifold() {
    let crank: SliderCrank = SLIDER_CRANK;
    let rate = |theta: f64, theta_dot: f64| -> [f64; 6] {
        let state = crank.assembled(theta, theta_dot);
        let (vdot, _) =
            constrained_accelerations(&crank, 0.0, &state.q, &state.v, &[0.4]).expect("solvable");
        let v = state.v;
        [v[0], v[1], v[2], vdot[0], vdot[1], vdot[2]]
    };
    let step = 1e-5;
    for (theta, theta_dot) in [(0.3, 5.0), (2.2, -7.0), (-1.4, 12.0)] {
        let state = crank.assembled(theta, theta_dot);
        let (a, b) = crank
            .linearize(0.0, &state.q, &state.v, &[0.4])
            .expect("linearisable");
        let difference = |by_angle: bool| -> [f64; 6] {
            let (plus, minus) = match by_angle {
                true => (rate(theta + step, theta_dot), rate(theta - step, theta_dot)),
                false => (rate(theta, theta_dot + step), rate(theta, theta_dot - step)),
            };
            std::array::from_fn(|i| (plus[i] - minus[i]) / (2.0 * step))
        };
        let (by_angle, by_rate) = (difference(true), difference(false));
        // The perturbation δθ = 1 moves q by E e_θ and v by F e_θ; its A
        // column is A's θ column (the dependent columns are zero).
        let scale = 1.0
            + by_angle
                .iter()
                .chain(&by_rate)
                .fold(0.0_f64, |m, x| m.max(x.abs()));
        for i in 0..6 {
            assert!(
                (a[i][0] - by_angle[i]).abs() < 1e-6 * scale,
                "row {i} by θ: {} against {}",
                a[i][0],
                by_angle[i]
            );
            assert!(
                (a[i][3] - by_rate[i]).abs() < 1e-6 * scale,
                "row {i} by θ̇: {} against {}",
                a[i][3],
                by_rate[i]
            );
        }
        // ∂v̇/∂T_motor against differences of the torque.
        let torque = |t: f64| {
            constrained_accelerations(&crank, 0.0, &state.q, &state.v, &[t])
                .expect("solvable")
                .0
        };
        let (plus, minus) = (torque(0.4 + step), torque(0.4 - step));
        for i in 0..3 {
            let numeric = (plus[i] - minus[i]) / (2.0 * step);
            assert!((b[3 + i][0] - numeric).abs() < 1e-6 * (1.0 + numeric.abs()));
            assert_eq!(b[i][0], 0.0);
        }
    }
}

/// The step of the central differences.
const STEP: f64 = 1e-6;

/// `exact` against `numeric`, entry by entry, to `1e-7` relative.
fn matches<const NV: usize, const N: usize>(
    what: &str,
    exact: &[[f64; N]; NV],
    numeric: &[[f64; N]; NV],
) {
    for (i, (exact, numeric)) in exact.iter().zip(numeric).enumerate() {
        assert_near_all(&format!("{what}[{i}]"), exact, numeric, 1e-7);
    }
}

/// The derivatives of the constrained accelerations, on the manifold and
/// off it (the accelerations are a function of the whole state), those by
/// `q` along `integrate_configuration` (`q + δ` for plain coordinates, the
/// tangent space of a spherical joint).
fn jacobian_matches_differences<S: MultibodySystem<NQ, 3, NU>, const NQ: usize, const NU: usize>(
    system: &S,
    jacobian: impl Fn(
        &[f64; NQ],
        &[f64; 3],
        &[f64; NU],
    ) -> ([[f64; 3]; 3], [[f64; 3]; 3], [[f64; NU]; 3]),
    states: &[([f64; NQ], [f64; 3])],
    u: &[f64; NU],
) {
    let vdot = |q: &[f64; NQ], v: &[f64; 3], u: &[f64; NU]| {
        dalembert::accelerations(system, 0.0, q, v, u).expect("solvable")
    };
    for (q, v) in states {
        let (by_q, by_v, by_u) = jacobian(q, v, u);
        let along = central_differences(&[0.0; 3], STEP, |delta| {
            vdot(&system.integrate_configuration(q, delta, 1.0), v, u)
        });
        matches("dv/dq", &by_q, &along);
        matches(
            "dv/dv",
            &by_v,
            &central_differences(v, STEP, |v| vdot(q, v, u)),
        );
        matches(
            "dv/du",
            &by_u,
            &central_differences(u, STEP, |u| vdot(q, v, u)),
        );
    }
}

#[test]
fn accelerations_jacobian_of_seed_example_3_matches_differences() {
    let (q, v) = assembled(BAR.l, 0.7, -1.3);
    let off = (
        [q[0] + 0.05, q[1] - 0.02, q[2]],
        [v[0] - 0.3, v[1], v[2] + 0.1],
    );
    jacobian_matches_differences(
        &BAR,
        |q, v, u| BAR.accelerations_jacobian(0.0, q, v, u).expect("regular"),
        &[(q, v), off],
        &[0.4],
    );
}

#[test]
fn accelerations_jacobian_of_a_nonholonomic_sled_matches_differences() {
    let sled = Sled {
        m: 2.5,
        I: 0.3,
        c: 0.4,
        g: 9.81,
    };
    let theta: f64 = 0.6;
    let along = [theta.cos(), theta.sin(), 0.0];
    let on = ([0.2, -0.1, theta], [1.5 * along[0], 1.5 * along[1], 0.8]);
    let off = ([0.2, -0.1, theta], [0.3, 1.1, -0.5]);
    jacobian_matches_differences(
        &sled,
        |q, v, u| sled.accelerations_jacobian(0.0, q, v, u).expect("regular"),
        &[on, off],
        &[0.7, -0.2],
    );
}

/// The sled's reduced `A` and `B` (states `x, y, θ, ẋ, θ̇`; the speed `ẏ`
/// dependent) against SymPy's own `KanesMethod.linearize(A_and_B=True)`
/// about the same state on the manifold, moving along its blade while
/// turning (`scripts/sled_linearize_reference.py` made the numbers; its
/// header says how).
#[test]
fn nonholonomic_sled_matches_sympys_linearizer() {
    let sled = Sled {
        m: 2.5,
        I: 0.3,
        c: 0.4,
        g: 9.81,
    };
    let (theta, speed, rate) = (0.6_f64, 1.5, 0.8);
    let q = [0.2, -0.1, theta];
    let v = [speed * theta.cos(), speed * theta.sin(), rate];
    let (a, b) = sled
        .linearize(0.0, &q, &v, &[0.7, -0.2])
        .expect("linearisable");
    let sympy_a: [[f64; 5]; 5] = [
        [0.0, 0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 1.8174424717684752, 0.6841368083416922, 0.0],
        [0.0, 0.0, 0.0, 0.0, 1.0],
        [
            0.0,
            0.0,
            -5.31133191457069,
            -0.5473094466733538,
            -0.31874891655035886,
        ],
        [
            0.0,
            0.0,
            6.740254991421808,
            -1.384718073728362,
            -2.142857142857143,
        ],
    ];
    let sympy_b: [[f64; 2]; 5] = [
        [0.0, 0.0],
        [0.0, 0.0],
        [0.0, 0.0],
        [0.3301342459638714, 0.0],
        [0.0, 1.4285714285714284],
    ];
    // x, y, θ, ẋ, θ̇ in the state (x, y, θ, ẋ, ẏ, θ̇).
    let independent = [0, 1, 2, 3, 5];
    for (r, &i) in independent.iter().enumerate() {
        let row: Vec<f64> = independent.iter().map(|&j| a[i][j]).collect();
        assert_near_all(&format!("A[{i}]"), &row, &sympy_a[r], 1e-12);
        assert_near_all(&format!("B[{i}]"), &b[i], &sympy_b[r], 1e-12);
        assert_eq!(a[i][4], 0.0, "the dependent speed's column");
    }
}

// Seed example 3 in body-axis speeds: the velocity of `G` along `B.x` and
// `B.y`, and the rate of `theta`.
seed_example_3!(
    BodyAxisBar,
    theta,
    speeds u1, u2, w {
        x: cos(theta) * u1 - sin(theta) * u2,
        y: sin(theta) * u1 + cos(theta) * u2,
        theta: w
    };
);

dalembert::dalembert! {
    /// A bob on a spherical joint at `O`, held to turn about `N.y` only by
    /// two rows on its quaternion: a compound pendulum, pushed about `B.y`.
    pub HeldBall {
        parameters m, d, g;
        inputs u;
        joint spherical ball { parent: N, child: B, at: O };
        body bob { mass: m, center: ball - d * B.z + 0.05 * B.x, frame: B, inertia: [0.02, 0.03, 0.04, 0.002, -0.001, 0.003] };
        gravity -g * N.z;
        torque u * B.y on B;
        constraint ball_qx == 0;
        constraint ball_qz == 0;
        outputs accelerations_jacobian, linearize(ball_wy);
    }
}

/// The reduced rows and columns `(i, j)` of `a` against `expected`, to
/// `1e-12` relative, and the other columns zero.
fn reduced_matrix_is<const N: usize>(
    a: &[[f64; N]; N],
    independent: [usize; 2],
    expected: [[f64; 2]; 2],
) {
    for (r, &i) in independent.iter().enumerate() {
        let row = independent.map(|j| a[i][j]);
        assert_near_all(&format!("A[{i}]"), &row, &expected[r], 1e-12);
    }
    for (i, row) in a.iter().enumerate() {
        for (j, x) in row.iter().enumerate() {
            if !independent.contains(&j) {
                assert_eq!(*x, 0.0, "A[{i}][{j}]: a dependent column");
            }
        }
    }
}

/// In body-axis speeds the bar's `(θ, w)` rows and columns are still the
/// one-coordinate pendulum's `[[0, 1], [−3g cos θ / 2l, 0]]` (`θ̇ = w`).
#[test]
fn seed_example_3_in_body_axis_speeds_is_the_one_coordinate_pendulum() {
    let bar = BodyAxisBar {
        m: 1.7,
        l: 1.1,
        g: 9.81,
    };
    for (theta, rate) in [(0.0, 0.0), (0.4_f64, -1.3), (2.0, 0.7)] {
        let (q, _) = assembled(bar.l, theta, rate);
        // G moves along B.x at (l/2) θ̇.
        let v = [bar.l / 2.0 * rate, 0.0, rate];
        let (a, _) = bar.linearize(0.0, &q, &v, &[0.3]).expect("linearisable");
        let stiffness = -3.0 * bar.g * theta.cos() / (2.0 * bar.l);
        reduced_matrix_is(&a, [2, 5], [[0.0, 1.0], [stiffness, 0.0]]);
    }
}

const HELD: HeldBall = HeldBall {
    m: 1.3,
    d: 0.6,
    g: 9.81,
};

/// The quaternion `(x, y, z, w)` turned by `theta` about `y`, and the speeds
/// of turning about `B.y` at `rate`.
fn held_state(theta: f64, rate: f64) -> ([f64; 4], [f64; 3]) {
    let (s, c) = (theta / 2.0).sin_cos();
    ([0.0, s, 0.0, c], [0.0, rate, 0.0])
}

/// Turning about `B.y` only, the bob is a compound pendulum: its centre at
/// `−d B.z + e B.x` (`B.x = (cos θ, 0, −sin θ)`, `B.z = (sin θ, 0, cos θ)`)
/// has the potential `m g z = −m g (d cos θ + e sin θ)`, so the stiffness
/// is `−m g (d cos θ + e sin θ) / I_O` with `I_O = I_yy + m (d² + e²)`
/// about `O`, and the torque turns it by `1 / I_O`.
#[test]
fn held_spherical_joint_is_a_compound_pendulum() {
    let HeldBall { m, d, g } = HELD;
    let e = 0.05;
    let inertia = 0.03 + m * (d * d + e * e);
    for (theta, rate) in [(0.0, 0.0), (0.5_f64, 1.1), (-2.4, -0.6)] {
        let (q, v) = held_state(theta, rate);
        let (a, b) = HELD.linearize(0.0, &q, &v, &[0.2]).expect("linearisable");
        let stiffness = -m * g * (d * theta.cos() + e * theta.sin()) / inertia;
        reduced_matrix_is(&a, [1, 4], [[0.0, 1.0], [stiffness, 0.0]]);
        assert_near_all("B[4]", &b[4], &[1.0 / inertia], 1e-12);
    }
}

#[test]
fn accelerations_jacobian_of_a_held_spherical_joint_matches_tangent_differences() {
    let (on_q, on_v) = held_state(0.7, 1.2);
    // Off the manifold: turned about x and z too, and turning about them.
    let off_q = HELD.integrate_configuration(&on_q, &[0.2, 0.0, -0.1], 1.0);
    jacobian_matches_differences(
        &HELD,
        |q, v, u| HELD.accelerations_jacobian(0.0, q, v, u).expect("regular"),
        &[(on_q, on_v), (off_q, [0.3, 1.2, -0.4])],
        &[0.3],
    );
}

/// With the blade along `N.y` the no-slip row is `ẋ = 0`: the speed of `y`
/// does not follow from those of `x` and `θ`.
#[test]
fn a_choice_of_speeds_that_does_not_determine_the_others_is_an_error_naming_one() {
    let sled = Sled {
        m: 2.5,
        I: 0.3,
        c: 0.4,
        g: 9.81,
    };
    let q = [0.2, -0.1, std::f64::consts::FRAC_PI_2];
    match sled.linearize(0.0, &q, &[0.0, 1.5, 0.8], &[0.0, 0.0]) {
        Err(DynamicsError::SingularDependentSpeeds { speed, .. }) => assert_eq!(speed, "dt(y)"),
        other => panic!("expected SingularDependentSpeeds, got {other:?}"),
    }
}

/// With `ẋ` as the independent speed of the bar pinned at one end, at rest
/// at `θ₀`: `θ̇ = ẋ / (l/2 cos θ₀)` and `ẍ = l/2 (cos θ θ̈ − sin θ θ̇²)` with
/// `θ̈ = −ω² sin θ`, `ω² = 3g / 2l`, so the exponents are
/// `±i ω √(cos 2θ₀ / cos θ₀)` (not those of `θ̇` independent,
/// `±i ω √(cos θ₀)`: off an equilibrium the choice matters), and four zeros.
#[test]
fn a_holonomic_system_takes_another_independent_speed() {
    let bar = BySlide {
        m: 1.7,
        l: 1.1,
        g: 9.81,
    };
    let omega = (3.0 * bar.g / (2.0 * bar.l)).sqrt();
    for theta in [0.0_f64, 0.3, -0.6] {
        let (q, v) = assembled(bar.l, theta, 0.0);
        let (a, _) = bar.linearize(0.0, &q, &v, &[0.0]).expect("ẋ determines θ̇");
        let eigenvalues = SMatrix::<f64, 6, 6>::from_fn(|i, j| a[i][j]).complex_eigenvalues();
        let mut imaginary: Vec<f64> = eigenvalues.iter().map(|z| z.im).collect();
        imaginary.sort_by(f64::total_cmp);
        let rate = omega * ((2.0 * theta).cos() / theta.cos()).sqrt();
        let expected = [-rate, 0.0, 0.0, 0.0, 0.0, rate];
        assert_near_all("exponents", &imaginary, &expected, 1e-12);
        assert!(
            eigenvalues.iter().all(|z| z.re.abs() < 1e-12 * omega),
            "{eigenvalues:?}"
        );
    }
}
