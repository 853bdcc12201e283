//! The index-3 augmented Lagrangian formulation with mass-orthogonal
//! projections (Bayo and Ledesma, Nonlinear Dynamics 9, 1996): the method of
//! the reference solutions of the IFToMM multibody benchmarks.
//!
//! Each step of the trapezoidal rule solves the equations of motion at the
//! end of the step together with the constraints at position level,
//! `M v̇ + Aᵀ (λ* + α φ) = f` with `λ* ← λ* + α φ` after every Newton
//! iteration, for the displacement `d` of the step (`q₁ = q₀ ⊕ d`,
//! `v₁ = 2d/h − v₀`, `v̇₁ = 4(d − h v₀)/h² − v̇₀`). The Newton matrix
//! `M + (h²/4) α AᵀA` is positive definite whenever the mechanism's motion is
//! determined, whatever the rank of `A` and even where `M` is singular, so
//! redundant constraints and singular positions need nothing special. The
//! speeds and accelerations are then projected onto the velocity and
//! acceleration constraints in the metric of the mass matrix.

use nalgebra::{SMatrix, SVector};

use super::arguments::fixed_steps_to_take;
use super::integration::{Method, sealed};
use super::{Constrained, Failure, InputLaw, IntegrationError, Solution, State, Statistics};
use crate::constrained::checked as finite;
use crate::dynamics::{factor_mass_matrix, pivot_names};
use crate::{ConstrainedSystem, DynamicsError};

/// The relative precision of the velocity form `ψ` that the method's
/// projection holds near singular positions, the floor of the velocity
/// limit its drift is watched against: `1e-3`. The projection
/// `(M + (h²/4) α AᵀA) v = …` holds `ψ` only as far as the penalty
/// outweighs `M` along the vanishing singular value of `A`: `1.2e-5` in
/// the IFToMM A02 mechanism (two four-bars, `h = 1e-3 s`) after 13 s of
/// crossings, while its positions hold `φ` to the tolerance.
const VELOCITY_PRECISION: f64 = 1e-3;

/// The settings of the [`AugmentedLagrangian`] method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AugmentedLagrangianSettings {
    /// The penalty factor `α` (force per unit of constraint residual per
    /// unit of Jacobian row). It needs to be large against the mass matrix
    /// over `h²/4`, more so near singular positions, where the multipliers
    /// along the rows that become dependent converge at a rate of about
    /// `1 − 1/(1 + α h² σ²/4m)` per iteration (`σ` the vanishing singular
    /// value of `A`); not so large that `(h²/4) α AᵀA` swamps `M` in floating
    /// point (`α h²/4 ≲ 1e8 m`). Changing the step, keep `α h²` about
    /// constant ([`for_step`](Self::for_step)): the default `1e10` suits
    /// `h ≈ 1e-3 s` with unit masses.
    pub penalty: f64,
    /// A step's Newton iteration has converged when its largest correction
    /// of the displacement and its largest holonomic residual `|φᵢ|` are
    /// both at most this.
    pub tolerance: f64,
    /// Newton iterations allowed per step before the integration stops with
    /// [`Failure::NotConverged`].
    pub max_iterations: usize,
}

impl AugmentedLagrangianSettings {
    /// The default settings with the penalty raised for steps below
    /// `1e-3 s`: `α = max(1e10, 1e4 / h²)` (in SI units, for masses about
    /// 1 kg), which keeps the penalty's weight `α h²/4` in the Newton matrix
    /// at 2500 or more. (Lowering `α` for larger steps makes the iteration
    /// stall at singular positions: the A02 mechanism fails at `h = 4e-3 s`
    /// with `α = 6.25e8`.)
    pub fn for_step(h: f64) -> Self {
        let default = Self::default();
        Self {
            penalty: default.penalty.max(1e4 / (h * h)),
            ..default
        }
    }
}

impl Default for AugmentedLagrangianSettings {
    /// `α = 1e10`, tolerance `1e-8`, 50 iterations: what the N-four-bar
    /// mechanism (A02) needs to cross its singular positions with unit
    /// masses and steps about `1e-3 s`.
    fn default() -> Self {
        Self {
            penalty: 1e10,
            tolerance: 1e-8,
            max_iterations: 50,
        }
    }
}

/// The index-3 augmented Lagrangian formulation with mass-orthogonal
/// projections (the trapezoidal rule; second order) in `steps` equal steps
/// to the final time (exactly there): closed loops with redundant
/// constraints or singular positions at a fixed step, the formulation of
/// the IFToMM benchmarks' reference solutions. It integrates
/// [`Constrained`] dynamics only; the statistics' `rhs_evaluations` count
/// the evaluations of `M`, `f` and `A`, one per Newton iteration and one
/// per projection.
///
/// It takes the same [`Constrained`] dynamics as the Runge–Kutta methods;
/// their [`Stabilisation`](crate::Stabilisation) is not used (the method
/// keeps `φ`, `ψ` and `A v̇ − b` at the level of its tolerance and penalty
/// by itself), their [`ConstraintSolver`](crate::constrained::ConstraintSolver)
/// only for the initial accelerations. Holonomic constraints are enforced
/// at position, velocity and acceleration level; nonholonomic rows (with
/// `φ = 0`) by the projections only. The Newton matrix neglects the
/// derivatives of the forcing and of `M` and `A` with respect to the
/// configuration (exact for constant loads such as gravity at the
/// solution; a quasi-Newton iteration otherwise, which converges for steps
/// small against the stiffness of the loads).
///
/// Errors: the initial accelerations cannot be computed, the Newton matrix
/// is not positive definite (a coordinate free to move without inertia), a
/// non-finite value, or a step that does not converge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AugmentedLagrangian {
    /// The number of equal steps to the final time.
    pub steps: u64,
    /// The penalty, tolerance and iterations of each step.
    pub settings: AugmentedLagrangianSettings,
}

impl AugmentedLagrangian {
    /// `steps` equal steps with the default settings for steps of about
    /// `1e-3 s` ([`AugmentedLagrangianSettings::default`]).
    pub fn with_steps(steps: u64) -> Self {
        Self {
            steps,
            settings: AugmentedLagrangianSettings::default(),
        }
    }
}

impl sealed::Sealed for AugmentedLagrangian {}

impl<S, F, const NQ: usize, const NV: usize, const NU: usize, const NC: usize>
    Method<Constrained<'_, S, F, NU, NC>, NQ, NV> for AugmentedLagrangian
where
    S: ConstrainedSystem<NQ, NV, NU, NC>,
    F: InputLaw<NQ, NV, NU>,
{
    fn integrate(
        self,
        dynamics: &Constrained<'_, S, F, NU, NC>,
        initial: State<NQ, NV>,
        t_end: f64,
        observer: impl FnMut(&State<NQ, NV>),
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>> {
        augmented_lagrangian(dynamics, initial, t_end, self, observer)
    }
}

/// [`AugmentedLagrangian`]'s integration of `dynamics` from `initial` to
/// `t_end`, showing `observer` the initial state and every step's end.
fn augmented_lagrangian<S, F, const NQ: usize, const NV: usize, const NU: usize, const NC: usize>(
    dynamics: &Constrained<'_, S, F, NU, NC>,
    initial: State<NQ, NV>,
    t_end: f64,
    AugmentedLagrangian { steps, settings }: AugmentedLagrangian,
    mut observer: impl FnMut(&State<NQ, NV>),
) -> Result<Solution<NQ, NV>, IntegrationError<NQ>>
where
    S: ConstrainedSystem<NQ, NV, NU, NC>,
    F: InputLaw<NQ, NV, NU>,
{
    let steps = fixed_steps_to_take(&initial, t_end, steps)?;
    // The drift watched like a projection's (the method crosses singular
    // positions on its branch), its precision the floor of the limits.
    let limits = dynamics.drift_limits();
    let floor = [settings.tolerance, VELOCITY_PRECISION];
    let watch = |state: &State<NQ, NV>, last_good: &State<NQ, NV>| {
        limits
            .check(dynamics.system(), state, floor, true)
            .map_err(|cause| IntegrationError::at(last_good, cause))
    };
    watch(&initial, &initial)?;
    let system = dynamics.system();
    let u = dynamics.inputs(initial.t, &initial.q, &initial.v);
    let (vdot, lambda) = dynamics
        .solver()
        .accelerations(system, initial.t, &initial.q, &initial.v, &u)
        .map_err(|cause| IntegrationError::dynamics(initial.t, initial.q, cause))?;
    let mut stepper = Stepper {
        dynamics,
        settings,
        evaluations: 0,
    };
    let mut point = Point {
        state: initial,
        vdot: SVector::from(vdot),
        multipliers: -SVector::from(lambda),
    };
    observer(&initial);
    let span = t_end - initial.t;
    for k in 1..=steps {
        let t = if k == steps {
            t_end
        } else {
            initial.t + span * (k as f64 / steps as f64)
        };
        let next = stepper.step(&point, t)?;
        watch(&next.state, &point.state)?;
        point = next;
        observer(&point.state);
    }
    Ok(Solution {
        end: point.state,
        statistics: Statistics {
            rhs_evaluations: stepper.evaluations,
            accepted_steps: steps,
            rejected_steps: 0,
        },
    })
}

/// A point of the trajectory with what the next step starts from: the
/// accelerations and the multipliers `λ* = −λ` of `M v̇ + Aᵀ λ* = f`.
struct Point<const NQ: usize, const NV: usize, const NC: usize> {
    state: State<NQ, NV>,
    vdot: SVector<f64, NV>,
    multipliers: SVector<f64, NC>,
}

/// The dynamics, the settings and the work done so far.
struct Stepper<'d, 's, S, F, const NU: usize, const NC: usize> {
    dynamics: &'d Constrained<'s, S, F, NU, NC>,
    settings: AugmentedLagrangianSettings,
    evaluations: u64,
}

/// `M`, `A` and the factorised Newton matrix `M + (h²/4) α AᵀA` at a
/// configuration.
struct Linearisation<const NV: usize, const NC: usize> {
    mass: SMatrix<f64, NV, NV>,
    jacobian: SMatrix<f64, NC, NV>,
    newton: nalgebra::Cholesky<f64, nalgebra::Const<NV>>,
}

impl<S, F, const NU: usize, const NC: usize> Stepper<'_, '_, S, F, NU, NC> {
    /// One step from `start` to the time `t`.
    fn step<const NQ: usize, const NV: usize>(
        &mut self,
        start: &Point<NQ, NV, NC>,
        t: f64,
    ) -> Result<Point<NQ, NV, NC>, IntegrationError<NQ>>
    where
        S: ConstrainedSystem<NQ, NV, NU, NC>,
        F: InputLaw<NQ, NV, NU>,
    {
        let system = self.dynamics.system();
        let State { q: q0, v: v0, .. } = start.state;
        let (v0, a0) = (SVector::from(v0), start.vdot);
        let h = t - start.state.t;
        let weight = h * h / 4.0 * self.settings.penalty;
        let speeds = |d: &SVector<f64, NV>| d * (2.0 / h) - v0;
        let accelerations = |d: &SVector<f64, NV>| (d - v0 * h) * (4.0 / (h * h)) - a0;
        let configuration =
            |d: &SVector<f64, NV>| system.integrate_configuration(&q0, &(*d).into(), 1.0);
        // Predictor: constant accelerations over the step.
        let mut d = v0 * h + a0 * (h * h / 2.0);
        let mut multipliers = start.multipliers;
        let mut iterations = 0;
        loop {
            let q = configuration(&d);
            let (v, a) = (speeds(&d), accelerations(&d));
            let fail = |cause| IntegrationError::dynamics(t, q, cause);
            let residual = SVector::from(finite(system.constraint_residual(t, &q)).map_err(fail)?);
            let forcing = self.forcing(t, &q, &v).map_err(fail)?;
            let local = self.linearise(t, &q, weight).map_err(fail)?;
            let equations = local.mass * a - forcing
                + local.jacobian.transpose() * (multipliers + residual * self.settings.penalty);
            let correction = local.newton.solve(&(equations * (-h * h / 4.0)));
            d += correction;
            iterations += 1;
            let q = configuration(&d);
            let residual = SVector::from(finite(system.constraint_residual(t, &q)).map_err(fail)?);
            multipliers += residual * self.settings.penalty;
            if correction.amax() <= self.settings.tolerance {
                return self.project(t, q, speeds(&d), accelerations(&d), multipliers, weight);
            }
            if iterations >= self.settings.max_iterations || !d.iter().all(|x| x.is_finite()) {
                return Err(IntegrationError {
                    t,
                    q,
                    cause: Failure::NotConverged { iterations },
                });
            }
        }
    }

    /// The converged step's speeds and accelerations projected onto
    /// `A v + φₜ = 0` and `A v̇ = b` in the metric of `M`:
    /// `(M + (h²/4) α AᵀA) v = M v* − (h²/4) α Aᵀ φₜ` and
    /// `(M + (h²/4) α AᵀA) v̇ = M v̇* + (h²/4) α Aᵀ b`.
    fn project<const NQ: usize, const NV: usize>(
        &mut self,
        t: f64,
        q: [f64; NQ],
        v: SVector<f64, NV>,
        a: SVector<f64, NV>,
        multipliers: SVector<f64, NC>,
        weight: f64,
    ) -> Result<Point<NQ, NV, NC>, IntegrationError<NQ>>
    where
        S: ConstrainedSystem<NQ, NV, NU, NC>,
        F: InputLaw<NQ, NV, NU>,
    {
        let system = self.dynamics.system();
        let fail = |cause| IntegrationError::dynamics(t, q, cause);
        let local = self.linearise(t, &q, weight).map_err(fail)?;
        let at_rest =
            SVector::from(finite(system.constraint_velocity(t, &q, &[0.0; NV])).map_err(fail)?);
        let v = local
            .newton
            .solve(&(local.mass * v - local.jacobian.transpose() * at_rest * weight));
        let speeds: [f64; NV] = v.into();
        let bias = SVector::from(finite(system.constraint_bias(t, &q, &speeds)).map_err(fail)?);
        let vdot = local
            .newton
            .solve(&(local.mass * a + local.jacobian.transpose() * bias * weight));
        if !(v.iter().chain(vdot.iter()).all(|x| x.is_finite())) {
            return Err(fail(DynamicsError::NonFiniteAccelerations));
        }
        Ok(Point {
            state: State { t, q, v: speeds },
            vdot,
            multipliers,
        })
    }

    /// The forcing at `(t, q, v)` with the inputs of the dynamics' law.
    fn forcing<const NQ: usize, const NV: usize>(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &SVector<f64, NV>,
    ) -> Result<SVector<f64, NV>, DynamicsError>
    where
        S: ConstrainedSystem<NQ, NV, NU, NC>,
        F: InputLaw<NQ, NV, NU>,
    {
        let v: [f64; NV] = (*v).into();
        let u = self.dynamics.inputs(t, q, &v);
        let forcing = self.dynamics.system().forcing(t, q, &v, &u);
        if forcing.iter().all(|x| x.is_finite()) {
            Ok(SVector::from(forcing))
        } else {
            Err(DynamicsError::NonFiniteEquations)
        }
    }

    /// `M`, `A` and the Newton matrix at `(t, q)`, counted as one evaluation.
    fn linearise<const NQ: usize, const NV: usize>(
        &mut self,
        t: f64,
        q: &[f64; NQ],
        weight: f64,
    ) -> Result<Linearisation<NV, NC>, DynamicsError>
    where
        S: ConstrainedSystem<NQ, NV, NU, NC>,
    {
        self.evaluations += 1;
        let system = self.dynamics.system();
        let mass = system.mass_matrix_at(t, q);
        let jacobian = system.constraint_jacobian_at(t, q);
        if !mass.iter().flatten().all(|x| x.is_finite()) {
            return Err(DynamicsError::NonFiniteEquations);
        }
        if !jacobian.iter().flatten().all(|x| x.is_finite()) {
            return Err(DynamicsError::NonFiniteConstraints);
        }
        let mass = SMatrix::<f64, NV, NV>::from_fn(|i, j| mass[i][j]);
        let jacobian = SMatrix::<f64, NC, NV>::from_fn(|i, j| jacobian[i][j]);
        let newton = mass + jacobian.transpose() * jacobian * weight;
        let newton: [[f64; NV]; NV] =
            std::array::from_fn(|i| std::array::from_fn(|j| newton[(i, j)]));
        let newton = factor_mass_matrix(&newton, &pivot_names::<S, NQ, NV, NU>())?;
        Ok(Linearisation {
            mass,
            jacobian,
            newton,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constrained::test_systems::{PointOnCircle, TiedMassless};
    use crate::integrate::{Integration, Rk4};
    use crate::test_systems::Pendulum;
    use crate::{Stabilisation, Unconstrained};

    /// The angle of the minimal-coordinate pendulum after 2 s from rest at
    /// 1 rad (RK4, 20 000 steps: converged to about 1e-14).
    fn reference_angle() -> f64 {
        let pendulum = Pendulum {
            m: 1.0,
            l: 1.0,
            g: 9.81,
        };
        let start = State {
            t: 0.0,
            q: [1.0],
            v: [0.0],
        };
        let dynamics = Unconstrained::without_inputs(&pendulum);
        Integration::new(&dynamics, start, 2.0, Rk4 { steps: 20_000 })
            .run()
            .unwrap()
            .end
            .q[0]
    }

    /// The angle error after 2 s of the circle pendulum with its constraint
    /// written twice (redundant), and the largest residual on the way.
    fn error_with_steps(steps: u64) -> (f64, f64) {
        let circle = PointOnCircle::<2> {
            m: 1.0,
            l: 1.0,
            g: 9.81,
        };
        let (s, c) = 1.0f64.sin_cos();
        let start = State {
            t: 0.0,
            q: [s, -c],
            v: [0.0; 2],
        };
        let dynamics = Constrained::without_inputs(&circle, Stabilisation::None);
        let mut residual: f64 = 0.0;
        let observe = |s: &State<2, 2>| {
            residual = residual.max((s.q[0].hypot(s.q[1]) - 1.0).abs());
        };
        let end = Integration::new(
            &dynamics,
            start,
            2.0,
            AugmentedLagrangian {
                steps,
                settings: Default::default(),
            },
        )
        .observe(observe)
        .run()
        .unwrap()
        .end;
        (
            (end.q[0].atan2(-end.q[1]) - reference_angle()).abs(),
            residual,
        )
    }

    #[test]
    fn redundant_pendulum_converges_at_second_order_on_its_circle() {
        let (coarse, residual) = error_with_steps(1000);
        let (fine, _) = error_with_steps(2000);
        let order = (coarse / fine).log2();
        assert!(
            (order - 2.0).abs() < 0.15,
            "order {order}: {coarse:e} → {fine:e}"
        );
        assert!(coarse < 1e-4, "{coarse:e}");
        assert!(residual < 1e-12, "{residual:e}");
    }

    #[test]
    fn a_coordinate_without_inertia_is_carried_along() {
        let system = TiedMassless {
            m: 2.0,
            g: 9.81,
            push: 5.0,
        };
        let start = State {
            t: 0.0,
            q: [0.0; 2],
            v: [1.0; 2],
        };
        let dynamics = Constrained::without_inputs(&system, Stabilisation::None);
        let end = Integration::new(
            &dynamics,
            start,
            1.0,
            AugmentedLagrangian {
                steps: 100,
                settings: Default::default(),
            },
        )
        .run()
        .unwrap()
        .end;
        // Uniform acceleration: the trapezoidal rule is exact, up to the
        // Newton tolerance (1e-8 per step).
        let a = system.push / system.m - system.g;
        for (i, q) in end.q.iter().enumerate() {
            assert!((q - (1.0 + a / 2.0)).abs() < 1e-8, "q[{i}] = {q}");
            assert!((end.v[i] - (1.0 + a)).abs() < 1e-8, "v[{i}]");
        }
    }
}
