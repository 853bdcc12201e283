//! Dense output and events of the adaptive pairs against closed forms: an
//! oscillator's state between steps, the times a pendulum passes the
//! vertical (complete elliptic integral) and the time a thrown body reaches
//! a height (a parabola). The systems are written here by hand.

use std::f64::consts::PI;
use std::ops::ControlFlow;

use dalembert::MultibodySystem;
use dalembert::integrate::{
    Adaptive, AdaptiveOptions, Crossing, Event, ExplicitPair, Failure, Integration, State,
    Unconstrained,
};

/// One degree of freedom `x` with `m ẍ = force(x)`.
struct OneDof {
    mass: f64,
    force: fn(f64) -> f64,
}

impl MultibodySystem<1, 1, 0> for OneDof {
    const COORDINATES: [&'static str; 1] = ["x"];
    const SPEEDS: [&'static str; 1] = ["dt(x)"];
    const INPUTS: [&'static str; 0] = [];

    fn mass_matrix(&self, _q: &[f64; 1]) -> [[f64; 1]; 1] {
        [[self.mass]]
    }

    fn forcing(&self, _t: f64, q: &[f64; 1], _v: &[f64; 1], _u: &[f64; 0]) -> [f64; 1] {
        [(self.force)(q[0])]
    }

    fn kinetic_energy(&self, _q: &[f64; 1], v: &[f64; 1]) -> f64 {
        0.5 * self.mass * v[0] * v[0]
    }

    fn potential_energy(&self, _q: &[f64; 1]) -> f64 {
        0.0
    }

    fn coordinate_rates(&self, _q: &[f64; 1], v: &[f64; 1]) -> [f64; 1] {
        *v
    }

    fn integrate_configuration(&self, q: &[f64; 1], v: &[f64; 1], h: f64) -> [f64; 1] {
        [q[0] + h * v[0]]
    }
}

/// Gravity, m/s².
const G: f64 = 9.81;

/// A pendulum of unit length and mass: `θ̈ = −g sin θ`.
const PENDULUM: OneDof = OneDof {
    mass: 1.0,
    force: |theta| -G * theta.sin(),
};

/// A unit mass on a unit spring: `ẍ = −x`.
const OSCILLATOR: OneDof = OneDof {
    mass: 1.0,
    force: |x| -x,
};

/// A body of 2 kg under gravity: `ż̈ = −g`.
const THROWN: OneDof = OneDof {
    mass: 2.0,
    force: |_| -2.0 * G,
};

fn at_rest(x: f64) -> State<1, 1> {
    State {
        t: 0.0,
        q: [x],
        v: [0.0],
    }
}

/// The complete elliptic integral of the first kind `K(k)`, by the
/// arithmetic-geometric mean: `K = π / (2 AGM(1, √(1 − k²)))`.
fn complete_elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    // Quadratic convergence: a handful of iterations reach rounding.
    for _ in 0..10 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    PI / (2.0 * a)
}

/// The time a unit pendulum released at rest at `amplitude` takes to reach
/// the vertical: a quarter period, `K(sin(amplitude / 2)) / √g`.
fn quarter_period(amplitude: f64) -> f64 {
    complete_elliptic_k((amplitude / 2.0).sin()) / G.sqrt()
}

const PAIRS: [ExplicitPair; 2] = [ExplicitPair::DormandPrince54, ExplicitPair::Dop853];

#[test]
fn a_pendulum_stops_as_it_passes_the_vertical() {
    let dynamics = Unconstrained::without_inputs(&PENDULUM);
    for amplitude in [0.1, 1.0] {
        let expected = quarter_period(amplitude);
        for pair in PAIRS {
            let options = AdaptiveOptions::with_tolerance(1e-14);
            let vertical = Event::stop_at(|_, q: &[f64; 1], _: &[f64; 1]| q[0], Crossing::Falling);
            let mut seen = Vec::new();
            let solution = Integration::new(
                &dynamics,
                at_rest(amplitude),
                10.0,
                Adaptive { pair, options },
            )
            .event(vertical, |s| seen.push(*s))
            .run()
            .unwrap();
            let end = solution.end;
            assert_eq!(seen, [end], "{pair:?}: the event is the end");
            let error = (end.t - expected).abs();
            assert!(error < 1e-12, "{pair:?}, {amplitude}: {error:e} s off");
            assert!(end.q[0].abs() < 1e-12 && end.v[0] < 0.0, "{end:?}");
        }
    }
}

#[test]
fn every_pass_of_the_vertical_is_recorded() {
    let dynamics = Unconstrained::without_inputs(&PENDULUM);
    let amplitude = 0.5;
    let (quarter, options) = (
        quarter_period(amplitude),
        AdaptiveOptions::with_tolerance(1e-14),
    );
    let vertical = Event::record(|_, q: &[f64; 1], _: &[f64; 1]| q[0], Crossing::Either);
    let mut passes = Vec::new();
    let end = Integration::new(
        &dynamics,
        at_rest(amplitude),
        5.0,
        Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .event(vertical, |s| passes.push(s.t))
    .run()
    .unwrap()
    .end;
    assert_eq!(end.t, 5.0, "recording events does not stop");
    // Passes at T/4, 3T/4, 5T/4, …: every other quarter period.
    let expected: Vec<f64> = (0..)
        .map(|k| f64::from(2 * k + 1) * quarter)
        .take_while(|&t| t < 5.0)
        .collect();
    assert_eq!(passes.len(), expected.len(), "{passes:?}");
    for (t, exact) in passes.iter().zip(&expected) {
        assert!((t - exact).abs() < 1e-12, "{t} against {exact}");
    }
}

#[test]
fn a_thrown_body_stops_where_it_falls_through_a_height() {
    // z = z₀ + v₀ t − g t²/2 reaches h on the way down at
    // t = (v₀ + √(v₀² + 2 g (z₀ − h))) / g.
    let (z0, v0, height) = (10.0, 3.0, 2.0);
    let expected = (v0 + (v0 * v0 + 2.0 * G * (z0 - height)).sqrt()) / G;
    let dynamics = Unconstrained::without_inputs(&THROWN);
    let start = State {
        t: 0.0,
        q: [z0],
        v: [v0],
    };
    for pair in PAIRS {
        let options = AdaptiveOptions::with_tolerance(1e-10);
        let floor = Event::stop_at(
            move |_, q: &[f64; 1], _: &[f64; 1]| q[0] - height,
            Crossing::Falling,
        );
        let end = Integration::new(&dynamics, start, 100.0, Adaptive { pair, options })
            .event(floor, |_| {})
            .run()
            .unwrap()
            .end;
        assert!((end.t - expected).abs() < 1e-12, "{pair:?}: {}", end.t);
        assert!((end.q[0] - height).abs() < 1e-12, "{end:?}");
    }
}

#[test]
fn dense_output_follows_the_oscillator_between_steps() {
    let dynamics = Unconstrained::without_inputs(&OSCILLATOR);
    for (pair, tolerance, bound) in [
        (ExplicitPair::DormandPrince54, 1e-10, 1e-8),
        (ExplicitPair::Dop853, 1e-13, 1e-11),
    ] {
        let options = AdaptiveOptions::with_tolerance(tolerance);
        let (mut worst, mut steps) = (0.0f64, 0);
        Integration::new(&dynamics, at_rest(1.0), 20.0, Adaptive { pair, options })
            .dense(|step| {
                let (a, b) = (step.start().t, step.end().t);
                for k in 1..8 {
                    let t = a + (b - a) * f64::from(k) / 8.0;
                    let s = step.state_at(t);
                    assert_eq!(s.t, t);
                    worst = worst.max((s.q[0] - t.cos()).abs().max((s.v[0] + t.sin()).abs()));
                }
                steps += 1;
                ControlFlow::Continue(())
            })
            .run()
            .unwrap();
        assert!(steps > 10, "{pair:?}: {steps} steps");
        assert!(worst < bound, "{pair:?}: {worst:e}");
    }
}

#[test]
fn a_step_observer_may_end_the_integration() {
    let dynamics = Unconstrained::without_inputs(&OSCILLATOR);
    let options = AdaptiveOptions::with_tolerance(1e-10);
    let solution = Integration::new(
        &dynamics,
        at_rest(1.0),
        20.0,
        Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .dense(|step| {
        if step.end().t > 1.0 {
            ControlFlow::Break(step.state_at(1.0))
        } else {
            ControlFlow::Continue(())
        }
    })
    .run()
    .unwrap();
    assert_eq!(solution.end.t, 1.0);
    assert!((solution.end.q[0] - 1f64.cos()).abs() < 1e-9);
}

#[test]
fn a_non_finite_event_value_is_an_error_naming_its_time() {
    let dynamics = Unconstrained::without_inputs(&OSCILLATOR);
    let options = AdaptiveOptions::with_tolerance(1e-8);
    for bad in [f64::NAN, f64::INFINITY] {
        // Undefined from 1.3 s on: taken as "no event" before, an error now.
        let undefined_late = |t: f64, q: &[f64; 1], _: &[f64; 1]| {
            if t > 1.3 { bad } else { q[0] - 2.0 }
        };
        for pair in PAIRS {
            let mut events = 0;
            let event = Event::record(undefined_late, Crossing::Either);
            let error = Integration::new(&dynamics, at_rest(1.0), 5.0, Adaptive { pair, options })
                .event(event, |_| events += 1)
                .run()
                .unwrap_err();
            println!("{pair:?}: {error}");
            assert!(
                matches!(error.cause, Failure::NonFiniteEvent { value } if value.is_nan() == bad.is_nan()),
                "{error}"
            );
            // At the first sample past 1.3 s (an eighth of a step or less).
            assert!(error.t > 1.3 && error.t < 1.5, "{error}");
            assert!((error.q[0] - error.t.cos()).abs() < 1e-6, "{error}");
            assert!(
                error.to_string().contains("event function returned"),
                "{error}"
            );
            assert_eq!(events, 0);
        }
        // Undefined at the start: refused before any step.
        let event = Event::stop_at(|_: f64, _: &[f64; 1], _: &[f64; 1]| bad, Crossing::Either);
        let error = Integration::new(
            &dynamics,
            at_rest(1.0),
            5.0,
            Adaptive {
                pair: ExplicitPair::Dop853,
                options,
            },
        )
        .event(event, |_| {})
        .run()
        .unwrap_err();
        assert_eq!(error.t, 0.0);
        assert!(
            matches!(error.cause, Failure::NonFiniteEvent { .. }),
            "{error}"
        );
    }
}

#[test]
fn two_zeros_closer_than_an_eighth_of_a_step_are_both_found() {
    // The oscillator x = cos t passes x = 1/2 + δ and x = 1/2 a time
    // δ / sin(π/3) ≈ 1.2e-4 s apart, going down and again coming up: four
    // zeros of g = (x − 1/2)(x − 1/2 − δ) in one period, in two close pairs.
    let delta = 1e-4;
    let g = move |_: f64, q: &[f64; 1], _: &[f64; 1]| (q[0] - 0.5) * (q[0] - 0.5 - delta);
    let (near, far) = ((0.5 + delta).acos(), 0.5f64.acos());
    let expected = [near, far, 2.0 * PI - far, 2.0 * PI - near];
    let dynamics = Unconstrained::without_inputs(&OSCILLATOR);
    for pair in PAIRS {
        let options = AdaptiveOptions::with_tolerance(1e-9);
        // The steps that hold the pairs are far longer than eight times
        // their separation: the signs at the eight samples agree.
        let mut holding = Vec::new();
        Integration::new(
            &dynamics,
            at_rest(1.0),
            2.0 * PI,
            Adaptive { pair, options },
        )
        .dense(|step| {
            let (a, b) = (step.start().t, step.end().t);
            if expected.iter().any(|&t| a < t && t < b) {
                holding.push(b - a);
            }
            ControlFlow::Continue(())
        })
        .run()
        .unwrap();
        assert!(!holding.is_empty());
        for h in &holding {
            assert!(h / 8.0 > 10.0 * (far - near), "{pair:?}: step {h}");
        }
        // The times of the zeros crossing as `crossing` says, recorded.
        let zeros = |crossing| {
            let mut found = Vec::new();
            let event = Event::record(g, crossing);
            let start = at_rest(1.0);
            Integration::new(&dynamics, start, 2.0 * PI, Adaptive { pair, options })
                .event(event, |s| found.push(s.t))
                .run()
                .unwrap();
            found
        };
        let found = zeros(Crossing::Either);
        println!("{pair:?}: steps {holding:?}, zeros {found:?}");
        assert_eq!(found.len(), 4, "{pair:?}: {found:?}");
        for (t, want) in found.iter().zip(expected) {
            assert!((t - want).abs() < 1e-7, "{pair:?}: {t} vs {want}");
        }
        // Only the rising ones, and stopping at the first falling one.
        let rising = zeros(Crossing::Rising);
        assert_eq!(rising.len(), 2, "{rising:?}");
        assert!((rising[0] - far).abs() < 1e-7 && (rising[1] - expected[3]).abs() < 1e-7);
        let event = Event::stop_at(g, Crossing::Falling);
        let end = Integration::new(
            &dynamics,
            at_rest(1.0),
            2.0 * PI,
            Adaptive { pair, options },
        )
        .event(event, |_| {})
        .run()
        .unwrap()
        .end;
        assert!((end.t - near).abs() < 1e-7, "{end:?}");
    }
}
