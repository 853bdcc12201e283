//! The simulation API as a user meets it, on models written here in the
//! macro (none of the repository's fixtures): every integrator on a free
//! body in quaternions, a stiff spring-mass chain, a driven pendulum whose
//! input turns NaN, and the arguments an integration cannot start from;
//! dense output against an oscillator's closed form; events against closed
//! forms (a falling mass reaching the floor, the pendulum's period from the
//! complete elliptic integral, computed apart with mpmath); the Taylor
//! method on a heavy top and with an input. Expected values come from
//! closed forms or another method at a tight tolerance, never from the code
//! under test.

use std::ops::ControlFlow;

use dalembert::integrate::{
    self, AdaptiveOptions, Crossing, Event, ExplicitPair, Failure, GaussLegendre, State,
    TaylorOptions, Unconstrained,
};
use dalembert::{DynamicsError, energy};

dalembert::dalembert! {
    /// A brick floating freely, its attitude a unit quaternion.
    pub FreeBrick {
        parameters m, I1, I2, I3;
        joint free base { parent: N, child: B, at: O };
        body brick { mass: m, center: base, frame: B, inertia: [I1, I2, I3] };
        outputs taylor;
    }
}

dalembert::dalembert! {
    /// Three masses in a row on soft springs `k` from a wall, the first two
    /// tied by a stiff spring `K`.
    pub SpringChain {
        parameters m, k, K;
        coordinates x1, x2, x3;
        particle a { mass: m, at: O + x1 * N.x };
        particle b { mass: m, at: O + x2 * N.x };
        particle c { mass: m, at: O + x3 * N.x };
        potential k / 2 * x1^2 + K / 2 * (x2 - x1)^2 + k / 2 * (x3 - x2)^2;
    }
}

dalembert::dalembert! {
    /// A pendulum pushed sideways at its bob by a force `F`.
    pub PushedPendulum {
        parameters m, L, g;
        coordinates theta;
        inputs F;
        frame B = N.rotate_z(theta);
        point P = O - L * B.y;
        particle bob { mass: m, at: P };
        gravity -g * N.y;
        force F * N.x at P;
        outputs taylor;
    }
}

dalembert::dalembert! {
    /// A mass falling along `N.z`.
    pub Falling {
        parameters m, g;
        coordinates z;
        particle p { mass: m, at: O + z * N.z };
        gravity -g * N.z;
    }
}

dalembert::dalembert! {
    /// A mass on a spring.
    pub Oscillator {
        parameters m, k;
        coordinates x;
        particle p { mass: m, at: O + x * N.x };
        potential k / 2 * x^2;
    }
}

dalembert::dalembert! {
    /// A heavy top on a ball joint, its centre on its symmetry axis.
    pub HeavyTop {
        parameters m, a, I1, I3, g;
        joint spherical ball { parent: N, child: B, at: O };
        body top { mass: m, center: ball + a * B.z, frame: B, inertia: [I1, I1, I3] };
        gravity -g * N.z;
        outputs taylor;
    }
}

const BRICK: FreeBrick = FreeBrick {
    m: 2.0,
    I1: 1.0,
    I2: 2.0,
    I3: 3.0,
};

/// The brick thrown spinning near its intermediate axis, tilted.
fn brick_start() -> State<7, 6> {
    let (s, c) = 0.35f64.sin_cos();
    State {
        t: 0.0,
        q: [0.1, -0.2, 0.3, s * 0.6, s * 0.8, 0.0, c],
        v: [1.0, 0.5, -0.3, 0.01, 2.0, 0.02],
    }
}

/// DOP853 at `tolerance` from `start` to `t_end`: the reference runs.
fn dop853<D, const NQ: usize, const NV: usize>(
    dynamics: &D,
    start: State<NQ, NV>,
    t_end: f64,
    tolerance: f64,
) -> integrate::Solution<NQ, NV>
where
    D: integrate::Dynamics<NQ, NV>,
{
    let options = AdaptiveOptions::with_tolerance(tolerance);
    integrate::adaptive(
        dynamics,
        start,
        t_end,
        ExplicitPair::Dop853,
        options,
        |_| {},
    )
    .unwrap()
}

fn quaternion_norm(q: &[f64; 7]) -> f64 {
    q[3..].iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn distance<const NQ: usize, const NV: usize>(a: &State<NQ, NV>, b: &State<NQ, NV>) -> f64 {
    a.q.iter()
        .zip(&b.q)
        .chain(a.v.iter().zip(&b.v))
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn every_integrator_keeps_a_free_bodys_quaternion_unit_over_ten_thousand_steps() {
    let dynamics = Unconstrained::without_inputs(&BRICK);
    let start = brick_start();
    let steps = 10_000;
    let t_end = 20.0;
    let mut worst: f64 = 0.0;
    let mut unit = |s: &State<7, 6>| worst = worst.max((quaternion_norm(&s.q) - 1.0).abs());
    let reference = integrate::adaptive(
        &dynamics,
        start,
        t_end,
        ExplicitPair::Dop853,
        AdaptiveOptions::with_tolerance(1e-13),
        &mut unit,
    )
    .unwrap()
    .end;
    let rk4 = integrate::rk4(&dynamics, start, t_end, steps, &mut unit).unwrap();
    let gauss = integrate::gauss_legendre(
        &dynamics,
        start,
        t_end,
        steps,
        GaussLegendre::Order4,
        &mut unit,
    )
    .unwrap();
    let sdirk = integrate::sdirk(&dynamics, start, t_end, steps, &mut unit).unwrap();
    let dopri = integrate::adaptive(
        &dynamics,
        start,
        t_end,
        ExplicitPair::DormandPrince54,
        AdaptiveOptions::with_tolerance(1e-10),
        &mut unit,
    )
    .unwrap();
    let taylor = integrate::taylor(
        &dynamics,
        start,
        t_end,
        TaylorOptions::with_tolerance(1e-15),
        &mut unit,
    )
    .unwrap();
    assert!(worst < 4.0 * f64::EPSILON, "|q| off one by {worst:e}");
    // Each follows the tight DOP853 run: the centre moves on a line, the
    // attitude tumbles (h = 2 ms; SDIRK, third order, is the loosest).
    for (name, end, tolerance) in [
        ("RK4", rk4.end, 1e-8),
        ("Gauss 4", gauss.end, 1e-8),
        ("SDIRK", sdirk.end, 1e-3),
        ("DOPRI5", dopri.end, 1e-7),
        ("Taylor", taylor.end, 1e-10),
    ] {
        let error = distance(&end, &reference);
        assert!(error < tolerance, "{name}: {error:e}");
    }
    // No force: the centre moves on a straight line in N, at the velocity
    // the body-axis speeds give at the start.
    let velocity = rotated(&start.q, [start.v[0], start.v[1], start.v[2]]);
    for (i, speed) in velocity.iter().enumerate() {
        let line = start.q[i] + speed * t_end;
        assert!((reference.q[i] - line).abs() < 1e-10, "{reference:?}");
    }
}

/// `x` in the body's axes turned into N's by the attitude `q[3..]` of a
/// free joint, `(qx, qy, qz, qw)`: `x + 2w (u × x) + 2 u × (u × x)`.
fn rotated(q: &[f64; 7], x: [f64; 3]) -> [f64; 3] {
    let (u, w) = ([q[3], q[4], q[5]], q[6]);
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let ux = cross(u, x);
    let uux = cross(u, ux);
    std::array::from_fn(|i| x[i] + 2.0 * w * ux[i] + 2.0 * uux[i])
}

const CHAIN: SpringChain = SpringChain {
    m: 1.0,
    k: 1.0,
    K: 1e6,
};

fn chain_start() -> State<3, 3> {
    State {
        t: 0.0,
        q: [0.1, 0.1001, 0.3],
        v: [0.0, 0.0, 0.0],
    }
}

#[test]
fn a_stiff_spring_chain_collapses_explicit_steps_or_fails_with_an_error_never_a_panic() {
    let dynamics = Unconstrained::without_inputs(&CHAIN);
    let start = chain_start();
    let t_end = 1.0;
    // The fast mode, ω = √(2K/m) ≈ 1414 rad/s, bounds explicit steps.
    let tight = dop853(&dynamics, start, t_end, 1e-12);
    let loose = integrate::adaptive(
        &dynamics,
        start,
        t_end,
        ExplicitPair::DormandPrince54,
        AdaptiveOptions::with_tolerance(1e-3),
        |_| {},
    )
    .unwrap();
    // Even at 1e-3, stability alone keeps DOPRI5 below h ≈ 3.3 / ω.
    assert!(
        loose.statistics.accepted_steps > 300,
        "{:?}",
        loose.statistics
    );
    // RK4 beyond its stability limit 2.8 / ω ≈ 2e-3 s blows up into an
    // error naming where, never a NaN state returned as a success.
    let unstable = integrate::rk4(&dynamics, start, t_end, 200, |s| {
        assert!(s.q.iter().chain(&s.v).all(|x| x.is_finite()), "{s:?}");
    })
    .unwrap_err();
    assert!(matches!(unstable.cause, Failure::Dynamics(_)), "{unstable}");
    // Gauss 4 is A-stable, but its fixed-point stage iteration does not
    // converge at a step this long against the fast mode: an error.
    let gauss =
        integrate::gauss_legendre(&dynamics, start, t_end, 200, GaussLegendre::Order4, |_| {})
            .unwrap_err();
    assert!(
        matches!(gauss.cause, Failure::NotConverged { .. }),
        "{gauss}"
    );
    // SDIRK (L-stable) damps the fast mode and follows the slow masses.
    let sdirk = integrate::sdirk(&dynamics, start, t_end, 200, |_| {}).unwrap();
    assert!(
        (sdirk.end.q[2] - tight.end.q[2]).abs() < 1e-3,
        "{:?} vs {:?}",
        sdirk.end,
        tight.end
    );
}

#[test]
fn a_nan_input_stops_every_integrator_at_its_time() {
    let pendulum = PushedPendulum {
        m: 1.0,
        L: 1.0,
        g: 9.81,
    };
    // The push turns NaN at t = 0.5.
    let dynamics = Unconstrained::new(&pendulum, |t, _, _| [if t < 0.5 { 0.1 } else { f64::NAN }]);
    let start = State {
        t: 0.0,
        q: [0.2],
        v: [0.0],
    };
    let finite = |s: &State<1, 1>| assert!(s.q[0].is_finite() && s.v[0].is_finite(), "{s:?}");
    let options = AdaptiveOptions::with_tolerance(1e-9);
    let results = [
        ("RK4", integrate::rk4(&dynamics, start, 1.0, 100, finite)),
        (
            "Gauss 4",
            integrate::gauss_legendre(&dynamics, start, 1.0, 100, GaussLegendre::Order4, finite),
        ),
        (
            "SDIRK",
            integrate::sdirk(&dynamics, start, 1.0, 100, finite),
        ),
        (
            "DOPRI5",
            integrate::adaptive(
                &dynamics,
                start,
                1.0,
                ExplicitPair::DormandPrince54,
                options,
                finite,
            ),
        ),
        (
            "DOP853",
            integrate::adaptive(&dynamics, start, 1.0, ExplicitPair::Dop853, options, finite),
        ),
        (
            "Taylor",
            integrate::taylor(
                &dynamics,
                start,
                1.0,
                TaylorOptions::with_tolerance(1e-12),
                finite,
            ),
        ),
    ];
    for (name, result) in results {
        let error = result.expect_err(name);
        assert!(error.t >= 0.5 - 0.1 && error.t < 1.0, "{name}: {error}");
        assert!(
            matches!(
                error.cause,
                Failure::Dynamics(DynamicsError::NonFiniteState)
            ),
            "{name}: {error}"
        );
    }
}

/// What an integration of a pendulum ended with, method by method.
type Outcomes = Vec<(&'static str, Result<State<1, 1>, Failure>)>;

fn pendulum() -> PushedPendulum {
    PushedPendulum {
        m: 1.0,
        L: 1.0,
        g: 9.81,
    }
}

fn outcome(
    result: Result<integrate::Solution<1, 1>, integrate::IntegrationError<1>>,
) -> Result<State<1, 1>, Failure> {
    result.map(|s| s.end).map_err(|e| e.cause)
}

/// The fixed-step methods from `start` to `t_end` in `steps` steps.
fn fixed_step_outcomes(start: State<1, 1>, t_end: f64, steps: u64) -> Outcomes {
    let pendulum = pendulum();
    let dynamics = Unconstrained::new(&pendulum, |_, _, _| [0.0]);
    let gauss = GaussLegendre::Order4;
    vec![
        (
            "RK4",
            outcome(integrate::rk4(&dynamics, start, t_end, steps, |_| {})),
        ),
        (
            "Gauss 4",
            outcome(integrate::gauss_legendre(
                &dynamics,
                start,
                t_end,
                steps,
                gauss,
                |_| {},
            )),
        ),
        (
            "SDIRK",
            outcome(integrate::sdirk(&dynamics, start, t_end, steps, |_| {})),
        ),
    ]
}

/// DOP853 with `options` and Taylor at `tolerance`, from `start` to `t_end`.
fn variable_step_outcomes(
    start: State<1, 1>,
    t_end: f64,
    options: AdaptiveOptions,
    tolerance: f64,
) -> Outcomes {
    let pendulum = pendulum();
    let dynamics = Unconstrained::new(&pendulum, |_, _, _| [0.0]);
    let pair = ExplicitPair::Dop853;
    let taylor = TaylorOptions::with_tolerance(tolerance);
    vec![
        (
            "DOP853",
            outcome(integrate::adaptive(
                &dynamics,
                start,
                t_end,
                pair,
                options,
                |_| {},
            )),
        ),
        (
            "Taylor",
            outcome(integrate::taylor(&dynamics, start, t_end, taylor, |_| {})),
        ),
    ]
}

fn assert_refused(case: &str, outcomes: Outcomes) {
    for (name, result) in outcomes {
        assert!(
            matches!(result, Err(Failure::InvalidArgument { .. })),
            "{case}, {name}: {result:?}"
        );
    }
}

#[test]
fn arguments_an_integration_cannot_start_from_are_errors() {
    let start = State {
        t: 1.0,
        q: [0.2],
        v: [0.0],
    };
    let good = AdaptiveOptions::with_tolerance(1e-8);
    let nan_start = State {
        t: f64::NAN,
        ..start
    };
    for (case, start, t_end) in [
        ("t_end < t0", start, 0.5),
        ("t_end NaN", start, f64::NAN),
        ("t0 NaN", nan_start, 2.0),
    ] {
        assert_refused(case, fixed_step_outcomes(start, t_end, 10));
        assert_refused(case, variable_step_outcomes(start, t_end, good, 1e-12));
    }
    assert_refused(
        "t_end infinite",
        fixed_step_outcomes(start, f64::INFINITY, 10),
    );
    assert_refused("no steps", fixed_step_outcomes(start, 2.0, 0));
    for tolerance in [0.0, -1e-8, f64::NAN, f64::INFINITY] {
        let options = AdaptiveOptions::with_tolerance(tolerance);
        assert_refused(
            "tolerance",
            variable_step_outcomes(start, 2.0, options, tolerance),
        );
    }
    for h in [0.0, -0.1, f64::NAN] {
        let options = AdaptiveOptions {
            initial_step: Some(h),
            ..good
        };
        let dop853 = variable_step_outcomes(start, 2.0, options, 1e-12);
        assert_refused("first step", dop853.into_iter().take(1).collect());
        let pendulum = pendulum();
        let dynamics = Unconstrained::new(&pendulum, |_, _, _| [0.0]);
        let step = integrate::rk4_step(&dynamics, &start, h).map_err(|e| e.cause);
        assert!(
            matches!(step, Err(Failure::InvalidArgument { .. })),
            "{step:?}"
        );
    }
    // No time to cover is no error: the start is the end.
    let empty = fixed_step_outcomes(start, 1.0, 10);
    for (name, result) in empty
        .into_iter()
        .chain(variable_step_outcomes(start, 1.0, good, 1e-12))
    {
        assert_eq!(result, Ok(start), "{name}");
    }
    // A refused integration shows the observer nothing, and says why.
    let pendulum = pendulum();
    let dynamics = Unconstrained::new(&pendulum, |_, _, _| [0.0]);
    let unseen = |_: &State<1, 1>| panic!("a refused integration shows no state");
    let refused = [
        integrate::rk4(&dynamics, start, 0.5, 10, unseen),
        integrate::adaptive(&dynamics, start, 0.5, ExplicitPair::Dop853, good, unseen),
        integrate::taylor(
            &dynamics,
            start,
            0.5,
            TaylorOptions::with_tolerance(1e-12),
            unseen,
        ),
    ];
    for result in refused {
        let message = result.unwrap_err().to_string();
        assert!(
            message.starts_with(
                "cannot integrate: the final time is before the initial time at t = 1"
            ),
            "{message}"
        );
    }
}

const SPRING: Oscillator = Oscillator { m: 2.0, k: 8.0 };

/// The oscillator released from x = 1 at rest: x = cos 2t.
fn oscillator_at(t: f64) -> [f64; 2] {
    [(2.0 * t).cos(), -2.0 * (2.0 * t).sin()]
}

/// The largest error of `pair`'s dense output over one step of length `h`
/// from t = 0.3, at nine inner points, and the step's ends against the
/// states it reports.
fn one_step_dense_error(pair: ExplicitPair, h: f64) -> f64 {
    let dynamics = Unconstrained::without_inputs(&SPRING);
    let [x, v] = oscillator_at(0.3);
    let start = State {
        t: 0.3,
        q: [x],
        v: [v],
    };
    let options = AdaptiveOptions {
        initial_step: Some(h),
        ..AdaptiveOptions::with_tolerance(1e-2)
    };
    let mut worst: f64 = 0.0;
    let solution = integrate::adaptive_dense(&dynamics, start, 0.3 + h, pair, options, |step| {
        assert_eq!(step.state_at(step.start().t), *step.start());
        let end = step.state_at(step.end().t);
        assert!(distance(&end, step.end()) <= 4.0 * f64::EPSILON, "{end:?}");
        for i in 1..10 {
            let t = 0.3 + h * f64::from(i) / 10.0;
            let s = step.state_at(t);
            let [x, v] = oscillator_at(t);
            worst = worst.max((s.q[0] - x).abs()).max((s.v[0] - v).abs());
        }
        ControlFlow::Continue(())
    })
    .unwrap();
    assert_eq!(solution.statistics.accepted_steps, 1);
    worst
}

/// The slopes of the one-step dense output's error against the step
/// length, halved from 0.4 s twice, and the smallest error.
fn dense_error_slopes(pair: ExplicitPair) -> (Vec<f64>, f64) {
    let errors: Vec<f64> = [0.4, 0.2, 0.1]
        .into_iter()
        .map(|h| one_step_dense_error(pair, h))
        .collect();
    let slopes = errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
    (slopes, errors[2])
}

#[test]
fn the_dense_outputs_have_their_orders_between_steps() {
    // One step of each length: the interpolant of order p has a local
    // error going as h^(p+1): DOP853's seventh order, DOPRI5's fourth.
    for (pair, expected, smallest) in [
        (ExplicitPair::Dop853, 8.0, 1e-10),
        (ExplicitPair::DormandPrince54, 5.0, 1e-5),
    ] {
        let (slopes, error) = dense_error_slopes(pair);
        for slope in &slopes {
            assert!((slope - expected).abs() < 0.6, "{pair:?}: {slopes:?}");
        }
        assert!(error < smallest, "{pair:?}: {error:e}");
    }
}

#[test]
fn dense_output_outside_a_step_extrapolates_its_polynomial() {
    let dynamics = Unconstrained::without_inputs(&SPRING);
    let [x, v] = oscillator_at(0.0);
    let start = State {
        t: 0.0,
        q: [x],
        v: [v],
    };
    let options = AdaptiveOptions::with_tolerance(1e-12);
    integrate::adaptive_dense(
        &dynamics,
        start,
        2.0,
        ExplicitPair::Dop853,
        options,
        |step| {
            let h = step.end().t - step.start().t;
            // A tenth of a step past the end: the polynomial, still close.
            let t = step.end().t + 0.1 * h;
            let [x, _] = oscillator_at(t);
            assert!((step.state_at(t).q[0] - x).abs() < 1e-6, "at {t}");
            ControlFlow::Continue(())
        },
    )
    .unwrap();
}

const G: f64 = 9.81;

const MASS: Falling = Falling { m: 3.0, g: G };

/// The mass at height `z` moving up at `v` at t = 0.
fn falling_from(z: f64, v: f64) -> State<1, 1> {
    State {
        t: 0.0,
        q: [z],
        v: [v],
    }
}

#[test]
fn a_falling_mass_stops_at_the_floor_at_the_square_root_of_two_h_over_g_with_or_without_a_final_time()
 {
    let dynamics = Unconstrained::without_inputs(&MASS);
    let start = falling_from(2.0, 0.0);
    let floor = Event::stop_at(|_, q: &[f64; 1], _: &[f64; 1]| q[0], Crossing::Falling);
    for pair in [ExplicitPair::DormandPrince54, ExplicitPair::Dop853] {
        let options = AdaptiveOptions::with_tolerance(1e-10);
        let mut events = 0;
        let end =
            integrate::adaptive_with_events(&dynamics, start, 5.0, pair, options, floor, |_| {
                events += 1;
            })
            .unwrap()
            .end;
        // mpmath: √(2 · 2 / 9.81) (30 digits, rounded to f64).
        let expected = 0.638_550_856_814_101;
        assert!((end.t - expected).abs() < 1e-12, "{pair:?}: {}", end.t);
        assert!(end.q[0].abs() < 1e-12 && events == 1, "{pair:?}: {end:?}");
        // With no final time, the integration runs until the event.
        let options = AdaptiveOptions::with_tolerance(1e-10);
        let open = integrate::adaptive_with_events(
            &dynamics,
            start,
            f64::INFINITY,
            pair,
            options,
            floor,
            |_| {},
        );
        assert_eq!(open.unwrap().end.t, end.t, "{pair:?}");
    }
}

/// The pendulum of the period test: L = 1.3 m, released from 2.5 rad.
const LONG: PushedPendulum = PushedPendulum {
    m: 0.7,
    L: 1.3,
    g: G,
};

#[test]
fn a_large_swing_passes_the_vertical_once_a_period_of_its_elliptic_integral() {
    // mpmath: T = 4 √(L/g) K(sin²(θ₀/2)), θ₀ = 2.5, (30 digits, rounded to f64).
    let period = 3.757_940_950_269_470_3;
    let quarter = 0.939_485_237_567_367_6;
    let dynamics = Unconstrained::new(&LONG, |_, _, _| [0.0]);
    let start = State {
        t: 0.0,
        q: [2.5],
        v: [0.0],
    };
    let vertical = |_: f64, q: &[f64; 1], _: &[f64; 1]| q[0];
    let options = AdaptiveOptions::with_tolerance(1e-13);
    let passes = |crossing| {
        let mut times = Vec::new();
        integrate::adaptive_with_events(
            &dynamics,
            start,
            2.2 * period,
            ExplicitPair::Dop853,
            options,
            Event::record(vertical, crossing),
            |s| times.push(s.t),
        )
        .unwrap();
        times
    };
    let falling = passes(Crossing::Falling);
    let rising = passes(Crossing::Rising);
    let either = passes(Crossing::Either);
    let expect = |times: &[f64], first: f64| {
        assert_eq!(times.len(), 2, "{times:?}");
        for (k, t) in times.iter().enumerate() {
            let expected = first + k as f64 * period;
            assert!((t - expected).abs() < 1e-12, "{times:?} vs {expected}");
        }
    };
    expect(&falling, quarter);
    expect(&rising, 3.0 * quarter);
    assert_eq!(either.len(), 4, "{either:?}");
    assert!(either.windows(2).all(|w| w[0] < w[1]), "{either:?}");
}

#[test]
fn two_zeros_inside_one_step_are_both_recorded_in_order() {
    // The mass falls through the band 1.0 > z > 0.8: two zeros of
    // (z − 1)(z − 0.8) 43 ms apart, inside one step of a motion DOP853
    // integrates exactly (its steps grow as fast as the controller allows).
    let dynamics = Unconstrained::without_inputs(&MASS);
    let start = falling_from(2.0, 0.0);
    let band = |_: f64, q: &[f64; 1], _: &[f64; 1]| (q[0] - 1.0) * (q[0] - 0.8);
    let mut times = Vec::new();
    let mut steps = Vec::new();
    integrate::adaptive_dense(
        &dynamics,
        start,
        1.0,
        ExplicitPair::Dop853,
        AdaptiveOptions::with_tolerance(1e-8),
        |step| {
            steps.push((step.start().t, step.end().t));
            ControlFlow::Continue(())
        },
    )
    .unwrap();
    let (t1, t2) = ((2.0 / G).sqrt(), (2.0 * 1.2 / G).sqrt());
    assert!(
        steps.iter().any(|&(a, b)| a < t1 && t2 < b),
        "no step holds both zeros: {steps:?}"
    );
    integrate::adaptive_with_events(
        &dynamics,
        start,
        1.0,
        ExplicitPair::Dop853,
        AdaptiveOptions::with_tolerance(1e-8),
        Event::record(band, Crossing::Either),
        |s| times.push(s.t),
    )
    .unwrap();
    assert_eq!(times.len(), 2, "{times:?}");
    assert!(
        (times[0] - t1).abs() < 1e-12 && (times[1] - t2).abs() < 1e-12,
        "{times:?}"
    );
    // A stopping event ends at the first of the two.
    let end = integrate::adaptive_with_events(
        &dynamics,
        start,
        1.0,
        ExplicitPair::Dop853,
        AdaptiveOptions::with_tolerance(1e-8),
        Event::stop_at(band, Crossing::Rising),
        |_| {},
    )
    .unwrap()
    .end;
    assert!(
        (end.t - t2).abs() < 1e-12,
        "{end:?}: the rising zero is the second"
    );
}

#[test]
fn a_zero_at_the_start_or_a_touch_is_no_event_and_the_landing_is() {
    // Thrown up from the floor at 4 m/s: g = z is zero at t0, touches no
    // zero at the top, and crosses it falling at 2 v / g.
    let dynamics = Unconstrained::without_inputs(&MASS);
    let start = falling_from(0.0, 4.0);
    let options = AdaptiveOptions::with_tolerance(1e-10);
    let floor = |_: f64, q: &[f64; 1], _: &[f64; 1]| q[0];
    let end = integrate::adaptive_with_events(
        &dynamics,
        start,
        5.0,
        ExplicitPair::Dop853,
        options,
        Event::stop_at(floor, Crossing::Either),
        |_| {},
    )
    .unwrap()
    .end;
    assert!((end.t - 8.0 / G).abs() < 1e-12, "{end:?}");
    // The top, z = v² / 2g, touched from below: −(z − top)² ≤ 0 throughout.
    let top = 16.0 / (2.0 * G);
    let touch = move |_: f64, q: &[f64; 1], _: &[f64; 1]| -(q[0] - top).powi(2);
    let mut touches = 0;
    integrate::adaptive_with_events(
        &dynamics,
        start,
        8.0 / G,
        ExplicitPair::Dop853,
        options,
        Event::record(touch, Crossing::Either),
        |_| touches += 1,
    )
    .unwrap();
    assert_eq!(touches, 0);
}

const TOP: HeavyTop = HeavyTop {
    m: 1.5,
    a: 0.2,
    I1: 0.05,
    I3: 0.02,
    g: G,
};

fn top_start() -> State<4, 3> {
    let (s, c) = 0.15f64.sin_cos();
    State {
        t: 0.0,
        q: [s, 0.0, 0.0, c],
        v: [0.0, 0.1, 40.0],
    }
}

#[test]
fn taylor_follows_dop853_on_a_heavy_top_and_keeps_its_energy() {
    let dynamics = Unconstrained::without_inputs(&TOP);
    let start = top_start();
    let t_end = 5.0;
    let reference = dop853(&dynamics, start, t_end, 1e-14).end;
    let e0 = energy(&TOP, &start.q, &start.v);
    let mut drift: f64 = 0.0;
    let taylor = integrate::taylor(
        &dynamics,
        start,
        t_end,
        TaylorOptions::with_tolerance(1e-16),
        |s| drift = drift.max((energy(&TOP, &s.q, &s.v) - e0).abs() / e0.abs()),
    )
    .unwrap();
    let error = distance(&taylor.end, &reference);
    assert!(error < 1e-9, "{error:e}");
    assert!(drift < 1e-13, "{drift:e}");
}

#[test]
fn taylor_holds_a_constant_input_as_dop853_does() {
    let pendulum = PushedPendulum {
        m: 1.0,
        L: 0.8,
        g: G,
    };
    let dynamics = Unconstrained::new(&pendulum, |_, _, _| [0.7]);
    let start = State {
        t: 0.0,
        q: [0.3],
        v: [0.0],
    };
    let reference = dop853(&dynamics, start, 10.0, 1e-14).end;
    let taylor = integrate::taylor(
        &dynamics,
        start,
        10.0,
        TaylorOptions::with_tolerance(1e-15),
        |_| {},
    )
    .unwrap()
    .end;
    assert!(
        distance(&taylor, &reference) < 1e-11,
        "{taylor:?} vs {reference:?}"
    );
    assert_eq!(PushedPendulum::NU, 1);
}
