//! Dense output against an oscillator's closed form, and events against
//! closed forms: a falling mass reaching the floor, the pendulum's period
//! from the complete elliptic integral (computed apart with mpmath), two zeros
//! in one step, a zero at the start and a touch.

use crate::free_body_and_stiff_chain_integration::distance;
use crate::integration_errors::PushedPendulum;

use std::ops::ControlFlow;

use dalembert::integrate::{
    self, AdaptiveOptions, Crossing, Event, ExplicitPair, State, Unconstrained,
};

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
    let solution = integrate::Integration::new(
        &dynamics,
        start,
        0.3 + h,
        integrate::Adaptive { pair, options },
    )
    .dense(|step| {
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
    .run()
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
    integrate::Integration::new(
        &dynamics,
        start,
        2.0,
        integrate::Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .dense(|step| {
        let h = step.end().t - step.start().t;
        // A tenth of a step past the end: the polynomial, still close.
        let t = step.end().t + 0.1 * h;
        let [x, _] = oscillator_at(t);
        assert!((step.state_at(t).q[0] - x).abs() < 1e-6, "at {t}");
        ControlFlow::Continue(())
    })
    .run()
    .unwrap();
}

pub(crate) const G: f64 = 9.81;

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
        let end = integrate::Integration::new(
            &dynamics,
            start,
            5.0,
            integrate::Adaptive { pair, options },
        )
        .event(floor, |_| {
            events += 1;
        })
        .run()
        .unwrap()
        .end;
        // mpmath: √(2 · 2 / 9.81) (30 digits, rounded to f64).
        let expected = 0.638_550_856_814_101;
        assert!((end.t - expected).abs() < 1e-12, "{pair:?}: {}", end.t);
        assert!(end.q[0].abs() < 1e-12 && events == 1, "{pair:?}: {end:?}");
        // With no final time, the integration runs until the event.
        let options = AdaptiveOptions::with_tolerance(1e-10);
        let open = integrate::Integration::new(
            &dynamics,
            start,
            f64::INFINITY,
            integrate::Adaptive { pair, options },
        )
        .event(floor, |_| {})
        .run();
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
        integrate::Integration::new(
            &dynamics,
            start,
            2.2 * period,
            integrate::Adaptive {
                pair: ExplicitPair::Dop853,
                options,
            },
        )
        .event(Event::record(vertical, crossing), |s| times.push(s.t))
        .run()
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
    integrate::Integration::new(&dynamics, start, 1.0, integrate::Adaptive::dop853(1e-8))
        .dense(|step| {
            steps.push((step.start().t, step.end().t));
            ControlFlow::Continue(())
        })
        .run()
        .unwrap();
    let (t1, t2) = ((2.0 / G).sqrt(), (2.0 * 1.2 / G).sqrt());
    assert!(
        steps.iter().any(|&(a, b)| a < t1 && t2 < b),
        "no step holds both zeros: {steps:?}"
    );
    integrate::Integration::new(&dynamics, start, 1.0, integrate::Adaptive::dop853(1e-8))
        .event(Event::record(band, Crossing::Either), |s| times.push(s.t))
        .run()
        .unwrap();
    assert_eq!(times.len(), 2, "{times:?}");
    assert!(
        (times[0] - t1).abs() < 1e-12 && (times[1] - t2).abs() < 1e-12,
        "{times:?}"
    );
    // A stopping event ends at the first of the two.
    let end = integrate::Integration::new(&dynamics, start, 1.0, integrate::Adaptive::dop853(1e-8))
        .event(Event::stop_at(band, Crossing::Rising), |_| {})
        .run()
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
    let end = integrate::Integration::new(
        &dynamics,
        start,
        5.0,
        integrate::Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .event(Event::stop_at(floor, Crossing::Either), |_| {})
    .run()
    .unwrap()
    .end;
    assert!((end.t - 8.0 / G).abs() < 1e-12, "{end:?}");
    // The top, z = v² / 2g, touched from below: −(z − top)² ≤ 0 throughout.
    let top = 16.0 / (2.0 * G);
    let touch = move |_: f64, q: &[f64; 1], _: &[f64; 1]| -(q[0] - top).powi(2);
    let mut touches = 0;
    integrate::Integration::new(
        &dynamics,
        start,
        8.0 / G,
        integrate::Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .event(Event::record(touch, Crossing::Either), |_| touches += 1)
    .run()
    .unwrap();
    assert_eq!(touches, 0);
}
