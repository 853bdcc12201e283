//! Taylor-series integration of a system whose model asks for
//! `outputs taylor;` (the method of TIDES and heyoka).
//!
//! At each step the generated `taylor_coefficients` expands the motion
//! through the current state to order `p` (every elementary operation of
//! the equations by its coefficient recurrence; each
//! order of `M(q) v̇ = f` solved with the one factorisation of `M` at the
//! step's start), and the step sums the series. Order and step follow Jorba
//! & Zou (2005), as heyoka does, with their cost model re-fitted: for the
//! tolerance `ε` the order is `p = ⌈−ln(ε)/a + 1⌉`, and the step
//! `h = min(ρ_{p−1}, ρ_p) e⁻ᵃ e^(−0.7/(p−1))` with
//! `ρⱼ = (m / ‖xⱼ‖∞)^(1/j)` from the last two coefficients `xⱼ` of the state
//! `x = (q, v)`, `m = max(1, ‖x₀‖∞)` (absolute error for a state of norm
//! below one, relative above). The local error is then about
//! `(h/ρ)^p = e^(−a p) ≈ ε`, and the work per unit of time, the cost of an
//! expansion of order `p` over `h`, is least at `a = β` when that cost grows
//! as `p^β`: Jorba and Zou count the Cauchy products' `p²` (`a = 2`); the
//! recurrences here cost between `p` and `p²`, and `a = 1.5` was the
//! fastest of 1, 1.25, 1.5 and 2 measured on seed example 1.
//!
//! The polynomial of a step is its continuous
//! extension, free: [`Integration::dense`](super::Integration::dense) gives
//! it, and events are located on it
//! ([`Integration::event`](super::Integration::event)).
//!
//! The inputs are held at their value at the start of each step (the
//! series of a system driven by `u(t, q, v)` is that of the frozen inputs):
//! drive it by steps no longer than the inputs' own time scale, or use the
//! Runge–Kutta methods. Systems with constraints integrate through
//! [`Constrained`] (the series of their index-1 form, a projection settling
//! each step's end if asked for); where the speeds are not the coordinates'
//! rates (free and spherical joints, `speeds` statements) the series of
//! `q̇ = N(q) v` are expanded with the rest, and each step's end has its
//! quaternions renormalised (`q ⊕ 0`), as in every integrator.

use std::ops::ControlFlow;

use super::adaptive::{Continuous, DenseStep, observe};
use super::arguments::{check_positive, check_span};
use super::dynamics::{Closed, Constraints, InputLaw};
use super::integration::{DenseMethod, Method, sealed};
use super::{Dynamics, Failure, IntegrationError, Solution, State, Statistics};
use crate::__private::series;
use crate::DynamicsError;
use crate::system::{Expansion, TaylorSystem};

/// The highest order the integrator uses (`ε ≈ 3e−20`).
pub const MAX_ORDER: usize = 31;

/// `a` of the order `⌈−ln(ε)/a + 1⌉` and the step `e⁻ᵃ` of the radius of
/// convergence (module docs).
const STEP_EXPONENT: f64 = 1.5;

/// Equations that can be expanded in Taylor series: the dynamics of a
/// [`TaylorSystem`] closed over its input law.
pub trait TaylorDynamics<const NQ: usize, const NV: usize>: Dynamics<NQ, NV> {
    /// The coefficients of orders `0..=order` (below `K`) of the motion
    /// through `(t, q, v)`, the inputs held at their value there.
    fn expansion<const K: usize>(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
        order: usize,
    ) -> Result<Expansion<K, NQ, NV>, DynamicsError>;
}

/// The series of a system closed over its inputs, held at their value at
/// the start of the step. Those of a constrained system are those of its
/// index-1 form `A v̇ = b`, solved by the default
/// [`ConstraintSolver`](crate::constrained::ConstraintSolver) whatever
/// [`with_solver`](super::Constrained::with_solver) chose: a
/// [`Stabilisation::Projection`](crate::Stabilisation::Projection) settles
/// each step's end, Baumgarte's terms are not expanded (the motion is that
/// of [`Stabilisation::None`](crate::Stabilisation::None)).
impl<S, F, C, const NQ: usize, const NV: usize, const NU: usize> TaylorDynamics<NQ, NV>
    for Closed<'_, S, F, C, NU>
where
    S: TaylorSystem<NQ, NV, NU>,
    F: InputLaw<NQ, NV, NU>,
    C: Constraints<S, NQ, NV, NU>,
{
    #[inline]
    fn expansion<const K: usize>(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
        order: usize,
    ) -> Result<Expansion<K, NQ, NV>, DynamicsError> {
        let u = self.inputs(t, q, v);
        self.system().taylor_coefficients::<K>(t, q, v, &u, order)
    }
}

/// Taylor series of the motion, of the order and with the steps that a
/// tolerance asks for, to the final time (exactly there): tight tolerances
/// (`1e-12`…`1e-16`) on systems whose model asks for `outputs taylor;`
/// ([`TaylorDynamics`]; the series compiled from the model). The
/// statistics' `rhs_evaluations` count the expansions, one a step. Stops
/// at the first expansion that fails (singular mass matrix, non-finite
/// values: the error names its time and configuration), when the step
/// falls below the resolution of the time, or when `max_steps` run out.
/// Each step's polynomial is its continuous extension ([`DenseMethod`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Taylor {
    /// The local error asked of each step: absolute for a state of norm
    /// below one, relative above.
    pub tolerance: f64,
    /// Steps allowed before giving up.
    pub max_steps: u64,
}

impl Taylor {
    /// `tolerance` and a budget of ten million steps.
    pub fn with_tolerance(tolerance: f64) -> Self {
        Self {
            tolerance,
            max_steps: 10_000_000,
        }
    }

    /// The order for the tolerance, `⌈−ln(ε)/1.5 + 1⌉` (Jorba and Zou's
    /// has 2 for 1.5; the module docs say why), between 2 and
    /// [`MAX_ORDER`].
    pub fn order(&self) -> usize {
        let order = (-self.tolerance.ln() / STEP_EXPONENT + 1.0).ceil();
        if order.is_nan() {
            return MAX_ORDER;
        }
        (order.max(2.0) as usize).min(MAX_ORDER)
    }
}

impl sealed::Sealed for Taylor {}

impl<D, const NQ: usize, const NV: usize> Method<D, NQ, NV> for Taylor
where
    D: TaylorDynamics<NQ, NV>,
{
    fn integrate(
        self,
        dynamics: &D,
        initial: State<NQ, NV>,
        t_end: f64,
        observer: impl FnMut(&State<NQ, NV>),
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>> {
        Run::checked(dynamics, initial, t_end, self)?.dense(observe(&initial, observer))
    }
}

impl<D, const NQ: usize, const NV: usize> DenseMethod<D, NQ, NV> for Taylor
where
    D: TaylorDynamics<NQ, NV>,
{
    fn integrate_dense(
        self,
        dynamics: &D,
        initial: State<NQ, NV>,
        t_end: f64,
        on_step: impl FnMut(&DenseStep<'_, NQ, NV, D>) -> ControlFlow<State<NQ, NV>>,
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>> {
        Run::checked(dynamics, initial, t_end, self)?.dense(on_step)
    }
}

/// What a Taylor integration is asked to do.
struct Run<'a, D, const NQ: usize, const NV: usize> {
    dynamics: &'a D,
    initial: State<NQ, NV>,
    t_end: f64,
    options: Taylor,
}

impl<'a, D, const NQ: usize, const NV: usize> Run<'a, D, NQ, NV>
where
    D: TaylorDynamics<NQ, NV>,
{
    /// The integration of `dynamics` from `initial` to `t_end` with
    /// `options`, if it can start (see `arguments.rs`): checked before
    /// anything is shown.
    fn checked(
        dynamics: &'a D,
        initial: State<NQ, NV>,
        t_end: f64,
        options: Taylor,
    ) -> Result<Self, IntegrationError<NQ>> {
        check_span(&initial, t_end, true)?;
        check_positive(
            &initial,
            options.tolerance,
            "the tolerance is not a positive finite number",
        )?;
        dynamics
            .check_start(&initial)
            .map_err(|cause| IntegrationError::at(&initial, cause))?;
        Ok(Run {
            dynamics,
            initial,
            t_end,
            options,
        })
    }

    /// The integration, its series kept to the smallest length that holds
    /// the order.
    fn dense(
        self,
        on_step: impl FnMut(&DenseStep<'_, NQ, NV, D>) -> ControlFlow<State<NQ, NV>>,
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>> {
        match self.options.order() {
            0..16 => self.integrate::<16>(on_step),
            16..24 => self.integrate::<24>(on_step),
            _ => self.integrate::<{ MAX_ORDER + 1 }>(on_step),
        }
    }

    /// The integration with series of `K` coefficients.
    fn integrate<const K: usize>(
        self,
        mut on_step: impl FnMut(&DenseStep<'_, NQ, NV, D>) -> ControlFlow<State<NQ, NV>>,
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>> {
        let Run {
            dynamics,
            initial,
            t_end,
            options,
        } = self;
        let order = options.order().min(K - 1);
        let fraction = radius_fraction(order);
        let mut state = initial;
        let mut statistics = Statistics::default();
        while state.t < t_end {
            if statistics.accepted_steps == options.max_steps {
                let steps = options.max_steps;
                return Err(IntegrationError::at(
                    &state,
                    Failure::TooManySteps { steps },
                ));
            }
            let (q, v) = dynamics
                .expansion::<K>(state.t, &state.q, &state.v, order)
                .map_err(|cause| IntegrationError::dynamics(state.t, state.q, cause))?;
            statistics.rhs_evaluations += 1;
            let polynomial = Polynomial {
                start: state,
                q,
                v,
                terms: order + 1,
            };
            let mut h = polynomial.step(order, fraction);
            let last = state.t + h >= t_end;
            if last {
                h = t_end - state.t;
            }
            if h.is_nan() || h <= 16.0 * f64::EPSILON * state.t.abs() {
                return Err(IntegrationError::at(
                    &state,
                    Failure::StepSizeTooSmall { h },
                ));
            }
            let t = if last { t_end } else { state.t + h };
            let mut next = polynomial.state_at(t);
            next.q = dynamics.renormalise(&next.q);
            if !next.q.iter().chain(&next.v).all(|x| x.is_finite()) {
                let cause = DynamicsError::NonFiniteAccelerations;
                return Err(IntegrationError::dynamics(state.t, state.q, cause));
            }
            let settled = dynamics
                .settle(&next)
                .map_err(|cause| IntegrationError::dynamics(t, next.q, cause))?;
            dynamics
                .watch(&settled)
                .map_err(|cause| IntegrationError::at(&state, cause))?;
            statistics.accepted_steps += 1;
            let step = DenseStep::new(dynamics, &state, &settled, Some(&polynomial));
            if let ControlFlow::Break(end) = on_step(&step) {
                state = end;
                break;
            }
            state = settled;
        }
        Ok(Solution {
            end: state,
            statistics,
        })
    }
}

/// The Taylor polynomial of one step: the motion through `start`.
struct Polynomial<const K: usize, const NQ: usize, const NV: usize> {
    start: State<NQ, NV>,
    q: [[f64; K]; NQ],
    v: [[f64; K]; NV],
    /// The coefficients summed: orders `0..terms`.
    terms: usize,
}

impl<const K: usize, const NQ: usize, const NV: usize> Polynomial<K, NQ, NV> {
    /// Jorba and Zou's step for `order`: the radius of convergence
    /// `min(ρ_{p−1}, ρ_p)` times `fraction` ([`radius_fraction`]); infinite
    /// when the last two orders vanish. The three norms it reads are taken
    /// in one pass over the series.
    fn step(&self, order: usize, fraction: f64) -> f64 {
        let mut norms = [0.0_f64; 3];
        for x in self.q.iter().chain(&self.v) {
            for (norm, k) in norms.iter_mut().zip([0, order - 1, order]) {
                *norm = norm.max(series::at(x, k).abs());
            }
        }
        let [now, below, last] = norms;
        let scale = now.max(1.0);
        let radius = |norm: f64, j: usize| (scale / norm).powf(1.0 / j as f64);
        radius(below, order - 1).min(radius(last, order)) * fraction
    }
}

/// What the step takes of the radius of convergence at `order`: `e⁻ᵃ`
/// (`a` = [`STEP_EXPONENT`]), with heyoka's safety factor `e^(−0.7/(p−1))`.
fn radius_fraction(order: usize) -> f64 {
    (-STEP_EXPONENT - 0.7 / (order as f64 - 1.0)).exp()
}

impl<const K: usize, const NQ: usize, const NV: usize> Continuous<NQ, NV>
    for Polynomial<K, NQ, NV>
{
    fn state_at(&self, t: f64) -> State<NQ, NV> {
        let tau = t - self.start.t;
        let sum = |x: &[f64; K]| series::sum(x, self.terms, tau);
        State {
            t,
            q: std::array::from_fn(|i| sum(&self.q[i])),
            v: std::array::from_fn(|i| sum(&self.v[i])),
        }
    }
}
