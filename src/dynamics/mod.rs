//! Forward dynamics: the accelerations `v̇` that solve `M(q) v̇ = f`, and the
//! total energy.

pub(crate) mod adjoint_rows;
pub(crate) mod cholesky;
mod error;
pub(crate) mod null_motion;
pub(crate) mod pairs;
pub(crate) mod rows;
pub(crate) mod tree_vectors;

pub use cholesky::RELATIVE_PIVOT_TOLERANCE;
pub(crate) use cholesky::{cholesky, cholesky_accelerations, factor_mass_matrix};
pub use error::DynamicsError;
pub use null_motion::NullMotion;

use crate::MultibodySystem;

/// How near zero a divisor of the coordinate rates `q̇ = N(q) v` of a
/// `speeds` statement may come before
/// [`MultibodySystem::check_coordinate_rates`] reports
/// [`DynamicsError::SingularCoordinateRates`]: a divisor `d` fails when
/// `|d| ≤ 1e-8 s`, where `s` is the sum of the magnitudes of its terms for a
/// sum (`a + b cos θ` fails when it cancels to eight digits) and `1` for
/// anything else (`cos θ`). Past it, the rates amplify the speeds by more
/// than `10⁸`.
pub const SINGULAR_RATES_TOLERANCE: f64 = 1e-8;

/// The accelerations `v̇` that solve `M(q) v̇ = f(t, q, v, u)`: the system's
/// own [`MultibodySystem::accelerations`], which for generated systems is
/// their emitted solver, unrolled for their size. For a generated system
/// with constraints it is the `v̇` of `M v̇ = f + Aᵀ λ`, `A v̇ = b`
/// ([`constrained_accelerations`](crate::constrained::constrained_accelerations),
/// whose errors it returns).
///
/// Allocates nothing and never returns a non-finite value: a non-finite
/// state or equation, or a mass matrix that is not safely positive definite
/// (a Cholesky pivot `Lⱼⱼ²` not above `1e-14` times the largest diagonal
/// entry), is an error. Only the lower triangle of `M` is read (generated
/// mass matrices are symmetric by construction).
pub fn accelerations<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    t: f64,
    q: &[f64; NQ],
    v: &[f64; NV],
    u: &[f64; NU],
) -> Result<[f64; NV], DynamicsError>
where
    S: MultibodySystem<NQ, NV, NU> + ?Sized,
{
    system.accelerations(t, q, v, u)
}

/// The accelerations of four states at once: entry `k` is
/// [`accelerations`] of state `(t[k], q[k], v[k], u[k])`, with its checks
/// and errors. The system's own [`MultibodySystem::accelerations_x4`]:
/// for a generated system whose model asks for `outputs accelerations_x4;`,
/// its emitted solve with one state in each lane of a SIMD vector (results
/// equal to the scalar call's to a few units in the last place), else the
/// four scalar calls.
pub fn accelerations_x4<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    t: [f64; 4],
    q: &[[f64; NQ]; 4],
    v: &[[f64; NV]; 4],
    u: &[[f64; NU]; 4],
) -> [Result<[f64; NV], DynamicsError>; 4]
where
    S: MultibodySystem<NQ, NV, NU> + ?Sized,
{
    system.accelerations_x4(t, q, v, u)
}

/// The name reported for each pivot of the mass matrix: the coordinate when
/// every speed is its coordinate's rate, else the speed.
pub(crate) fn pivot_names<S, const NQ: usize, const NV: usize, const NU: usize>()
-> [&'static str; NV]
where
    S: MultibodySystem<NQ, NV, NU> + ?Sized,
{
    std::array::from_fn(|i| {
        if NQ == NV {
            S::COORDINATES[i]
        } else {
            S::SPEEDS[i]
        }
    })
}

/// The total energy `T(q, v) + V(q)`.
///
/// A diagnostic, not a solver: it returns a plain `f64` and, given a NaN or
/// infinite state or parameter, a non-finite value (never a finite wrong
/// one). Check [`f64::is_finite`] where that matters; the solvers report
/// such input as [`DynamicsError`]s. Of a
/// [time-dependent](MultibodySystem::TIME_DEPENDENT) system it is NaN: see
/// [`energy_at`].
pub fn energy<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    q: &[f64; NQ],
    v: &[f64; NV],
) -> f64
where
    S: MultibodySystem<NQ, NV, NU>,
{
    system.kinetic_energy(q, v) + system.potential_energy(q)
}

/// The total energy `T(t, q, v) + V(t, q)` at time `t`, for every system.
///
/// Where a motion is prescribed in time (a shaken pivot, a platform turned
/// at a set rate, a constraint with `t`), the driver does work and
/// `T + V` is not conserved; the [`jacobi_integral`] is, when the
/// Lagrangian has no `t` of its own.
pub fn energy_at<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    t: f64,
    q: &[f64; NQ],
    v: &[f64; NV],
) -> f64
where
    S: MultibodySystem<NQ, NV, NU>,
{
    system.kinetic_energy_at(t, q, v) + system.potential_energy_at(t, q)
}

/// The Jacobi integral `h = T₂ − T₀ + V` at `(t, q, v)`, with `T₂ = ½ vᵀ M v`
/// the part of the kinetic energy quadratic in the speeds and
/// `T₀ = T(t, q, 0)` the part without them (the energy of the prescribed
/// motion alone); `h = T + V` for a system whose motion nothing prescribes.
///
/// It is conserved, with conservative loads only, when neither the
/// Lagrangian nor the speeds' definition has a `t` of its own: a bead on a
/// hoop spun at a constant rate, a body on a platform turning at `Ω t`, a
/// rheonomic constraint that steady rotation makes time-free in the
/// turning axes — not a pivot shaken as `A sin(ω t)`, whose `T` depends on
/// `t`. (`T₁`, linear in the speeds, drops out of `h`.)
pub fn jacobi_integral<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    t: f64,
    q: &[f64; NQ],
    v: &[f64; NV],
) -> f64
where
    S: MultibodySystem<NQ, NV, NU>,
{
    let mass = system.mass_matrix_at(t, q);
    let quadratic: f64 = (0..NV)
        .map(|i| v[i] * (0..NV).map(|j| mass[i][j] * v[j]).sum::<f64>())
        .sum();
    quadratic / 2.0 - system.kinetic_energy_at(t, q, &[0.0; NV]) + system.potential_energy_at(t, q)
}

/// Whether every entry is finite.
pub(crate) fn all_finite<const N: usize>(values: &[f64; N]) -> bool {
    values.iter().all(|v| v.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_systems::{FixedEquations, Pendulum, RotatingBar};
    use std::f64::consts::FRAC_PI_2;

    const PENDULUM: Pendulum = Pendulum {
        m: 2.0,
        l: 0.5,
        g: 9.81,
    };

    fn fixed(mass: [[f64; 2]; 2]) -> FixedEquations {
        FixedEquations {
            mass,
            forcing: [1.0, 2.0],
        }
    }

    #[test]
    fn pendulum_acceleration_is_minus_g_over_l_sin_theta() {
        for theta in [-3.0, -1.0, 0.0, 0.3, 2.5] {
            let [qdd] = accelerations(&PENDULUM, 0.0, &[theta], &[0.7], &[]).unwrap();
            let expected = -PENDULUM.g / PENDULUM.l * f64::sin(theta);
            assert!((qdd - expected).abs() <= 1e-14 * PENDULUM.g / PENDULUM.l);
        }
    }

    #[test]
    fn rotating_bar_accelerations_match_its_closed_form() {
        let bar = RotatingBar {
            m: 3.0,
            l: 2.0,
            d: 0.4,
        };
        let (q, qd, u) = ([0.2, 0.7], [1.5, -0.8], [0.3, -0.1]);
        let qdd = accelerations(&bar, 0.0, &q, &qd, &u).unwrap();
        let i = bar.m * bar.l * bar.l / 12.0;
        let (s, c) = q[1].sin_cos();
        let expected = [
            (2.0 * i * s * c * qd[0] * qd[1] + u[0]) / (bar.m * bar.d * bar.d + i * c * c),
            -s * c * qd[0] * qd[0] + u[1] / i,
        ];
        for (got, want) in qdd.iter().zip(expected) {
            assert!(
                (got - want).abs() <= 1e-14 * want.abs().max(1.0),
                "{got} vs {want}"
            );
        }
    }

    #[test]
    fn coupled_mass_matrix_is_solved_exactly() {
        // [[4, 2], [2, 3]] x = [1, 2]  →  x = [-1/8, 3/4]
        let qdd = accelerations(
            &fixed([[4.0, 2.0], [2.0, 3.0]]),
            0.0,
            &[0.0; 2],
            &[0.0; 2],
            &[],
        );
        let qdd = qdd.unwrap();
        assert!((qdd[0] + 0.125).abs() < 1e-15 && (qdd[1] - 0.75).abs() < 1e-15);
    }

    #[test]
    fn bar_along_its_axis_of_rotation_has_a_singular_mass_matrix() {
        let bar = RotatingBar {
            m: 1.0,
            l: 1.0,
            d: 0.0,
        };
        let error = accelerations(&bar, 0.0, &[0.0, FRAC_PI_2], &[0.0; 2], &[0.0; 2]);
        match error {
            Err(DynamicsError::SingularMassMatrix {
                index: 0,
                coordinate: "phi",
                pivot,
                null_motion,
            }) => {
                assert!(pivot.abs() < 1e-20);
                assert_eq!(null_motion.names(), ["phi"]);
            }
            other => panic!("expected a singular pivot for phi, got {other:?}"),
        }
    }

    #[test]
    fn nearly_singular_mass_matrix_is_an_error_and_mildly_ill_conditioned_is_not() {
        let nearly_singular = fixed([[1.0, 0.0], [0.0, 1e-16]]);
        let error = accelerations(&nearly_singular, 0.0, &[0.0; 2], &[0.0; 2], &[]).unwrap_err();
        assert!(
            matches!(
                error,
                DynamicsError::SingularMassMatrix {
                    index: 1,
                    coordinate: "b",
                    pivot: 1e-16,
                    ..
                }
            ),
            "{error:?}"
        );
        let ill_conditioned = fixed([[1.0, 0.0], [0.0, 1e-12]]);
        let qdd = accelerations(&ill_conditioned, 0.0, &[0.0; 2], &[0.0; 2], &[]).unwrap();
        assert!((qdd[1] - 2e12).abs() < 1e-3);
    }

    #[test]
    fn rank_deficient_and_indefinite_mass_matrices_report_their_pivot() {
        let cases = [
            ([[1.0, 1.0], [1.0, 1.0]], 0.0),
            ([[1.0, 2.0], [2.0, 1.0]], -3.0),
        ];
        for (mass, expected_pivot) in cases {
            match accelerations(&fixed(mass), 0.0, &[0.0; 2], &[0.0; 2], &[]) {
                Err(DynamicsError::SingularMassMatrix {
                    index: 1, pivot, ..
                }) => {
                    assert!((pivot - expected_pivot).abs() < 1e-15, "pivot {pivot}")
                }
                other => panic!("expected pivot 1 to fail for {mass:?}, got {other:?}"),
            }
        }
    }

    #[test]
    fn zero_and_negative_leading_inertia_fail_at_the_first_pivot() {
        for leading in [0.0, -1.0] {
            let error = accelerations(
                &fixed([[leading, 0.0], [0.0, 1.0]]),
                0.0,
                &[0.0; 2],
                &[0.0; 2],
                &[],
            );
            assert!(matches!(
                error,
                Err(DynamicsError::SingularMassMatrix { index: 0, .. })
            ));
        }
    }

    #[test]
    fn non_finite_state_is_an_error() {
        let bar = RotatingBar {
            m: 1.0,
            l: 1.0,
            d: 1.0,
        };
        let finite = ([0.1, 0.2], [0.3, 0.4], [0.5, 0.6]);
        let states = [
            (f64::NAN, finite.0, finite.1, finite.2),
            (0.0, [f64::INFINITY, 0.2], finite.1, finite.2),
            (0.0, finite.0, [0.3, f64::NAN], finite.2),
            (0.0, finite.0, finite.1, [f64::NEG_INFINITY, 0.6]),
        ];
        for (t, q, qd, u) in states {
            let result = accelerations(&bar, t, &q, &qd, &u);
            assert_eq!(result, Err(DynamicsError::NonFiniteState));
        }
    }

    #[test]
    fn non_finite_equations_are_an_error() {
        let nan_mass = fixed([[1.0, f64::NAN], [f64::NAN, 1.0]]);
        let infinite_forcing = FixedEquations {
            mass: [[1.0, 0.0], [0.0, 1.0]],
            forcing: [f64::INFINITY, 0.0],
        };
        for system in [nan_mass, infinite_forcing] {
            let result = accelerations(&system, 0.0, &[0.0; 2], &[0.0; 2], &[]);
            assert_eq!(result, Err(DynamicsError::NonFiniteEquations));
        }
    }

    #[test]
    fn overflowing_accelerations_are_an_error() {
        let huge = FixedEquations {
            mass: [[1e-300, 0.0], [0.0, 1e-300]],
            forcing: [1e300, 0.0],
        };
        let result = accelerations(&huge, 0.0, &[0.0; 2], &[0.0; 2], &[]);
        assert_eq!(result, Err(DynamicsError::NonFiniteAccelerations));
    }

    #[test]
    fn energy_is_kinetic_plus_potential() {
        let (theta, omega) = (0.4, -1.3);
        let (m, l, g) = (PENDULUM.m, PENDULUM.l, PENDULUM.g);
        let expected = 0.5 * m * l * l * omega * omega - m * g * l * f64::cos(theta);
        assert!((energy(&PENDULUM, &[theta], &[omega]) - expected).abs() < 1e-14);
    }

    #[test]
    fn singular_mass_matrix_message_names_the_coordinate_and_pivot() {
        let error = DynamicsError::SingularMassMatrix {
            index: 1,
            coordinate: "theta",
            pivot: -3.0,
            null_motion: NullMotion::default(),
        };
        let message = error.to_string();
        assert!(message.starts_with("singular mass matrix"), "{message}");
        assert!(
            message.contains("`theta` (index 1)") && message.contains("pivot -3.000e0"),
            "{message}"
        );
    }
}
