//! [`Differentiated`]: a system paired with its generated derivative
//! functions, for a system whose struct lives in another crate (where
//! [`differentiable!`](crate::differentiable) cannot implement this crate's
//! traits for it).

use super::adjoint::InverseDynamicsAdjoint;
use super::{AccelerationsJacobian, Differentiable, InverseDifferentiable};
use crate::{DynamicsError, MultibodySystem};

/// `system` with its `accelerations_jacobian` (and, for the adjoints, its
/// `inverse_dynamics_adjoint`) passed as functions:
///
/// ```ignore
/// let ur5 = Differentiated::new(&Ur5 {}, Ur5::accelerations_jacobian)
///     .with_inverse(Ur5::inverse_dynamics_adjoint);
/// let (next, jacobian) = dalembert::control::euler_step_jacobian(&ur5, &state, &u, 0.01)?;
/// ```
///
/// It is the system everywhere else too: every function of
/// [`MultibodySystem`] forwards to `system`.
#[derive(Clone, Copy, Debug)]
pub struct Differentiated<'a, S, J, I = ()> {
    /// The system.
    pub system: &'a S,
    /// Its `accelerations_jacobian(&system, t, q, v, u)`.
    pub accelerations_jacobian: J,
    /// Its `inverse_dynamics_adjoint(&system, t, q, v, v̇, u, μ)`, or `()`.
    pub inverse_dynamics_adjoint: I,
}

impl<'a, S, J> Differentiated<'a, S, J> {
    /// `system` with its `accelerations_jacobian`.
    pub fn new(system: &'a S, accelerations_jacobian: J) -> Self {
        Self {
            system,
            accelerations_jacobian,
            inverse_dynamics_adjoint: (),
        }
    }

    /// The same with its `inverse_dynamics_adjoint` too.
    pub fn with_inverse<I>(self, inverse_dynamics_adjoint: I) -> Differentiated<'a, S, J, I> {
        Differentiated {
            system: self.system,
            accelerations_jacobian: self.accelerations_jacobian,
            inverse_dynamics_adjoint,
        }
    }
}

impl<S, J, I, const NQ: usize, const NV: usize, const NU: usize> MultibodySystem<NQ, NV, NU>
    for Differentiated<'_, S, J, I>
where
    S: MultibodySystem<NQ, NV, NU>,
{
    const COORDINATES: [&'static str; NQ] = S::COORDINATES;
    const SPEEDS: [&'static str; NV] = S::SPEEDS;
    const INPUTS: [&'static str; NU] = S::INPUTS;
    const TIME_DEPENDENT: bool = S::TIME_DEPENDENT;

    #[inline]
    fn mass_matrix(&self, q: &[f64; NQ]) -> [[f64; NV]; NV] {
        self.system.mass_matrix(q)
    }

    #[inline]
    fn mass_matrix_at(&self, t: f64, q: &[f64; NQ]) -> [[f64; NV]; NV] {
        self.system.mass_matrix_at(t, q)
    }

    #[inline]
    fn forcing(&self, t: f64, q: &[f64; NQ], v: &[f64; NV], u: &[f64; NU]) -> [f64; NV] {
        self.system.forcing(t, q, v, u)
    }

    #[inline]
    fn kinetic_energy(&self, q: &[f64; NQ], v: &[f64; NV]) -> f64 {
        self.system.kinetic_energy(q, v)
    }

    #[inline]
    fn kinetic_energy_at(&self, t: f64, q: &[f64; NQ], v: &[f64; NV]) -> f64 {
        self.system.kinetic_energy_at(t, q, v)
    }

    #[inline]
    fn potential_energy(&self, q: &[f64; NQ]) -> f64 {
        self.system.potential_energy(q)
    }

    #[inline]
    fn potential_energy_at(&self, t: f64, q: &[f64; NQ]) -> f64 {
        self.system.potential_energy_at(t, q)
    }

    #[inline]
    fn coordinate_rates(&self, q: &[f64; NQ], v: &[f64; NV]) -> [f64; NQ] {
        self.system.coordinate_rates(q, v)
    }

    #[inline]
    fn integrate_configuration(&self, q: &[f64; NQ], v: &[f64; NV], h: f64) -> [f64; NQ] {
        self.system.integrate_configuration(q, v, h)
    }

    #[inline]
    fn check_coordinate_rates(&self, q: &[f64; NQ]) -> Result<(), DynamicsError> {
        self.system.check_coordinate_rates(q)
    }

    #[inline]
    fn accelerations(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
        u: &[f64; NU],
    ) -> Result<[f64; NV], DynamicsError> {
        self.system.accelerations(t, q, v, u)
    }
}

impl<S, J, I, const NQ: usize, const NV: usize, const NU: usize> Differentiable<NQ, NV, NU>
    for Differentiated<'_, S, J, I>
where
    S: MultibodySystem<NQ, NV, NU>,
    J: Fn(
        &S,
        f64,
        &[f64; NQ],
        &[f64; NV],
        &[f64; NU],
    ) -> Result<AccelerationsJacobian<NV, NU>, DynamicsError>,
{
    #[inline]
    fn accelerations_jacobian(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
        u: &[f64; NU],
    ) -> Result<AccelerationsJacobian<NV, NU>, DynamicsError> {
        (self.accelerations_jacobian)(self.system, t, q, v, u)
    }
}

impl<S, J, I, const NQ: usize, const NV: usize, const NU: usize> InverseDifferentiable<NQ, NV, NU>
    for Differentiated<'_, S, J, I>
where
    S: MultibodySystem<NQ, NV, NU>,
    J: Fn(
        &S,
        f64,
        &[f64; NQ],
        &[f64; NV],
        &[f64; NU],
    ) -> Result<AccelerationsJacobian<NV, NU>, DynamicsError>,
    I: Fn(
        &S,
        f64,
        &[f64; NQ],
        &[f64; NV],
        &[f64; NV],
        &[f64; NU],
        &[f64; NV],
    ) -> InverseDynamicsAdjoint<NV, NU>,
{
    #[inline]
    fn inverse_dynamics_adjoint(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
        vdot: &[f64; NV],
        u: &[f64; NU],
        mu: &[f64; NV],
    ) -> InverseDynamicsAdjoint<NV, NU> {
        (self.inverse_dynamics_adjoint)(self.system, t, q, v, vdot, u, mu)
    }
}
