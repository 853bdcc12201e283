//! How a constrained integration keeps the numerical solution on the
//! constraint manifold ([`Stabilisation`], applied by
//! [`Constrained`](crate::Constrained)), and how far it has drifted off.

use super::projection::largest_magnitude;
use crate::{ConstrainedSystem, State};

/// How a constrained integration keeps the numerical solution on the
/// constraint manifold.
///
/// Solving `A q̈ = b` enforces the constraints only at acceleration level, so
/// the truncation and rounding errors of every step accumulate in the
/// residual `φ` and in the velocity form `ψ` (the drift). Whatever the
/// stabilisation, every integration of [`Constrained`](crate::Constrained)
/// dynamics checks the drift after every step against its
/// [`DriftLimits`](super::DriftLimits) and stops beyond them. The
/// projections and the augmented Lagrangian method cross singular
/// positions on the branch they were on; [`None`](Self::None) and
/// [`Baumgarte`](Self::Baumgarte) stop there with an error, and refuse a
/// start off the constraints (the projections move it onto them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stabilisation {
    /// Integrate `A q̈ = b` as it is: the drift grows with time, slowly
    /// while the rows are independent, but exponentially along redundant
    /// rows, which nothing holds once the state is off the manifold: in a
    /// parallelogram with a third, redundant crank (`tests/suite/redundant_parallelogram.rs`)
    /// the middle crank leaves the others by `1e-9` rad in 4 s and by
    /// `1e-5` in 5.5 s. The integration stops with
    /// [`Failure::ConstraintDrift`](crate::integrate::Failure::ConstraintDrift)
    /// when the drift passes its [`DriftLimits`](super::DriftLimits) (at
    /// 5.2 s there, by RK4 at `h = 1e-3 s`); unwatched
    /// ([`DriftLimits::UNWATCHED`](super::DriftLimits::UNWATCHED)) it would
    /// go on until the rows contradict each other
    /// ([`InconsistentConstraints`](crate::DynamicsError::InconsistentConstraints)),
    /// or, by DOP853 at `1e-10`, end 29 % of the swing's energy off without
    /// an error. Integrate redundant mechanisms with
    /// [`Baumgarte`](Self::Baumgarte) or [`Projection`](Self::Projection).
    /// Nor does it cross singular positions: the speeds' drift that one
    /// crossing leaves meets the vanishing gradient of the next (unwatched,
    /// a parallelogram four-bar lying flat, RK4 at `h = 1e-4 s`: a jump of
    /// 12 % of its energy at the second crossing, onto another motion). So
    /// the integration stops with
    /// [`Failure::SingularPosition`](crate::integrate::Failure::SingularPosition),
    /// naming the rows, where they become barely independent
    /// ([`BARELY_INDEPENDENT`](super::BARELY_INDEPENDENT)); cross them with
    /// [`Projection`](Self::Projection).
    None,
    /// Baumgarte's `φ̈ + 2α φ̇ + β² φ = 0` (velocity level only for
    /// nonholonomic rows): the drift stays bounded at a level set by the step
    /// and the gains. See [`baumgarte_accelerations`](super::baumgarte_accelerations) for how to choose them.
    /// Not through singular positions: there the stabilising terms are
    /// divided by the vanishing gradient of a row, and the motion diverges
    /// (unwatched, the parallelogram four-bar of `tests/suite/loop_rows.rs`
    /// stops with
    /// [`NonFiniteEquations`](crate::DynamicsError::NonFiniteEquations)
    /// after its third flat position); watched, it stops with
    /// [`Failure::SingularPosition`](crate::integrate::Failure::SingularPosition)
    /// at the first, like [`None`](Self::None).
    Baumgarte {
        /// Damping rate `α` of the velocity error, in 1/s.
        alpha: f64,
        /// Natural frequency `β` of the position error, in 1/s.
        beta: f64,
    },
    /// After every step, project the state back onto the manifold with
    /// [`project_onto_constraints`](super::project_onto_constraints): `max |φᵢ| ≤ tolerance` and `ψ = 0` to
    /// rounding after each step.
    Projection {
        /// Largest holonomic residual `|φᵢ|` accepted.
        tolerance: f64,
        /// Gauss–Newton iterations allowed per step before it fails (one or
        /// two suffice after an ordinary step).
        max_iterations: usize,
    },
    /// [`Projection`](Self::Projection), then the speeds scaled so that
    /// the energy `T + V` is `energy` again
    /// ([`project_onto_energy_level`](super::project_onto_energy_level)):
    /// for conservative systems (no inputs, no dissipation, no force and no
    /// constraint depending on time), whose energy is a first integral
    /// that the other stabilisations let drift. Where a mechanism passes
    /// singular positions this is what keeps a long run accurate: each
    /// passage perturbs the state a little off the motion; a perturbation
    /// of the energy would change the speed, hence the phase, for the rest
    /// of the run, while with the energy held it stays a one-off shift
    /// (the IFToMM N-four-bar mechanism, `docs/iftomm.md`).
    EnergyProjection {
        /// Largest holonomic residual `|φᵢ|` accepted.
        tolerance: f64,
        /// Gauss–Newton iterations allowed per step before it fails.
        max_iterations: usize,
        /// The energy `T + V` to hold, that of the initial state
        /// ([`energy`](crate::energy)).
        energy: f64,
    },
}

/// The position-level drift of `state`: the largest holonomic residual
/// `max |φᵢ(t, q)|` (nonholonomic rows count as `0`).
pub fn constraint_drift<S, const NQ: usize, const NV: usize, const NU: usize, const NC: usize>(
    system: &S,
    state: &State<NQ, NV>,
) -> f64
where
    S: ConstrainedSystem<NQ, NV, NU, NC>,
{
    largest_magnitude(&system.constraint_residual(state.t, &state.q))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constrained::ConstraintSolver;
    use crate::constrained::test_systems::PointOnCircle;
    use crate::integrate::{Failure, Integration, Rk4};
    use crate::test_systems::Pendulum;
    use crate::{Constrained, DynamicsError, Unconstrained};

    const CIRCLE: PointOnCircle<1> = PointOnCircle {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };

    /// On the circle at `theta` from the downward vertical, at rest.
    fn at_rest(theta: f64) -> State<2, 2> {
        let (s, c) = theta.sin_cos();
        State {
            t: 0.0,
            q: [s, -c],
            v: [0.0; 2],
        }
    }

    /// The angle history of the circle pendulum over 2 s with `h = 1e-3`.
    fn angles(stabilisation: Stabilisation) -> (Vec<f64>, f64) {
        let mut angles = Vec::new();
        let mut drift: f64 = 0.0;
        let observe = |s: &State<2, 2>| {
            angles.push(s.q[0].atan2(-s.q[1]));
            drift = drift.max(constraint_drift(&CIRCLE, s));
        };
        let dynamics = Constrained::without_inputs(&CIRCLE, stabilisation);
        Integration::new(&dynamics, at_rest(1.0), 2.0, Rk4 { steps: 2000 })
            .observe(observe)
            .run()
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
            v: [0.0],
        };
        let dynamics = Unconstrained::without_inputs(&pendulum);
        Integration::new(&dynamics, start, 2.0, Rk4 { steps: 2000 })
            .observe(|s| reference.push(s.q[0]))
            .run()
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
            Stabilisation::EnergyProjection {
                tolerance: 1e-13,
                max_iterations: 5,
                energy: crate::energy(&CIRCLE, &at_rest(1.0).q, &[0.0; 2]),
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
    fn energy_projection_holds_the_energy_of_the_start() {
        let start = crate::energy(&CIRCLE, &at_rest(1.0).q, &[0.0; 2]);
        let energy_projection = Stabilisation::EnergyProjection {
            tolerance: 1e-13,
            max_iterations: 5,
            energy: start,
        };
        let mut worst: f64 = 0.0;
        let dynamics = Constrained::without_inputs(&CIRCLE, energy_projection);
        // Long steps (0.1 s), whose truncation errors the scaling removes.
        Integration::new(&dynamics, at_rest(1.0), 2.0, Rk4 { steps: 20 })
            .observe(|s| {
                worst = worst.max((crate::energy(&CIRCLE, &s.q, &s.v) - start).abs());
            })
            .run()
            .unwrap();
        assert!(worst < 1e-13, "{worst:e}");
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
        let dynamics = Constrained::without_inputs(&twice, Stabilisation::None)
            .with_solver(ConstraintSolver::SchurComplement);
        let error = Rk4::step(&dynamics, &start, 0.1).unwrap_err();
        assert_eq!((error.t, error.q), (3.0, start.q));
        assert!(matches!(
            error.cause,
            Failure::Dynamics(DynamicsError::DependentConstraints { row: 1, .. })
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
        let dynamics = Constrained::without_inputs(&CIRCLE, stingy);
        let error = Rk4::step(&dynamics, &start, 0.1).unwrap_err();
        assert_eq!(error.t, 0.1);
        assert!(matches!(
            error.cause,
            Failure::Dynamics(DynamicsError::ProjectionNotConverged { iterations: 0, .. })
        ));
    }
}
