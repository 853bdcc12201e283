//! What an integrator steps: a [`Dynamics`], that is a generated system
//! closed over its input law (and, with constraints, over a drift
//! [`Stabilisation`]): the accelerations `v̇(t, q, v)`, the configuration
//! update `q ⊕ h v`, and a correction applied after each step.

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

/// A system closed over its input law `u(t, q, v)` and over how its
/// constraints are held (`C`): the [`Dynamics`] an integration steps, in
/// one of two forms, [`Unconstrained`] (`C` = [`NoConstraints`]) and
/// [`Constrained`] (`C` = [`Stabilised`]). `NU` is the number of inputs.
#[derive(Clone, Copy, Debug)]
pub struct Closed<'a, S, F, C, const NU: usize> {
    system: &'a S,
    inputs: F,
    constraints: C,
}

/// An unconstrained system `M(q) v̇ = f(t, q, v, u)` with the inputs given by
/// a law `u(t, q, v)`. `NU` is the number of inputs.
pub type Unconstrained<'a, S, F, const NU: usize> = Closed<'a, S, F, NoConstraints, NU>;

/// A constrained system `M v̇ = f + Aᵀ λ`, `A v̇ = b` with the inputs given by
/// a law `u(t, q, v)` and its drift held by a [`Stabilisation`]
/// (Baumgarte's in the accelerations, projection after every step). `NU` is
/// the number of inputs and `NC` that of constraints.
pub type Constrained<'a, S, F, const NU: usize, const NC: usize> =
    Closed<'a, S, F, Stabilised<NC>, NU>;

/// No constraints: the system's own accelerations, nothing settled or
/// watched.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NoConstraints;

/// `NC` constraints held by a [`Stabilisation`], solved by a
/// [`ConstraintSolver`] and watched against [`DriftLimits`].
#[derive(Clone, Copy, Debug)]
pub struct Stabilised<const NC: usize> {
    stabilisation: Stabilisation,
    solver: ConstraintSolver,
    limits: DriftLimits,
}

/// How a [`Closed`] system's constraints are held: its accelerations, and
/// what the integration does with a step's end. Implemented by
/// [`NoConstraints`] and [`Stabilised`].
pub trait Constraints<S, const NQ: usize, const NV: usize, const NU: usize>:
    super::integration::sealed::Sealed
{
    /// The accelerations of `system` at `(t, q, v)` with the inputs `u`.
    #[doc(hidden)]
    fn accelerations(
        &self,
        system: &S,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
        u: &[f64; NU],
    ) -> Result<[f64; NV], DynamicsError>;

    /// [`Dynamics::settle`] for `system`.
    #[doc(hidden)]
    fn settle(&self, system: &S, state: &State<NQ, NV>) -> Result<State<NQ, NV>, DynamicsError>;

    /// [`Dynamics::watch`] for `system`.
    #[doc(hidden)]
    fn watch(&self, system: &S, state: &State<NQ, NV>) -> Result<(), Failure>;

    /// [`Dynamics::check_start`] for `system`.
    #[doc(hidden)]
    fn check_start(&self, system: &S, state: &State<NQ, NV>) -> Result<(), Failure>;
}

impl super::integration::sealed::Sealed for NoConstraints {}
impl<const NC: usize> super::integration::sealed::Sealed for Stabilised<NC> {}

impl<S, const NQ: usize, const NV: usize, const NU: usize> Constraints<S, NQ, NV, NU>
    for NoConstraints
where
    S: MultibodySystem<NQ, NV, NU>,
{
    #[inline]
    fn accelerations(
        &self,
        system: &S,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
        u: &[f64; NU],
    ) -> Result<[f64; NV], DynamicsError> {
        system.accelerations(t, q, v, u)
    }

    #[inline]
    fn settle(&self, _system: &S, state: &State<NQ, NV>) -> Result<State<NQ, NV>, DynamicsError> {
        Ok(*state)
    }

    #[inline]
    fn watch(&self, _system: &S, _state: &State<NQ, NV>) -> Result<(), Failure> {
        Ok(())
    }

    #[inline]
    fn check_start(&self, _system: &S, _state: &State<NQ, NV>) -> Result<(), Failure> {
        Ok(())
    }
}

impl<const NC: usize> Stabilised<NC> {
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
}

impl<S, const NQ: usize, const NV: usize, const NU: usize, const NC: usize>
    Constraints<S, NQ, NV, NU> for Stabilised<NC>
where
    S: ConstrainedSystem<NQ, NV, NU, NC>,
{
    fn accelerations(
        &self,
        system: &S,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
        u: &[f64; NU],
    ) -> Result<[f64; NV], DynamicsError> {
        let solution = match self.stabilisation {
            Stabilisation::Baumgarte { alpha, beta } => self
                .solver
                .baumgarte_accelerations(system, t, q, v, u, alpha, beta),
            Stabilisation::None
            | Stabilisation::Projection { .. }
            | Stabilisation::EnergyProjection { .. } => {
                self.solver.accelerations(system, t, q, v, u)
            }
        };
        solution.map(|(vdot, _)| vdot)
    }

    fn settle(&self, system: &S, state: &State<NQ, NV>) -> Result<State<NQ, NV>, DynamicsError> {
        match self.stabilisation {
            Stabilisation::Projection {
                tolerance,
                max_iterations,
            } => self
                .solver
                .project_onto_constraints(system, state, tolerance, max_iterations),
            Stabilisation::EnergyProjection {
                tolerance,
                max_iterations,
                energy,
            } => {
                let projected = self.solver.project_onto_constraints(
                    system,
                    state,
                    tolerance,
                    max_iterations,
                )?;
                Ok(project_onto_energy_level(system, &projected, energy))
            }
            Stabilisation::None | Stabilisation::Baumgarte { .. } => Ok(*state),
        }
    }

    /// The drift of every row against the [`DriftLimits`], and, without
    /// projection, the conditioning of the rows.
    fn watch(&self, system: &S, state: &State<NQ, NV>) -> Result<(), Failure> {
        let projection = self.projection();
        let floor = [projection.unwrap_or(0.0), 0.0];
        self.limits
            .check(system, state, floor, projection.is_some())
    }

    /// [`watch`](Self::watch), unless the stabilisation projects (the
    /// first step's end is then projected onto the constraints).
    fn check_start(&self, system: &S, state: &State<NQ, NV>) -> Result<(), Failure> {
        match self.projection() {
            Some(_) => Ok(()),
            None => self.watch(system, state),
        }
    }
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
            constraints: NoConstraints,
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
        Self {
            system,
            inputs,
            constraints: NoConstraints,
        }
    }
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
        Self::held(system, NoInputs, stabilisation)
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
        Self::held(system, inputs, stabilisation)
    }

    /// `system` with the inputs `inputs`, stabilised by `stabilisation`,
    /// solved by the default solver and watched against the default limits.
    fn held(system: &'a S, inputs: F, stabilisation: Stabilisation) -> Self {
        Self {
            system,
            inputs,
            constraints: Stabilised {
                stabilisation,
                solver: ConstraintSolver::default(),
                limits: DriftLimits::default(),
            },
        }
    }

    /// The same dynamics solved by `solver` instead of the default
    /// [`ConstraintSolver::RankRevealing`] (its docs say which solver when).
    pub fn with_solver(mut self, solver: ConstraintSolver) -> Self {
        self.constraints.solver = solver;
        self
    }

    /// The same dynamics watched against `limits` instead of the default
    /// [`DriftLimits`] (`DriftLimits::UNWATCHED` to watch nothing).
    pub fn with_drift_limits(mut self, limits: DriftLimits) -> Self {
        self.constraints.limits = limits;
        self
    }

    /// The limits of the drift watched after every step.
    pub fn drift_limits(&self) -> DriftLimits {
        self.constraints.limits
    }

    /// The solver of the saddle-point system.
    pub fn solver(&self) -> ConstraintSolver {
        self.constraints.solver
    }
}

impl<'a, S, F, C, const NU: usize> Closed<'a, S, F, C, NU> {
    /// The system.
    pub fn system(&self) -> &'a S {
        self.system
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

impl<S, F, C, const NQ: usize, const NV: usize, const NU: usize> Dynamics<NQ, NV>
    for Closed<'_, S, F, C, NU>
where
    S: MultibodySystem<NQ, NV, NU>,
    F: InputLaw<NQ, NV, NU>,
    C: Constraints<S, NQ, NV, NU>,
{
    #[inline]
    fn accelerations(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
    ) -> Result<[f64; NV], DynamicsError> {
        self.system.check_coordinate_rates(q)?;
        let u = self.inputs(t, q, v);
        self.constraints.accelerations(self.system, t, q, v, &u)
    }

    #[inline]
    fn coordinate_rates(&self, q: &[f64; NQ], v: &[f64; NV]) -> [f64; NQ] {
        self.system.coordinate_rates(q, v)
    }

    #[inline]
    fn integrate_configuration(&self, q: &[f64; NQ], v: &[f64; NV], h: f64) -> [f64; NQ] {
        self.system.integrate_configuration(q, v, h)
    }

    #[inline]
    fn settle(&self, state: &State<NQ, NV>) -> Result<State<NQ, NV>, DynamicsError> {
        self.constraints.settle(self.system, state)
    }

    #[inline]
    fn watch(&self, state: &State<NQ, NV>) -> Result<(), Failure> {
        self.constraints.watch(self.system, state)
    }

    #[inline]
    fn check_start(&self, state: &State<NQ, NV>) -> Result<(), Failure> {
        self.constraints.check_start(self.system, state)
    }
}
