//! What every integrator reports: the final state with the work spent
//! ([`Solution`], [`Statistics`]), or an [`IntegrationError`] that names the
//! time and configuration where the integration stopped and why
//! ([`Failure`]).

use std::fmt;

use super::State;
use crate::DynamicsError;

/// The work an integration did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Statistics {
    /// Evaluations of the accelerations `v̇(t, q, v)` (right-hand sides),
    /// including those of finite-difference Jacobians and of rejected steps.
    pub rhs_evaluations: u64,
    /// Steps taken.
    pub accepted_steps: u64,
    /// Steps tried and rejected by an error estimate.
    pub rejected_steps: u64,
}

/// The end of a successful integration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution<const NQ: usize, const NV: usize> {
    /// The final state.
    pub end: State<NQ, NV>,
    /// The work it took.
    pub statistics: Statistics,
}

/// An integration stopped: where, and why.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntegrationError<const NQ: usize> {
    /// Time of the failing evaluation or step.
    pub t: f64,
    /// Configuration there.
    pub q: [f64; NQ],
    /// Why the integration stopped.
    pub cause: Failure,
}

/// Why an integration stopped.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Failure {
    /// The equations could not be evaluated (singular mass matrix,
    /// non-finite values, …).
    Dynamics(DynamicsError),
    /// The step-size control asked for a step too small to advance the time
    /// in floating point: the solution is (nearly) singular there.
    StepSizeTooSmall {
        /// The step asked for.
        h: f64,
    },
    /// The step budget ran out before the final time.
    TooManySteps {
        /// Steps taken.
        steps: u64,
    },
    /// The implicit stage equations of a step did not converge (the step is
    /// too large for the iteration, or the solution is singular there).
    NotConverged {
        /// Iterations made.
        iterations: usize,
    },
    /// The integration did not start: a time that is NaN, a final time
    /// before the initial one (or infinite, for a fixed number of steps),
    /// no steps, a step, a tolerance or a first step that is zero, negative
    /// or NaN. The error's time and configuration are the initial state's.
    InvalidArgument {
        /// What is wrong.
        reason: &'static str,
    },
    /// A constrained integration left its constraints: at time `t` the
    /// holonomic residual `φ` (or the velocity form `ψ`) of constraint `row`
    /// exceeded the [`DriftLimits`](crate::constrained::DriftLimits) of its
    /// dynamics. The error's own time and configuration are those of the
    /// last good state, the start of the step that drifted (the initial
    /// state when the start itself is off the constraints); the observer
    /// saw that state, speeds included, last.
    ConstraintDrift {
        /// The constraint row (declaration order).
        row: usize,
        /// Position (`φ`) or velocity (`ψ`) level.
        level: DriftLevel,
        /// Its value `φᵢ` or `ψᵢ`.
        residual: f64,
        /// The largest magnitude allowed.
        limit: f64,
        /// When the limit was passed.
        t: f64,
    },
    /// A constrained integration that does not cross singular positions
    /// (unstabilised or Baumgarte's: see
    /// [`Stabilisation`](crate::Stabilisation)) reached one: at time `t`
    /// constraint `row` became barely independent of the others (among them
    /// `with`, the one weighing most), its relative singular value below
    /// the [`DriftLimits`](crate::constrained::DriftLimits)'
    /// `conditioning`. The error's own time and configuration are those of
    /// the last good state, as for
    /// [`ConstraintDrift`](Self::ConstraintDrift).
    SingularPosition {
        /// The constraint row that lost its independence.
        row: usize,
        /// The independent row weighing most in its near-dependency.
        with: usize,
        /// Its relative singular value (estimate, see
        /// [`constraint_conditioning`](crate::constrained::constraint_conditioning)).
        singular_value: f64,
        /// When.
        t: f64,
    },
    /// An event function returned NaN or an infinity at the error's time
    /// and configuration: whether it crossed zero cannot be known.
    NonFiniteEvent {
        /// The value returned.
        value: f64,
    },
}

/// The level of a constraint's drift: its holonomic residual `φ` or its
/// velocity form `ψ`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DriftLevel {
    /// `φ(t, q)`: the positions.
    Position,
    /// `ψ(t, q, v)`: the speeds.
    Velocity,
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Dynamics(cause) => cause.fmt(f),
            Self::StepSizeTooSmall { h } => write!(f, "step size {h:.3e} too small"),
            Self::TooManySteps { steps } => write!(f, "step budget of {steps} steps exhausted"),
            Self::NotConverged { iterations } => write!(
                f,
                "implicit stage equations did not converge in {iterations} iterations"
            ),
            Self::InvalidArgument { reason } => write!(f, "cannot integrate: {reason}"),
            Self::ConstraintDrift {
                row,
                level,
                residual,
                limit,
                t,
            } => {
                let (name, symbol) = match level {
                    DriftLevel::Position => ("residual", "φ"),
                    DriftLevel::Velocity => ("velocity form", "ψ"),
                };
                write!(
                    f,
                    "constraint drift: the {name} of constraint row {row} reached \
                     {symbol} = {residual:.3e} at t = {t} s, beyond the limit {limit:.1e} \
                     (stabilise the run, or start on the constraints); last good state"
                )
            }
            Self::SingularPosition {
                row,
                with,
                singular_value,
                t,
            } => write!(
                f,
                "singular position: constraint row {row} became nearly dependent on row \
                 {with} at t = {t} s (relative singular value {singular_value:.1e}), which this \
                 stabilisation cannot cross (use projection); last good state"
            ),
            Self::NonFiniteEvent { value } => {
                write!(f, "the event function returned {value}")
            }
        }
    }
}

impl<const NQ: usize> fmt::Display for IntegrationError<NQ> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} at t = {} s, q = {:?}", self.cause, self.t, self.q)
    }
}

/// The cause is part of the message, so it is not repeated as a `source`.
impl<const NQ: usize> std::error::Error for IntegrationError<NQ> {}

impl<const NQ: usize> IntegrationError<NQ> {
    /// The failure `cause` at `state`.
    pub(crate) fn at<const NV: usize>(state: &State<NQ, NV>, cause: Failure) -> Self {
        Self {
            t: state.t,
            q: state.q,
            cause,
        }
    }

    /// The equations failed with `cause` at `(t, q)`.
    pub(crate) fn dynamics(t: f64, q: [f64; NQ], cause: DynamicsError) -> Self {
        Self {
            t,
            q,
            cause: Failure::Dynamics(cause),
        }
    }
}
