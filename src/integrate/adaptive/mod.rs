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
mod rows;
mod tableaux;

use std::ops::ControlFlow;

use dense::Interpolant;
pub(crate) use dense::{Continuous, EventFailure, observe, watch};
pub use dense::{Crossing, DenseStep, Event};
use rows::{Estimate, MAX_SLOPES, Slopes, Tableau};
use tableaux::{DOP853, DOPRI5};

use super::arguments::{BAD_STEP, check_positive, check_span, check_tolerances};
use super::integration::{DenseMethod, Method, sealed};
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

/// An embedded explicit pair with step-size control to the final time
/// (exactly there), the method of choice for non-stiff systems at a
/// tolerance: DOPRI5 for moderate ones (`1e-6`…`1e-9`), DOP853 for tight
/// ones (`1e-10` and below, the least work per digit). Stops at the first
/// evaluation that fails (singular mass matrix, non-finite values: the
/// error names its time and configuration), when the step size falls below
/// the resolution of the time, or when `options.max_steps` run out. Its
/// steps have a continuous extension ([`DenseMethod`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Adaptive {
    /// The pair.
    pub pair: ExplicitPair,
    /// Its tolerances and limits.
    pub options: AdaptiveOptions,
}

impl Adaptive {
    /// Dormand–Prince 5(4) with `rtol = atol = tolerance`
    /// ([`AdaptiveOptions::with_tolerance`]).
    pub fn dopri5(tolerance: f64) -> Self {
        Self {
            pair: ExplicitPair::DormandPrince54,
            options: AdaptiveOptions::with_tolerance(tolerance),
        }
    }

    /// Dormand–Prince 8(5,3) with `rtol = atol = tolerance`
    /// ([`AdaptiveOptions::with_tolerance`]).
    pub fn dop853(tolerance: f64) -> Self {
        Self {
            pair: ExplicitPair::Dop853,
            options: AdaptiveOptions::with_tolerance(tolerance),
        }
    }

    /// The integration of `dynamics` from `initial` to `t_end`, checked,
    /// with or without the steps' continuous extension.
    fn run<D, const NQ: usize, const NV: usize>(
        self,
        dynamics: &D,
        initial: State<NQ, NV>,
        t_end: f64,
        dense: bool,
    ) -> Result<Run<'_, D, NQ, NV>, IntegrationError<NQ>>
    where
        D: Dynamics<NQ, NV>,
    {
        let run = Run {
            dynamics,
            initial,
            t_end,
            options: self.options,
            dense,
        };
        run.check()?;
        Ok(run)
    }
}

impl sealed::Sealed for Adaptive {}

impl<D, const NQ: usize, const NV: usize> Method<D, NQ, NV> for Adaptive
where
    D: Dynamics<NQ, NV>,
{
    fn integrate(
        self,
        dynamics: &D,
        initial: State<NQ, NV>,
        t_end: f64,
        observer: impl FnMut(&State<NQ, NV>),
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>> {
        let run = self.run(dynamics, initial, t_end, false)?;
        integrate_with(run, self.pair, observe(&initial, observer))
    }
}

impl<D, const NQ: usize, const NV: usize> DenseMethod<D, NQ, NV> for Adaptive
where
    D: Dynamics<NQ, NV>,
{
    fn integrate_dense(
        self,
        dynamics: &D,
        initial: State<NQ, NV>,
        t_end: f64,
        on_step: impl FnMut(&DenseStep<'_, NQ, NV, D>) -> ControlFlow<State<NQ, NV>>,
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>> {
        let run = self.run(dynamics, initial, t_end, true)?;
        integrate_with(run, self.pair, on_step)
    }
}

/// The integration `run` with the tableau of `pair`, showing `on_step`
/// every step.
///
/// Every evaluation of the integration, from the initial slope to the
/// dense output's extra stages, happens at the one call in this loop, for
/// either pair: with that single call site the compiler inlines the
/// system's accelerations into it (see `rows.rs`). The [`Stepper`] says
/// where to evaluate next, and takes each slope.
fn integrate_with<D, const NQ: usize, const NV: usize>(
    run: Run<'_, D, NQ, NV>,
    pair: ExplicitPair,
    on_step: impl FnMut(&DenseStep<'_, NQ, NV, D>) -> ControlFlow<State<NQ, NV>>,
) -> Result<Solution<NQ, NV>, IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    let tableau = match pair {
        ExplicitPair::DormandPrince54 => Tableau::of(&DOPRI5),
        ExplicitPair::Dop853 => Tableau::of(&DOP853),
    };
    let kernel = Kernel::new(run.dynamics);
    let mut pending = Some(Evaluation {
        at: run.initial,
        purpose: Purpose::Start,
    });
    let mut stepper = Stepper::new(&kernel, &tableau, run, on_step);
    while let Some(Evaluation { at, purpose }) = pending {
        let slope = kernel.rate(&at)?;
        pending = stepper.take(purpose, slope)?;
    }
    Ok(Solution {
        end: stepper.state,
        statistics: Statistics {
            rhs_evaluations: kernel.evaluations(),
            ..stepper.statistics
        },
    })
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

impl<D, const NQ: usize, const NV: usize> Run<'_, D, NQ, NV>
where
    D: Dynamics<NQ, NV>,
{
    /// Whether the integration can start: its span, tolerances and first
    /// step (see `arguments.rs`), and the dynamics' own check of the start
    /// ([`Dynamics::check_start`]). Called before [`integrate_with`], whose
    /// loop it leaves as it was.
    #[inline(never)]
    fn check(&self) -> Result<(), IntegrationError<NQ>> {
        let (initial, options) = (&self.initial, &self.options);
        check_span(initial, self.t_end, true)?;
        let (relative, absolute) = (options.relative_tolerance, options.absolute_tolerance);
        check_tolerances(initial, relative, absolute)?;
        if let Some(h) = options.initial_step {
            check_positive(initial, h, BAD_STEP)?;
        }
        Kernel::new(self.dynamics).check_start(initial)
    }
}

/// What the slope at a state is wanted for.
#[derive(Clone, Copy)]
enum Purpose {
    /// The slope at the initial state.
    Start,
    /// Hairer's first step: the slope after an explicit Euler step of
    /// length `guess` from the initial state, whose slope has the weighted
    /// norm `speed`.
    InitialStep { guess: f64, speed: f64 },
    /// Stage `i` of the trial step.
    Stage(usize),
    /// The slope at the trial step's end, before it is settled: the
    /// error estimate's (DOPRI5), the next step's first stage, the dense
    /// output's.
    End,
    /// The slope at the settled end of an accepted step that the settling
    /// moved: the next step's first stage.
    Settled,
    /// Extra stage `k` of the dense output.
    Extra(usize),
}

/// A state whose slope is wanted, and what for.
struct Evaluation<const NQ: usize, const NV: usize> {
    at: State<NQ, NV>,
    purpose: Purpose,
}

/// The next evaluation, none when the integration is over, or why it
/// stopped.
type Next<const NQ: usize, const NV: usize> =
    Result<Option<Evaluation<NQ, NV>>, IntegrationError<NQ>>;

/// An adaptive integration between two evaluations of the slope: the step
/// under way, the controller's state and the work done.
struct Stepper<'k, 'a, D, F, const NQ: usize, const NV: usize> {
    kernel: &'k Kernel<'a, D>,
    tableau: &'k Tableau,
    scale: Scale,
    t_end: f64,
    options: AdaptiveOptions,
    dense: bool,
    on_step: F,
    /// Where the step under way starts, and the slope there.
    state: State<NQ, NV>,
    start_slope: Rate<NQ, NV>,
    /// The step's length, and whether it ends at `t_end`.
    h: f64,
    last: bool,
    /// The step's slopes (the first is `start_slope`).
    slopes: Slopes<NQ, NV>,
    /// The trial step's end, and where the dynamics settled it once accepted.
    end: State<NQ, NV>,
    settled: State<NQ, NV>,
    /// The factor from the step's length to the next one's.
    factor: f64,
    after_rejection: bool,
    statistics: Statistics,
}

impl<'k, 'a, D, F, const NQ: usize, const NV: usize> Stepper<'k, 'a, D, F, NQ, NV>
where
    D: Dynamics<NQ, NV>,
    F: FnMut(&DenseStep<'_, NQ, NV, D>) -> ControlFlow<State<NQ, NV>>,
{
    fn new(
        kernel: &'k Kernel<'a, D>,
        tableau: &'k Tableau,
        run: Run<'a, D, NQ, NV>,
        on_step: F,
    ) -> Self {
        Self {
            kernel,
            tableau,
            scale: Scale::from(&run.options),
            t_end: run.t_end,
            options: run.options,
            dense: run.dense,
            on_step,
            state: run.initial,
            start_slope: Rate::ZERO,
            h: 0.0,
            last: false,
            slopes: [Rate::ZERO; MAX_SLOPES],
            end: run.initial,
            settled: run.initial,
            factor: 1.0,
            after_rejection: false,
            statistics: Statistics::default(),
        }
    }

    /// Takes the `slope` evaluated for `purpose`; says where to evaluate
    /// next.
    #[inline(always)]
    fn take(&mut self, purpose: Purpose, slope: Rate<NQ, NV>) -> Next<NQ, NV> {
        let stages = self.tableau.stages;
        match purpose {
            Purpose::Start => {
                self.start_slope = slope;
                match self.options.initial_step {
                    Some(h) => {
                        self.h = h;
                        self.begin_step()
                    }
                    None => Ok(Some(self.initial_probe())),
                }
            }
            Purpose::InitialStep { guess, speed } => {
                self.h = self.initial_step(guess, speed, &slope);
                self.begin_step()
            }
            Purpose::Stage(i) => {
                self.slopes[i] = slope;
                self.after_stage(i)
            }
            Purpose::End => {
                self.slopes[stages] = slope;
                match self.tableau.estimate {
                    Estimate::Embedded { .. } => self.judge(),
                    Estimate::FifthAndThird => self.after_end(),
                }
            }
            Purpose::Settled => {
                self.start_slope = slope;
                self.extra_stage(0)
            }
            Purpose::Extra(k) => {
                self.slopes[stages + 1 + k] = slope;
                self.extra_stage(k + 1)
            }
        }
    }

    /// The next step from `state`, if `t_end` is not reached: its first
    /// stage to evaluate.
    fn begin_step(&mut self) -> Next<NQ, NV> {
        let state = &self.state;
        let running = state.t < self.t_end;
        if !running {
            return Ok(None);
        }
        let steps = self.statistics.accepted_steps + self.statistics.rejected_steps;
        if steps == self.options.max_steps {
            let steps = self.options.max_steps;
            return Err(IntegrationError::at(state, Failure::TooManySteps { steps }));
        }
        self.last = state.t + 1.01 * self.h >= self.t_end;
        if self.last {
            self.h = self.t_end - state.t;
        }
        let h = self.h;
        if h.is_nan() || h <= 16.0 * f64::EPSILON * state.t.abs() {
            return Err(IntegrationError::at(state, Failure::StepSizeTooSmall { h }));
        }
        self.slopes[0] = self.start_slope;
        Ok(Some(self.stage(1)))
    }

    /// Stage `i` of the step under way.
    #[inline(always)]
    fn stage(&self, i: usize) -> Evaluation<NQ, NV> {
        let combined = self.tableau.a[i].apply(&self.slopes);
        Evaluation {
            at: self
                .kernel
                .stage(&self.state, &combined, self.h, self.tableau.c[i]),
            purpose: Purpose::Stage(i),
        }
    }

    /// After stage `i`: the next stage, or the trial step's end.
    #[inline(always)]
    fn after_stage(&mut self, i: usize) -> Next<NQ, NV> {
        if i + 1 < self.tableau.stages {
            return Ok(Some(self.stage(i + 1)));
        }
        self.end_trial()
    }

    /// The trial step's end, then its slope (DOPRI5) or its error (DOP853).
    fn end_trial(&mut self) -> Next<NQ, NV> {
        self.end = self
            .kernel
            .step_end(&self.state, &self.tableau.b.apply(&self.slopes), self.h);
        if self.last {
            self.end.t = self.t_end;
        }
        match self.tableau.estimate {
            Estimate::Embedded { .. } => Ok(Some(Evaluation {
                at: self.end,
                purpose: Purpose::End,
            })),
            Estimate::FifthAndThird => self.judge(),
        }
    }

    /// The trial step's error, and the step accepted or rejected.
    fn judge(&mut self) -> Next<NQ, NV> {
        let weights = self.scale.weights(&self.state, &self.end);
        let slopes = &self.slopes;
        let [e, e3] = &self.tableau.error;
        let error = match self.tableau.estimate {
            Estimate::Embedded { e_new } => {
                let estimate = combined_with(&e.apply(slopes), e_new, &slopes[self.tableau.stages]);
                self.h.abs() * weights.norm(&estimate)
            }
            Estimate::FifthAndThird => {
                let fifth = weights.norm(&e.apply(slopes));
                let third = weights.norm(&e3.apply(slopes));
                let blend = (fifth * fifth + 0.01 * third * third).sqrt();
                if blend > 0.0 {
                    self.h.abs() * fifth * fifth / blend
                } else {
                    0.0
                }
            }
        };
        self.factor = step_factor(self.tableau, error, self.after_rejection);
        if error <= 1.0 {
            self.statistics.accepted_steps += 1;
            self.settled = self.kernel.settle(&self.state, &self.end)?;
            let end_slope_wanted = self.dense || self.settled == self.end;
            match self.tableau.estimate {
                Estimate::FifthAndThird if end_slope_wanted => Ok(Some(Evaluation {
                    at: self.end,
                    purpose: Purpose::End,
                })),
                _ => self.after_end(),
            }
        } else {
            self.statistics.rejected_steps += 1;
            self.after_rejection = true;
            self.h *= self.factor;
            self.begin_step()
        }
    }

    /// After the slope at an accepted step's end (when it was wanted): the
    /// slope at the settled end if the settling moved it, else the extra
    /// stages.
    fn after_end(&mut self) -> Next<NQ, NV> {
        if self.settled != self.end {
            return Ok(Some(Evaluation {
                at: self.settled,
                purpose: Purpose::Settled,
            }));
        }
        self.start_slope = self.slopes[self.tableau.stages];
        self.extra_stage(0)
    }

    /// The dense output's extra stage `k`, or the accepted step shown.
    fn extra_stage(&mut self, k: usize) -> Next<NQ, NV> {
        let tableau = self.tableau;
        if !self.dense || k == tableau.extras {
            return self.show_step();
        }
        let combined = tableau.extra[k].apply(&self.slopes);
        Ok(Some(Evaluation {
            at: self
                .kernel
                .stage(&self.state, &combined, self.h, tableau.extra_c[k]),
            purpose: Purpose::Extra(k),
        }))
    }

    /// The accepted step shown to `on_step`, then the next one begun.
    fn show_step(&mut self) -> Next<NQ, NV> {
        let interpolant = self
            .dense
            .then(|| Interpolant::new(self.tableau, &self.state, &self.end, &self.slopes, self.h));
        let extension = interpolant.as_ref().map(|i| i as &dyn Continuous<NQ, NV>);
        let step = DenseStep::new(
            self.kernel.dynamics(),
            &self.state,
            &self.settled,
            extension,
        );
        if let ControlFlow::Break(end) = (self.on_step)(&step) {
            self.state = end;
            return Ok(None);
        }
        self.state = self.settled;
        self.after_rejection = false;
        self.h *= self.factor;
        self.begin_step()
    }

    /// Hairer's first step, its probe: an explicit Euler step from the
    /// sizes of the initial state and of its slope.
    fn initial_probe(&self) -> Evaluation<NQ, NV> {
        let state = &self.state;
        let as_rate = Rate {
            dq: state.q,
            dv: state.v,
        };
        let weights = self.scale.weights(state, state);
        let size = weights.norm(&as_rate);
        let speed = weights.norm(&self.start_slope);
        let guess = if size < 1e-5 || speed < 1e-5 {
            1e-6
        } else {
            0.01 * size / speed
        };
        let guess = guess.min(self.t_end - state.t);
        Evaluation {
            at: self.kernel.advance(state, &self.start_slope, guess),
            purpose: Purpose::InitialStep { guess, speed },
        }
    }

    /// Hairer's first step, from the probe's `slope`: the slope's change
    /// over the probe's step of length `guess`, and the initial slope's
    /// weighted norm `speed`.
    fn initial_step(&self, guess: f64, speed: f64, slope: &Rate<NQ, NV>) -> f64 {
        let weights = self.scale.weights(&self.state, &self.state);
        let change = weights.norm(&slope.minus(&self.start_slope)) / guess;
        let largest = speed.max(change);
        let step = if largest <= 1e-15 {
            (guess * 1e-3).max(1e-6)
        } else {
            (0.01 / largest).powf(1.0 / f64::from(self.tableau.order))
        };
        step.min(100.0 * guess)
    }
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
fn step_factor(tableau: &Tableau, error: f64, after_rejection: bool) -> f64 {
    let max_factor = if after_rejection || error > 1.0 {
        1.0
    } else {
        tableau.max_factor
    };
    if !error.is_finite() {
        return tableau.min_factor;
    }
    if error == 0.0 {
        return max_factor;
    }
    (SAFETY * error.powf(-tableau.exponent)).clamp(tableau.min_factor, max_factor)
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
