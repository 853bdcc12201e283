//! Vector–jacobian products: `λᵀ ∂v̇/∂(q, v, u)` without forming the
//! jacobian, and the step counterparts `λ⁺ᵀ ∂x⁺/∂(x, u)` of semi-implicit
//! Euler and RK4, for gradient methods and long horizons.
//!
//! Differentiating `τ(q, v, v̇(q, v, u), u) = 0`, with `τ = M v̇ − f` the
//! inverse dynamics, gives `∂v̇/∂x = −M⁻¹ ∂τ/∂x`, so
//! `λᵀ ∂v̇/∂x = −μᵀ ∂τ/∂x` with `μ = M⁻¹ λ` (`M` is symmetric): one solve
//! with `M` (the runtime's Cholesky factorisation) where the jacobian takes
//! one per column, then the generated `inverse_dynamics_adjoint` (the model
//! asks for it), the gradient of `μᵀ τ` by one reverse sweep over `τ`:
//! `O(n)` on a tree, whose `τ` is the Newton–Euler recursion, where
//! `∂τ/∂x` has `2n²` entries. It is exact by the inputs too (`∂τ/∂u`
//! is differentiated like the rest, however the inputs enter).
//!
//! `inverse_dynamics_adjoint` is that of the unconstrained equations, and
//! the code generator refuses it for a model with constraints: these
//! products are for systems without constraints (the step jacobians of
//! [`step`](super::step) hold with constraints).

use super::step::{NODES, WEIGHTS};
use super::{ConfigurationSpace, ControlError, Differentiable};
use crate::dynamics::factor_mass_matrix;
use crate::{DynamicsError, State};

/// `(μᵀ ∂τ/∂q, μᵀ ∂τ/∂v, μᵀ ∂τ/∂u)`, `∂τ/∂q` in the tangent space.
pub type InverseDynamicsAdjoint<const NV: usize, const NU: usize> =
    ([f64; NV], [f64; NV], [f64; NU]);

/// A system whose model also asks for `inverse_dynamics_adjoint`, through
/// [`differentiable!`](crate::differentiable) with `; inverse`.
pub trait InverseDifferentiable<const NQ: usize, const NV: usize, const NU: usize>:
    Differentiable<NQ, NV, NU>
{
    /// `(μᵀ ∂τ/∂q, μᵀ ∂τ/∂v, μᵀ ∂τ/∂u)` of `τ = M v̇ − f` at
    /// `(t, q, v, v̇, u)` and weights `mu`, `∂τ/∂q` in the tangent space.
    fn inverse_dynamics_adjoint(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
        vdot: &[f64; NV],
        u: &[f64; NU],
        mu: &[f64; NV],
    ) -> InverseDynamicsAdjoint<NV, NU>;
}

/// `λᵀ ∂v̇/∂q` (in the tangent space), `λᵀ ∂v̇/∂v`, `λᵀ ∂v̇/∂u`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AccelerationsAdjoint<const NV: usize, const NU: usize> {
    /// `λᵀ ∂v̇/∂q`.
    pub by_q: [f64; NV],
    /// `λᵀ ∂v̇/∂v`.
    pub by_v: [f64; NV],
    /// `λᵀ ∂v̇/∂u`.
    pub by_u: [f64; NU],
}

/// `M⁻¹ λ` by the runtime's Cholesky factorisation of `M`, or the error
/// naming the speed whose pivot is not safely positive.
fn solve<const NV: usize>(
    mass: &[[f64; NV]; NV],
    lambda: &[f64; NV],
    speeds: &[&'static str; NV],
) -> Result<[f64; NV], DynamicsError> {
    let factor = factor_mass_matrix(mass, speeds)?;
    let x = factor.solve(&nalgebra::SVector::<f64, NV>::from_column_slice(lambda));
    Ok(std::array::from_fn(|i| x[i]))
}

/// `λᵀ ∂v̇/∂(q, v, u)` at `(t, q, v, u)` whose accelerations are `vdot`:
/// `−μᵀ ∂τ/∂(q, v, u)` at `μ = M⁻¹ λ`.
fn adjoint_at<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    (t, q, v, u): (f64, &[f64; NQ], &[f64; NV], &[f64; NU]),
    vdot: &[f64; NV],
    lambda: &[f64; NV],
) -> Result<AccelerationsAdjoint<NV, NU>, ControlError>
where
    S: InverseDifferentiable<NQ, NV, NU>,
{
    let mu = solve(&system.mass_matrix_at(t, q), lambda, &S::SPEEDS)?;
    let (by_q, by_v, by_u) = system.inverse_dynamics_adjoint(t, q, v, vdot, u, &mu);
    Ok(AccelerationsAdjoint {
        by_q: by_q.map(|x| -x),
        by_v: by_v.map(|x| -x),
        by_u: by_u.map(|x| -x),
    })
}

/// The accelerations `v̇` at `(t, q, v, u)` and `λᵀ ∂v̇/∂(q, v, u)`, by one
/// solve with `M` (see the module's docs for the route and its limits).
/// Errors: those of the system's `accelerations`, and a mass matrix that is
/// not safely positive definite.
pub fn accelerations_adjoint<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    t: f64,
    q: &[f64; NQ],
    v: &[f64; NV],
    u: &[f64; NU],
    lambda: &[f64; NV],
) -> Result<([f64; NV], AccelerationsAdjoint<NV, NU>), ControlError>
where
    S: InverseDifferentiable<NQ, NV, NU>,
{
    let vdot = system.accelerations(t, q, v, u)?;
    Ok((vdot, adjoint_at(system, (t, q, v, u), &vdot, lambda)?))
}

/// The cotangent of a step: `λᵀ ∂x⁺/∂q`, `λᵀ ∂x⁺/∂v`, `λᵀ ∂x⁺/∂u` for
/// `λ = (λ_q, λ_v)` at `x⁺`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepAdjoint<const NV: usize, const NU: usize> {
    /// `λᵀ ∂x⁺/∂q`, in the tangent space.
    pub by_q: [f64; NV],
    /// `λᵀ ∂x⁺/∂v`.
    pub by_v: [f64; NV],
    /// `λᵀ ∂x⁺/∂u`.
    pub by_u: [f64; NU],
}

/// The step of [`euler_step`](super::euler_step) (the same operations) and
/// `λ_qᵀ ∂q⁺/∂(x, u) + λ_vᵀ ∂v⁺/∂(x, u)`, by the reverse of its chain
/// rule: `ξ = λ_v + h (∂(q ⊕ w)/∂w)ᵀ λ_q` at `w = h v⁺`, then
/// `(∂(q ⊕ w)/∂q)ᵀ λ_q + h ξᵀ ∂v̇/∂q`, `ξ + h ξᵀ ∂v̇/∂v`, `h ξᵀ ∂v̇/∂u`
/// with one [`accelerations_adjoint`]. Errors: those of
/// [`accelerations_adjoint`] and [`ControlError::UnsupportedSpeed`].
pub fn euler_step_adjoint<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    state: &State<NQ, NV>,
    u: &[f64; NU],
    h: f64,
    lambda_q: &[f64; NV],
    lambda_v: &[f64; NV],
) -> Result<(State<NQ, NV>, StepAdjoint<NV, NU>), ControlError>
where
    S: InverseDifferentiable<NQ, NV, NU>,
{
    let space = ConfigurationSpace::of(system)?;
    let State { t, q, v } = state;
    let vdot = system.accelerations(*t, q, v, u)?;
    let next_v: [f64; NV] = std::array::from_fn(|i| v[i] + h * vdot[i]);
    let next = State {
        t: t + h,
        q: system.integrate_configuration(q, &next_v, h),
        v: next_v,
    };
    let derivatives = space.update_derivatives(&next.v.map(|x| h * x));
    let (mut by_q, mut through_w) = (*lambda_q, *lambda_q);
    derivatives.by_configuration_transposed(&mut by_q);
    derivatives.by_step_transposed(&mut through_w);
    let xi: [f64; NV] = std::array::from_fn(|i| lambda_v[i] + h * through_w[i]);
    let weight = xi.map(|x| h * x);
    let a = adjoint_at(system, (*t, q, v, u), &vdot, &weight)?;
    Ok((
        next,
        StepAdjoint {
            by_q: std::array::from_fn(|i| by_q[i] + a.by_q[i]),
            by_v: std::array::from_fn(|i| xi[i] + a.by_v[i]),
            by_u: a.by_u,
        },
    ))
}

/// `x + s y`.
fn plus<const N: usize>(x: &[f64; N], s: f64, y: &[f64; N]) -> [f64; N] {
    std::array::from_fn(|i| x[i] + s * y[i])
}

/// The step of [`rk4_group_step`](super::rk4_group_step) (the same operations) and
/// `λ_qᵀ ∂q⁺/∂(x, u) + λ_vᵀ ∂v⁺/∂(x, u)`, by the reverse of the chain rule
/// through its four stages: the stages forward, then from the last to the
/// first one [`accelerations_adjoint`] each, the cotangents of each stage's
/// `qᵢ = q ⊕ cᵢ h vᵢ₋₁` and `vᵢ = v + cᵢ h v̇ᵢ₋₁` sent back through the
/// transposed derivatives of the update. Errors: those of
/// [`accelerations_adjoint`] and [`ControlError::UnsupportedSpeed`].
pub fn rk4_step_adjoint<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    state: &State<NQ, NV>,
    u: &[f64; NU],
    h: f64,
    lambda_q: &[f64; NV],
    lambda_v: &[f64; NV],
) -> Result<(State<NQ, NV>, StepAdjoint<NV, NU>), ControlError>
where
    S: InverseDifferentiable<NQ, NV, NU>,
{
    let space = ConfigurationSpace::of(system)?;
    let State { t, q, v } = state;
    // Forward: the stages' times, configurations, speeds and accelerations.
    let mut stages = [(0.0, *q, *v, [0.0; NV]); 4];
    let (mut sum_v, mut sum_a) = ([0.0; NV], [0.0; NV]);
    for i in 0..4 {
        let c = if i == 0 { 0.0 } else { NODES[i - 1] };
        let (_, qi, vi, _) = stages[i];
        let a = system.accelerations(t + c * h, &qi, &vi, u)?;
        stages[i] = (t + c * h, qi, vi, a);
        sum_v = plus(&sum_v, WEIGHTS[i], &vi);
        sum_a = plus(&sum_a, WEIGHTS[i], &a);
        if let Some(&next) = NODES.get(i) {
            stages[i + 1] = (
                0.0,
                system.integrate_configuration(q, &vi, next * h),
                plus(v, next * h, &a),
                [0.0; NV],
            );
        }
    }
    let next = State {
        t: t + h,
        q: system.integrate_configuration(q, &sum_v, h),
        v: plus(v, h, &sum_a),
    };
    // Reverse: `by_q`, `by_v`, `by_u` of the start; the cotangents of each
    // stage's speeds and accelerations as they are completed.
    let final_update = space.update_derivatives(&sum_v.map(|x| h * x));
    let (mut by_q, mut through_w) = (*lambda_q, *lambda_q);
    final_update.by_configuration_transposed(&mut by_q);
    final_update.by_step_transposed(&mut through_w);
    let mut by_v = *lambda_v;
    let mut by_u = [0.0; NU];
    let mut speeds: [[f64; NV]; 4] = std::array::from_fn(|i| through_w.map(|x| h * WEIGHTS[i] * x));
    let mut accelerations: [[f64; NV]; 4] =
        std::array::from_fn(|i| lambda_v.map(|x| h * WEIGHTS[i] * x));
    for i in (0..4).rev() {
        let (ti, qi, vi, a) = &stages[i];
        let adjoint = adjoint_at(system, (*ti, qi, vi, u), a, &accelerations[i])?;
        by_u = plus(&by_u, 1.0, &adjoint.by_u);
        let stage_q = adjoint.by_q;
        let stage_v = plus(&speeds[i], 1.0, &adjoint.by_v);
        by_v = plus(&by_v, 1.0, &stage_v);
        if i == 0 {
            by_q = plus(&by_q, 1.0, &stage_q);
        } else {
            // `vᵢ = v + cᵢ h v̇ᵢ₋₁` and `qᵢ = q ⊕ cᵢ h vᵢ₋₁`.
            let step = NODES[i - 1] * h;
            accelerations[i - 1] = plus(&accelerations[i - 1], step, &stage_v);
            let update = space.update_derivatives(&stages[i - 1].2.map(|x| step * x));
            let (mut to_q, mut to_w) = (stage_q, stage_q);
            update.by_configuration_transposed(&mut to_q);
            update.by_step_transposed(&mut to_w);
            by_q = plus(&by_q, 1.0, &to_q);
            speeds[i - 1] = plus(&speeds[i - 1], step, &to_w);
        }
    }
    Ok((next, StepAdjoint { by_q, by_v, by_u }))
}
