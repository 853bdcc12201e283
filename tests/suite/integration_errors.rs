//! The errors of the simulation API: a driven pendulum whose input turns NaN
//! stops every integrator at its time, and the arguments an integration
//! cannot start from are refused with an error, never a panic.

use dalembert::DynamicsError;
use dalembert::integrate::{
    self, AdaptiveOptions, ExplicitPair, Failure, GaussLegendre, State, Taylor, Unconstrained,
};

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
        (
            "RK4",
            integrate::Integration::new(&dynamics, start, 1.0, integrate::Rk4 { steps: 100 })
                .observe(finite)
                .run(),
        ),
        (
            "Gauss 4",
            integrate::Integration::new(
                &dynamics,
                start,
                1.0,
                integrate::Gauss {
                    rule: GaussLegendre::Order4,
                    steps: 100,
                },
            )
            .observe(finite)
            .run(),
        ),
        (
            "SDIRK",
            integrate::Integration::new(&dynamics, start, 1.0, integrate::Sdirk { steps: 100 })
                .observe(finite)
                .run(),
        ),
        (
            "DOPRI5",
            integrate::Integration::new(
                &dynamics,
                start,
                1.0,
                integrate::Adaptive {
                    pair: ExplicitPair::DormandPrince54,
                    options,
                },
            )
            .observe(finite)
            .run(),
        ),
        (
            "DOP853",
            integrate::Integration::new(
                &dynamics,
                start,
                1.0,
                integrate::Adaptive {
                    pair: ExplicitPair::Dop853,
                    options,
                },
            )
            .observe(finite)
            .run(),
        ),
        (
            "Taylor",
            integrate::Integration::new(
                &dynamics,
                start,
                1.0,
                integrate::Taylor::with_tolerance(1e-12),
            )
            .observe(finite)
            .run(),
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
            outcome(
                integrate::Integration::new(&dynamics, start, t_end, integrate::Rk4 { steps })
                    .run(),
            ),
        ),
        (
            "Gauss 4",
            outcome(
                integrate::Integration::new(
                    &dynamics,
                    start,
                    t_end,
                    integrate::Gauss { rule: gauss, steps },
                )
                .run(),
            ),
        ),
        (
            "SDIRK",
            outcome(
                integrate::Integration::new(&dynamics, start, t_end, integrate::Sdirk { steps })
                    .run(),
            ),
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
    let taylor = Taylor::with_tolerance(tolerance);
    vec![
        (
            "DOP853",
            outcome(
                integrate::Integration::new(
                    &dynamics,
                    start,
                    t_end,
                    integrate::Adaptive { pair, options },
                )
                .run(),
            ),
        ),
        (
            "Taylor",
            outcome(integrate::Integration::new(&dynamics, start, t_end, taylor).run()),
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
        let step = integrate::Rk4::step(&dynamics, &start, h).map_err(|e| e.cause);
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
        integrate::Integration::new(&dynamics, start, 0.5, integrate::Rk4 { steps: 10 })
            .observe(unseen)
            .run(),
        integrate::Integration::new(
            &dynamics,
            start,
            0.5,
            integrate::Adaptive {
                pair: ExplicitPair::Dop853,
                options: good,
            },
        )
        .observe(unseen)
        .run(),
        integrate::Integration::new(
            &dynamics,
            start,
            0.5,
            integrate::Taylor::with_tolerance(1e-12),
        )
        .observe(unseen)
        .run(),
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
