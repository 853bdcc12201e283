//! `linearize` of systems with constraints, on the constraint manifold with
//! the independent coordinates the model names: seed example 3 with `θ`
//! independent against the closed form of the same pendulum in one
//! coordinate (its small oscillations `±i √(3g / 2l)` at the hanging
//! position), the slider-crank with the crank angle independent against
//! central differences of the constrained accelerations along the
//! manifold, and the error where the chosen coordinates do not determine
//! the others. And `accelerations_jacobian` of constrained systems (seed
//! example 3, a knife-edge sled with a nonholonomic row) against central
//! differences of `dalembert::accelerations`, on and off the manifold.

use dalembert::DynamicsError;
use dalembert::constrained::constrained_accelerations;
use dalembert_fixtures::differences::central_differences;
use dalembert_fixtures::reference::assert_near_all;
use dalembert_fixtures::slider_crank::{SLIDER_CRANK, SliderCrank};
use nalgebra::SMatrix;

/// Seed example 3 as `$name`, linearised with `$independent` independent.
macro_rules! seed_example_3 {
    ($name:ident, $independent:ident) => {
        dalembert::dalembert! {
            /// Seed example 3, linearised with one coordinate independent.
            pub $name {
                parameters m, l, g;
                coordinates x, y, theta;
                inputs M;
                frame B = N.rotate_z(theta);
                point G = O + x * N.x + y * N.y;
                body bar { mass: m, center: G, frame: B, inertia: [0, 0, m*l^2/12] };
                gravity -g * N.y;
                torque M * N.z on B;
                constraint x - l/2 * sin(theta) == 0;
                constraint y + l/2 * cos(theta) == 0;
                outputs linearize($independent), accelerations_jacobian;
            }
        }
    };
}

seed_example_3!(ByAngle, theta);
// `x` and `theta` follow from `y` except where `sin θ = 0`.
seed_example_3!(ByHeight, y);

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
        outputs accelerations_jacobian;
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
/// off it (the accelerations are a function of the whole state).
fn jacobian_matches_differences<S: dalembert::MultibodySystem<3, 3, NU>, const NU: usize>(
    system: &S,
    jacobian: impl Fn(
        &[f64; 3],
        &[f64; 3],
        &[f64; NU],
    ) -> ([[f64; 3]; 3], [[f64; 3]; 3], [[f64; NU]; 3]),
    states: &[([f64; 3], [f64; 3])],
    u: &[f64; NU],
) {
    let vdot = |q: &[f64; 3], v: &[f64; 3], u: &[f64; NU]| {
        dalembert::accelerations(system, 0.0, q, v, u).expect("solvable")
    };
    for (q, v) in states {
        let (by_q, by_v, by_u) = jacobian(q, v, u);
        matches(
            "dv/dq",
            &by_q,
            &central_differences(q, STEP, |q| vdot(q, v, u)),
        );
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
