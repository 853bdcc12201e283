//! The Taylor series of a constrained motion, order by order: what a
//! generated `taylor_coefficients` calls for a system with constraints.
//!
//! Expanding `M v̇ − Aᵀ λ = f`, `A v̇ = b` in the time, order `k` is the
//! saddle-point system of the expansion point with the lower orders moved
//! to the right:
//! `M₀ v̇ₖ − A₀ᵀ λₖ = fₖ − Σⱼ₌₁ᵏ (Mⱼ v̇ₖ₋ⱼ − Aⱼᵀ λₖ₋ⱼ)`,
//! `A₀ v̇ₖ = bₖ − Σⱼ₌₁ᵏ Aⱼ v̇ₖ₋ⱼ`. Every order is solved with the one
//! factorisation of `M₀` and `A₀` that [`constrained_accelerations`]
//! makes (the default [`ConstraintSolver`]).
//!
//! [`constrained_accelerations`]: super::constrained_accelerations

use nalgebra::SVector;

use super::multipliers::{ConstraintMetric, ConstraintSolver, Dependents, SaddlePoint};
use crate::{ConstrainedSystem, DynamicsError};

/// The saddle-point system of the expansion point, factorised: it solves
/// the orders `k ≥ 1` of the accelerations and multipliers.
#[derive(Clone, Copy)]
pub struct SeriesSolver<'a, const NV: usize, const NC: usize> {
    metric: ConstraintMetric<'a, NV, NC>,
}

impl<const NV: usize, const NC: usize> SeriesSolver<'_, NV, NC> {
    /// `v̇ₖ` and `λₖ` from the right-hand sides of order `k`: the
    /// independent rows held exactly, the dependent ones (checked at order
    /// 0, whose derivatives these are) taken in the least-squares sense,
    /// `λₖ` the least-norm one. Not checked for finiteness (the integrator
    /// checks the state it sums).
    #[inline]
    pub fn solve(
        &self,
        forcing: [f64; NV],
        bias: [f64; NC],
    ) -> Result<([f64; NV], [f64; NC]), DynamicsError> {
        let (f, b) = (SVector::from(forcing), SVector::from(bias));
        self.metric
            .solve(&f, &b, Dependents::LeastSquares)
            .map(|(vdot, lambda)| (vdot.into(), lambda.into()))
    }
}

/// Order 0 of the accelerations and multipliers of `equations`, the
/// saddle-point system of `system` at `(t, q)`, solved as
/// [`constrained_accelerations`](super::constrained_accelerations) solves
/// it (with its errors), then `orders` with them and the factorised system
/// for the higher orders.
pub fn constrained_series<
    S,
    R,
    const NQ: usize,
    const NV: usize,
    const NU: usize,
    const NC: usize,
>(
    system: &S,
    t: f64,
    q: &[f64; NQ],
    equations: SaddlePoint<'_, NV, NC>,
    orders: impl FnOnce(([f64; NV], [f64; NC]), SeriesSolver<'_, NV, NC>) -> Result<R, DynamicsError>,
) -> Result<R, DynamicsError>
where
    S: ConstrainedSystem<NQ, NV, NU, NC>,
{
    ConstraintSolver::default().solve_saddle_point(system, t, q, equations, |solution, metric| {
        orders(solution, SeriesSolver { metric })
    })
}
