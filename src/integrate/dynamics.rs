//! What an integrator steps: a [`Dynamics`], that is a generated system
//! closed over its input law (and, with constraints, over a drift
//! [`Stabilisation`]): the accelerations `v̇(t, q, v)`, the configuration
//! update `q ⊕ h v`, and a correction applied after each step.

use std::marker::PhantomData;

use super::{Failure, State};
use crate::constrained::{ConstraintSolver, DriftLimits, Stabilisation, project_onto_energy_level};
use crate::{ConstrainedSystem, DynamicsError, MultibodySystem};

/// Equations of motion `v̇ = a(t, q, v)`, `q̇ = N(q) v` as the integrators
/// see them.
pub trait Dynamics<const NQ: usize, const NV: usize> {
    /// The accelerations at `(t, q, v)`, or why they (or the coordinate
    /// rates there: [`MultibodySystem::check_coordinate_rates`]) cannot be
    /// computed.
    fn accelerations(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
    ) -> Result<[f64; NV], DynamicsError>;

    /// The coordinates' rates `q̇ = N(q) v`.
    fn coordinate_rates(&self, q: &[f64; NQ], v: &[f64; NV]) -> [f64; NQ];

    /// `q ⊕ h v`: the configuration reached from `q` at the constant speeds
    /// `v` after the time `h`.
    fn integrate_configuration(&self, q: &[f64; NQ], v: &[f64; NV], h: f64) -> [f64; NQ];

    /// `q` put back on its manifold after a step: `q ⊕ 0`, the system's own
    /// configuration update with no motion, which renormalises a quaternion
    /// when the system's update does (see the module's docs). The identity
    /// when every speed is a coordinate's rate.
    #[inline]
    fn renormalise(&self, q: &[f64; NQ]) -> [f64; NQ] {
        if NQ == NV {
            *q
        } else {
            self.integrate_configuration(q, &[0.0; NV], 0.0)
        }
    }

    /// The state to continue from after a step ended at `state`: `state`
    /// itself unless the dynamics correct it (coordinate projection).
    fn settle(&self, state: &State<NQ, NV>) -> Result<State<NQ, NV>, DynamicsError> {
        Ok(*state)
    }

    /// Whether a settled state may be trusted, checked after every step:
    /// always, unless the dynamics watch something (a constrained system's
    /// drift and singular positions: [`DriftLimits`]). The integrations
    /// stop at the first failure, reported at the step's start.
    #[inline]
    fn watch(&self, _state: &State<NQ, NV>) -> Result<(), Failure> {
        Ok(())
    }

    /// Whether an integration may start from `state`: always, unless the
    /// dynamics watch it and do not correct it after the first step (an
    /// unstabilised or Baumgarte constrained system must start on its
    /// constraints; a projected one is moved onto them).
    #[inline]
    fn check_start(&self, _state: &State<NQ, NV>) -> Result<(), Failure> {
        Ok(())
    }
}

/// The inputs `u(t, q, v)` of a system during an integration: any closure
/// `Fn(f64, &[f64; NQ], &[f64; NV]) -> [f64; NU]`, or [`NoInputs`].
pub trait InputLaw<const NQ: usize, const NV: usize, const NU: usize> {
    /// The inputs at a time, configuration and speed.
    fn inputs(&self, t: f64, q: &[f64; NQ], v: &[f64; NV]) -> [f64; NU];
}

impl<F, const NQ: usize, const NV: usize, const NU: usize> InputLaw<NQ, NV, NU> for F
where
    F: Fn(f64, &[f64; NQ], &[f64; NV]) -> [f64; NU],
{
    #[inline]
    fn inputs(&self, t: f64, q: &[f64; NQ], v: &[f64; NV]) -> [f64; NU] {
        self(t, q, v)
    }
}

/// Every input zero at all times (and no inputs at all for a system that
/// has none).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NoInputs;

impl<const NQ: usize, const NV: usize, const NU: usize> InputLaw<NQ, NV, NU> for NoInputs {
    #[inline]
    fn inputs(&self, _t: f64, _q: &[f64; NQ], _v: &[f64; NV]) -> [f64; NU] {
        [0.0; NU]
    }
}

/// An unconstrained system `M(q) v̇ = f(t, q, v, u)` with the inputs given by
/// a law `u(t, q, v)`.
/// `NU` is the number of inputs.
#[derive(Clone, Copy, Debug)]
pub struct Unconstrained<'a, S, F, const NU: usize> {
    pub(super) system: &'a S,
    pub(super) inputs: F,
}

impl<'a, S, const NU: usize> Unconstrained<'a, S, NoInputs, NU> {
    /// `system` with every input zero.
    pub fn without_inputs<const NQ: usize, const NV: usize>(system: &'a S) -> Self
    where
        S: MultibodySystem<NQ, NV, NU>,
    {
        Self {
            system,
            inputs: NoInputs,
        }
    }
}

impl<'a, S, F, const NU: usize> Unconstrained<'a, S, F, NU> {
    /// `system` driven by the input law `inputs(t, q, v)`, a closure such as
    /// `|t, _, _| [t.sin()]`.
    pub fn new<const NQ: usize, const NV: usize>(system: &'a S, inputs: F) -> Self
    where
        S: MultibodySystem<NQ, NV, NU>,
        F: Fn(f64, &[f64; NQ], &[f64; NV]) -> [f64; NU],
    {
        Self { system, inputs }
    }
}

impl<S, F, const NQ: usize, const NV: usize, const NU: usize> Dynamics<NQ, NV>
    for Unconstrained<'_, S, F, NU>
where
    S: MultibodySystem<NQ, NV, NU>,
    F: InputLaw<NQ, NV, NU>,
{
    #[inline]
    fn accelerations(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
    ) -> Result<[f64; NV], DynamicsError> {
        self.system.check_coordinate_rates(q)?;
        self.system
            .accelerations(t, q, v, &self.inputs.inputs(t, q, v))
    }

    #[inline]
    fn coordinate_rates(&self, q: &[f64; NQ], v: &[f64; NV]) -> [f64; NQ] {
        self.system.coordinate_rates(q, v)
    }

    #[inline]
    fn integrate_configuration(&self, q: &[f64; NQ], v: &[f64; NV], h: f64) -> [f64; NQ] {
        self.system.integrate_configuration(q, v, h)
    }
}

/// A constrained system `M v̇ = f + Aᵀ λ`, `A v̇ = b` with the inputs given by
/// a law `u(t, q, v)` and its drift held by a [`Stabilisation`]
/// (Baumgarte's in the accelerations, projection after every step). `NU` is
/// the number of inputs and `NC` that of constraints.
#[derive(Clone, Copy, Debug)]
pub struct Constrained<'a, S, F, const NU: usize, const NC: usize> {
    system: &'a S,
    inputs: F,
    stabilisation: Stabilisation,
    solver: ConstraintSolver,
    limits: DriftLimits,
    constraints: PhantomData<[(); NC]>,
}

impl<'a, S, const NU: usize, const NC: usize> Constrained<'a, S, NoInputs, NU, NC> {
    /// `system` with every input zero, stabilised by `stabilisation`.
    pub fn without_inputs<const NQ: usize, const NV: usize>(
        system: &'a S,
        stabilisation: Stabilisation,
    ) -> Self
    where
        S: ConstrainedSystem<NQ, NV, NU, NC>,
    {
        Self {
            system,
            inputs: NoInputs,
            stabilisation,
            solver: ConstraintSolver::default(),
            limits: DriftLimits::default(),
            constraints: PhantomData,
        }
    }
}

impl<'a, S, F, const NU: usize, const NC: usize> Constrained<'a, S, F, NU, NC> {
    /// `system` driven by the input law `inputs(t, q, v)`, stabilised by
    /// `stabilisation`.
    pub fn new<const NQ: usize, const NV: usize>(
        system: &'a S,
        inputs: F,
        stabilisation: Stabilisation,
    ) -> Self
    where
        S: ConstrainedSystem<NQ, NV, NU, NC>,
        F: Fn(f64, &[f64; NQ], &[f64; NV]) -> [f64; NU],
    {
        Self {
            system,
            inputs,
            stabilisation,
            solver: ConstraintSolver::default(),
            limits: DriftLimits::default(),
            constraints: PhantomData,
        }
    }

    /// The same dynamics solved by `solver` instead of the default
    /// [`ConstraintSolver::RankRevealing`] (its docs say which solver when).
    pub fn with_solver(self, solver: ConstraintSolver) -> Self {
        Self { solver, ..self }
    }

    /// The same dynamics watched against `limits` instead of the default
    /// [`DriftLimits`] (`DriftLimits::UNWATCHED` to watch nothing).
    pub fn with_drift_limits(self, limits: DriftLimits) -> Self {
        Self { limits, ..self }
    }

    /// The limits of the drift watched after every step.
    pub fn drift_limits(&self) -> DriftLimits {
        self.limits
    }

    /// Whether the stabilisation projects the state after every step (and
    /// so crosses singular positions on its branch), and the projection's
    /// own tolerance of `|φᵢ|` (`0` without projection).
    fn projection(&self) -> Option<f64> {
        match self.stabilisation {
            Stabilisation::Projection { tolerance, .. }
            | Stabilisation::EnergyProjection { tolerance, .. } => Some(tolerance),
            Stabilisation::None | Stabilisation::Baumgarte { .. } => None,
        }
    }

    /// The system.
    pub fn system(&self) -> &'a S {
        self.system
    }

    /// The solver of the saddle-point system.
    pub fn solver(&self) -> ConstraintSolver {
        self.solver
    }

    /// The inputs at `(t, q, v)`.
    pub(crate) fn inputs<const NQ: usize, const NV: usize>(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
    ) -> [f64; NU]
    where
        F: InputLaw<NQ, NV, NU>,
    {
        self.inputs.inputs(t, q, v)
    }
}

impl<S, F, const NQ: usize, const NV: usize, const NU: usize, const NC: usize> Dynamics<NQ, NV>
    for Constrained<'_, S, F, NU, NC>
where
    S: ConstrainedSystem<NQ, NV, NU, NC>,
    F: InputLaw<NQ, NV, NU>,
{
    fn accelerations(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
    ) -> Result<[f64; NV], DynamicsError> {
        self.system.check_coordinate_rates(q)?;
        let u = self.inputs.inputs(t, q, v);
        let solution = match self.stabilisation {
            Stabilisation::Baumgarte { alpha, beta } => {
                self.solver
                    .baumgarte_accelerations(self.system, t, q, v, &u, alpha, beta)
            }
            Stabilisation::None
            | Stabilisation::Projection { .. }
            | Stabilisation::EnergyProjection { .. } => {
                self.solver.accelerations(self.system, t, q, v, &u)
            }
        };
        solution.map(|(vdot, _)| vdot)
    }

    #[inline]
    fn coordinate_rates(&self, q: &[f64; NQ], v: &[f64; NV]) -> [f64; NQ] {
        self.system.coordinate_rates(q, v)
    }

    #[inline]
    fn integrate_configuration(&self, q: &[f64; NQ], v: &[f64; NV], h: f64) -> [f64; NQ] {
        self.system.integrate_configuration(q, v, h)
    }

    fn settle(&self, state: &State<NQ, NV>) -> Result<State<NQ, NV>, DynamicsError> {
        match self.stabilisation {
            Stabilisation::Projection {
                tolerance,
                max_iterations,
            } => {
                self.solver
                    .project_onto_constraints(self.system, state, tolerance, max_iterations)
            }
            Stabilisation::EnergyProjection {
                tolerance,
                max_iterations,
                energy,
            } => {
                let projected = self.solver.project_onto_constraints(
                    self.system,
                    state,
                    tolerance,
                    max_iterations,
                )?;
                Ok(project_onto_energy_level(self.system, &projected, energy))
            }
            Stabilisation::None | Stabilisation::Baumgarte { .. } => Ok(*state),
        }
    }

    /// The drift of every row against the [`DriftLimits`], and, without
    /// projection, the conditioning of the rows.
    fn watch(&self, state: &State<NQ, NV>) -> Result<(), Failure> {
        let projection = self.projection();
        let floor = [projection.unwrap_or(0.0), 0.0];
        self.limits
            .check(self.system, state, floor, projection.is_some())
    }

    /// [`watch`](Self::watch), unless the stabilisation projects (the
    /// first step's end is then projected onto the constraints).
    fn check_start(&self, state: &State<NQ, NV>) -> Result<(), Failure> {
        match self.projection() {
            Some(_) => Ok(()),
            None => self.watch(state),
        }
    }
}
