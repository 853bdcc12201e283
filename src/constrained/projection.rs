//! Coordinate projection: a state that has drifted off the constraint
//! manifold is moved back onto it, positions by Gauss–Newton on `φ(t, q) = 0`
//! and speeds by the exact projection onto `ψ(t, q, q̇) = 0`, both along the
//! shortest path in the metric of the mass matrix; and the speeds of a
//! conservative system onto its energy level.

use nalgebra::SVector;

use super::multipliers::ConstraintMetric;
use super::{ConstraintSolver, RANK_TOLERANCE};
use crate::dynamics::{all_finite, pivot_names};
use crate::{ConstrainedSystem, DynamicsError, MultibodySystem, State};

/// `state` moved onto the constraint manifold at its time: first the
/// coordinates, until the largest holonomic residual `|φᵢ(t, q)|` is at most
/// `tolerance`, then the speeds, so that the velocity form `ψ(t, q, v)` of
/// every constraint vanishes. Solved by the default
/// [`ConstraintSolver::RankRevealing`], so redundant rows are welcome.
///
/// Both corrections are the smallest in the metric of the mass matrix `M` at
/// `state.q` (the kinetic-energy norm): the speeds change by
/// `Δv = −M⁻¹ Aᵀ (A M⁻¹ Aᵀ)⁻¹ ψ`, exact in one step because `ψ` is linear in
/// `v`, and every Gauss–Newton iteration moves the coordinates by
/// `q ⊕ (−Δ)`, `Δ = M⁻¹ Aᵀ (A M⁻¹ Aᵀ)⁻¹ φ`, with `A` re-evaluated at each iterate.
/// With [`ConstraintSolver::Sparse`], an iteration that leaves more than
/// half the residual before it (near a singular position, where its
/// multiplier iteration barely moves the rows whose gradients nearly
/// vanish) hands the remaining iterations to the rank-revealing solve.
/// Nonholonomic rows have `φ = 0`, so the coordinates move only along
/// directions that their rows of `A` leave unchanged; their speeds are
/// projected like the others. A state already within `tolerance` keeps its
/// coordinates exactly.
///
/// Errors: non-finite coordinates or speeds, equations or constraints; a
/// coordinate free to move without inertia at an iterate; and
/// [`ProjectionNotConverged`](DynamicsError::ProjectionNotConverged) if
/// `max_iterations` corrections leave `max |φᵢ| > tolerance` (a state too
/// far off the manifold, or a `tolerance` below rounding).
pub fn project_onto_constraints<
    S,
    const NQ: usize,
    const NV: usize,
    const NU: usize,
    const NC: usize,
>(
    system: &S,
    state: &State<NQ, NV>,
    tolerance: f64,
    max_iterations: usize,
) -> Result<State<NQ, NV>, DynamicsError>
where
    S: ConstrainedSystem<NQ, NV, NU, NC>,
{
    ConstraintSolver::default().project_onto_constraints(system, state, tolerance, max_iterations)
}

impl ConstraintSolver {
    /// [`project_onto_constraints`] by this solver
    /// ([`SchurComplement`](Self::SchurComplement) fails with
    /// [`DependentConstraints`](DynamicsError::DependentConstraints) at
    /// redundant rows).
    pub fn project_onto_constraints<
        S,
        const NQ: usize,
        const NV: usize,
        const NU: usize,
        const NC: usize,
    >(
        self,
        system: &S,
        state: &State<NQ, NV>,
        tolerance: f64,
        max_iterations: usize,
    ) -> Result<State<NQ, NV>, DynamicsError>
    where
        S: ConstrainedSystem<NQ, NV, NU, NC>,
    {
        let State { t, q, v } = *state;
        if !(t.is_finite() && all_finite(&q) && all_finite(&v)) {
            return Err(DynamicsError::NonFiniteState);
        }
        let mass = system.mass_matrix_at(t, &q);
        let names = pivot_names::<S, NQ, NV, NU>();
        let least_norm = |solver, q: &[f64; NQ], c: [f64; NC]| {
            let jacobian = system.constraint_jacobian_at(t, q);
            let rows = (&jacobian, &S::VANISHING_ROWS);
            ConstraintMetric::with(solver, RANK_TOLERANCE, &mass, &names, rows, |metric| {
                Ok(metric.least_norm(&SVector::from(c)).into())
            })
        };
        let q = project_coordinates(system, t, q, self, &least_norm, tolerance, max_iterations)?;
        let v = project_speeds(system, t, &q, v, self, &least_norm)?;
        Ok(State { t, q, v })
    }
}

/// The smallest correction `x` in the metric at `q` with `A(q) x = c`, by a
/// solver.
type LeastNorm<'a, const NQ: usize, const NV: usize, const NC: usize> =
    dyn Fn(ConstraintSolver, &[f64; NQ], [f64; NC]) -> Result<[f64; NV], DynamicsError> + 'a;

/// A Gauss–Newton iteration that leaves more than this fraction of the
/// residual before it has stalled: its solve does not reach the rows that
/// hold the residual (near a singular position, rows whose gradients
/// nearly vanish, which the sparse solver's multiplier iteration leaves as
/// they are).
const STALLED: f64 = 0.5;

/// Gauss–Newton on `φ(t, q) = 0` from `q`, each correction the smallest in
/// the metric at its iterate: by the projection's solver, and by the
/// rank-revealing one from the first iteration that stalls on.
fn project_coordinates<S, const NQ: usize, const NV: usize, const NU: usize, const NC: usize>(
    system: &S,
    t: f64,
    q: [f64; NQ],
    mut solver: ConstraintSolver,
    least_norm: &LeastNorm<'_, NQ, NV, NC>,
    tolerance: f64,
    max_iterations: usize,
) -> Result<[f64; NQ], DynamicsError>
where
    S: ConstrainedSystem<NQ, NV, NU, NC>,
{
    let mut q = q;
    let mut iterations = 0;
    let mut before = f64::INFINITY;
    loop {
        let residual = checked(system.constraint_residual(t, &q))?;
        let largest = largest_magnitude(&residual);
        if largest <= tolerance {
            return Ok(q);
        }
        if iterations == max_iterations {
            return Err(DynamicsError::ProjectionNotConverged {
                iterations,
                residual: largest,
            });
        }
        if largest > STALLED * before && solver == ConstraintSolver::Sparse {
            solver = ConstraintSolver::RankRevealing;
        }
        before = largest;
        let correction = least_norm(solver, &q, residual)?;
        q = system.integrate_configuration(&q, &correction, -1.0);
        iterations += 1;
    }
}

/// The speeds nearest to `v` in the metric at `q` with `ψ(t, q, v) = 0`,
/// by `solver`.
fn project_speeds<S, const NQ: usize, const NV: usize, const NU: usize, const NC: usize>(
    system: &S,
    t: f64,
    q: &[f64; NQ],
    v: [f64; NV],
    solver: ConstraintSolver,
    least_norm: &LeastNorm<'_, NQ, NV, NC>,
) -> Result<[f64; NV], DynamicsError>
where
    S: ConstrainedSystem<NQ, NV, NU, NC>,
{
    let velocity = checked(system.constraint_velocity(t, q, &v))?;
    let correction = least_norm(solver, q, velocity)?;
    Ok(std::array::from_fn(|i| v[i] - correction[i]))
}

/// `state` with its speeds scaled so that its energy `T + V` is `energy`:
/// the nearest such state in the metric of the mass matrix along the
/// speeds (the gradient of `T = ½ vᵀ M v` in that metric is `v` itself),
/// which keeps every velocity constraint `A v = 0` of a system whose
/// constraints do not depend on time. A state at rest, or whose potential
/// energy alone exceeds `energy`, has no such speeds and is returned as it
/// is (so is a non-finite one).
pub fn project_onto_energy_level<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    state: &State<NQ, NV>,
    energy: f64,
) -> State<NQ, NV>
where
    S: MultibodySystem<NQ, NV, NU>,
{
    let kinetic = system.kinetic_energy_at(state.t, &state.q, &state.v);
    let available = energy - system.potential_energy_at(state.t, &state.q);
    let scale = (available / kinetic).sqrt();
    if kinetic > 0.0 && scale.is_finite() {
        State {
            v: state.v.map(|v| v * scale),
            ..*state
        }
    } else {
        *state
    }
}

/// `values`, or an error if one of them is not finite.
pub(crate) fn checked<const NC: usize>(values: [f64; NC]) -> Result<[f64; NC], DynamicsError> {
    if all_finite(&values) {
        Ok(values)
    } else {
        Err(DynamicsError::NonFiniteConstraints)
    }
}

/// `max |vᵢ|`, `0` for no values.
pub(crate) fn largest_magnitude<const N: usize>(values: &[f64; N]) -> f64 {
    values.iter().fold(0.0, |m, v| m.max(v.abs()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constrained::test_systems::PointOnCircle;

    const PENDULUM: PointOnCircle<1> = PointOnCircle {
        m: 2.0,
        l: 0.5,
        g: 9.81,
    };

    fn off_circle() -> State<2, 2> {
        // Radius 0.55 at 0.7 rad from the vertical, moving partly outward.
        let (s, c) = 0.7f64.sin_cos();
        State {
            t: 1.5,
            q: [0.55 * s, -0.55 * c],
            v: [0.9, 0.4],
        }
    }

    #[test]
    fn projection_returns_to_the_circle_along_the_radius_and_kills_radial_speed() {
        let start = off_circle();
        let projected = project_onto_constraints(&PENDULUM, &start, 1e-14, 10).unwrap();
        let [x, y] = projected.q;
        assert!((x.hypot(y) - PENDULUM.l).abs() < 1e-14, "{projected:?}");
        // Isotropic mass: the nearest point is on the same ray.
        assert!((y.atan2(x) - start.q[1].atan2(start.q[0])).abs() < 1e-15);
        let [psi] = PENDULUM.constraint_velocity(projected.t, &projected.q, &projected.v);
        assert!(psi.abs() < 1e-15, "{psi}");
        // Only the radial part of the speed is removed.
        let tangent = [-y / PENDULUM.l, x / PENDULUM.l];
        let along = |v: [f64; 2]| v[0] * tangent[0] + v[1] * tangent[1];
        assert!((along(projected.v) - along(start.v)).abs() < 1e-15);
        assert_eq!(projected.t, start.t);
    }

    #[test]
    fn the_energy_level_is_reached_by_scaling_the_speeds_along_the_circle() {
        let PointOnCircle { m, l, g } = PENDULUM;
        // On the circle at 0.7 rad from the downward vertical, moving along it
        // at 0.8 m/s: the level of 3 J needs the speed √(2 (3 + m g l cos θ) / m).
        let (s, c) = 0.7f64.sin_cos();
        let on = State {
            t: 0.0,
            q: [l * s, -l * c],
            v: [0.8 * c, 0.8 * s],
        };
        let level = project_onto_energy_level(&PENDULUM, &on, 3.0);
        let speed = (2.0 * (3.0 + m * g * l * c) / m).sqrt();
        assert!((level.v[0] - speed * c).abs() < 1e-14, "{level:?}");
        assert!((level.v[1] - speed * s).abs() < 1e-14, "{level:?}");
        assert_eq!(level.q, on.q);
        let [psi] = PENDULUM.constraint_velocity(0.0, &level.q, &level.v);
        assert!(psi.abs() < 1e-15, "{psi}");
        // At rest, or below the potential energy, there is nothing to scale.
        let at_rest = State { v: [0.0; 2], ..on };
        assert_eq!(project_onto_energy_level(&PENDULUM, &at_rest, 3.0), at_rest);
        let too_low = project_onto_energy_level(&PENDULUM, &on, -m * g * l);
        assert_eq!(too_low, on);
    }

    #[test]
    fn a_state_on_the_manifold_keeps_its_coordinates() {
        let (s, c) = 0.7f64.sin_cos();
        let on = State {
            t: 0.0,
            q: [0.5 * s, -0.5 * c],
            v: [0.5 * c, 0.5 * s],
        };
        let projected = project_onto_constraints(&PENDULUM, &on, 1e-12, 0).unwrap();
        assert_eq!(projected.q, on.q);
        assert!((projected.v[0] - on.v[0]).abs() < 1e-16);
    }

    #[test]
    fn too_small_a_budget_is_an_error_with_the_residual_left() {
        let error = project_onto_constraints(&PENDULUM, &off_circle(), 1e-14, 1).unwrap_err();
        match error {
            DynamicsError::ProjectionNotConverged {
                iterations: 1,
                residual,
            } => assert!(residual > 1e-14 && residual < 1e-2, "{residual}"),
            other => panic!("expected non-convergence, got {other:?}"),
        }
        assert!(error.to_string().contains("after 1 iterations"), "{error}");
    }

    #[test]
    fn non_finite_state_is_an_error_and_redundant_rows_need_the_rank_revealing_solver() {
        let mut bad = off_circle();
        bad.v[1] = f64::INFINITY;
        let error = project_onto_constraints(&PENDULUM, &bad, 1e-12, 5);
        assert_eq!(error, Err(DynamicsError::NonFiniteState));
        let twice = PointOnCircle::<2> {
            m: PENDULUM.m,
            l: PENDULUM.l,
            g: PENDULUM.g,
        };
        let error = ConstraintSolver::SchurComplement.project_onto_constraints(
            &twice,
            &off_circle(),
            1e-12,
            5,
        );
        assert!(matches!(
            error,
            Err(DynamicsError::DependentConstraints { row: 1, .. })
        ));
        // The default solver projects redundant rows like a single one.
        let once = project_onto_constraints(&PENDULUM, &off_circle(), 1e-14, 10).unwrap();
        let twice = project_onto_constraints(&twice, &off_circle(), 1e-14, 10).unwrap();
        for i in 0..2 {
            assert!((once.q[i] - twice.q[i]).abs() < 1e-15);
            assert!((once.v[i] - twice.v[i]).abs() < 1e-14);
        }
    }
}
