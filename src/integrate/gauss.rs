//! Gauss–Legendre collocation (implicit midpoint, orders 4 and 6) for
//! long-time energy behaviour.
//!
//! # The choice of form
//!
//! The methods are applied to the first-order Lagrangian form
//! `(q, q̇)' = (q̇, q̈(t, q, q̇))`, with the stage equations solved by
//! fixed-point iteration to rounding. They are
//!
//! * **symplectic** whenever the mass matrix is constant (springs, linear
//!   joints, point masses in Cartesian coordinates): Gauss methods are
//!   symplectic and commute with the linear map `p = M q̇`;
//! * **symmetric** (time-reversible) for every system: a Gauss step
//!   backwards undoes a step forwards, and the reversal `q̇ → −q̇` of a
//!   conservative mechanical system is linear, so the method inherits its
//!   reversibility. Symmetric methods applied to reversible systems keep the
//!   energy error bounded without drift over long times (Hairer, Lubich and
//!   Wanner, *Geometric Numerical Integration*, ch. XI), which
//!   `tests/suite/stability.rs` measures on the chaotic double pendulum over
//!   10⁴ s.
//!
//! The canonical alternative — a symplectic method on the Hamiltonian form
//! `p = M(q) q̇` — needs `∂H/∂q`, that is `∂M/∂q`, which the generated code
//! does not provide (finite differences of `M` would trade the structure for
//! an error of their own). The Lagrangian form needs nothing but the
//! accelerations, works for constrained systems through the same
//! [`Dynamics`], and has a fixed-point iteration that converges for steps
//! below about `1 / ‖∂q̈/∂(q, q̇)‖` — large enough for non-stiff mechanics.
//! The first guess of each step's stage slopes extrapolates the previous
//! step's collocation polynomial, which saves a few iterations a step.

use super::integration::{Method, sealed};
use super::runge_kutta::{Kernel, Rate};
use super::{Dynamics, Failure, IntegrationError, Solution, State};

/// Fixed-point iterations allowed per step: a converging iteration gains at
/// least a digit every few, a diverging one overflows or stalls.
const MAX_ITERATIONS: usize = 60;
/// Once the iteration stops contracting, a change up to this fraction of the
/// state's size is rounding, not divergence.
const ROUNDING_PLATEAU: f64 = 1e-11;

/// A Gauss–Legendre collocation method.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GaussLegendre {
    /// One stage, order 2: the implicit midpoint rule.
    Midpoint,
    /// Two stages, order 4.
    Order4,
    /// Three stages, order 6.
    Order6,
}

/// The Gauss–Legendre collocation method `rule` in `steps` equal steps to
/// the final time: long runs of conservative systems, whose energy error
/// stays bounded. The final state is exactly at the final time. Stops at
/// the first evaluation that fails, or with [`Failure::NotConverged`] when
/// the stage iteration of a step does not converge (a step too large for
/// the system's fastest motion, or a singular solution).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Gauss {
    /// Which of the methods.
    pub rule: GaussLegendre,
    /// The number of equal steps to the final time.
    pub steps: u64,
}

impl sealed::Sealed for Gauss {}

impl<D, const NQ: usize, const NV: usize> Method<D, NQ, NV> for Gauss
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
        let run = (dynamics, initial, t_end, self.steps);
        match self.rule {
            GaussLegendre::Midpoint => integrate(run, &MIDPOINT, observer),
            GaussLegendre::Order4 => integrate(run, &GAUSS4, observer),
            GaussLegendre::Order6 => integrate(run, &GAUSS6, observer),
        }
    }
}

/// The most stages of any method here (Gauss 6).
const MAX_STAGES: usize = 3;

/// The stage slopes of one step; those past the method's stage count are
/// unused.
type Stages<const NQ: usize, const NV: usize> = [Rate<NQ, NV>; MAX_STAGES];

/// The Butcher tableau of a collocation method of up to [`MAX_STAGES`]
/// stages, padded with zeros.
///
/// The stage count is a value, not a type parameter, so that every method
/// runs the same code, whose stage iteration is the only place that
/// evaluates the accelerations: with that single call site the compiler
/// inlines the system's accelerations into it, as into RK4's stage loop
/// (BENCHMARKS.md, "Integrators: cost per evaluation").
struct Collocation {
    stages: usize,
    c: [f64; MAX_STAGES],
    a: [[f64; MAX_STAGES]; MAX_STAGES],
    b: [f64; MAX_STAGES],
}

/// The implicit midpoint rule.
const MIDPOINT: Collocation = Collocation {
    stages: 1,
    c: [0.5, 0.0, 0.0],
    a: [[0.5, 0.0, 0.0], [0.0; MAX_STAGES], [0.0; MAX_STAGES]],
    b: [1.0, 0.0, 0.0],
};

/// `√3 / 6`.
const SQRT3_6: f64 = 0.288_675_134_594_812_9;
/// Two-stage Gauss–Legendre, nodes `1/2 ∓ √3/6`.
const GAUSS4: Collocation = Collocation {
    stages: 2,
    c: [0.5 - SQRT3_6, 0.5 + SQRT3_6, 0.0],
    a: [
        [0.25, 0.25 - SQRT3_6, 0.0],
        [0.25 + SQRT3_6, 0.25, 0.0],
        [0.0; MAX_STAGES],
    ],
    b: [0.5, 0.5, 0.0],
};

/// `√15`.
const SQRT15: f64 = 3.872_983_346_207_417;
/// Three-stage Gauss–Legendre, nodes `1/2 − √15/10, 1/2, 1/2 + √15/10`.
const GAUSS6: Collocation = Collocation {
    stages: 3,
    c: [0.5 - SQRT15 / 10.0, 0.5, 0.5 + SQRT15 / 10.0],
    a: [
        [
            5.0 / 36.0,
            2.0 / 9.0 - SQRT15 / 15.0,
            5.0 / 36.0 - SQRT15 / 30.0,
        ],
        [
            5.0 / 36.0 + SQRT15 / 24.0,
            2.0 / 9.0,
            5.0 / 36.0 - SQRT15 / 24.0,
        ],
        [
            5.0 / 36.0 + SQRT15 / 30.0,
            2.0 / 9.0 + SQRT15 / 15.0,
            5.0 / 36.0,
        ],
    ],
    b: [5.0 / 18.0, 4.0 / 9.0, 5.0 / 18.0],
};

impl Collocation {
    /// The matrix that carries the stage slopes of one step to a first guess
    /// of those of the next: entry `(i, j)` is the Lagrange basis polynomial
    /// of node `cⱼ` at `1 + cᵢ` (zero past the stage count).
    fn extrapolation(&self) -> [[f64; MAX_STAGES]; MAX_STAGES] {
        let s = self.stages;
        std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                if i >= s || j >= s {
                    return 0.0;
                }
                let x = 1.0 + self.c[i];
                (0..s)
                    .filter(|&m| m != j)
                    .map(|m| (x - self.c[m]) / (self.c[j] - self.c[m]))
                    .product()
            })
        })
    }

    /// Row `i` of `weights` applied to the method's stage slopes.
    #[inline(always)]
    fn combine<const NQ: usize, const NV: usize>(
        &self,
        weights: &[f64; MAX_STAGES],
        stages: &Stages<NQ, NV>,
    ) -> Rate<NQ, NV> {
        Rate::combination_of_first(self.stages, weights, stages)
    }
}

/// [`Gauss`] with the tableau `scheme`; the first guess of each
/// step's stage slopes extrapolates the previous step's (the first step's
/// is the slope at the start, for every stage).
fn integrate<D, const NQ: usize, const NV: usize>(
    (dynamics, initial, t_end, steps): (&D, State<NQ, NV>, f64, u64),
    scheme: &Collocation,
    observer: impl FnMut(&State<NQ, NV>),
) -> Result<Solution<NQ, NV>, IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    let kernel = Kernel::new(dynamics);
    let extrapolation = scheme.extrapolation();
    // Two sets of slopes kept from step to step: the iteration's last and
    // the one it computes trade places by reference, and the next step's
    // first guess is written into the one the iteration ended off: no
    // zeroing and no copy of the stages, per sweep or per step.
    let mut buffers = [[Rate::ZERO; MAX_STAGES]; 2];
    let mut guess = None;
    let step = |state: &State<NQ, NV>, h: f64| {
        let at = solve_stages(&kernel, scheme, state, h, &mut buffers, guess)?;
        let (stages, next_guess) = split(&mut buffers, at);
        for (slope, row) in next_guess.iter_mut().zip(&extrapolation) {
            *slope = scheme.combine(row, stages);
        }
        guess = Some(1 - at);
        Ok(kernel.step_end(state, &scheme.combine(&scheme.b, stages), h))
    };
    kernel.fixed_steps(initial, t_end, steps, step, observer)
}

/// The set of slopes `buffers[first]`, and the other one.
fn split<const NQ: usize, const NV: usize>(
    buffers: &mut [Stages<NQ, NV>; 2],
    first: usize,
) -> (&mut Stages<NQ, NV>, &mut Stages<NQ, NV>) {
    let [a, b] = buffers.each_mut();
    if first == 0 { (a, b) } else { (b, a) }
}

/// The stage slopes `Kᵢ = F(y + h Σⱼ aᵢⱼ Kⱼ)` of one step from `state`, by
/// fixed-point iteration from the first guess `buffers[guess]` until the
/// change is rounding; without a guess, the first sweep evaluates the slope
/// at `state` alone and takes it for every stage. Returns which of the two
/// `buffers` holds the slopes.
///
/// Every evaluation of the method happens at the one call in the sweep.
fn solve_stages<D, const NQ: usize, const NV: usize>(
    kernel: &Kernel<'_, D>,
    scheme: &Collocation,
    state: &State<NQ, NV>,
    h: f64,
    buffers: &mut [Stages<NQ, NV>; 2],
    guess: Option<usize>,
) -> Result<usize, IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    let size = 1.0
        + state
            .q
            .iter()
            .chain(&state.v)
            .fold(0.0f64, |m, x| m.max(x.abs()));
    // The iteration's last slopes and the ones it computes trade places by
    // reference: no copy of the stages per sweep.
    let mut at = guess.unwrap_or(0);
    let (mut stages, mut updated) = split(buffers, at);
    let mut from_start = guess.is_none();
    let mut previous_change = f64::INFINITY;
    let mut iterations = 0;
    while iterations < MAX_ITERATIONS {
        let sweep = if from_start { 1 } else { scheme.stages };
        for (i, slope) in updated.iter_mut().enumerate().take(sweep) {
            let point = if from_start {
                *state
            } else {
                let combined = scheme.combine(&scheme.a[i], stages);
                kernel.stage(state, &combined, h, scheme.c[i])
            };
            *slope = kernel.rate(&point)?;
        }
        if from_start {
            *stages = [updated[0]; MAX_STAGES];
            from_start = false;
            continue;
        }
        iterations += 1;
        let change = updated
            .iter()
            .zip(stages.iter())
            .take(scheme.stages)
            .fold(0.0f64, |m, (new, old)| m.max(new.largest_difference(old)))
            * h.abs();
        std::mem::swap(&mut stages, &mut updated);
        at = 1 - at;
        if change <= f64::EPSILON * size {
            return Ok(at);
        }
        if change >= previous_change && change <= ROUNDING_PLATEAU * size {
            return Ok(at);
        }
        previous_change = change;
    }
    Err(IntegrationError::at(
        state,
        Failure::NotConverged {
            iterations: MAX_ITERATIONS,
        },
    ))
}
