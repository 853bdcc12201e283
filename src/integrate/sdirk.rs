//! A stiff solver: the three-stage, third-order, L-stable and stiffly
//! accurate SDIRK method of Alexander (1977), with fixed steps, for stiff
//! springs and joints whose fast modes would force an explicit method to
//! tiny steps.
//!
//! # Why not `diffsol`
//!
//! `diffsol` (BDF/SDIRK with error control) works on heap vectors (`DVector`
//! with its nalgebra backend) and asks for the problem as closures with
//! their own Jacobian-action types; it costs about 3.5 minutes of build on
//! two cores, so it would have to sit behind a feature that CI skips. Our
//! systems are small and second order, which makes a hand-written SDIRK
//! short and allocation-free: each stage is one `NV × NV` Newton system in
//! the stage speeds `V` (the configuration follows as
//! `Q = q + h (Σ aᵢⱼ N(Qⱼ) Vⱼ)`, the coordinates' rates `N(q) v` integrated
//! like the speeds),
//! with the matrix `I − hγ ∂v̇/∂v − (hγ)² ∂v̇/∂q` built once per step from a
//! forward-difference Jacobian (`2 NV` evaluations) and factored on the
//! stack (by the partial-pivoting LU of `lu.rs`: nalgebra's `LU` needs a
//! typenum dimension, not a const generic). The stage slopes are recovered from the stage equations, not by
//! evaluating the right-hand side again, so stiff components are damped,
//! not amplified.

use super::integration::{Method, sealed};
use super::lu::Lu;
use super::runge_kutta::{Kernel, Rate};
use super::{Dynamics, Failure, IntegrationError, Solution, State};

/// The diagonal `γ` of the tableau: the root of `x³ − 3x² + 3x/2 − 1/6` in
/// `(1/6, 1/2)`, which makes the method L-stable.
const GAMMA: f64 = 0.435_866_521_508_459;
/// The second stage time.
const TAU: f64 = (1.0 + GAMMA) / 2.0;
/// The first weight.
const B1: f64 = -(6.0 * GAMMA * GAMMA - 16.0 * GAMMA + 1.0) / 4.0;
/// The second weight.
const B2: f64 = (6.0 * GAMMA * GAMMA - 20.0 * GAMMA + 5.0) / 4.0;
/// Stage times.
const C: [f64; 3] = [GAMMA, TAU, 1.0];
/// The stage coefficients; the last row is the weights (stiffly accurate).
const A: [[f64; 3]; 3] = [
    [GAMMA, 0.0, 0.0],
    [TAU - GAMMA, GAMMA, 0.0],
    [B1, B2, GAMMA],
];
/// Passes of the fixed-point iteration for a stage configuration
/// `Q = q + h (… + γ N(Q) V)` when `N` depends on `Q`: each gains the factor
/// `hγ ‖∂(N v)/∂q‖`, small at any step the Newton iteration converges for.
const MAX_CONFIGURATION_ITERATIONS: usize = 8;
/// Newton iterations allowed per stage (the Jacobian is that of the step's
/// start, so the convergence is linear, not quadratic).
const MAX_NEWTON_ITERATIONS: usize = 25;
/// A Newton correction below this fraction of the stage speeds' size ends
/// the iteration.
const NEWTON_TOLERANCE: f64 = 1e-12;
/// Once the iteration stops contracting, a correction up to this fraction of
/// the stage speeds' size is rounding, not divergence.
const ROUNDING_PLATEAU: f64 = 1e-9;

/// The L-stable SDIRK method in `steps` equal steps to the final time:
/// stiff springs and joints, whose fast modes an explicit method must
/// resolve. The final state is exactly at the final time. Stops at the
/// first evaluation that fails, or with [`Failure::NotConverged`] when the
/// Newton iteration of a stage does not converge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sdirk {
    /// The number of equal steps to the final time.
    pub steps: u64,
}

impl sealed::Sealed for Sdirk {}

impl<D, const NQ: usize, const NV: usize> Method<D, NQ, NV> for Sdirk
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
        let kernel = Kernel::new(dynamics);
        let step = |state: &State<NQ, NV>, h| sdirk_step(&kernel, state, h);
        kernel.fixed_steps(initial, t_end, self.steps, step, observer)
    }
}

/// One SDIRK step of length `h` from `state`.
fn sdirk_step<D, const NQ: usize, const NV: usize>(
    kernel: &Kernel<'_, D>,
    state: &State<NQ, NV>,
    h: f64,
) -> Result<State<NQ, NV>, IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    let hg = h * GAMMA;
    let newton = NewtonMatrix::at(kernel, state, hg)?;
    let mut stages = [Rate::ZERO; 3];
    let mut speeds = state.v;
    for i in 0..3 {
        let explicit = Rate::combination(&A[i], &stages);
        let stage = Stage {
            t: state.t + C[i] * h,
            start: state,
            explicit: &explicit,
            h,
        };
        speeds = newton.solve_stage(kernel, &stage, hg, speeds)?;
        let (q, explicit_speeds) = stage.at(kernel, &speeds);
        stages[i] = Rate {
            dq: kernel.dynamics().coordinate_rates(&q, &speeds),
            dv: std::array::from_fn(|k| (speeds[k] - explicit_speeds[k]) / hg),
        };
    }
    Ok(kernel.step_end(state, &Rate::combination(&A[2], &stages), h))
}

/// A stage of a step: its time, the step's start and the explicit part
/// `Σⱼ₍ⱼ₍ᵢ₎ aᵢⱼ Kⱼ` of its slope.
struct Stage<'s, const NQ: usize, const NV: usize> {
    t: f64,
    start: &'s State<NQ, NV>,
    explicit: &'s Rate<NQ, NV>,
    h: f64,
}

impl<const NQ: usize, const NV: usize> Stage<'_, NQ, NV> {
    /// The stage configuration and speeds given the stage speeds `V`:
    /// `Q = q + h (Σ aᵢⱼ Q̇ⱼ + γ N(Q) V)` (by fixed-point iteration, exact at
    /// the first pass when `N` does not depend on `Q`),
    /// `V̂ = v + h Σ aᵢⱼ v̇ⱼ`.
    fn at<D>(&self, kernel: &Kernel<'_, D>, speeds: &[f64; NV]) -> ([f64; NQ], [f64; NV])
    where
        D: Dynamics<NQ, NV>,
    {
        let dynamics = kernel.dynamics();
        let along = |rates: [f64; NQ]| {
            let motion = Rate {
                dq: std::array::from_fn(|k| self.explicit.dq[k] + GAMMA * rates[k]),
                dv: self.explicit.dv,
            };
            kernel.advance(self.start, &motion, self.h)
        };
        let mut moved = along(dynamics.coordinate_rates(&self.start.q, speeds));
        for _ in 0..MAX_CONFIGURATION_ITERATIONS {
            let next = along(dynamics.coordinate_rates(&moved.q, speeds));
            let settled = next.q == moved.q;
            moved = next;
            if settled {
                break;
            }
        }
        (moved.q, moved.v)
    }
}

/// The factored Newton matrix `I − hγ ∂v̇/∂v − (hγ)² ∂v̇/∂q` of a step.
struct NewtonMatrix<const NV: usize> {
    lu: Lu<NV>,
}

impl<const NV: usize> NewtonMatrix<NV> {
    /// The matrix at `state` from a forward-difference Jacobian of the
    /// accelerations (`2 NV + 1` evaluations; the configuration moved along
    /// each speed by `q ⊕ δ eⱼ`).
    fn at<D, const NQ: usize>(
        kernel: &Kernel<'_, D>,
        state: &State<NQ, NV>,
        hg: f64,
    ) -> Result<Self, IntegrationError<NQ>>
    where
        D: Dynamics<NQ, NV>,
    {
        let State { t, q, v } = *state;
        let base = kernel.accelerations(t, &q, &v)?;
        let mut matrix: [[f64; NV]; NV] =
            std::array::from_fn(|i| std::array::from_fn(|j| f64::from(u8::from(i == j))));
        for j in 0..NV {
            let direction = std::array::from_fn(|k| f64::from(u8::from(k == j)));
            let dq = difference_step(if NQ == NV { q[j] } else { 0.0 });
            let shifted = kernel
                .dynamics()
                .integrate_configuration(&q, &direction, dq);
            let by_q = kernel.accelerations(t, &shifted, &v)?;
            let dv = difference_step(v[j]);
            let mut shifted = v;
            shifted[j] += dv;
            let by_v = kernel.accelerations(t, &q, &shifted)?;
            for i in 0..NV {
                let d_dq = (by_q[i] - base[i]) / dq;
                let d_dv = (by_v[i] - base[i]) / dv;
                matrix[i][j] -= hg * d_dv + hg * hg * d_dq;
            }
        }
        Ok(Self {
            lu: Lu::factor(matrix),
        })
    }

    /// The stage speeds `V` with `V = V̂ + hγ v̇(t, Q(V), V)`, by simplified
    /// Newton iteration from `guess`.
    fn solve_stage<D, const NQ: usize>(
        &self,
        kernel: &Kernel<'_, D>,
        stage: &Stage<'_, NQ, NV>,
        hg: f64,
        guess: [f64; NV],
    ) -> Result<[f64; NV], IntegrationError<NQ>>
    where
        D: Dynamics<NQ, NV>,
    {
        let mut speeds = guess;
        let mut previous_correction = f64::INFINITY;
        for iteration in 1..=MAX_NEWTON_ITERATIONS {
            let (q, explicit_speeds) = stage.at(kernel, &speeds);
            let vdot = kernel.accelerations(stage.t, &q, &speeds)?;
            let residual = std::array::from_fn(|k| speeds[k] - explicit_speeds[k] - hg * vdot[k]);
            let not_converged = IntegrationError {
                t: stage.t,
                q,
                cause: Failure::NotConverged {
                    iterations: iteration,
                },
            };
            let correction = self.lu.solve(&residual).ok_or(not_converged)?;
            speeds = std::array::from_fn(|k| speeds[k] - correction[k]);
            let size = correction.iter().fold(0.0f64, |m, c| m.max(c.abs()));
            if !size.is_finite() {
                return Err(not_converged);
            }
            let scale = 1.0 + speeds.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let stalled = size >= previous_correction && size <= ROUNDING_PLATEAU * scale;
            if size <= NEWTON_TOLERANCE * scale || stalled {
                return Ok(speeds);
            }
            previous_correction = size;
        }
        let (q, _) = stage.at(kernel, &speeds);
        Err(IntegrationError {
            t: stage.t,
            q,
            cause: Failure::NotConverged {
                iterations: MAX_NEWTON_ITERATIONS,
            },
        })
    }
}

/// The forward-difference step for an entry of size `x`: `√ε max(1, |x|)`.
fn difference_step(x: f64) -> f64 {
    f64::EPSILON.sqrt() * x.abs().max(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tableau_has_order_three() {
        let b = A[2];
        let sum = |f: &dyn Fn(usize) -> f64| (0..3).map(f).sum::<f64>();
        assert!((sum(&|i| b[i]) - 1.0).abs() < 1e-15);
        assert!((sum(&|i| b[i] * C[i]) - 0.5).abs() < 1e-15);
        assert!((sum(&|i| b[i] * C[i] * C[i]) - 1.0 / 3.0).abs() < 1e-15);
        let ac = |i: usize| (0..3).map(|j| A[i][j] * C[j]).sum::<f64>();
        assert!((sum(&|i| b[i] * ac(i)) - 1.0 / 6.0).abs() < 1e-15);
        for i in 0..3 {
            assert!((A[i].iter().sum::<f64>() - C[i]).abs() < 1e-15);
        }
    }
}
