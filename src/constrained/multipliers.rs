//! The accelerations and Lagrange multipliers of a constrained system, from
//! the saddle-point system `[[M, −Aᵀ], [A, 0]] [q̈; λ] = [f; b]` solved by its
//! Schur complement.

use nalgebra::{Cholesky, Const, SMatrix, SVector};

use crate::ConstrainedSystem;
use crate::DynamicsError;
use crate::dynamics::{all_finite, cholesky, factor_mass_matrix, pivot_names};

/// The constraint Jacobian `A` seen through the metric of the mass matrix
/// `M`, factorised once for several right-hand sides: `Y = M⁻¹ Aᵀ` and the
/// Cholesky factor of the Schur complement `S = A M⁻¹ Aᵀ`.
///
/// It solves every problem of the form "minimise `½ xᵀ M x − fᵀ x` subject to
/// `A x = c`": the accelerations (`f` the forcing, `c = b`) and the
/// M-orthogonal projections onto the constraints (`f = 0`, `c` the residual).
pub(crate) struct ConstraintMetric<'m, const NV: usize, const NC: usize> {
    mass: &'m Cholesky<f64, Const<NV>>,
    jacobian: SMatrix<f64, NC, NV>,
    mass_inverse_jacobian_t: SMatrix<f64, NV, NC>,
    schur: Cholesky<f64, Const<NC>>,
}

impl<'m, const NV: usize, const NC: usize> ConstraintMetric<'m, NV, NC> {
    /// Factorises `S = A M⁻¹ Aᵀ` for the factored mass matrix `mass`; fails
    /// if `A` has a non-finite entry or rows dependent to working precision.
    pub(crate) fn new(
        mass: &'m Cholesky<f64, Const<NV>>,
        jacobian: &[[f64; NV]; NC],
    ) -> Result<Self, DynamicsError> {
        if !jacobian.iter().all(all_finite) {
            return Err(DynamicsError::NonFiniteConstraints);
        }
        let jacobian = SMatrix::<f64, NC, NV>::from_fn(|i, j| jacobian[i][j]);
        let mass_inverse_jacobian_t = mass.solve(&jacobian.transpose());
        let schur = cholesky(jacobian * mass_inverse_jacobian_t).map_err(|pivot| {
            DynamicsError::DependentConstraints {
                row: pivot.index,
                pivot: pivot.value,
            }
        })?;
        Ok(Self {
            mass,
            jacobian,
            mass_inverse_jacobian_t,
            schur,
        })
    }

    /// The `x` and `λ` of `M x = f + Aᵀ λ`, `A x = c`:
    /// `λ = S⁻¹ (c − A M⁻¹ f)` and `x = M⁻¹ f + M⁻¹ Aᵀ λ`.
    pub(crate) fn solve(
        &self,
        f: &SVector<f64, NV>,
        c: &SVector<f64, NC>,
    ) -> (SVector<f64, NV>, SVector<f64, NC>) {
        let unconstrained = self.mass.solve(f);
        let lambda = self.schur.solve(&(c - self.jacobian * unconstrained));
        (
            unconstrained + self.mass_inverse_jacobian_t * lambda,
            lambda,
        )
    }

    /// The smallest correction in the M-norm, `x = M⁻¹ Aᵀ S⁻¹ c`, with
    /// `A x = c`.
    pub(crate) fn least_norm(&self, c: &SVector<f64, NC>) -> SVector<f64, NV> {
        self.mass_inverse_jacobian_t * self.schur.solve(c)
    }
}

/// The accelerations `q̈` and the Lagrange multipliers `λ` that solve
/// `M(q) q̈ = f(t, q, q̇, u) + A(q)ᵀ λ` and `A(q) q̈ = b(t, q, q̇)`.
///
/// Solved by the Schur complement on the stack (nothing is allocated):
/// `M = L Lᵀ`, `S = A M⁻¹ Aᵀ`, `λ = S⁻¹ (b − A M⁻¹ f)`, `q̈ = M⁻¹ (f + Aᵀ λ)`.
/// `λᵢ` is the generalized constraint force of row `i` per unit of its
/// Jacobian row: `Aᵀ λ` is the force that the constraints add to `f`.
///
/// Never returns a non-finite value. Errors: a non-finite state
/// ([`NonFiniteState`](DynamicsError::NonFiniteState)), mass matrix or forcing
/// ([`NonFiniteEquations`](DynamicsError::NonFiniteEquations)) or constraint
/// ([`NonFiniteConstraints`](DynamicsError::NonFiniteConstraints)); a mass
/// matrix that is not safely positive definite
/// ([`SingularMassMatrix`](DynamicsError::SingularMassMatrix): the Schur route
/// needs every coordinate to carry inertia); constraint rows that are
/// linearly dependent at `q`
/// ([`DependentConstraints`](DynamicsError::DependentConstraints): redundant or
/// contradictory constraints, or a singular configuration).
pub fn constrained_accelerations<
    S,
    const NQ: usize,
    const NV: usize,
    const NU: usize,
    const NC: usize,
>(
    system: &S,
    t: f64,
    q: &[f64; NQ],
    v: &[f64; NV],
    u: &[f64; NU],
) -> Result<([f64; NV], [f64; NC]), DynamicsError>
where
    S: ConstrainedSystem<NQ, NV, NU, NC>,
{
    check_state(t, q, v, u)?;
    let bias = system.constraint_bias(t, q, v);
    solve_with_bias(system, t, q, v, u, bias)
}

/// Like [`constrained_accelerations`], with the constraints enforced as
/// Baumgarte's `φ̈ + 2α φ̇ + β² φ = 0` instead of `φ̈ = 0`: the bias `b` is
/// replaced by `b − 2α ψ − β² φ`, where `φ` is the residual and `ψ` the
/// velocity form of the constraints. A drift off the manifold then decays
/// like a damped oscillator instead of growing.
///
/// Nonholonomic rows have `φ = 0` by definition, so they are stabilised at
/// velocity level only: `ψ̇ + 2α ψ = 0`.
///
/// Choosing `α` and `β` (both in 1/s): `α = β` is critical damping, the
/// error then decaying like `e^(−β t)`. Take them about the natural frequency
/// of the motion (`√(3g/2l)` for a swinging bar). Larger gains do not help:
/// they make the stabilising terms dominate the truncation error, and the
/// added eigenvalues `−β` make the equations stiff, so that an explicit
/// method goes unstable once `β h` leaves its stability region (`β h ≳ 2.8`
/// for RK4). Measured on seed example 3 with RK4, `h = 1e-3 s`, over 10 s
/// (`tests/constraints.rs`): max `|φ|` is `2e-10` unstabilised, `2e-12` with
/// `α = β = 3.66/s` (the natural frequency), `1e-9` with `α = β = 100/s`;
/// with `h = 1e-2 s` and `α = β = 300/s` the integration diverges. `α = β =
/// 0` is [`constrained_accelerations`]. The returned `λ` include the
/// stabilising force.
pub fn baumgarte_accelerations<
    S,
    const NQ: usize,
    const NV: usize,
    const NU: usize,
    const NC: usize,
>(
    system: &S,
    t: f64,
    q: &[f64; NQ],
    v: &[f64; NV],
    u: &[f64; NU],
    alpha: f64,
    beta: f64,
) -> Result<([f64; NV], [f64; NC]), DynamicsError>
where
    S: ConstrainedSystem<NQ, NV, NU, NC>,
{
    check_state(t, q, v, u)?;
    let bias = system.constraint_bias(t, q, v);
    let residual = system.constraint_residual(t, q);
    let velocity = system.constraint_velocity(t, q, v);
    let stabilised =
        std::array::from_fn(|i| bias[i] - 2.0 * alpha * velocity[i] - beta * beta * residual[i]);
    solve_with_bias(system, t, q, v, u, stabilised)
}

/// The factored mass matrix `M(q)`, which also serves as the metric of the
/// projections.
pub(crate) fn factored_mass<S, const NQ: usize, const NV: usize, const NU: usize, const NC: usize>(
    system: &S,
    q: &[f64; NQ],
) -> Result<Cholesky<f64, Const<NV>>, DynamicsError>
where
    S: ConstrainedSystem<NQ, NV, NU, NC>,
{
    let mass = system.mass_matrix(q);
    if !mass.iter().all(all_finite) {
        return Err(DynamicsError::NonFiniteEquations);
    }
    factor_mass_matrix(&mass, &pivot_names::<S, NQ, NV, NU>())
}

/// Fails unless the time, coordinates, speeds and inputs are all finite.
fn check_state<const NQ: usize, const NV: usize, const NU: usize>(
    t: f64,
    q: &[f64; NQ],
    v: &[f64; NV],
    u: &[f64; NU],
) -> Result<(), DynamicsError> {
    if t.is_finite() && all_finite(q) && all_finite(v) && all_finite(u) {
        Ok(())
    } else {
        Err(DynamicsError::NonFiniteState)
    }
}

/// `q̈` and `λ` of `M q̈ = f + Aᵀ λ`, `A q̈ = bias`, at a finite state.
fn solve_with_bias<S, const NQ: usize, const NV: usize, const NU: usize, const NC: usize>(
    system: &S,
    t: f64,
    q: &[f64; NQ],
    v: &[f64; NV],
    u: &[f64; NU],
    bias: [f64; NC],
) -> Result<([f64; NV], [f64; NC]), DynamicsError>
where
    S: ConstrainedSystem<NQ, NV, NU, NC>,
{
    let forcing = system.forcing(t, q, v, u);
    if !all_finite(&forcing) {
        return Err(DynamicsError::NonFiniteEquations);
    }
    let mass = factored_mass(system, q)?;
    if !all_finite(&bias) {
        return Err(DynamicsError::NonFiniteConstraints);
    }
    let metric = ConstraintMetric::new(&mass, &system.constraint_jacobian(q))?;
    let (qdd, lambda) = metric.solve(&SVector::from(forcing), &SVector::from(bias));
    let (qdd, lambda): ([f64; NV], [f64; NC]) = (qdd.into(), lambda.into());
    if all_finite(&qdd) && all_finite(&lambda) {
        Ok((qdd, lambda))
    } else {
        Err(DynamicsError::NonFiniteAccelerations)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constrained::test_systems::PointOnCircle;

    const PENDULUM: PointOnCircle<1> = PointOnCircle {
        m: 2.0,
        l: 0.5,
        g: 9.81,
    };

    /// Position and velocity on the circle at angle `theta` from the
    /// downward vertical, moving counter-clockwise at `speed`.
    fn on_circle(l: f64, theta: f64, speed: f64) -> ([f64; 2], [f64; 2]) {
        let (s, c) = theta.sin_cos();
        ([l * s, -l * c], [speed * c, speed * s])
    }

    #[test]
    fn pendulum_on_a_circle_has_its_tangential_acceleration_and_rod_tension() {
        let PointOnCircle { m, l, g } = PENDULUM;
        for (theta, speed) in [(0.3, 1.2), (-2.0, 0.0), (2.9, -3.0)] {
            let (q, qd) = on_circle(l, theta, speed);
            let (qdd, [lambda]) = constrained_accelerations(&PENDULUM, 0.0, &q, &qd, &[]).unwrap();
            let (s, c) = theta.sin_cos();
            let tangential = qdd[0] * c + qdd[1] * s;
            let centripetal = -(qdd[0] * s - qdd[1] * c);
            assert!((tangential + g * s).abs() < 1e-13, "{tangential}");
            assert!(
                (centripetal - speed * speed / l).abs() < 1e-12,
                "{centripetal}"
            );
            // Radially outward: −m v²/l = m g cos θ + 2 l λ.
            let expected = -(m * speed * speed / l + m * g * c) / (2.0 * l);
            assert!(
                (lambda - expected).abs() < 1e-12 * expected.abs(),
                "{lambda}"
            );
        }
    }

    #[test]
    fn constraint_written_twice_is_a_dependent_row_not_nan() {
        let twice = PointOnCircle::<2> {
            m: PENDULUM.m,
            l: PENDULUM.l,
            g: PENDULUM.g,
        };
        let (q, qd) = on_circle(twice.l, 0.4, 1.0);
        match constrained_accelerations(&twice, 0.0, &q, &qd, &[]) {
            Err(DynamicsError::DependentConstraints { row: 1, pivot }) => {
                assert!(pivot.abs() < 1e-14, "{pivot}")
            }
            other => panic!("expected row 1 to depend on row 0, got {other:?}"),
        }
    }

    #[test]
    fn dependent_constraints_message_names_the_row_and_pivot() {
        let message = DynamicsError::DependentConstraints {
            row: 2,
            pivot: 1e-20,
        }
        .to_string();
        assert!(
            message.starts_with("constraint row 2 depends on"),
            "{message}"
        );
        assert!(message.contains("Schur pivot 1.000e-20"), "{message}");
    }

    #[test]
    fn non_finite_state_and_singular_mass_are_errors() {
        let (q, qd) = on_circle(PENDULUM.l, 0.4, 1.0);
        let result = constrained_accelerations(&PENDULUM, f64::NAN, &q, &qd, &[]);
        assert_eq!(result, Err(DynamicsError::NonFiniteState));
        let massless = PointOnCircle::<1> { m: 0.0, ..PENDULUM };
        let result = constrained_accelerations(&massless, 0.0, &q, &qd, &[]);
        assert!(matches!(
            result,
            Err(DynamicsError::SingularMassMatrix { index: 0, .. })
        ));
    }

    #[test]
    fn constraint_at_its_singular_point_is_a_dependent_row() {
        // At the centre of the circle the Jacobian [2x, 2y] vanishes.
        let result = constrained_accelerations(&PENDULUM, 0.0, &[0.0; 2], &[1.0, 0.0], &[]);
        assert!(matches!(
            result,
            Err(DynamicsError::DependentConstraints { row: 0, .. })
        ));
    }

    #[test]
    fn baumgarte_enforces_the_stabilised_acceleration_constraint() {
        // Off the manifold, moving outward: φ > 0 and ψ > 0.
        let (q, qd) = ([0.3, -0.45], [0.6, 0.1]);
        let (alpha, beta) = (7.0, 11.0);
        let (qdd, _) = baumgarte_accelerations(&PENDULUM, 0.0, &q, &qd, &[], alpha, beta).unwrap();
        let [a] = PENDULUM.constraint_jacobian(&q);
        let [b] = PENDULUM.constraint_bias(0.0, &q, &qd);
        let [phi] = PENDULUM.constraint_residual(0.0, &q);
        let [psi] = PENDULUM.constraint_velocity(0.0, &q, &qd);
        let achieved = a[0] * qdd[0] + a[1] * qdd[1];
        let demanded = b - 2.0 * alpha * psi - beta * beta * phi;
        assert!((achieved - demanded).abs() < 1e-12 * demanded.abs());
        let unstabilised = baumgarte_accelerations(&PENDULUM, 0.0, &q, &qd, &[], 0.0, 0.0);
        let exact = constrained_accelerations(&PENDULUM, 0.0, &q, &qd, &[]);
        assert_eq!(unstabilised, exact);
    }
}
