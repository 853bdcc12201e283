//! Between the steps of an adaptive integration: the continuous extension
//! of each accepted step ([`DenseStep`]: the state at any time inside it)
//! and the zeros of a user function `g(t, q, v)` located on it ([`Event`],
//! [`Integration::event`](crate::integrate::Integration::event)).
//!
//! The extensions are Hairer's: Shampine's fourth-order interpolant of
//! DOPRI5 (free: it reuses the step's slopes) and DOP853's seventh-order one
//! (three more evaluations a step). A zero is bracketed by the signs of `g`
//! at eight points of a step, or by the turning point of `g` between two of
//! them, and located on the interpolant by the Illinois variant of regula
//! falsi, to a few units in the last place of the time
//! ([`Integration::event`](crate::integrate::Integration::event) says what
//! is guaranteed).

use std::cell::Cell;
use std::ops::ControlFlow;

use super::rows::{Slopes, Tableau};
use crate::integrate::runge_kutta::Rate;
use crate::integrate::{Dynamics, Failure, IntegrationError, State};

/// The coefficients `r₂…r₈` of the nested interpolant of one step (see
/// `tableaux::DenseOutput`).
pub(super) struct Interpolant<const NQ: usize, const NV: usize> {
    start: State<NQ, NV>,
    h: f64,
    r: [Rate<NQ, NV>; 7],
}

impl<const NQ: usize, const NV: usize> Interpolant<NQ, NV> {
    /// The continuous extension of `tableau`'s step of length `h` from
    /// `start` to `end`, from its `slopes` (the stages, the slope at `end`
    /// and the extra stages).
    pub(super) fn new(
        tableau: &Tableau,
        start: &State<NQ, NV>,
        end: &State<NQ, NV>,
        slopes: &Slopes<NQ, NV>,
        h: f64,
    ) -> Self {
        let mut interpolant = Self {
            start: *start,
            h,
            r: [Rate::ZERO; 7],
        };
        let r = &mut interpolant.r;
        r[0] = difference(end, start);
        let mut r3 = slopes[0];
        r3.scale(h);
        r3.add_scaled(-1.0, &r[0]);
        let mut r4 = r[0].minus(&r3);
        r4.add_scaled(-h, &slopes[tableau.stages]);
        (r[1], r[2]) = (r3, r4);
        let rows = tableau.d.iter().take(tableau.dense_rows);
        for (row, d) in r[3..].iter_mut().zip(rows) {
            *row = d.apply(slopes);
            row.scale(h);
        }
        interpolant
    }

    /// The interpolated state at the fraction `theta` of the step (the
    /// configuration not yet put back on its manifold; the time that of
    /// the start).
    fn at_fraction(&self, theta: f64) -> State<NQ, NV> {
        let other = 1.0 - theta;
        let mut sum = self.r[6];
        for (k, r) in self.r[..6].iter().enumerate().rev() {
            // r₇ + θ r₈, r₆ + θ' (…), r₅ + θ (…), …, r₂ + θ' (…)
            sum.scale(if k % 2 == 1 { theta } else { other });
            sum.add_scaled(1.0, r);
        }
        sum.scale(theta);
        offset_from(&self.start, &sum)
    }
}

/// The state at any time of one step, between its ends: a continuous
/// extension of a Runge–Kutta step, a Taylor polynomial.
pub(crate) trait Continuous<const NQ: usize, const NV: usize> {
    /// The state at time `t` (its configuration not yet put back on the
    /// manifold).
    fn state_at(&self, t: f64) -> State<NQ, NV>;
}

impl<const NQ: usize, const NV: usize> Continuous<NQ, NV> for Interpolant<NQ, NV> {
    fn state_at(&self, t: f64) -> State<NQ, NV> {
        let state = self.at_fraction((t - self.start.t) / self.h);
        State { t, ..state }
    }
}

/// `start + offset` (coordinates and speeds).
fn offset_from<const NQ: usize, const NV: usize>(
    start: &State<NQ, NV>,
    offset: &Rate<NQ, NV>,
) -> State<NQ, NV> {
    State {
        t: start.t,
        q: std::array::from_fn(|i| start.q[i] + offset.dq[i]),
        v: std::array::from_fn(|i| start.v[i] + offset.dv[i]),
    }
}

/// `a − b` as a [`Rate`] (coordinates and speeds).
fn difference<const NQ: usize, const NV: usize>(
    a: &State<NQ, NV>,
    b: &State<NQ, NV>,
) -> Rate<NQ, NV> {
    Rate {
        dq: std::array::from_fn(|i| a.q[i] - b.q[i]),
        dv: std::array::from_fn(|i| a.v[i] - b.v[i]),
    }
}

/// One accepted step of an adaptive integration with its continuous
/// extension: the state at any time between its start and its end.
pub struct DenseStep<'a, const NQ: usize, const NV: usize, D> {
    dynamics: &'a D,
    start: &'a State<NQ, NV>,
    end: &'a State<NQ, NV>,
    /// `None` when the integration did not ask for the extension (then the
    /// step is only shown by its ends).
    interpolant: Option<&'a dyn Continuous<NQ, NV>>,
}

impl<'a, const NQ: usize, const NV: usize, D> DenseStep<'a, NQ, NV, D>
where
    D: Dynamics<NQ, NV>,
{
    /// The step from `start` that ended (after the dynamics' correction) at
    /// `end`, with its continuous extension if it was asked for.
    pub(crate) fn new(
        dynamics: &'a D,
        start: &'a State<NQ, NV>,
        end: &'a State<NQ, NV>,
        interpolant: Option<&'a dyn Continuous<NQ, NV>>,
    ) -> Self {
        Self {
            dynamics,
            start,
            end,
            interpolant,
        }
    }

    /// The state the step started from.
    pub fn start(&self) -> &State<NQ, NV> {
        self.start
    }

    /// The state the step ended at, after the dynamics'
    /// [`settle`](Dynamics::settle).
    pub fn end(&self) -> &State<NQ, NV> {
        self.end
    }

    /// The state at time `t`, between [`start`](Self::start) and
    /// [`end`](Self::end), from the step's continuous extension (its
    /// configuration put back on the system's manifold). Outside the step
    /// the polynomial is extrapolated.
    pub fn state_at(&self, t: f64) -> State<NQ, NV> {
        let (start, end) = (self.start, self.end);
        let state = match self.interpolant {
            Some(interpolant) => interpolant.state_at(t),
            None => {
                let mut line = difference(end, start);
                line.scale((t - start.t) / (end.t - start.t));
                offset_from(start, &line)
            }
        };
        State {
            t,
            q: self.dynamics.renormalise(&state.q),
            v: state.v,
        }
    }
}

/// Which sign changes of an event function are its zeros.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Crossing {
    /// From negative to zero or positive.
    Rising,
    /// From positive to zero or negative.
    Falling,
    /// Either way.
    Either,
}

impl Crossing {
    /// Whether `g` going from `before` to `after` crosses zero this way.
    fn between(self, before: f64, after: f64) -> bool {
        let rising = before < 0.0 && after >= 0.0;
        let falling = before > 0.0 && after <= 0.0;
        match self {
            Self::Rising => rising,
            Self::Falling => falling,
            Self::Either => rising || falling,
        }
    }
}

/// A function `g(t, q, v)` whose zeros an integration records or stops at
/// (a pendulum passing the vertical: `g = θ`; a slider reaching a stop:
/// `g = x − x_stop`).
#[derive(Clone, Copy, Debug)]
pub struct Event<G> {
    /// `g(t, q, v)`.
    pub function: G,
    /// Which zeros count.
    pub crossing: Crossing,
    /// Whether the integration ends at the first zero.
    pub stop: bool,
}

impl<G> Event<G> {
    /// The integration ends at the first zero of `function` crossing as
    /// `crossing` says.
    pub fn stop_at(function: G, crossing: Crossing) -> Self {
        Self {
            function,
            crossing,
            stop: true,
        }
    }

    /// Every zero of `function` crossing as `crossing` says is recorded;
    /// the integration goes on.
    pub fn record(function: G, crossing: Crossing) -> Self {
        Self {
            function,
            crossing,
            stop: false,
        }
    }
}

/// The equal parts of each step whose ends' signs of the event function
/// are compared: zeros further apart than a part are each found, in order;
/// closer ones by the turning point between them.
const SAMPLES_PER_STEP: usize = 8;

/// The step of the central differences that give the event function's
/// rate at a sample, as a fraction of a part.
const RATE_STEP: f64 = 1e-4;

/// Iterations of the root finder; Illinois converges superlinearly, so a
/// zero is located to the last bits of the time long before.
const MAX_ROOT_ITERATIONS: usize = 200;

/// What an integration reporting to `observer` does at each step: shows it
/// the step's end and goes on. `observer` sees `initial` first, here.
pub(crate) fn observe<D, const NQ: usize, const NV: usize>(
    initial: &State<NQ, NV>,
    mut observer: impl FnMut(&State<NQ, NV>),
) -> impl FnMut(&DenseStep<'_, NQ, NV, D>) -> ControlFlow<State<NQ, NV>>
where
    D: Dynamics<NQ, NV>,
{
    observer(initial);
    move |step| {
        observer(step.end());
        ControlFlow::Continue(())
    }
}

/// Where an event function returned a NaN or an infinity, once it has:
/// the integration that [`watch`] broke off is then that error.
#[derive(Default)]
pub(crate) struct EventFailure<const NQ: usize>(Cell<Option<IntegrationError<NQ>>>);

impl<const NQ: usize> EventFailure<NQ> {
    /// The event function's failure if there was one, else `result`.
    pub(crate) fn or<T>(
        &self,
        result: Result<T, IntegrationError<NQ>>,
    ) -> Result<T, IntegrationError<NQ>> {
        match self.0.take() {
            Some(error) => Err(error),
            None => result,
        }
    }
}

/// A value of the event function that is NaN or infinite, at `state`.
struct NonFinite<const NQ: usize>(IntegrationError<NQ>);

/// `g` at `state`, or the error it is not finite.
fn finite_at<const NQ: usize, const NV: usize>(
    g: impl Fn(&State<NQ, NV>) -> f64,
    state: &State<NQ, NV>,
) -> Result<f64, NonFinite<NQ>> {
    let value = g(state);
    if value.is_finite() {
        Ok(value)
    } else {
        let cause = Failure::NonFiniteEvent { value };
        Err(NonFinite(IntegrationError::at(state, cause)))
    }
}

/// What an integration watching `event` from `initial` does at each step
/// (its continuous extension, [`DenseStep`]): locates the zeros crossed in
/// the step (see [`Integration::event`](crate::integrate::Integration::event)), gives the state at each to
/// `on_event`, and breaks at the first if the event stops the integration;
/// breaks at a non-finite value of the event function, recorded in
/// `failure`. Fails at once if the value at `initial` is not finite.
pub(crate) fn watch<'f, D, G, const NQ: usize, const NV: usize>(
    event: Event<G>,
    initial: &State<NQ, NV>,
    mut on_event: impl FnMut(&State<NQ, NV>) + 'f,
    failure: &'f EventFailure<NQ>,
) -> Result<
    impl FnMut(&DenseStep<'_, NQ, NV, D>) -> ControlFlow<State<NQ, NV>> + 'f,
    IntegrationError<NQ>,
>
where
    D: Dynamics<NQ, NV>,
    G: Fn(f64, &[f64; NQ], &[f64; NV]) -> f64 + 'f,
{
    let Event {
        function,
        crossing,
        stop,
    } = event;
    let g = move |s: &State<NQ, NV>| function(s.t, &s.q, &s.v);
    let mut before = finite_at(&g, initial).map_err(|NonFinite(error)| error)?;
    Ok(move |step: &DenseStep<'_, NQ, NV, D>| {
        let on_zero = |t: f64| {
            let state = step.state_at(t);
            on_event(&state);
            if stop {
                ControlFlow::Break(state)
            } else {
                ControlFlow::Continue(())
            }
        };
        match zeros_in_step(&g, step, before, crossing, on_zero) {
            Ok((ControlFlow::Continue(()), last)) => {
                before = last;
                ControlFlow::Continue(())
            }
            Ok((ControlFlow::Break(state), _)) => ControlFlow::Break(state),
            Err(NonFinite(error)) => {
                let state = State {
                    t: error.t,
                    q: error.q,
                    v: step.state_at(error.t).v,
                };
                failure.0.set(Some(error));
                ControlFlow::Break(state)
            }
        }
    })
}

/// The zeros of `g` crossing as `crossing` says in `step` (its value at
/// the start `before`), each given to `on_zero` in the order of time until
/// it breaks; with the value at the step's end.
fn zeros_in_step<D, const NQ: usize, const NV: usize>(
    g: impl Fn(&State<NQ, NV>) -> f64,
    step: &DenseStep<'_, NQ, NV, D>,
    before: f64,
    crossing: Crossing,
    mut on_zero: impl FnMut(f64) -> ControlFlow<State<NQ, NV>>,
) -> Result<(ControlFlow<State<NQ, NV>>, f64), NonFinite<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    let (start, end) = (step.start().t, step.end().t);
    let part = (end - start) / SAMPLES_PER_STEP as f64;
    let at = |t: f64| finite_at(&g, &step.state_at(t));
    let rate = |t: f64| -> Result<f64, NonFinite<NQ>> {
        let dt = RATE_STEP * part;
        Ok((at(t + dt)? - at(t - dt)?) / (2.0 * dt))
    };
    let mut from = (start, before);
    for k in 1..=SAMPLES_PER_STEP {
        let to = if k == SAMPLES_PER_STEP {
            (end, finite_at(&g, step.end())?)
        } else {
            (start + part * k as f64, at(start + part * k as f64)?)
        };
        let mut zeros = [None; 2];
        if crossing.between(from.1, to.1) {
            zeros[0] = Some(zero(at, (from.0, to.0), (from.1, to.1))?);
        } else if let Some(turn) = turning_towards_zero(at, rate, from, to)? {
            zeros[0] = crossing
                .between(from.1, turn.1)
                .then(|| zero(at, (from.0, turn.0), (from.1, turn.1)))
                .transpose()?;
            zeros[1] = crossing
                .between(turn.1, to.1)
                .then(|| zero(at, (turn.0, to.0), (turn.1, to.1)))
                .transpose()?;
        }
        for t in zeros.into_iter().flatten() {
            if let ControlFlow::Break(state) = on_zero(t) {
                return Ok((ControlFlow::Break(state), to.1));
            }
        }
        from = to;
    }
    Ok((ControlFlow::Continue(()), from.1))
}

/// Where `g`, of one sign at both ends of the part `from`..`to` (time and
/// value), turns back from zero inside it, and its value there: when its
/// `rate` points towards zero at the start and away from it at the end.
/// `None` when it does not (or when an end is zero).
fn turning_towards_zero<const NQ: usize>(
    at: impl Fn(f64) -> Result<f64, NonFinite<NQ>>,
    rate: impl Fn(f64) -> Result<f64, NonFinite<NQ>>,
    from: (f64, f64),
    to: (f64, f64),
) -> Result<Option<(f64, f64)>, NonFinite<NQ>> {
    let sign = from.1.signum();
    if from.1 == 0.0 || to.1 == 0.0 || sign != to.1.signum() {
        return Ok(None);
    }
    let (rate_from, rate_to) = (rate(from.0)?, rate(to.0)?);
    if sign * rate_from >= 0.0 || sign * rate_to <= 0.0 {
        return Ok(None);
    }
    let t = zero(&rate, (from.0, to.0), (rate_from, rate_to))?;
    Ok(Some((t, at(t)?)))
}

/// The zero of `f` in `[a, b]`, where `f(a) = fa` and `f(b) = fb` differ in
/// sign (or `fb = 0`): Illinois' regula falsi, which halves the value kept
/// at an end that stays twice, until the bracket is a few units in the last
/// place wide; the first error of `f` stops it.
fn zero<E>(
    f: impl Fn(f64) -> Result<f64, E>,
    (mut a, mut b): (f64, f64),
    (mut fa, mut fb): (f64, f64),
) -> Result<f64, E> {
    if fb == 0.0 {
        return Ok(b);
    }
    let mut kept = 0i8;
    for _ in 0..MAX_ROOT_ITERATIONS {
        if b - a <= 4.0 * f64::EPSILON * a.abs().max(b.abs()) {
            break;
        }
        let secant = b - fb * (b - a) / (fb - fa);
        let t = if secant > a && secant < b {
            secant
        } else {
            0.5 * (a + b)
        };
        let ft = f(t)?;
        if ft == 0.0 {
            return Ok(t);
        }
        if (ft < 0.0) == (fa < 0.0) {
            (a, fa) = (t, ft);
            if kept == 1 {
                fb *= 0.5;
            }
            kept = 1;
        } else {
            (b, fb) = (t, ft);
            if kept == -1 {
                fa *= 0.5;
            }
            kept = -1;
        }
    }
    Ok(0.5 * (a + b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn illinois_finds_a_zero_to_the_last_bits() {
        let exact = |f: fn(f64) -> f64| move |x| Ok::<_, ()>(f(x));
        let root = zero(exact(|x| x * x * x - 2.0), (1.0, 2.0), (-1.0, 6.0)).unwrap();
        assert!((root - 2f64.cbrt()).abs() <= 4.0 * f64::EPSILON, "{root}");
        let root = zero(exact(f64::cos), (0.0, 3.0), (1.0, 3f64.cos())).unwrap();
        assert!((root - std::f64::consts::FRAC_PI_2).abs() <= 8.0 * f64::EPSILON);
    }
}
