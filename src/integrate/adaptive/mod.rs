//! Adaptive explicit integration with the embedded Dormand–Prince pairs
//! 5(4) and 8(5,3) and Hairer's step-size control.
//!
//! # Why not a crate
//!
//! The crates that offer these pairs do not fit the runtime's contract:
//! `ode_solvers` pins another nalgebra than this crate's, and
//! `russell_ode`'s `Solver` works on heap `Vector`s through a boxed
//! `System` closure and integrates whole intervals with its own output
//! machinery. Here the state is the const-generic [`State`] on the stack, a
//! step allocates nothing, the slopes are those of the Runge–Kutta kernel
//! (shared with RK4), and a failure is an [`IntegrationError`] naming time and configuration
//! like every other integrator of the crate. The tableaux are transcribed
//! from Hairer's codes (`tableaux.rs`), and so is the controller: an error
//! norm `‖err / (atol + rtol max(|y₀|, |y₁|))‖` (root mean square), the next
//! step `h · clamp(0.9 err^(−1/(q̂+1)), min, max)`, no growth right after a
//! rejection, and Hairer's initial-step heuristic. The continuous
//! extensions (dense output) and the location of events are in `dense.rs`.

mod dense;
mod tableaux;

use std::ops::ControlFlow;

use dense::Interpolant;
pub(crate) use dense::{Continuous, observe, watch};
pub use dense::{Crossing, DenseStep, Event, adaptive_with_events};
use tableaux::{DOP853, DOPRI5, EmbeddedPair, ErrorEstimate};

use super::runge_kutta::{Kernel, Rate};
use super::{Dynamics, Failure, IntegrationError, Solution, State, Statistics};

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

/// Integrates `dynamics` from `initial` to `t_end` with the adaptive pair
/// `pair`, and returns the final state (exactly at `t_end`) with the work
/// done.
///
/// `observer` sees the initial state and then every accepted step, after
/// the dynamics' [`settle`](Dynamics::settle). Allocates nothing. Stops
/// at the first evaluation that fails (singular mass matrix, non-finite
/// values: the error names its time and configuration), when the step size
/// falls below the resolution of the time, or when `options.max_steps` run
/// out.
pub fn adaptive<D, const NQ: usize, const NV: usize>(
    dynamics: &D,
    initial: State<NQ, NV>,
    t_end: f64,
    pair: ExplicitPair,
    options: AdaptiveOptions,
    observer: impl FnMut(&State<NQ, NV>),
) -> Result<Solution<NQ, NV>, IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    let on_step = observe(&initial, observer);
    let run = Run {
        dynamics,
        initial,
        t_end,
        options,
        dense: false,
    };
    integrate_with(run, pair, on_step)
}

/// [`adaptive`] with the continuous extension of every step: `on_step`
/// sees each accepted step as a [`DenseStep`], which gives the state at any
/// time inside it (DOPRI5: Shampine's fourth-order interpolant, no extra
/// evaluation; DOP853: its seventh-order one, three more evaluations a
/// step), and may end the integration there by returning
/// [`ControlFlow::Break`] with the state to end at.
pub fn adaptive_dense<D, const NQ: usize, const NV: usize>(
    dynamics: &D,
    initial: State<NQ, NV>,
    t_end: f64,
    pair: ExplicitPair,
    options: AdaptiveOptions,
    on_step: impl FnMut(&DenseStep<'_, NQ, NV, D>) -> ControlFlow<State<NQ, NV>>,
) -> Result<Solution<NQ, NV>, IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    let run = Run {
        dynamics,
        initial,
        t_end,
        options,
        dense: true,
    };
    integrate_with(run, pair, on_step)
}

/// [`adaptive_dense`] of `run` with the tableau of `pair`.
fn integrate_with<D, const NQ: usize, const NV: usize>(
    run: Run<'_, D, NQ, NV>,
    pair: ExplicitPair,
    on_step: impl FnMut(&DenseStep<'_, NQ, NV, D>) -> ControlFlow<State<NQ, NV>>,
) -> Result<Solution<NQ, NV>, IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    match pair {
        ExplicitPair::DormandPrince54 => integrate(run, &DOPRI5, on_step),
        ExplicitPair::Dop853 => integrate(run, &DOP853, on_step),
    }
}

/// What an adaptive integration is asked to do.
struct Run<'a, D, const NQ: usize, const NV: usize> {
    dynamics: &'a D,
    initial: State<NQ, NV>,
    t_end: f64,
    options: AdaptiveOptions,
    /// Whether the steps need their continuous extension.
    dense: bool,
}

/// [`adaptive_dense`] with the tableau `pair`.
fn integrate<D, const NQ: usize, const NV: usize, const S: usize, const T: usize>(
    run: Run<'_, D, NQ, NV>,
    pair: &EmbeddedPair<S, T>,
    mut on_step: impl FnMut(&DenseStep<'_, NQ, NV, D>) -> ControlFlow<State<NQ, NV>>,
) -> Result<Solution<NQ, NV>, IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    let Run {
        dynamics,
        initial,
        t_end,
        options,
        dense,
    } = run;
    let kernel = Kernel::new(dynamics);
    let rows = Rows::of(pair);
    let scale = Scale::from(&options);
    let mut state = initial;
    let mut slope = kernel.rate(&state)?;
    let mut h = match options.initial_step {
        Some(h) => h,
        None => initial_step(&kernel, &state, &slope, t_end, pair.order, &scale)?,
    };
    let mut statistics = Statistics::default();
    let mut after_rejection = false;
    while state.t < t_end {
        if statistics.accepted_steps + statistics.rejected_steps == options.max_steps {
            let steps = options.max_steps;
            return Err(IntegrationError::at(
                &state,
                Failure::TooManySteps { steps },
            ));
        }
        let last = state.t + 1.01 * h >= t_end;
        if last {
            h = t_end - state.t;
        }
        if h.is_nan() || h <= 16.0 * f64::EPSILON * state.t.abs() {
            return Err(IntegrationError::at(
                &state,
                Failure::StepSizeTooSmall { h },
            ));
        }
        let trial = attempt(&kernel, pair, &rows, &state, &slope, h)?;
        let mut next = trial.state;
        if last {
            next.t = t_end;
        }
        let weights = scale.weights(&state, &next);
        let (error, new_slope) = match &pair.estimate {
            ErrorEstimate::Embedded { e_new, .. } => {
                let new_slope = kernel.rate(&next)?;
                let estimate = rows.error[0].apply(&trial.stages);
                let estimate = combined_with(&estimate, *e_new, &new_slope);
                (h.abs() * weights.norm(&estimate), Some(new_slope))
            }
            ErrorEstimate::FifthAndThird { .. } => {
                let fifth = weights.norm(&rows.error[0].apply(&trial.stages));
                let third = weights.norm(&rows.error[1].apply(&trial.stages));
                let blend = (fifth * fifth + 0.01 * third * third).sqrt();
                let error = if blend > 0.0 {
                    h.abs() * fifth * fifth / blend
                } else {
                    0.0
                };
                (error, None)
            }
        };
        let factor = step_factor(pair, error, after_rejection);
        if error <= 1.0 {
            statistics.accepted_steps += 1;
            let settled = kernel.settle(&next)?;
            // The slope at the unsettled end: the error estimate's, or one
            // evaluation when the next step (not settled) or the dense
            // output needs it.
            let end_slope = match new_slope {
                Some(new_slope) => Some(new_slope),
                None if dense || settled == next => Some(kernel.rate(&next)?),
                None => None,
            };
            slope = match end_slope {
                Some(end_slope) if settled == next => end_slope,
                _ => kernel.rate(&settled)?,
            };
            let interpolant = match (dense, &end_slope) {
                (true, Some(end_slope)) => {
                    let stages = &trial.stages;
                    Some(Interpolant::new(
                        &kernel, pair, &state, &next, stages, end_slope, h,
                    )?)
                }
                _ => None,
            };
            let extension = interpolant.as_ref().map(|i| i as &dyn Continuous<NQ, NV>);
            let step = DenseStep::new(dynamics, &state, &settled, extension);
            if let ControlFlow::Break(end) = on_step(&step) {
                state = end;
                break;
            }
            state = settled;
            after_rejection = false;
        } else {
            statistics.rejected_steps += 1;
            after_rejection = true;
        }
        h *= factor;
    }
    statistics.rhs_evaluations = kernel.evaluations();
    Ok(Solution {
        end: state,
        statistics,
    })
}

/// The stage slopes and the propagated solution of one trial step.
struct Trial<const NQ: usize, const NV: usize, const S: usize> {
    stages: [Rate<NQ, NV>; S],
    state: State<NQ, NV>,
}

/// A row of a tableau without its zero weights: `(stage, weight)` for the
/// first `count` entries, in the row's order. A quarter of DOP853's
/// weights are zero; skipping them leaves every sum as it was (a product
/// `0 · k` of a finite slope adds a zero, and a sum that starts from `+0`
/// is never `−0`).
#[derive(Clone, Copy)]
struct Terms<const S: usize> {
    terms: [(usize, f64); S],
    count: usize,
}

impl<const S: usize> Terms<S> {
    /// The non-zero weights of `row`.
    fn of(row: &[f64; S]) -> Self {
        let mut terms = [(0, 0.0); S];
        let mut count = 0;
        for (j, &w) in row.iter().enumerate().filter(|(_, w)| **w != 0.0) {
            terms[count] = (j, w);
            count += 1;
        }
        Self { terms, count }
    }

    /// `Σⱼ wⱼ · stages[j]` over the row's terms.
    #[inline(always)]
    fn apply<const NQ: usize, const NV: usize>(&self, stages: &[Rate<NQ, NV>; S]) -> Rate<NQ, NV> {
        let mut sum = Rate::ZERO;
        for &(j, w) in self.terms.iter().take(self.count) {
            sum.add_scaled(w, &stages[j]);
        }
        sum
    }
}

/// The rows of a pair without their zero weights, built once per
/// integration: the stages', the propagated solution's and the error
/// estimate's (`e`, or `e5` then `e3`).
struct Rows<const S: usize> {
    a: [Terms<S>; S],
    b: Terms<S>,
    error: [Terms<S>; 2],
}

impl<const S: usize> Rows<S> {
    fn of<const T: usize>(pair: &EmbeddedPair<S, T>) -> Self {
        let error = match &pair.estimate {
            ErrorEstimate::Embedded { e, .. } => [Terms::of(e), Terms::of(&[0.0; S])],
            ErrorEstimate::FifthAndThird { e5, e3 } => [Terms::of(e5), Terms::of(e3)],
        };
        Self {
            a: pair.a.each_ref().map(Terms::of),
            b: Terms::of(&pair.b),
            error,
        }
    }
}

/// One trial step of length `h` from `state`, whose slope is `slope`.
fn attempt<D, const NQ: usize, const NV: usize, const S: usize, const T: usize>(
    kernel: &Kernel<'_, D>,
    pair: &EmbeddedPair<S, T>,
    rows: &Rows<S>,
    state: &State<NQ, NV>,
    slope: &Rate<NQ, NV>,
    h: f64,
) -> Result<Trial<NQ, NV, S>, IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    let mut stages = [Rate::ZERO; S];
    stages[0] = *slope;
    for i in 1..S {
        let combined = rows.a[i].apply(&stages);
        stages[i] = kernel.rate(&kernel.stage(state, &combined, h, pair.c[i]))?;
    }
    let state = kernel.step_end(state, &rows.b.apply(&stages), h);
    Ok(Trial { stages, state })
}

/// `estimate + w · slope`.
fn combined_with<const NQ: usize, const NV: usize>(
    estimate: &Rate<NQ, NV>,
    w: f64,
    slope: &Rate<NQ, NV>,
) -> Rate<NQ, NV> {
    Rate::combination(&[1.0, w], &[*estimate, *slope])
}

/// The factor from this step to the next: Hairer's controller. A non-finite
/// error estimate (an overflowing trial) rejects the step with the smallest
/// factor.
fn step_factor<const S: usize, const T: usize>(
    pair: &EmbeddedPair<S, T>,
    error: f64,
    after_rejection: bool,
) -> f64 {
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
fn initial_step<D, const NQ: usize, const NV: usize>(
    kernel: &Kernel<'_, D>,
    state: &State<NQ, NV>,
    slope: &Rate<NQ, NV>,
    t_end: f64,
    order: i32,
    scale: &Scale,
) -> Result<f64, IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    let as_rate = Rate {
        dq: state.q,
        dv: state.v,
    };
    let weights = scale.weights(state, state);
    let size = weights.norm(&as_rate);
    let speed = weights.norm(slope);
    let guess = if size < 1e-5 || speed < 1e-5 {
        1e-6
    } else {
        0.01 * size / speed
    };
    let guess = guess.min(t_end - state.t);
    let euler = kernel.advance(state, slope, guess);
    let change = weights.norm(&kernel.rate(&euler)?.minus(slope)) / guess;
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
    /// The reciprocal scales `1 / (atol + rtol max(|from|, |to|))` of the
    /// entries of a step from `from` to `to`.
    #[inline]
    fn weights<const NQ: usize, const NV: usize>(
        &self,
        from: &State<NQ, NV>,
        to: &State<NQ, NV>,
    ) -> Rate<NQ, NV> {
        let weight = |a: f64, b: f64| 1.0 / (self.absolute + self.relative * a.abs().max(b.abs()));
        Rate {
            dq: std::array::from_fn(|i| weight(from.q[i], to.q[i])),
            dv: std::array::from_fn(|i| weight(from.v[i], to.v[i])),
        }
    }
}

impl<const NQ: usize, const NV: usize> Rate<NQ, NV> {
    /// The root mean square of `values` times these weights, entry by entry.
    #[inline]
    fn norm(&self, values: &Self) -> f64 {
        let mut sum = 0.0;
        for i in 0..NQ {
            sum += (values.dq[i] * self.dq[i]).powi(2);
        }
        for i in 0..NV {
            sum += (values.dv[i] * self.dv[i]).powi(2);
        }
        (sum / (NQ + NV) as f64).sqrt()
    }
}
