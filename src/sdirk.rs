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
//! short and allocation-free: each stage is one `NQ × NQ` Newton system in
//! the stage speeds `V` (the coordinates follow as `Q = Q̂ + hγ V`), with the
//! matrix `I − hγ ∂q̈/∂q̇ − (hγ)² ∂q̈/∂q` built once per step from a
//! forward-difference Jacobian (`2 NQ` evaluations) and factored on the
//! stack (by our own partial-pivoting LU: nalgebra's `LU` needs a typenum
//! dimension, not a const generic). The stage slopes are recovered from the stage equations, not by
//! evaluating the right-hand side again, so stiff components are damped,
//! not amplified.

use crate::equations::Counted;
use crate::integrate::Rate;
use crate::{DynamicsError, Equations, Solution, SolverError, SolverFailure, State};

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
/// Newton iterations allowed per stage (the Jacobian is that of the step's
/// start, so the convergence is linear, not quadratic).
const MAX_NEWTON_ITERATIONS: usize = 25;
/// A Newton correction below this fraction of the stage speeds' size ends
/// the iteration.
const NEWTON_TOLERANCE: f64 = 1e-12;
/// Once the iteration stops contracting, a correction up to this fraction of
/// the stage speeds' size is rounding, not divergence.
const ROUNDING_PLATEAU: f64 = 1e-9;

/// Integrates `steps` fixed steps of length `h` of `equations` from
/// `initial` with the L-stable SDIRK method, and returns the final state with
/// the work done.
///
/// `observer` sees the initial state and then the state after every step
/// (after the equations' [`settle`](Equations::settle)). Allocates nothing.
/// Stops at the first evaluation that fails, or with
/// [`SolverFailure::NotConverged`] when the Newton iteration of a stage does
/// not converge.
pub fn simulate_sdirk<E, const NQ: usize>(
    equations: &E,
    initial: State<NQ>,
    h: f64,
    steps: u64,
    observer: impl FnMut(&State<NQ>),
) -> Result<Solution<NQ>, SolverError<NQ>>
where
    E: Equations<NQ>,
{
    let counted = Counted::new(equations);
    let acceleration = counted.acceleration();
    let step = |state: &State<NQ>| sdirk_step(&acceleration, state, h);
    counted.fixed_steps(initial, steps, step, observer)
}

/// One SDIRK step of length `h` from `state`.
fn sdirk_step<const NQ: usize>(
    acceleration: &impl Fn(f64, &[f64; NQ], &[f64; NQ]) -> Result<[f64; NQ], DynamicsError>,
    state: &State<NQ>,
    h: f64,
) -> Result<State<NQ>, SolverError<NQ>> {
    let hg = h * GAMMA;
    let newton = NewtonMatrix::at(acceleration, state, hg)?;
    let mut stages = [Rate::ZERO; 3];
    let mut speeds = state.qd;
    for i in 0..3 {
        let explicit = Rate::combination(&A[i], &stages).stage(state, h, C[i]);
        speeds = newton.solve_stage(acceleration, &explicit, hg, speeds)?;
        stages[i] = Rate {
            dq: speeds,
            dqd: std::array::from_fn(|k| (speeds[k] - explicit.qd[k]) / hg),
        };
    }
    Ok(Rate::combination(&A[2], &stages).advance(state, h))
}

/// The factored Newton matrix `I − hγ ∂q̈/∂q̇ − (hγ)² ∂q̈/∂q` of a step.
struct NewtonMatrix<const NQ: usize> {
    lu: Lu<NQ>,
}

impl<const NQ: usize> NewtonMatrix<NQ> {
    /// The matrix at `state` from a forward-difference Jacobian of the
    /// accelerations (`2 NQ + 1` evaluations).
    fn at(
        acceleration: &impl Fn(f64, &[f64; NQ], &[f64; NQ]) -> Result<[f64; NQ], DynamicsError>,
        state: &State<NQ>,
        hg: f64,
    ) -> Result<Self, SolverError<NQ>> {
        let State { t, q, qd } = *state;
        let failed = |cause| SolverError::at(state, SolverFailure::Dynamics(cause));
        let base = acceleration(t, &q, &qd).map_err(failed)?;
        let mut matrix: [[f64; NQ]; NQ] =
            std::array::from_fn(|i| std::array::from_fn(|j| f64::from(u8::from(i == j))));
        for j in 0..NQ {
            let dq = difference_step(q[j]);
            let mut shifted = q;
            shifted[j] += dq;
            let by_q = acceleration(t, &shifted, &qd).map_err(failed)?;
            let dv = difference_step(qd[j]);
            let mut shifted = qd;
            shifted[j] += dv;
            let by_qd = acceleration(t, &q, &shifted).map_err(failed)?;
            for i in 0..NQ {
                let d_dq = (by_q[i] - base[i]) / dq;
                let d_dqd = (by_qd[i] - base[i]) / dv;
                matrix[i][j] -= hg * d_dqd + hg * hg * d_dq;
            }
        }
        Ok(Self {
            lu: Lu::factor(matrix),
        })
    }

    /// The stage speeds `V` with `V = V̂ + hγ q̈(t, Q̂ + hγ V, V)`, where
    /// `explicit` holds the stage time and the explicit parts `Q̂`, `V̂`, by
    /// simplified Newton iteration from `guess`.
    fn solve_stage(
        &self,
        acceleration: &impl Fn(f64, &[f64; NQ], &[f64; NQ]) -> Result<[f64; NQ], DynamicsError>,
        explicit: &State<NQ>,
        hg: f64,
        guess: [f64; NQ],
    ) -> Result<[f64; NQ], SolverError<NQ>> {
        let mut speeds = guess;
        let mut previous_correction = f64::INFINITY;
        for iteration in 1..=MAX_NEWTON_ITERATIONS {
            let q = std::array::from_fn(|k| explicit.q[k] + hg * speeds[k]);
            let qdd = acceleration(explicit.t, &q, &speeds).map_err(|cause| SolverError {
                t: explicit.t,
                q,
                cause: SolverFailure::Dynamics(cause),
            })?;
            let residual = std::array::from_fn(|k| speeds[k] - explicit.qd[k] - hg * qdd[k]);
            let not_converged = SolverError {
                t: explicit.t,
                q,
                cause: SolverFailure::NotConverged {
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
        let q = std::array::from_fn(|k| explicit.q[k] + hg * speeds[k]);
        Err(SolverError {
            t: explicit.t,
            q,
            cause: SolverFailure::NotConverged {
                iterations: MAX_NEWTON_ITERATIONS,
            },
        })
    }
}

/// An LU factorisation with partial pivoting, `P A = L U`, on the stack.
struct Lu<const N: usize> {
    /// `L` below the diagonal (unit diagonal implied) and `U` on and above.
    factors: [[f64; N]; N],
    /// Row `i` of `P A` is row `rows[i]` of `A`.
    rows: [usize; N],
    /// Whether a pivot was zero or not finite.
    singular: bool,
}

impl<const N: usize> Lu<N> {
    /// Factors `matrix`.
    fn factor(mut matrix: [[f64; N]; N]) -> Self {
        let mut rows = std::array::from_fn(|i| i);
        let mut singular = false;
        for k in 0..N {
            let pivot = (k..N)
                .max_by(|&a, &b| matrix[a][k].abs().total_cmp(&matrix[b][k].abs()))
                .unwrap_or(k);
            matrix.swap(k, pivot);
            rows.swap(k, pivot);
            let diagonal = matrix[k][k];
            if diagonal == 0.0 || !diagonal.is_finite() {
                singular = true;
                continue;
            }
            let (upper, lower) = matrix.split_at_mut(k + 1);
            let pivot_row = &upper[k];
            for row in lower {
                let factor = row[k] / diagonal;
                row[k] = factor;
                for (entry, pivot) in row[k + 1..].iter_mut().zip(&pivot_row[k + 1..]) {
                    *entry -= factor * pivot;
                }
            }
        }
        Self {
            factors: matrix,
            rows,
            singular,
        }
    }

    /// `x` with `A x = b`, or `None` if `A` is singular.
    fn solve(&self, b: &[f64; N]) -> Option<[f64; N]> {
        if self.singular {
            return None;
        }
        let mut x: [f64; N] = std::array::from_fn(|i| b[self.rows[i]]);
        for i in 0..N {
            for j in 0..i {
                x[i] -= self.factors[i][j] * x[j];
            }
        }
        for i in (0..N).rev() {
            for j in i + 1..N {
                x[i] -= self.factors[i][j] * x[j];
            }
            x[i] /= self.factors[i][i];
        }
        Some(x)
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
    fn lu_solves_a_system_that_needs_pivoting_and_reports_a_singular_one() {
        let lu = Lu::factor([[0.0, 2.0, 1.0], [1.0, 1.0, 0.0], [3.0, 0.0, 1.0]]);
        let x = lu.solve(&[4.5, 3.0, 6.0]).unwrap();
        for (got, want) in x.iter().zip([1.5, 1.5, 1.5]) {
            assert!((got - want).abs() < 1e-14, "{x:?}");
        }
        assert_eq!(
            Lu::factor([[1.0, 2.0], [2.0, 4.0]]).solve(&[1.0, 1.0]),
            None
        );
    }

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
