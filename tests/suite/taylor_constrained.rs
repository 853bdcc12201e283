//! The Taylor output of a constrained system (seed example 3, a pendulum
//! in dependent coordinates) and of speeds that are not the coordinates'
//! rates (a body on a ball joint, a quaternion; seed example 3 in
//! body-axis speeds, a `speeds` statement), against values found
//! apart from the code under test: the SymPy reference accelerations of
//! `tests/reference/seed_examples.json`, DOP853 at 1e-14, the period of
//! the pendulum from its elliptic integral, the energy, and the closed form
//! of free precession.

use std::f64::consts::PI;

use dalembert::constrained::constraint_drift;
use dalembert::integrate::{Adaptive, AdaptiveOptions, ExplicitPair, Integration, State, Taylor};
use dalembert::{Constrained, ConstrainedSystem, Stabilisation, TaylorSystem, Unconstrained};
use dalembert_codegen::testing::quaternion_rotation as rotation;
use dalembert_fixtures::precession::free_precession;
use dalembert_fixtures::reference::{array, assert_close, flat, reference};
use dalembert_generated::taylor_ball_top::TaylorBallTop;
use dalembert_generated::taylor_constrained_pendulum::TaylorConstrainedPendulum;

const K: usize = 24;

/// Seed example 3 with the parameters of the reference data, and its
/// reference states.
fn seed_3() -> (TaylorConstrainedPendulum, Vec<serde_json::Value>) {
    let system = reference("seed_examples.json")["systems"]["S3"].clone();
    let parameter = |name: &str| system["parameters"][name].as_f64().expect("parameter");
    let pendulum = TaylorConstrainedPendulum {
        m: parameter("m"),
        l: parameter("l"),
        g: parameter("g"),
    };
    let states = dalembert_fixtures::reference::states(&system).to_vec();
    (pendulum, states)
}

/// The state on the constraints with the bar at `theta` from the downward
/// vertical, turning at `theta_dot`.
fn assembled(pendulum: &TaylorConstrainedPendulum, theta: f64, theta_dot: f64) -> State<3, 3> {
    let (half, (s, c)) = (pendulum.l / 2.0, theta.sin_cos());
    State {
        t: 0.0,
        q: [half * s, -half * c, theta],
        v: [half * c * theta_dot, half * s * theta_dot, theta_dot],
    }
}

/// `Σₖ xₖ τᵏ`.
fn sum(x: &[f64; K], tau: f64) -> f64 {
    x.iter().rev().fold(0.0, |s, c| s * tau + c)
}

/// At the 20 reference states, order 1 of the coordinates is the speeds,
/// and order 1 of the speeds (order 2 of the coordinates, halved) is
/// SymPy's solution of the saddle-point system.
#[test]
fn seed_3_first_orders_are_the_reference_accelerations() {
    let (pendulum, states) = seed_3();
    for (i, s) in states.iter().enumerate() {
        let t = s["t"].as_f64().expect("t");
        let (q, qd, u) = (
            array::<3>(&s["q"]),
            array::<3>(&s["qd"]),
            array::<1>(&s["inputs"]),
        );
        let qdd = array::<3>(&s["qdd"]);
        let (series_q, series_v) = pendulum
            .taylor_coefficients::<8>(t, &q, &qd, &u, 7)
            .expect("expands");
        let order = |x: &[[f64; 8]; 3], k: usize| x.map(|c| c[k]);
        assert_close(&format!("state {i} q₁"), &order(&series_q, 1), &qd, 1e-15);
        assert_close(&format!("state {i} v₁"), &order(&series_v, 1), &qdd, 1e-12);
        let half = qdd.map(|a| a / 2.0);
        assert_close(&format!("state {i} q₂"), &order(&series_q, 2), &half, 1e-12);
    }
}

/// The series summed a little way from a state are DOP853's motion at
/// 1e-14 on the index-1 form (no stabilisation), with the motor torque
/// of the reference state held.
#[test]
fn seed_3_series_sum_to_dop853s_motion() {
    let (pendulum, _) = seed_3();
    let start = assembled(&pendulum, 0.7, -1.3);
    let torque = 0.4;
    let (q, v) = pendulum
        .taylor_coefficients::<K>(0.0, &start.q, &start.v, &[torque], K - 1)
        .expect("expands");
    let dynamics = Constrained::new(&pendulum, move |_, _, _| [torque], Stabilisation::None);
    for tau in [0.02, 0.05, 0.1] {
        let options = AdaptiveOptions::with_tolerance(1e-14);
        let end = Integration::new(
            &dynamics,
            start,
            tau,
            Adaptive {
                pair: ExplicitPair::Dop853,
                options,
            },
        )
        .run()
        .expect("integrates")
        .end;
        let summed: Vec<f64> = q.iter().chain(&v).map(|x| sum(x, tau)).collect();
        let integrated: Vec<f64> = end.q.iter().chain(&end.v).copied().collect();
        assert_close(&format!("τ = {tau}"), &summed, &integrated, 1e-12);
    }
}

/// The period `4 √(2l / 3g) K(sin(θ₀/2))` of a bar of length `l` pinned at
/// its end, swinging from rest at `θ₀` (`K` the complete elliptic integral
/// of the first kind, by the arithmetic-geometric mean).
fn bar_period(l: f64, g: f64, theta0: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (theta0 / 2.0).cos());
    // Quadratic convergence: six steps reach the rounding from 1 and 0.88.
    for _ in 0..6 {
        (a, b) = ((a + b) / 2.0, (a * b).sqrt());
    }
    let elliptic_k = PI / (2.0 * a);
    4.0 * (2.0 * l / (3.0 * g)).sqrt() * elliptic_k
}

/// Integrated by Taylor at 1e-16 from `start` (the bar at rest at `θ₀`,
/// `q[2]`), the bar is at `−θ₀` half a `period` later and back at the start
/// a period later, to 1e-12, on the constraints to rounding.
fn assert_swings_back<S, const NQ: usize, const NV: usize, const NU: usize, const NC: usize>(
    system: &S,
    start: State<NQ, NV>,
    period: f64,
) where
    S: TaylorSystem<NQ, NV, NU> + ConstrainedSystem<NQ, NV, NU, NC>,
{
    let dynamics = Constrained::without_inputs(system, Stabilisation::None);
    let options = Taylor::with_tolerance(1e-16);
    let after = |t: f64| {
        Integration::new(&dynamics, start, t, options)
            .run()
            .expect("integrates")
            .end
    };
    let halfway = after(period / 2.0);
    assert_close(
        "θ half a period later",
        &[halfway.q[2]],
        &[-start.q[2]],
        1e-12,
    );
    let end = after(period);
    let (reached, expected): (Vec<f64>, Vec<f64>) = end
        .q
        .iter()
        .chain(&end.v)
        .zip(start.q.iter().chain(&start.v))
        .unzip();
    assert_close("one period later", &reached, &expected, 1e-12);
    let drift = constraint_drift(system, &end);
    assert!(drift < 1e-14, "constraint residual {drift:e}");
}

/// Swinging from rest at 1 rad, half a period of the elliptic integral
/// later the bar is at −1 rad, one period later back at the start.
#[test]
fn seed_3_swings_with_the_period_of_its_elliptic_integral() {
    let (pendulum, _) = seed_3();
    let period = bar_period(pendulum.l, pendulum.g, 1.0);
    assert_swings_back(&pendulum, assembled(&pendulum, 1.0, 0.0), period);
}

dalembert::dalembert! {
    /// Seed example 3 in body-axis speeds (a `speeds` statement): the
    /// velocity of `G` along `B.x` and `B.y`, and the rate of `theta`.
    pub BodyAxisBar {
        parameters m, l, g;
        coordinates x, y, theta;
        speeds u1, u2, w {
            x: cos(theta) * u1 - sin(theta) * u2,
            y: sin(theta) * u1 + cos(theta) * u2,
            theta: w
        };
        frame B = N.rotate_z(theta);
        point G = O + x * N.x + y * N.y;
        body bar { mass: m, center: G, frame: B, inertia: [0, 0, m*l^2/12] };
        gravity -g * N.y;
        constraint x - l/2 * sin(theta) == 0;
        constraint y + l/2 * cos(theta) == 0;
        outputs taylor;
    }
}

/// The same bar in body-axis speeds, `q̇ = N(q) v` and the constraints
/// expanded together, swings with the same period.
#[test]
fn seed_3_in_body_axis_speeds_swings_with_the_same_period() {
    let bar = BodyAxisBar {
        m: 1.7,
        l: 1.1,
        g: 9.81,
    };
    let theta0 = 1.0f64;
    let half = bar.l / 2.0;
    // At rest: every speed zero.
    let start = State {
        t: 0.0,
        q: [half * theta0.sin(), -half * theta0.cos(), theta0],
        v: [0.0; 3],
    };
    assert_swings_back(&bar, start, bar_period(bar.l, bar.g, theta0));
}

/// From the work-precision chart's start (1 rad, 2 rad/s) over its ten
/// seconds and then a hundred, unstabilised: the constraints hold to
/// rounding (1.7e-14 at 10 s, some 30 ulps of the bar's half-length) and
/// the energy drifts as rounding accumulates (7.7e-14 at 10 s, 1.9e-12 at
/// 100 s, measured in release).
#[test]
fn seed_3_keeps_its_constraints_and_energy() {
    let (pendulum, _) = seed_3();
    let start = assembled(&pendulum, 1.0, 2.0);
    let dynamics = Constrained::without_inputs(&pendulum, Stabilisation::None);
    let options = Taylor::with_tolerance(1e-16);
    let energy = |s: &State<3, 3>| dalembert::energy(&pendulum, &s.q, &s.v);
    for (t_end, drift_bound, energy_bound) in [(10.0, 1e-13, 5e-13), (100.0, 1e-12, 1e-11)] {
        let end = Integration::new(&dynamics, start, t_end, options)
            .run()
            .expect("integrates")
            .end;
        let drift = constraint_drift(&pendulum, &end);
        assert!(drift < drift_bound, "residual {drift:e} at {t_end} s");
        let error = ((energy(&end) - energy(&start)) / energy(&start)).abs();
        assert!(
            error < energy_bound,
            "relative energy error {error:e} at {t_end} s"
        );
    }
}

/// The symmetric top on a ball joint and a start off every axis.
fn ball_top() -> (TaylorBallTop, State<4, 3>) {
    let top = TaylorBallTop {
        m: 1.0,
        I1: 2.0,
        I3: 3.0,
    };
    let (half, axis) = (0.35f64, [0.6, 0.0, 0.8]);
    let q = [
        axis[0] * half.sin(),
        axis[1] * half.sin(),
        axis[2] * half.sin(),
        half.cos(),
    ];
    let start = State {
        t: 0.0,
        q,
        v: [0.7, -0.4, 1.5],
    };
    (top, start)
}

/// The exact motion keeps `|q| = 1`, so every coefficient of `|q|²`
/// above the first vanishes: the series of `N(q) v` are those of a unit
/// quaternion to rounding, and summed a step ahead they stay unit to 1e-15.
#[test]
fn the_quaternion_series_stay_unit() {
    let (top, start) = ball_top();
    let (q, _) = top
        .taylor_coefficients::<K>(0.0, &start.q, &start.v, &[], K - 1)
        .expect("expands");
    for k in 1..K {
        let square: f64 = q
            .iter()
            .map(|x| (0..=k).map(|j| x[j] * x[k - j]).sum::<f64>())
            .sum();
        assert!(square.abs() < 1e-15, "order {k} of |q|²: {square:e}");
    }
    let summed = q.map(|x| sum(&x, 0.3));
    let norm = summed.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(
        (norm - 1.0).abs() < 1e-15,
        "|q(0.3)| − 1 = {:e}",
        norm - 1.0
    );
}

/// `I₁ = I₂ = 2`, `I₃ = 3` on a ball joint: the Taylor integrator at
/// 1e-15 follows free precession (`ω` and `R`) for ten seconds.
#[test]
fn free_precession_on_a_ball_joint_is_the_closed_form() {
    let (top, start) = ball_top();
    let dynamics = Unconstrained::without_inputs(&top);
    let options = Taylor::with_tolerance(1e-15);
    let t = 10.0;
    let end = Integration::new(&dynamics, start, t, options)
        .run()
        .expect("integrates")
        .end;
    let (omega, expected) = free_precession((top.I1, top.I3), &rotation(start.q), start.v, t);
    assert_close("ω(10)", &end.v, &omega, 1e-12);
    assert_close("R(10)", &flat(&rotation(end.q)), &flat(&expected), 1e-12);
}
