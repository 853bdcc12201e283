//! The errors of the simulation API: a driven pendulum whose input turns NaN
//! stops every integrator at its time, and the arguments an integration
//! cannot start from are refused with an error, never a panic.

use dalembert::DynamicsError;
use dalembert::integrate::{
    self, AdaptiveOptions, ExplicitPair, Failure, GaussLegendre, State, TaylorOptions,
    Unconstrained,
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
