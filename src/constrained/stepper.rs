//! Time integration of constrained systems with a choice of drift
//! stabilisation, mirroring the unconstrained [`rk4_step`](crate::rk4_step)
//! and [`simulate`](crate::simulate).

use super::projection::largest_magnitude;
use crate::integrate::{march, rk4_step_with};
use crate::{Constrained, ConstrainedSystem, Equations, IntegrationError, State};

/// How a constrained integration keeps the numerical solution on the
/// constraint manifold.
///
/// Solving `A q̈ = b` enforces the constraints only at acceleration level, so
/// the truncation and rounding errors of every step accumulate in the
/// residual `φ` and in the velocity form `ψ` (the drift).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stabilisation {
    /// Integrate `A q̈ = b` as it is: the drift grows with time.
    None,
    /// Baumgarte's `φ̈ + 2α φ̇ + β² φ = 0` (velocity level only for
    /// nonholonomic rows): the drift stays bounded at a level set by the step
    /// and the gains. See [`baumgarte_accelerations`](crate::baumgarte_accelerations) for how to choose them.
    Baumgarte {
        /// Damping rate `α` of the velocity error, in 1/s.
        alpha: f64,
        /// Natural frequency `β` of the position error, in 1/s.
        beta: f64,
    },
    /// After every step, project the state back onto the manifold with
    /// [`project_onto_constraints`](crate::project_onto_constraints): `max |φᵢ| ≤ tolerance` and `ψ = 0` to
    /// rounding after each step.
    Projection {
        /// Largest holonomic residual `|φᵢ|` accepted.
        tolerance: f64,
        /// Gauss–Newton iterations allowed per step before it fails (one or
        /// two suffice after an ordinary step).
        max_iterations: usize,
    },
}

/// One step of length `h` of the classical fourth-order Runge–Kutta method
/// for `M q̈ = f + Aᵀ λ`, `A q̈ = b`, stabilised by `stabilisation`.
///
/// `inputs` gives the inputs at every stage, as for
/// [`rk4_step`](crate::rk4_step). Allocates nothing. A failure names the time
/// and configuration of the failing stage, or of the end of the step if the
/// projection failed.
pub fn constrained_rk4_step<S, const NQ: usize, const NU: usize, const NC: usize>(
    system: &S,
    state: &State<NQ>,
    inputs: impl Fn(f64, &[f64; NQ], &[f64; NQ]) -> [f64; NU],
    h: f64,
    stabilisation: Stabilisation,
) -> Result<State<NQ>, IntegrationError<NQ>>
where
    S: ConstrainedSystem<NQ, NU, NC>,
{
    let equations = Constrained::new(system, inputs, stabilisation);
    let next = rk4_step_with(state, h, |t, q, qd| equations.accelerations(t, q, qd))?;
    equations.settle(&next).map_err(|cause| IntegrationError {
        t: next.t,
        q: next.q,
        cause,
    })
}

/// Integrates `steps` fixed steps of length `h` with
/// [`constrained_rk4_step`], from `initial`, and returns the final state.
///
/// `observer` sees the initial state (as given: project it first with
/// [`project_onto_constraints`](crate::project_onto_constraints) if it is off the manifold) and then the state
/// after every step. Stops at the first step that fails.
pub fn simulate_constrained<S, const NQ: usize, const NU: usize, const NC: usize>(
    system: &S,
    initial: State<NQ>,
    inputs: impl Fn(f64, &[f64; NQ], &[f64; NQ]) -> [f64; NU],
    h: f64,
    steps: usize,
    stabilisation: Stabilisation,
    observer: impl FnMut(&State<NQ>),
) -> Result<State<NQ>, IntegrationError<NQ>>
where
    S: ConstrainedSystem<NQ, NU, NC>,
{
    let step = |state: &State<NQ>| constrained_rk4_step(system, state, &inputs, h, stabilisation);
    march(initial, steps as u64, step, observer)
}

/// The position-level drift of `state`: the largest holonomic residual
/// `max |φᵢ(t, q)|` (nonholonomic rows count as `0`).
pub fn constraint_drift<S, const NQ: usize, const NU: usize, const NC: usize>(
    system: &S,
    state: &State<NQ>,
) -> f64
where
    S: ConstrainedSystem<NQ, NU, NC>,
{
    largest_magnitude(&system.constraint_residual(state.t, &state.q))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constrained::test_systems::PointOnCircle;
    use crate::test_systems::Pendulum;
    use crate::{DynamicsError, simulate};

    const CIRCLE: PointOnCircle<1> = PointOnCircle {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };

    /// On the circle at `theta` from the downward vertical, at rest.
    fn at_rest(theta: f64) -> State<2> {
        let (s, c) = theta.sin_cos();
        State {
            t: 0.0,
            q: [s, -c],
            qd: [0.0; 2],
        }
    }

    /// The angle history of the circle pendulum over 2 s with `h = 1e-3`.
    fn angles(stabilisation: Stabilisation) -> (Vec<f64>, f64) {
        let mut angles = Vec::new();
        let mut drift: f64 = 0.0;
        let observe = |s: &State<2>| {
            angles.push(s.q[0].atan2(-s.q[1]));
            drift = drift.max(constraint_drift(&CIRCLE, s));
        };
        simulate_constrained(
            &CIRCLE,
            at_rest(1.0),
            |_, _, _| [],
            1e-3,
            2000,
            stabilisation,
            observe,
        )
        .unwrap();
        (angles, drift)
    }

    #[test]
    fn every_stabilisation_follows_the_minimal_coordinate_pendulum() {
        let pendulum = Pendulum {
            m: CIRCLE.m,
            l: CIRCLE.l,
            g: CIRCLE.g,
        };
        let mut reference = Vec::new();
        let start = State {
            t: 0.0,
            q: [1.0],
            qd: [0.0],
        };
        simulate(
            &pendulum,
            start,
            |_, _, _| [],
            1e-3,
            2000,
            |s| reference.push(s.q[0]),
        )
        .unwrap();
        let modes = [
            Stabilisation::None,
            Stabilisation::Baumgarte {
                alpha: 20.0,
                beta: 20.0,
            },
            Stabilisation::Projection {
                tolerance: 1e-13,
                max_iterations: 5,
            },
        ];
        for mode in modes {
            let (angles, drift) = angles(mode);
            let deviation = angles
                .iter()
                .zip(&reference)
                .fold(0.0f64, |m, (a, r)| m.max((a - r).abs()));
            assert!(deviation < 1e-9, "{mode:?}: max |Δθ| = {deviation:e}");
            assert!(drift < 1e-9, "{mode:?}: drift {drift:e}");
        }
    }

    #[test]
    fn projection_keeps_the_drift_within_its_tolerance() {
        let (_, drift) = angles(Stabilisation::Projection {
            tolerance: 1e-13,
            max_iterations: 5,
        });
        assert!(drift <= 1e-13, "{drift:e}");
    }

    #[test]
    fn a_failing_step_names_the_stage_time_and_the_dependent_row() {
        let twice = PointOnCircle::<2> {
            m: 1.0,
            l: 1.0,
            g: 9.81,
        };
        let start = State {
            t: 3.0,
            ..at_rest(0.5)
        };
        let error = constrained_rk4_step(&twice, &start, |_, _, _| [], 0.1, Stabilisation::None)
            .unwrap_err();
        assert_eq!((error.t, error.q), (3.0, start.q));
        assert!(matches!(
            error.cause,
            DynamicsError::DependentConstraints { row: 1, .. }
        ));
        assert!(error.to_string().contains("at t = 3 s"), "{error}");
    }

    #[test]
    fn a_failing_projection_names_the_end_of_the_step() {
        let start = at_rest(1.0);
        let stingy = Stabilisation::Projection {
            tolerance: 0.0,
            max_iterations: 0,
        };
        let error = constrained_rk4_step(&CIRCLE, &start, |_, _, _| [], 0.1, stingy).unwrap_err();
        assert_eq!(error.t, 0.1);
        assert!(matches!(
            error.cause,
            DynamicsError::ProjectionNotConverged { iterations: 0, .. }
        ));
    }
}
