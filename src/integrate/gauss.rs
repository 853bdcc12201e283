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
//!   `tests/stability.rs` measures on the chaotic double pendulum over
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

/// Integrates `dynamics` from `initial` to `t_end` in `steps` equal steps of
/// the Gauss–Legendre method `method`, and returns the final state, exactly
/// at `t_end`, with the work done.
///
/// `observer` sees the initial state and then the state after every step
/// (after the dynamics' [`settle`](Dynamics::settle)). Allocates nothing.
/// Stops at the first evaluation that fails, or with
/// [`Failure::NotConverged`] when the stage iteration of a step does
/// not converge (a step too large for the system's fastest motion, or a
/// singular solution).
pub fn gauss_legendre<D, const NQ: usize, const NV: usize>(
    dynamics: &D,
    initial: State<NQ, NV>,
    t_end: f64,
    steps: u64,
    method: GaussLegendre,
    observer: impl FnMut(&State<NQ, NV>),
) -> Result<Solution<NQ, NV>, IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    let run = (dynamics, initial, t_end, steps);
    match method {
        GaussLegendre::Midpoint => integrate(run, &MIDPOINT, observer),
        GaussLegendre::Order4 => integrate(run, &GAUSS4, observer),
        GaussLegendre::Order6 => integrate(run, &GAUSS6, observer),
    }
}

/// The Butcher tableau of an `S`-stage collocation method.
struct Collocation<const S: usize> {
    c: [f64; S],
    a: [[f64; S]; S],
    b: [f64; S],
}

/// The implicit midpoint rule.
const MIDPOINT: Collocation<1> = Collocation {
    c: [0.5],
    a: [[0.5]],
    b: [1.0],
};

/// `√3 / 6`.
const SQRT3_6: f64 = 0.288_675_134_594_812_9;
/// Two-stage Gauss–Legendre, nodes `1/2 ∓ √3/6`.
const GAUSS4: Collocation<2> = Collocation {
    c: [0.5 - SQRT3_6, 0.5 + SQRT3_6],
    a: [[0.25, 0.25 - SQRT3_6], [0.25 + SQRT3_6, 0.25]],
    b: [0.5, 0.5],
};

/// `√15`.
const SQRT15: f64 = 3.872_983_346_207_417;
/// Three-stage Gauss–Legendre, nodes `1/2 − √15/10, 1/2, 1/2 + √15/10`.
const GAUSS6: Collocation<3> = Collocation {
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

impl<const S: usize> Collocation<S> {
    /// The matrix that carries the stage slopes of one step to a first guess
    /// of those of the next: entry `(i, j)` is the Lagrange basis polynomial
    /// of node `cⱼ` at `1 + cᵢ`.
    fn extrapolation(&self) -> [[f64; S]; S] {
        std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let x = 1.0 + self.c[i];
                (0..S)
                    .filter(|&m| m != j)
                    .map(|m| (x - self.c[m]) / (self.c[j] - self.c[m]))
                    .product()
            })
        })
    }
}

/// [`gauss_legendre`] with the tableau `scheme`; the first guess of each
/// step's stage slopes extrapolates the previous step's.
fn integrate<D, const NQ: usize, const NV: usize, const S: usize>(
    (dynamics, initial, t_end, steps): (&D, State<NQ, NV>, f64, u64),
    scheme: &Collocation<S>,
    observer: impl FnMut(&State<NQ, NV>),
) -> Result<Solution<NQ, NV>, IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    let kernel = Kernel::new(dynamics);
    let extrapolation = scheme.extrapolation();
    let mut guess = [kernel.rate(&initial)?; S];
    let step = |state: &State<NQ, NV>, h: f64| {
        let stages = solve_stages(&kernel, scheme, state, h, guess)?;
        guess = std::array::from_fn(|i| Rate::combination(&extrapolation[i], &stages));
        Ok(kernel.step_end(state, &Rate::combination(&scheme.b, &stages), h))
    };
    kernel.fixed_steps(initial, t_end, steps, step, observer)
}

/// The stage slopes `Kᵢ = F(y + h Σⱼ aᵢⱼ Kⱼ)` of one step from `state`, by
/// fixed-point iteration from `guess` until the change is rounding.
fn solve_stages<D, const NQ: usize, const NV: usize, const S: usize>(
    kernel: &Kernel<'_, D>,
    scheme: &Collocation<S>,
    state: &State<NQ, NV>,
    h: f64,
    guess: [Rate<NQ, NV>; S],
) -> Result<[Rate<NQ, NV>; S], IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    let size = 1.0
        + state
            .q
            .iter()
            .chain(&state.v)
            .fold(0.0f64, |m, x| m.max(x.abs()));
    let mut stages = guess;
    let mut previous_change = f64::INFINITY;
    for _ in 0..MAX_ITERATIONS {
        let mut updated = [Rate::ZERO; S];
        for (i, slope) in updated.iter_mut().enumerate() {
            let combined = Rate::combination(&scheme.a[i], &stages);
            *slope = kernel.rate(&kernel.stage(state, &combined, h, scheme.c[i]))?;
        }
        let change = updated
            .iter()
            .zip(&stages)
            .fold(0.0f64, |m, (new, old)| m.max(new.largest_difference(old)))
            * h.abs();
        stages = updated;
        if change <= f64::EPSILON * size {
            return Ok(stages);
        }
        if change >= previous_change && change <= ROUNDING_PLATEAU * size {
            return Ok(stages);
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
