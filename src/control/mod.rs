//! What trajectory optimisation and model-predictive control consume: the
//! exact jacobian of one integration step and its vector–jacobian product.
//!
//! A system differentiates through this module when its model asks for
//! `outputs accelerations_jacobian;` (and, for the adjoints,
//! `inverse_dynamics_adjoint`) and it implements [`Differentiable`] (and
//! [`InverseDifferentiable`]): the [`differentiable!`](crate::differentiable)
//! macro writes both for a generated struct of the calling crate by
//! forwarding to its inherent functions, and [`Differentiated`] pairs any
//! system with those functions (a struct of another crate).
//!
//! * [`step`]: one step of semi-implicit Euler (MuJoCo's default, the step
//!   of Crocoddyl's `IntegratedActionModelEuler`) or of RK4, and its exact
//!   jacobian `∂x⁺/∂x`, `∂x⁺/∂u` for `x = (q, v)` in the tangent space, by
//!   the chain rule through the stages ([`euler_step_jacobian`],
//!   [`rk4_step_jacobian`]);
//! * [`adjoint`]: `λᵀ ∂v̇/∂(q, v, u)` and its step counterparts
//!   ([`euler_step_adjoint`], [`rk4_step_adjoint`]) without forming a
//!   jacobian;
//! * [`rk4_group_step_x4`]: the step of [`rk4_group_step`] from four states at once,
//!   its stages through the system's `accelerations_x4` (SIMD lanes);
//! * [`ConfigurationSpace`]: the product of vector spaces, SO(3) and SE(3)
//!   that the coordinates live in, read from the system's names, with the
//!   derivatives of `q ⊕ w` and the inverse of the update
//!   ([`ConfigurationSpace::difference`]).
//!
//! With constraints, `accelerations` and `accelerations_jacobian` of a
//! generated system are those of the index-1 equations
//! `M v̇ = f + Aᵀ λ`, `A v̇ = b` as functions of the whole state, so both
//! step jacobians hold for a constrained system: they differentiate the
//! step taken without drift stabilisation or projection (what
//! [`euler_step`] and [`rk4_group_step`] take).

pub mod adjoint;
mod batch;
mod differentiated;
pub mod step;
mod tangent;

use std::fmt;

use crate::{DynamicsError, MultibodySystem};

pub use adjoint::{
    AccelerationsAdjoint, InverseDifferentiable, StepAdjoint, accelerations_adjoint,
    euler_step_adjoint, rk4_step_adjoint,
};
pub use batch::rk4_group_step_x4;
pub use differentiated::Differentiated;
pub use step::{StepJacobian, euler_step, euler_step_jacobian, rk4_group_step, rk4_step_jacobian};
pub use tangent::ConfigurationSpace;

/// `∂v̇/∂q` (in the tangent space), `∂v̇/∂v`, `∂v̇/∂u`: entry `[i][j]` the
/// derivative of `v̇ᵢ`.
pub type AccelerationsJacobian<const NV: usize, const NU: usize> =
    ([[f64; NV]; NV], [[f64; NV]; NV], [[f64; NU]; NV]);

/// A system with the exact derivatives of its accelerations: the generated
/// `accelerations_jacobian` of a model asking for it (DESIGN §7), through
/// [`differentiable!`](crate::differentiable).
pub trait Differentiable<const NQ: usize, const NV: usize, const NU: usize>:
    MultibodySystem<NQ, NV, NU>
{
    /// `∂v̇/∂q` in the tangent space (along `q ⊕ δ`), `∂v̇/∂v`, `∂v̇/∂u` at
    /// `(t, q, v, u)`.
    fn accelerations_jacobian(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
        u: &[f64; NU],
    ) -> Result<AccelerationsJacobian<NV, NU>, DynamicsError>;
}

/// Implements [`Differentiable`](crate::control::Differentiable) for
/// generated structs whose model asks for `outputs accelerations_jacobian;`
/// (add `; inverse` after the list for
/// [`InverseDifferentiable`](crate::control::InverseDifferentiable) too, when
/// the model also asks for `inverse_dynamics_adjoint`), by forwarding to
/// their inherent functions:
///
/// ```ignore
/// dalembert::differentiable!(Ur5, CartPole; inverse);
/// ```
#[macro_export]
macro_rules! differentiable {
    ($($system:ty),+ $(,)?) => {$(
        impl $crate::control::Differentiable<{ <$system>::NQ }, { <$system>::NV }, { <$system>::NU }>
            for $system
        {
            #[inline]
            fn accelerations_jacobian(
                &self,
                t: f64,
                q: &[f64; <$system>::NQ],
                v: &[f64; <$system>::NV],
                u: &[f64; <$system>::NU],
            ) -> ::core::result::Result<
                $crate::control::AccelerationsJacobian<{ <$system>::NV }, { <$system>::NU }>,
                $crate::DynamicsError,
            > {
                <$system>::accelerations_jacobian(self, t, q, v, u)
            }
        }
    )+};
    ($($system:ty),+ ; inverse) => {
        $crate::differentiable!($($system),+);
        $(
        impl $crate::control::InverseDifferentiable<{ <$system>::NQ }, { <$system>::NV }, { <$system>::NU }>
            for $system
        {
            #[inline]
            fn inverse_dynamics_adjoint(
                &self,
                t: f64,
                q: &[f64; <$system>::NQ],
                v: &[f64; <$system>::NV],
                vdot: &[f64; <$system>::NV],
                u: &[f64; <$system>::NU],
                mu: &[f64; <$system>::NV],
            ) -> $crate::control::adjoint::InverseDynamicsAdjoint<{ <$system>::NV }, { <$system>::NU }> {
                <$system>::inverse_dynamics_adjoint(self, t, q, v, vdot, u, mu)
            }
        }
    )+};
}

/// Why a step or its derivatives could not be computed.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum ControlError {
    /// The accelerations or their derivatives failed at a stage.
    Dynamics(DynamicsError),
    /// The speed `speed` is neither a coordinate's rate (`dt(x)`) nor one of
    /// a spherical or free joint's: the coordinates of a `speeds` statement
    /// have no group update whose derivatives this module knows.
    UnsupportedSpeed {
        /// The speed's name.
        speed: &'static str,
    },
}

impl From<DynamicsError> for ControlError {
    fn from(cause: DynamicsError) -> Self {
        Self::Dynamics(cause)
    }
}

impl fmt::Display for ControlError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Dynamics(cause) => write!(f, "{cause}"),
            Self::UnsupportedSpeed { speed } => write!(
                f,
                "the speed `{speed}` is neither a coordinate's rate nor a spherical or free \
                 joint's: step derivatives need the group of its coordinates"
            ),
        }
    }
}

impl std::error::Error for ControlError {}

impl<const NQ: usize, const NV: usize> ConfigurationSpace<NQ, NV> {
    /// The space of `system`, from its coordinate and speed names
    /// ([`ConfigurationSpace::from_names`]).
    pub fn of<S, const NU: usize>(_system: &S) -> Result<Self, ControlError>
    where
        S: MultibodySystem<NQ, NV, NU>,
    {
        Self::from_names(&S::COORDINATES, &S::SPEEDS)
    }
}
