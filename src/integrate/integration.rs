//! The one way to run an integration: an [`Integration`] of some dynamics
//! from a state to a final time by a [`Method`], a value (`Rk4 { steps }`,
//! [`Adaptive::dop853(1e-10)`](super::Adaptive::dop853), …), with what the
//! caller sees on the way as an option: every step's end
//! ([`observe`](Integration::observe)), every step with its continuous
//! extension ([`dense`](Integration::dense)), or the zeros of an event
//! function ([`event`](Integration::event)).
//!
//! What a method needs of the dynamics is a bound of its [`Method`]
//! implementation, checked at compile time: the Taylor method needs a
//! system whose model asks for `outputs taylor;`
//! ([`TaylorDynamics`](super::TaylorDynamics)), the augmented Lagrangian
//! method [`Constrained`](super::Constrained) dynamics, and only the
//! methods with a continuous extension ([`DenseMethod`]: the adaptive pairs
//! and Taylor) give dense output and events.

use std::ops::ControlFlow;

use super::adaptive::{DenseStep, Event, EventFailure, watch};
use super::{Dynamics, IntegrationError, Solution, State};

/// A way of stepping dynamics `D` from a state to a final time: one of
/// [`Rk4`](super::Rk4), [`Adaptive`](super::Adaptive),
/// [`Gauss`](super::Gauss), [`Sdirk`](super::Sdirk),
/// [`Taylor`](super::Taylor) and
/// [`AugmentedLagrangian`](super::AugmentedLagrangian), each implemented
/// for the dynamics it can integrate.
#[diagnostic::on_unimplemented(
    message = "`{Self}` cannot integrate `{D}`",
    label = "this method cannot integrate these dynamics",
    note = "`Taylor` needs a system whose model asks for `outputs taylor;`, \
            `AugmentedLagrangian` needs `Constrained` dynamics"
)]
pub trait Method<D, const NQ: usize, const NV: usize>: sealed::Sealed {
    /// Integrates `dynamics` from `initial` to `t_end`, showing `observer`
    /// the initial state and every step's end.
    #[doc(hidden)]
    fn integrate(
        self,
        dynamics: &D,
        initial: State<NQ, NV>,
        t_end: f64,
        observer: impl FnMut(&State<NQ, NV>),
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>>;
}

/// A [`Method`] whose steps have a continuous extension: the state at any
/// time inside a step ([`DenseStep::state_at`]), so that it gives dense
/// output and locates events ([`Adaptive`](super::Adaptive) and
/// [`Taylor`](super::Taylor)).
#[diagnostic::on_unimplemented(
    message = "`{Self}` has no continuous extension for dense output or events",
    note = "dense output and events need `Adaptive` or `Taylor`"
)]
pub trait DenseMethod<D, const NQ: usize, const NV: usize>: Method<D, NQ, NV> {
    /// Integrates `dynamics` from `initial` to `t_end`, showing `on_step`
    /// every step with its continuous extension until it breaks.
    #[doc(hidden)]
    fn integrate_dense(
        self,
        dynamics: &D,
        initial: State<NQ, NV>,
        t_end: f64,
        on_step: impl FnMut(&DenseStep<'_, NQ, NV, D>) -> ControlFlow<State<NQ, NV>>,
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>>;
}

/// The methods are the crate's own: the traits' functions are the
/// integrators' internals.
pub(super) mod sealed {
    /// A method of this crate.
    pub trait Sealed {}
}

/// An integration of `dynamics` from a state to a final time by a
/// [`Method`] `M`, run by [`run`](Self::run), which returns the final state
/// with the work done ([`Solution`]) or where and why it stopped
/// ([`IntegrationError`]). `W` is what the caller sees on the way: nothing
/// ([`Quiet`]), every step's end ([`Observer`]), every step with its
/// continuous extension ([`Dense`]) or the zeros of an event function
/// ([`Events`]); each option replaces the one before.
///
/// ```
/// # dalembert::dalembert! {
/// #     pub Pendulum {
/// #         parameters m, l, g;
/// #         coordinates theta;
/// #         frame B = N.rotate_z(theta);
/// #         point P = O - l * B.y;
/// #         particle bob { mass: m, at: P };
/// #         gravity -g * N.y;
/// #     }
/// # }
/// use dalembert::integrate::{Adaptive, Integration, Rk4};
/// use dalembert::{State, Unconstrained};
///
/// let pendulum = Pendulum { m: 1.0, l: 1.0, g: 9.81 };
/// let dynamics = Unconstrained::without_inputs(&pendulum);
/// let start = State { t: 0.0, q: [1.0], v: [0.0] };
///
/// let fixed = Integration::new(&dynamics, start, 10.0, Rk4 { steps: 10_000 }).run()?;
/// let mut steps = 0;
/// let adaptive = Integration::new(&dynamics, start, 10.0, Adaptive::dop853(1e-10))
///     .observe(|_| steps += 1)
///     .run()?;
/// assert!((fixed.end.q[0] - adaptive.end.q[0]).abs() < 1e-9);
/// assert_eq!(steps, adaptive.statistics.accepted_steps + 1); // and the start
/// # Ok::<(), dalembert::IntegrationError<1>>(())
/// ```
#[must_use = "an integration does nothing until it is run"]
#[derive(Clone, Copy, Debug)]
pub struct Integration<'a, D, M, W, const NQ: usize, const NV: usize> {
    dynamics: &'a D,
    initial: State<NQ, NV>,
    t_end: f64,
    method: M,
    watcher: W,
}

/// Nothing shown during the integration.
#[derive(Clone, Copy, Debug, Default)]
pub struct Quiet;

/// Every step's end shown to a closure ([`Integration::observe`]).
#[derive(Clone, Copy, Debug)]
pub struct Observer<O>(O);

/// Every step shown with its continuous extension ([`Integration::dense`]).
#[derive(Clone, Copy, Debug)]
pub struct Dense<F>(F);

/// The zeros of an event function located and shown
/// ([`Integration::event`]).
#[derive(Clone, Copy, Debug)]
pub struct Events<G, E> {
    event: Event<G>,
    on_event: E,
}

impl<'a, D, M, const NQ: usize, const NV: usize> Integration<'a, D, M, Quiet, NQ, NV>
where
    M: Method<D, NQ, NV>,
{
    /// The integration of `dynamics` from `initial` to `t_end` by
    /// `method`, showing nothing on the way.
    ///
    /// `t_end` is not before `initial.t` (integrations run forward only); it
    /// may be `f64::INFINITY` for the methods that choose their steps
    /// ([`Adaptive`](super::Adaptive), [`Taylor`](super::Taylor)), which then
    /// run until a stopping event or their step budget.
    pub fn new(dynamics: &'a D, initial: State<NQ, NV>, t_end: f64, method: M) -> Self {
        Self {
            dynamics,
            initial,
            t_end,
            method,
            watcher: Quiet,
        }
    }
}

impl<'a, D, M, W, const NQ: usize, const NV: usize> Integration<'a, D, M, W, NQ, NV>
where
    M: Method<D, NQ, NV>,
{
    /// The same integration showing `observer` the initial state and then
    /// every step's end, after the dynamics'
    /// [`settle`](super::Dynamics::settle).
    pub fn observe<O>(self, observer: O) -> Integration<'a, D, M, Observer<O>, NQ, NV>
    where
        O: FnMut(&State<NQ, NV>),
    {
        self.watched_by(Observer(observer))
    }

    /// The same integration showing `on_step` every accepted step as a
    /// [`DenseStep`], which gives the state at any time inside it (DOPRI5:
    /// Shampine's fourth-order interpolant, no extra evaluation; DOP853:
    /// its seventh-order one, three more evaluations a step; Taylor: the
    /// step's series, free). `on_step` may end the integration there by
    /// returning [`ControlFlow::Break`] with the state to end at, which is
    /// then the [`Solution`]'s end.
    pub fn dense<F>(self, on_step: F) -> Integration<'a, D, M, Dense<F>, NQ, NV>
    where
        M: DenseMethod<D, NQ, NV>,
        F: FnMut(&DenseStep<'_, NQ, NV, D>) -> ControlFlow<State<NQ, NV>>,
    {
        self.watched_by(Dense(on_step))
    }

    /// The same integration watching the event `event`: every zero of its
    /// function on the way is located on the step's continuous extension
    /// to a few units in the last place of the time and given to `on_event`
    /// as the interpolated state there, in the order of time; a stopping
    /// event ends the integration at its first zero, and the [`Solution`]
    /// ends there. A zero at the initial state itself is not an event (the
    /// function must leave zero and come back), nor is a zero the function
    /// touches without changing sign.
    ///
    /// How the zeros are found, and what is guaranteed: each step is cut
    /// into eight equal parts, and `g` is evaluated at their ends on the
    /// continuous extension. A part whose ends differ in sign holds a zero,
    /// located by the Illinois regula falsi. A part whose ends agree in sign
    /// may still hold two zeros (closer together than an eighth of the
    /// step); then `g` turns back towards zero inside it, so its rate
    /// (central differences on the extension) points towards zero at the
    /// part's start and away from it at its end: the turning point between
    /// is located (a zero of the rate), and if `g` has changed sign there
    /// both zeros are located, one on either side. So every zero where `g`
    /// changes sign is found, in order, as long as `g` turns at most once
    /// in each eighth of a step (three zeros or two turning points inside
    /// one eighth of a step can still pair off unseen: keep the tolerance
    /// small against the time between them).
    ///
    /// A NaN or infinite value of `g` (at the start, at a sample or during
    /// a search) is an error, [`Failure::NonFiniteEvent`](super::Failure::NonFiniteEvent),
    /// at the time and interpolated configuration where it was met.
    pub fn event<G, E>(
        self,
        event: Event<G>,
        on_event: E,
    ) -> Integration<'a, D, M, Events<G, E>, NQ, NV>
    where
        M: DenseMethod<D, NQ, NV>,
        G: Fn(f64, &[f64; NQ], &[f64; NV]) -> f64,
        E: FnMut(&State<NQ, NV>),
    {
        self.watched_by(Events { event, on_event })
    }

    /// Runs the integration: the final state (exactly at the final time,
    /// or where a stopping event or a dense step's break ended it) with
    /// the work done, or where and why it stopped. Allocates nothing.
    pub fn run(self) -> Result<Solution<NQ, NV>, IntegrationError<NQ>>
    where
        W: Watcher<D, M, NQ, NV>,
    {
        let Self {
            dynamics,
            initial,
            t_end,
            method,
            watcher,
        } = self;
        watcher.run(method, dynamics, initial, t_end)
    }

    /// This integration watched by `watcher` instead.
    fn watched_by<V>(self, watcher: V) -> Integration<'a, D, M, V, NQ, NV> {
        Integration {
            dynamics: self.dynamics,
            initial: self.initial,
            t_end: self.t_end,
            method: self.method,
            watcher,
        }
    }
}

/// What the caller of an [`Integration`] sees on the way, and so how the
/// method runs: [`Quiet`], [`Observer`], [`Dense`] or [`Events`].
pub trait Watcher<D, M, const NQ: usize, const NV: usize>: sealed::Sealed {
    /// Runs `method` on `dynamics` from `initial` to `t_end`.
    #[doc(hidden)]
    fn run(
        self,
        method: M,
        dynamics: &D,
        initial: State<NQ, NV>,
        t_end: f64,
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>>;
}

impl sealed::Sealed for Quiet {}
impl<O> sealed::Sealed for Observer<O> {}
impl<F> sealed::Sealed for Dense<F> {}
impl<G, E> sealed::Sealed for Events<G, E> {}

impl<D, M, const NQ: usize, const NV: usize> Watcher<D, M, NQ, NV> for Quiet
where
    M: Method<D, NQ, NV>,
{
    #[inline]
    fn run(
        self,
        method: M,
        dynamics: &D,
        initial: State<NQ, NV>,
        t_end: f64,
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>> {
        method.integrate(dynamics, initial, t_end, |_| {})
    }
}

impl<D, M, O, const NQ: usize, const NV: usize> Watcher<D, M, NQ, NV> for Observer<O>
where
    M: Method<D, NQ, NV>,
    O: FnMut(&State<NQ, NV>),
{
    #[inline]
    fn run(
        self,
        method: M,
        dynamics: &D,
        initial: State<NQ, NV>,
        t_end: f64,
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>> {
        method.integrate(dynamics, initial, t_end, self.0)
    }
}

impl<D, M, F, const NQ: usize, const NV: usize> Watcher<D, M, NQ, NV> for Dense<F>
where
    M: DenseMethod<D, NQ, NV>,
    F: FnMut(&DenseStep<'_, NQ, NV, D>) -> ControlFlow<State<NQ, NV>>,
{
    #[inline]
    fn run(
        self,
        method: M,
        dynamics: &D,
        initial: State<NQ, NV>,
        t_end: f64,
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>> {
        method.integrate_dense(dynamics, initial, t_end, self.0)
    }
}

impl<D, M, G, E, const NQ: usize, const NV: usize> Watcher<D, M, NQ, NV> for Events<G, E>
where
    D: Dynamics<NQ, NV>,
    M: DenseMethod<D, NQ, NV>,
    G: Fn(f64, &[f64; NQ], &[f64; NV]) -> f64,
    E: FnMut(&State<NQ, NV>),
{
    fn run(
        self,
        method: M,
        dynamics: &D,
        initial: State<NQ, NV>,
        t_end: f64,
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>> {
        let failure = EventFailure::default();
        let on_step = watch(self.event, &initial, self.on_event, &failure)?;
        failure.or(method.integrate_dense(dynamics, initial, t_end, on_step))
    }
}
