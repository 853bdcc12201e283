//! Adaptive explicit integration with the embedded Dormand–Prince pairs
//! 5(4) and 8(5,3) and Hairer's step-size control.
//!
//! # Why not a crate
//!
//! The crates that offer these pairs do not fit the runtime's contract:
//! `ode_solvers` pins another nalgebra (see `ENGINEERING.md`), and
//! `russell_ode`'s `Solver` works on heap `Vector`s through a boxed
//! `System` closure and integrates whole intervals with its own output
//! machinery. Here the state is the const-generic [`State`] on the stack, a
//! step allocates nothing, the slopes are those of [`Rate`] (shared with
//! RK4), and a failure is a [`SolverError`] naming time and configuration
//! like every other integrator of the crate. The tableaux are transcribed
//! from Hairer's codes (`tableaux.rs`), and so is the controller: an error
//! norm `‖err / (atol + rtol max(|y₀|, |y₁|))‖` (root mean square), the next
//! step `h · clamp(0.9 err^(−1/(q̂+1)), min, max)`, no growth right after a
//! rejection, and Hairer's initial-step heuristic. No dense output: the
//! observer sees the accepted steps.

mod tableaux;

use tableaux::{DOP853, DOPRI5, EmbeddedPair, ErrorEstimate};

use crate::equations::Counted;
use crate::integrate::Rate;
use crate::{Equations, Solution, SolverError, SolverFailure, State, Statistics};

/// Safety factor of the step-size controller.
const SAFETY: f64 = 0.9;

/// An embedded explicit Runge–Kutta pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExplicitPair {
    /// Dormand–Prince 5(4) (`DOPRI5`, MATLAB's `ode45`, SciPy's `RK45`):
    /// six slope evaluations per step.
    DormandPrince54,
    /// Dormand–Prince 8(5,3) (`DOP853`): twelve slope evaluations per step;
    /// the method of choice for tight tolerances.
    Dop853,
}

/// Tolerances and limits of an adaptive integration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveOptions {
    /// Relative tolerance `rtol` of the local error of each coordinate and
    /// speed.
    pub relative_tolerance: f64,
    /// Absolute tolerance `atol`, in the units of each coordinate and speed.
    pub absolute_tolerance: f64,
    /// The first step; Hairer's heuristic (one extra evaluation) if `None`.
    pub initial_step: Option<f64>,
    /// Steps (accepted and rejected) allowed before giving up.
    pub max_steps: u64,
}

impl AdaptiveOptions {
    /// `rtol = atol = tolerance`, an automatic first step and a budget of
    /// ten million steps.
    pub fn with_tolerance(tolerance: f64) -> Self {
        Self {
            relative_tolerance: tolerance,
            absolute_tolerance: tolerance,
            initial_step: None,
            max_steps: 10_000_000,
        }
    }
}

/// Integrates `equations` from `initial` to `t_end` with the adaptive pair
/// `pair`, and returns the final state (exactly at `t_end`) with the work
/// done.
///
/// `observer` sees the initial state and then every accepted step, after
/// the equations' [`settle`](Equations::settle). Allocates nothing. Stops
/// at the first evaluation that fails (singular mass matrix, non-finite
/// values: the error names its time and configuration), when the step size
/// falls below the resolution of the time, or when `options.max_steps` run
/// out.
pub fn simulate_adaptive<E, const NQ: usize>(
    equations: &E,
    initial: State<NQ>,
    t_end: f64,
    pair: ExplicitPair,
    options: AdaptiveOptions,
    observer: impl FnMut(&State<NQ>),
) -> Result<Solution<NQ>, SolverError<NQ>>
where
    E: Equations<NQ>,
{
    match pair {
        ExplicitPair::DormandPrince54 => {
            integrate(equations, initial, t_end, &DOPRI5, options, observer)
        }
        ExplicitPair::Dop853 => integrate(equations, initial, t_end, &DOP853, options, observer),
    }
}

/// [`simulate_adaptive`] with the tableau `pair`.
fn integrate<E, const NQ: usize, const S: usize>(
    equations: &E,
    initial: State<NQ>,
    t_end: f64,
    pair: &EmbeddedPair<S>,
    options: AdaptiveOptions,
    mut observer: impl FnMut(&State<NQ>),
) -> Result<Solution<NQ>, SolverError<NQ>>
where
    E: Equations<NQ>,
{
    let counted = Counted::new(equations);
    let acceleration = counted.acceleration();
    let rate = |state: &State<NQ>| Rate::at(&acceleration, state);
    let scale = Scale::from(&options);
    observer(&initial);
    let mut state = initial;
    let mut slope = rate(&state)?;
    let mut h = match options.initial_step {
        Some(h) => h,
        None => initial_step(&state, &slope, t_end, pair.order, &scale, rate)?,
    };
    let mut statistics = Statistics::default();
    let mut after_rejection = false;
    while state.t < t_end {
        if statistics.accepted_steps + statistics.rejected_steps == options.max_steps {
            let steps = options.max_steps;
            return Err(SolverError::at(
                &state,
                SolverFailure::TooManySteps { steps },
            ));
        }
        let last = state.t + 1.01 * h >= t_end;
        if last {
            h = t_end - state.t;
        }
        if h.is_nan() || h <= 16.0 * f64::EPSILON * state.t.abs() {
            return Err(SolverError::at(
                &state,
                SolverFailure::StepSizeTooSmall { h },
            ));
        }
        let trial = attempt(pair, &state, &slope, h, &rate)?;
        let mut next = trial.state;
        if last {
            next.t = t_end;
        }
        let error = match &pair.estimate {
            ErrorEstimate::Embedded { e, e_new } => {
                let new_slope = rate(&next)?;
                let estimate = Rate::combination(e, &trial.stages);
                let estimate = combined_with(&estimate, *e_new, &new_slope);
                let error = h.abs() * scale.norm(&state, &next, &estimate);
                (error, Some(new_slope))
            }
            ErrorEstimate::FifthAndThird { e5, e3 } => {
                let fifth = scale.norm(&state, &next, &Rate::combination(e5, &trial.stages));
                let third = scale.norm(&state, &next, &Rate::combination(e3, &trial.stages));
                let blend = (fifth * fifth + 0.01 * third * third).sqrt();
                let error = if blend > 0.0 {
                    h.abs() * fifth * fifth / blend
                } else {
                    0.0
                };
                (error, None)
            }
        };
        let (error, new_slope) = error;
        let factor = step_factor(pair, error, after_rejection);
        if error <= 1.0 {
            statistics.accepted_steps += 1;
            let settled = counted.settle(&next)?;
            slope = match new_slope {
                Some(new_slope) if settled == next => new_slope,
                _ => rate(&settled)?,
            };
            state = settled;
            observer(&state);
            after_rejection = false;
        } else {
            statistics.rejected_steps += 1;
            after_rejection = true;
        }
        h *= factor;
    }
    statistics.rhs_evaluations = counted.evaluations();
    Ok(Solution {
        end: state,
        statistics,
    })
}

/// The stage slopes and the propagated solution of one trial step.
struct Trial<const NQ: usize, const S: usize> {
    stages: [Rate<NQ>; S],
    state: State<NQ>,
}

/// One trial step of length `h` from `state`, whose slope is `slope`.
fn attempt<const NQ: usize, const S: usize>(
    pair: &EmbeddedPair<S>,
    state: &State<NQ>,
    slope: &Rate<NQ>,
    h: f64,
    rate: &impl Fn(&State<NQ>) -> Result<Rate<NQ>, crate::IntegrationError<NQ>>,
) -> Result<Trial<NQ, S>, SolverError<NQ>> {
    let mut stages = [Rate::ZERO; S];
    stages[0] = *slope;
    for i in 1..S {
        let stage = Rate::combination(&pair.a[i], &stages).stage(state, h, pair.c[i]);
        stages[i] = rate(&stage)?;
    }
    let state = Rate::combination(&pair.b, &stages).advance(state, h);
    Ok(Trial { stages, state })
}

/// `estimate + w · slope`.
fn combined_with<const NQ: usize>(estimate: &Rate<NQ>, w: f64, slope: &Rate<NQ>) -> Rate<NQ> {
    Rate::combination(&[1.0, w], &[*estimate, *slope])
}

/// The factor from this step to the next: Hairer's controller. A non-finite
/// error estimate (an overflowing trial) rejects the step with the smallest
/// factor.
fn step_factor<const S: usize>(pair: &EmbeddedPair<S>, error: f64, after_rejection: bool) -> f64 {
    let max_factor = if after_rejection || error > 1.0 {
        1.0
    } else {
        pair.max_factor
    };
    if !error.is_finite() {
        return pair.min_factor;
    }
    if error == 0.0 {
        return max_factor;
    }
    (SAFETY * error.powf(-pair.exponent)).clamp(pair.min_factor, max_factor)
}

/// Hairer's first step: from the sizes of the state, of its slope and of the
/// slope's change over a tiny explicit Euler step (one evaluation).
fn initial_step<const NQ: usize>(
    state: &State<NQ>,
    slope: &Rate<NQ>,
    t_end: f64,
    order: i32,
    scale: &Scale,
    rate: impl Fn(&State<NQ>) -> Result<Rate<NQ>, crate::IntegrationError<NQ>>,
) -> Result<f64, SolverError<NQ>> {
    let as_rate = Rate {
        dq: state.q,
        dqd: state.qd,
    };
    let size = scale.norm(state, state, &as_rate);
    let speed = scale.norm(state, state, slope);
    let guess = if size < 1e-5 || speed < 1e-5 {
        1e-6
    } else {
        0.01 * size / speed
    };
    let guess = guess.min(t_end - state.t);
    let euler = slope.advance(state, guess);
    let change = scale.norm(state, state, &rate(&euler)?.minus(slope)) / guess;
    let largest = speed.max(change);
    let step = if largest <= 1e-15 {
        (guess * 1e-3).max(1e-6)
    } else {
        (0.01 / largest).powf(1.0 / f64::from(order))
    };
    Ok(step.min(100.0 * guess))
}

/// The error scale `atol + rtol · max(|y₀|, |y₁|)` of each entry.
struct Scale {
    relative: f64,
    absolute: f64,
}

impl From<&AdaptiveOptions> for Scale {
    fn from(options: &AdaptiveOptions) -> Self {
        Self {
            relative: options.relative_tolerance,
            absolute: options.absolute_tolerance,
        }
    }
}

impl Scale {
    /// The root mean square of `values / scale(from, to)` over the
    /// coordinates and speeds.
    fn norm<const NQ: usize>(&self, from: &State<NQ>, to: &State<NQ>, values: &Rate<NQ>) -> f64 {
        let entry = |value: f64, a: f64, b: f64| {
            let scale = self.absolute + self.relative * a.abs().max(b.abs());
            (value / scale).powi(2)
        };
        let sum: f64 = (0..NQ)
            .map(|i| {
                entry(values.dq[i], from.q[i], to.q[i]) + entry(values.dqd[i], from.qd[i], to.qd[i])
            })
            .sum();
        (sum / (2 * NQ) as f64).sqrt()
    }
}
