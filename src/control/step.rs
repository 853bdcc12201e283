//! One integration step `x⁺ = Φ(x, u)` of `x = (q, v)` with the inputs
//! held, and its exact jacobian in the tangent space, by the chain rule
//! through the stages with the system's `accelerations_jacobian` and the
//! derivatives of the configuration update `q ⊕ w`.
//!
//! * Semi-implicit Euler (MuJoCo's default step; Crocoddyl's
//!   `IntegratedActionModelEuler`): `v⁺ = v + h v̇(q, v, u)`,
//!   `q⁺ = q ⊕ h v⁺`.
//! * RK4, each stage moved by the group update from the step's start:
//!   `qᵢ = q ⊕ cᵢ h vᵢ₋₁`, `vᵢ = v + cᵢ h v̇ᵢ₋₁` (`c = ½, ½, 1`), and
//!   `q⁺ = q ⊕ (h/6)(v₁ + 2v₂ + 2v₃ + v₄)`,
//!   `v⁺ = v + (h/6)(v̇₁ + 2v̇₂ + 2v̇₃ + v̇₄)` (Crocoddyl's
//!   `IntegratedActionModelRK4`). Where every speed is its coordinate's
//!   rate this is the classical method of
//!   [`integrate::Rk4::step`](crate::integrate::Rk4::step), operation for
//!   operation; on a quaternion joint that integrator moves `q` along
//!   `q̇ = N(q) v` in the quaternion's four numbers instead (fourth order
//!   on the group, where this step is second order in the rotation), a map
//!   whose derivative by a point off the unit sphere the generated code
//!   does not give.
//!
//! In the tangent space, a perturbation `δq` of the configuration means
//! `q ⊕ δq` (DESIGN §7) and that of `q⁺` is read the same way at `q⁺`.
//! The stage `i` carries the sensitivities of its `qᵢ`, `vᵢ` and `v̇ᵢ` to
//! `(δq, δv, δu)`: `δv̇ᵢ = ∂v̇/∂q δqᵢ + ∂v̇/∂v δvᵢ + ∂v̇/∂u δu`, and
//! `δ(q ⊕ w) = ∂(q ⊕ w)/∂q δq + ∂(q ⊕ w)/∂w δw` with the group's
//! derivatives ([`ConfigurationSpace`]).

use super::tangent::UpdateDerivatives;
use super::{AccelerationsJacobian, ConfigurationSpace, ControlError, Differentiable};
use crate::{MultibodySystem, State};

/// The jacobian of a step `x⁺ = Φ(x, u)`, `x = (q, v)`, in blocks: entry
/// `[i][j]` of `q_by_v` is `∂q⁺ᵢ/∂vⱼ`, and so on; `q` and `q⁺` in the
/// tangent space (one row or column per speed). The state-space matrices
/// are `[[q_by_q, q_by_v], [v_by_q, v_by_v]]` and `[[q_by_u], [v_by_u]]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepJacobian<const NV: usize, const NU: usize> {
    /// `∂q⁺/∂q`.
    pub q_by_q: [[f64; NV]; NV],
    /// `∂q⁺/∂v`.
    pub q_by_v: [[f64; NV]; NV],
    /// `∂q⁺/∂u`.
    pub q_by_u: [[f64; NU]; NV],
    /// `∂v⁺/∂q`.
    pub v_by_q: [[f64; NV]; NV],
    /// `∂v⁺/∂v`.
    pub v_by_v: [[f64; NV]; NV],
    /// `∂v⁺/∂u`.
    pub v_by_u: [[f64; NU]; NV],
}

/// The derivatives of an `NV`-vector of a stage by `(δq, δv, δu)`.
#[derive(Clone, Copy, Debug)]
struct Sensitivity<const NV: usize, const NU: usize> {
    q: [[f64; NV]; NV],
    v: [[f64; NV]; NV],
    u: [[f64; NU]; NV],
}

fn identity<const N: usize>() -> [[f64; N]; N] {
    std::array::from_fn(|i| std::array::from_fn(|j| f64::from(u8::from(i == j))))
}

/// `a · b`.
fn product<const N: usize, const M: usize>(a: &[[f64; N]; N], b: &[[f64; M]; N]) -> [[f64; M]; N] {
    let mut c = [[0.0; M]; N];
    for (c_row, a_row) in c.iter_mut().zip(a) {
        for (&aik, b_row) in a_row.iter().zip(b) {
            for (x, y) in c_row.iter_mut().zip(b_row) {
                *x += aik * y;
            }
        }
    }
    c
}

/// `a += s b`.
fn add_scaled<const N: usize, const M: usize>(a: &mut [[f64; M]; N], s: f64, b: &[[f64; M]; N]) {
    for (a_row, b_row) in a.iter_mut().zip(b) {
        for (x, y) in a_row.iter_mut().zip(b_row) {
            *x += s * y;
        }
    }
}

fn scaled<const N: usize, const M: usize>(s: f64, a: &[[f64; M]; N]) -> [[f64; M]; N] {
    a.map(|row| row.map(|x| s * x))
}

impl<const NV: usize, const NU: usize> Sensitivity<NV, NU> {
    /// `self += s other`.
    fn add_scaled(&mut self, s: f64, other: &Self) {
        add_scaled(&mut self.q, s, &other.q);
        add_scaled(&mut self.v, s, &other.v);
        add_scaled(&mut self.u, s, &other.u);
    }

    /// `s self`.
    fn scaled(&self, s: f64) -> Self {
        Self {
            q: scaled(s, &self.q),
            v: scaled(s, &self.v),
            u: scaled(s, &self.u),
        }
    }

    /// `δv̇ = ∂v̇/∂q δq + ∂v̇/∂v δv + ∂v̇/∂u δu` at a stage whose
    /// configuration and speeds have the sensitivities `q`, `v`.
    fn accelerations(jacobian: &AccelerationsJacobian<NV, NU>, q: &Self, v: &Self) -> Self {
        let (by_q, by_v, by_u) = jacobian;
        let mut a = Self {
            q: product(by_q, &q.q),
            v: product(by_q, &q.v),
            u: product(by_q, &q.u),
        };
        add_scaled(&mut a.q, 1.0, &product(by_v, &v.q));
        add_scaled(&mut a.v, 1.0, &product(by_v, &v.v));
        add_scaled(&mut a.u, 1.0, &product(by_v, &v.u));
        add_scaled(&mut a.u, 1.0, by_u);
        a
    }

    /// The sensitivities of `q ⊕ w` given those of `w`: `∂/∂q · (I, 0, 0)
    /// + ∂/∂w · w`.
    fn update(derivatives: &UpdateDerivatives<NV>, mut w: Self) -> Self {
        let mut by_q = identity();
        derivatives.by_configuration(&mut by_q);
        derivatives.by_step(&mut w.q);
        derivatives.by_step(&mut w.v);
        derivatives.by_step(&mut w.u);
        add_scaled(&mut w.q, 1.0, &by_q);
        w
    }
}

/// The accelerations at `(t, q, v, u)` and, with `differentiate`, their
/// jacobian.
fn stage<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    t: f64,
    q: &[f64; NQ],
    v: &[f64; NV],
    u: &[f64; NU],
) -> Result<([f64; NV], AccelerationsJacobian<NV, NU>), ControlError>
where
    S: Differentiable<NQ, NV, NU>,
{
    let a = system.accelerations(t, q, v, u)?;
    Ok((a, system.accelerations_jacobian(t, q, v, u)?))
}

/// `v + s a`.
pub(super) fn moved<const NV: usize>(v: &[f64; NV], s: f64, a: &[f64; NV]) -> [f64; NV] {
    std::array::from_fn(|i| v[i] + s * a[i])
}

/// One step of semi-implicit Euler from `state` with the inputs `u`:
/// `v⁺ = v + h v̇(t, q, v, u)`, `q⁺ = q ⊕ h v⁺`, at `t + h`. MuJoCo's
/// default step and that of Crocoddyl's `IntegratedActionModelEuler`.
/// Errors: those of the system's `accelerations`.
pub fn euler_step<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    state: &State<NQ, NV>,
    u: &[f64; NU],
    h: f64,
) -> Result<State<NQ, NV>, ControlError>
where
    S: MultibodySystem<NQ, NV, NU>,
{
    let a = system.accelerations(state.t, &state.q, &state.v, u)?;
    let v = moved(&state.v, h, &a);
    Ok(State {
        t: state.t + h,
        q: system.integrate_configuration(&state.q, &v, h),
        v,
    })
}

/// The step of [`euler_step`] and its exact jacobian:
/// `∂v⁺/∂x = (h ∂v̇/∂q, I + h ∂v̇/∂v)`, `∂v⁺/∂u = h ∂v̇/∂u`, and
/// `∂q⁺/∂x = ∂(q ⊕ w)/∂q (I, 0) + h ∂(q ⊕ w)/∂w ∂v⁺/∂x` at `w = h v⁺`.
/// One evaluation of the accelerations and of their jacobian. Errors:
/// those of the system's `accelerations` and `accelerations_jacobian`, and
/// [`ControlError::UnsupportedSpeed`] for a system with a `speeds`
/// statement.
pub fn euler_step_jacobian<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    state: &State<NQ, NV>,
    u: &[f64; NU],
    h: f64,
) -> Result<(State<NQ, NV>, StepJacobian<NV, NU>), ControlError>
where
    S: Differentiable<NQ, NV, NU>,
{
    let space = ConfigurationSpace::of(system)?;
    let State { t, q, v } = state;
    let (a, jacobian) = stage(system, *t, q, v, u)?;
    let (by_q, by_v, by_u) = &jacobian;
    let next_v = moved(v, h, &a);
    let w = next_v.map(|x| h * x);
    let next_q = system.integrate_configuration(q, &next_v, h);
    let mut v_by_v = scaled(h, by_v);
    add_scaled(&mut v_by_v, 1.0, &identity());
    let velocity = Sensitivity {
        q: scaled(h, by_q),
        v: v_by_v,
        u: scaled(h, by_u),
    };
    let configuration = Sensitivity::update(&space.update_derivatives(&w), velocity.scaled(h));
    Ok((
        State {
            t: t + h,
            q: next_q,
            v: next_v,
        },
        joined(&configuration, &velocity),
    ))
}

/// The blocks of a step's jacobian from the sensitivities of `q⁺` and `v⁺`.
fn joined<const NV: usize, const NU: usize>(
    q: &Sensitivity<NV, NU>,
    v: &Sensitivity<NV, NU>,
) -> StepJacobian<NV, NU> {
    StepJacobian {
        q_by_q: q.q,
        q_by_v: q.v,
        q_by_u: q.u,
        v_by_q: v.q,
        v_by_v: v.v,
        v_by_u: v.u,
    }
}

/// The fraction of the step at which each of the first three slopes places
/// the next stage, and the weights of the four.
pub(super) const NODES: [f64; 3] = [0.5, 0.5, 1.0];
pub(super) const WEIGHTS: [f64; 4] = [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0];

/// One RK4 step from `state` with the inputs `u` held, each stage moved by
/// the group update `q ⊕ w` from the step's start (see the module's docs),
/// at `t + h`: the step that [`rk4_step_jacobian`] and
/// [`rk4_step_adjoint`](super::rk4_step_adjoint) differentiate. Where every
/// speed is its coordinate's rate, the same operations as
/// [`integrate::Rk4::step`](crate::integrate::Rk4::step), the integrator's
/// step, which on a quaternion joint integrates `q̇ = N(q) v` in the
/// quaternion's four numbers instead (hence the two names). Errors: those
/// of the system's `accelerations`.
pub fn rk4_group_step<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    state: &State<NQ, NV>,
    u: &[f64; NU],
    h: f64,
) -> Result<State<NQ, NV>, ControlError>
where
    S: MultibodySystem<NQ, NV, NU>,
{
    let State { t, q, v } = state;
    let (mut qi, mut vi) = (*q, *v);
    let (mut sum_v, mut sum_a) = ([0.0; NV], [0.0; NV]);
    for (i, &weight) in WEIGHTS.iter().enumerate() {
        let c = if i == 0 { 0.0 } else { NODES[i - 1] };
        let a = system.accelerations(t + c * h, &qi, &vi, u)?;
        sum_v = moved(&sum_v, weight, &vi);
        sum_a = moved(&sum_a, weight, &a);
        if let Some(&next) = NODES.get(i) {
            qi = system.integrate_configuration(q, &vi, next * h);
            vi = moved(v, next * h, &a);
        }
    }
    Ok(State {
        t: t + h,
        q: system.integrate_configuration(q, &sum_v, h),
        v: moved(v, h, &sum_a),
    })
}

/// The step of [`rk4_group_step`] and its exact jacobian, by the chain rule
/// through the four stages (see the module's docs): four evaluations of the
/// accelerations and of their jacobian. Errors: those of the system's
/// `accelerations` and `accelerations_jacobian`, and
/// [`ControlError::UnsupportedSpeed`] for a system with a `speeds`
/// statement.
pub fn rk4_step_jacobian<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    state: &State<NQ, NV>,
    u: &[f64; NU],
    h: f64,
) -> Result<(State<NQ, NV>, StepJacobian<NV, NU>), ControlError>
where
    S: Differentiable<NQ, NV, NU>,
{
    let space = ConfigurationSpace::of(system)?;
    let State { t, q, v } = state;
    let zero = Sensitivity {
        q: [[0.0; NV]; NV],
        v: [[0.0; NV]; NV],
        u: [[0.0; NU]; NV],
    };
    let start_q = Sensitivity {
        q: identity(),
        ..zero
    };
    let start_v = Sensitivity {
        v: identity(),
        ..zero
    };
    let (mut qi, mut vi) = (*q, *v);
    let (mut dqi, mut dvi) = (start_q, start_v);
    let (mut sum_v, mut sum_a) = ([0.0; NV], [0.0; NV]);
    let (mut d_sum_v, mut d_sum_a) = (zero, zero);
    for (i, &weight) in WEIGHTS.iter().enumerate() {
        let c = if i == 0 { 0.0 } else { NODES[i - 1] };
        let (a, jacobian) = stage(system, t + c * h, &qi, &vi, u)?;
        let da = match i {
            // At the start, `δq₁ = (I, 0, 0)` and `δv₁ = (0, I, 0)`.
            0 => Sensitivity {
                q: jacobian.0,
                v: jacobian.1,
                u: jacobian.2,
            },
            _ => Sensitivity::accelerations(&jacobian, &dqi, &dvi),
        };
        sum_v = moved(&sum_v, weight, &vi);
        sum_a = moved(&sum_a, weight, &a);
        d_sum_v.add_scaled(weight, &dvi);
        d_sum_a.add_scaled(weight, &da);
        if let Some(&next) = NODES.get(i) {
            let w = vi.map(|x| next * h * x);
            qi = system.integrate_configuration(q, &vi, next * h);
            dqi = Sensitivity::update(&space.update_derivatives(&w), dvi.scaled(next * h));
            vi = moved(v, next * h, &a);
            dvi = start_v;
            dvi.add_scaled(next * h, &da);
        }
    }
    let w = sum_v.map(|x| h * x);
    let configuration = Sensitivity::update(&space.update_derivatives(&w), d_sum_v.scaled(h));
    let mut velocity = start_v;
    velocity.add_scaled(h, &d_sum_a);
    Ok((
        State {
            t: t + h,
            q: system.integrate_configuration(q, &sum_v, h),
            v: moved(v, h, &sum_a),
        },
        joined(&configuration, &velocity),
    ))
}
