//! The equations an integrator steps: a generated system closed over its
//! input law (and, with constraints, over a drift [`Stabilisation`]), as the
//! accelerations `q̈(t, q, q̇)` plus a correction applied after each step.
//!
//! Every integrator of this crate beyond the original [`rk4_step`](crate::rk4_step)
//! takes `&impl Equations<NQ>`, so one implementation serves unconstrained
//! and constrained systems alike.

use std::cell::Cell;
use std::marker::PhantomData;

use crate::constrained::{
    baumgarte_accelerations, constrained_accelerations, project_onto_constraints,
};
use crate::integrate::march;
use crate::{
    ConstrainedSystem, DynamicsError, MultibodySystem, Solution, SolverError, SolverFailure,
    Stabilisation, State, Statistics, accelerations,
};

/// Second-order equations of motion `q̈ = a(t, q, q̇)` as integrators see
/// them.
pub trait Equations<const NQ: usize> {
    /// The accelerations at `(t, q, q̇)`, or why they cannot be computed.
    fn accelerations(
        &self,
        t: f64,
        q: &[f64; NQ],
        qd: &[f64; NQ],
    ) -> Result<[f64; NQ], DynamicsError>;

    /// The state to continue from after a step ended at `state`: `state`
    /// itself unless the equations correct it (coordinate projection).
    fn settle(&self, state: &State<NQ>) -> Result<State<NQ>, DynamicsError> {
        Ok(*state)
    }
}

/// An unconstrained system `M(q) q̈ = f(t, q, q̇, u)` with the inputs given by
/// the law `inputs(t, q, q̇)`.
#[derive(Clone, Copy, Debug)]
pub struct Unconstrained<'a, S, F> {
    /// The generated system.
    pub system: &'a S,
    /// The inputs `u` at a time, configuration and speed.
    pub inputs: F,
}

impl<S, F, const NQ: usize, const NU: usize> Equations<NQ> for Unconstrained<'_, S, F>
where
    S: MultibodySystem<NQ, NU>,
    F: Fn(f64, &[f64; NQ], &[f64; NQ]) -> [f64; NU],
{
    fn accelerations(
        &self,
        t: f64,
        q: &[f64; NQ],
        qd: &[f64; NQ],
    ) -> Result<[f64; NQ], DynamicsError> {
        accelerations(self.system, t, q, qd, &(self.inputs)(t, q, qd))
    }
}

/// A constrained system `M q̈ = f + Aᵀ λ`, `A q̈ = b` with the inputs given by
/// the law `inputs(t, q, q̇)` and its drift held by `stabilisation`
/// (Baumgarte's in the accelerations, projection after every step).
#[derive(Clone, Copy, Debug)]
pub struct Constrained<'a, S, F, const NC: usize> {
    system: &'a S,
    inputs: F,
    stabilisation: Stabilisation,
    constraints: PhantomData<[(); NC]>,
}

impl<'a, S, F, const NC: usize> Constrained<'a, S, F, NC> {
    /// `system` driven by `inputs`, stabilised by `stabilisation`.
    pub fn new<const NQ: usize, const NU: usize>(
        system: &'a S,
        inputs: F,
        stabilisation: Stabilisation,
    ) -> Self
    where
        S: ConstrainedSystem<NQ, NU, NC>,
        F: Fn(f64, &[f64; NQ], &[f64; NQ]) -> [f64; NU],
    {
        Self {
            system,
            inputs,
            stabilisation,
            constraints: PhantomData,
        }
    }
}

impl<S, F, const NQ: usize, const NU: usize, const NC: usize> Equations<NQ>
    for Constrained<'_, S, F, NC>
where
    S: ConstrainedSystem<NQ, NU, NC>,
    F: Fn(f64, &[f64; NQ], &[f64; NQ]) -> [f64; NU],
{
    fn accelerations(
        &self,
        t: f64,
        q: &[f64; NQ],
        qd: &[f64; NQ],
    ) -> Result<[f64; NQ], DynamicsError> {
        let u = (self.inputs)(t, q, qd);
        let solution = match self.stabilisation {
            Stabilisation::Baumgarte { alpha, beta } => {
                baumgarte_accelerations(self.system, t, q, qd, &u, alpha, beta)
            }
            Stabilisation::None | Stabilisation::Projection { .. } => {
                constrained_accelerations(self.system, t, q, qd, &u)
            }
        };
        solution.map(|(qdd, _)| qdd)
    }

    fn settle(&self, state: &State<NQ>) -> Result<State<NQ>, DynamicsError> {
        match self.stabilisation {
            Stabilisation::Projection {
                tolerance,
                max_iterations,
            } => project_onto_constraints(self.system, state, tolerance, max_iterations),
            Stabilisation::None | Stabilisation::Baumgarte { .. } => Ok(*state),
        }
    }
}

/// Equations that count their evaluations (the work measure of the
/// work-precision harness).
pub(crate) struct Counted<'a, E> {
    equations: &'a E,
    evaluations: Cell<u64>,
}

impl<'a, E> Counted<'a, E> {
    /// `equations`, counting from zero.
    pub(crate) fn new(equations: &'a E) -> Self {
        Self {
            equations,
            evaluations: Cell::new(0),
        }
    }

    /// Evaluations of the accelerations so far.
    pub(crate) fn evaluations(&self) -> u64 {
        self.evaluations.get()
    }

    /// The accelerations of the wrapped equations, counted: the closure form
    /// the Runge–Kutta stages take.
    pub(crate) fn acceleration<const NQ: usize>(
        &self,
    ) -> impl Fn(f64, &[f64; NQ], &[f64; NQ]) -> Result<[f64; NQ], DynamicsError> + '_
    where
        E: Equations<NQ>,
    {
        |t, q, qd| {
            self.evaluations.set(self.evaluations.get() + 1);
            self.equations.accelerations(t, q, qd)
        }
    }

    /// The wrapped equations' correction after a step that ended at
    /// `state`; a failure is reported at `state`.
    pub(crate) fn settle<const NQ: usize>(
        &self,
        state: &State<NQ>,
    ) -> Result<State<NQ>, SolverError<NQ>>
    where
        E: Equations<NQ>,
    {
        self.equations
            .settle(state)
            .map_err(|cause| SolverError::at(state, SolverFailure::Dynamics(cause)))
    }

    /// The report of `steps` fixed steps that ended at `end`: the
    /// evaluations so far, every step accepted.
    pub(crate) fn fixed_step_solution<const NQ: usize>(
        &self,
        end: State<NQ>,
        steps: u64,
    ) -> Solution<NQ> {
        Solution {
            end,
            statistics: Statistics {
                rhs_evaluations: self.evaluations(),
                accepted_steps: steps,
                rejected_steps: 0,
            },
        }
    }

    /// Integrates `steps` fixed steps from `initial`: `step` takes a state
    /// to the next, which the wrapped equations then settle, and `observer`
    /// sees the initial state and every settled one. Returns the final state
    /// with the work done; stops at the first step that fails.
    pub(crate) fn fixed_steps<const NQ: usize>(
        &self,
        initial: State<NQ>,
        steps: u64,
        mut step: impl FnMut(&State<NQ>) -> Result<State<NQ>, SolverError<NQ>>,
        observer: impl FnMut(&State<NQ>),
    ) -> Result<Solution<NQ>, SolverError<NQ>>
    where
        E: Equations<NQ>,
    {
        let end = march(initial, steps, |state| self.settle(&step(state)?), observer)?;
        Ok(self.fixed_step_solution(end, steps))
    }
}
