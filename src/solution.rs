//! What the integrators beyond fixed-step RK4 report: the final state with
//! the work spent ([`Solution`], [`Statistics`]), or a [`SolverError`] that
//! names the time and configuration where the integration stopped.

use std::fmt;

use crate::{DynamicsError, IntegrationError};

/// The work an integration did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Statistics {
    /// Evaluations of the accelerations `q̈(t, q, q̇)` (right-hand sides),
    /// including those of finite-difference Jacobians and of rejected steps.
    pub rhs_evaluations: u64,
    /// Steps taken.
    pub accepted_steps: u64,
    /// Steps tried and rejected by an error estimate.
    pub rejected_steps: u64,
}

/// The end of a successful integration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution<const NQ: usize> {
    /// The final state.
    pub end: crate::State<NQ>,
    /// The work it took.
    pub statistics: Statistics,
}

/// An integration stopped: where, and why.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolverError<const NQ: usize> {
    /// Time of the failing evaluation or step.
    pub t: f64,
    /// Configuration there.
    pub q: [f64; NQ],
    /// Why the integration stopped.
    pub cause: SolverFailure,
}

/// Why an integration stopped.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum SolverFailure {
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
}

impl fmt::Display for SolverFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Dynamics(cause) => cause.fmt(f),
            Self::StepSizeTooSmall { h } => write!(f, "step size {h:.3e} too small"),
            Self::TooManySteps { steps } => write!(f, "step budget of {steps} steps exhausted"),
            Self::NotConverged { iterations } => write!(
                f,
                "implicit stage equations did not converge in {iterations} iterations"
            ),
        }
    }
}

impl<const NQ: usize> fmt::Display for SolverError<NQ> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} at t = {} s, q = {:?}", self.cause, self.t, self.q)
    }
}

/// The cause is part of the message, so it is not repeated as a `source`.
impl<const NQ: usize> std::error::Error for SolverError<NQ> {}

impl<const NQ: usize> From<IntegrationError<NQ>> for SolverError<NQ> {
    fn from(error: IntegrationError<NQ>) -> Self {
        Self {
            t: error.t,
            q: error.q,
            cause: SolverFailure::Dynamics(error.cause),
        }
    }
}

impl<const NQ: usize> SolverError<NQ> {
    /// The failure `cause` at `state`.
    pub(crate) fn at(state: &crate::State<NQ>, cause: SolverFailure) -> Self {
        Self {
            t: state.t,
            q: state.q,
            cause,
        }
    }
}
