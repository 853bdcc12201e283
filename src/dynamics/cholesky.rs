//! Cholesky factorisation `M = L Lᵀ` on the stack with a relative pivot test,
//! shared by the mass matrix and the constraints' Schur complement.

use nalgebra::{Cholesky, Const, SMatrix, SVector};

use super::{DynamicsError, NullMotion, all_finite, pivot_names};
use crate::MultibodySystem;

/// A Cholesky pivot at most this fraction of the largest diagonal entry of the
/// matrix counts as zero: the matrix is singular to working precision. The
/// emitted solvers use the same value.
pub const RELATIVE_PIVOT_TOLERANCE: f64 = 1e-14;

/// The Cholesky factor of a finite mass matrix, or the error naming the
/// coordinate (of `coordinates`, one name per speed) whose pivot is not
/// safely positive.
pub(crate) fn factor_mass_matrix<const NV: usize>(
    mass: &[[f64; NV]; NV],
    coordinates: &[&'static str; NV],
) -> Result<Cholesky<f64, Const<NV>>, DynamicsError> {
    let matrix = SMatrix::<f64, NV, NV>::from_fn(|i, j| mass[i][j]);
    cholesky(matrix).map_err(|pivot| DynamicsError::SingularMassMatrix {
        index: pivot.index,
        coordinate: coordinates[pivot.index],
        pivot: pivot.value,
        null_motion: NullMotion::of(mass, coordinates),
    })
}

/// The smallest pivot that counts as nonzero in a factorisation of a matrix
/// with this diagonal (a pivot must exceed it):
/// [`RELATIVE_PIVOT_TOLERANCE`] times the largest diagonal entry. Called by
/// the emitted `L D Lᵀ` solvers and by [`check_pivots`], so that the rule
/// has one definition.
pub fn pivot_tolerance<const N: usize>(diagonal: [f64; N]) -> f64 {
    RELATIVE_PIVOT_TOLERANCE * diagonal.into_iter().fold(0.0, f64::max)
}

/// The pivot test of the emitted articulated-body solver: every pivot (a
/// joint's articulated inertia about its axis) must exceed
/// [`RELATIVE_PIVOT_TOLERANCE`] times the largest; the error names the first
/// that does not, by its entry of `names`. Called by generated code, which
/// keeps one definition of the test here (and leaves the linters of a user's
/// crate no long chain of generated bindings to trace back from a method
/// call).
pub fn check_pivots<const N: usize>(
    pivots: [f64; N],
    names: [&'static str; N],
) -> Result<(), DynamicsError> {
    let tolerance = pivot_tolerance(pivots);
    match pivots
        .into_iter()
        .zip(names)
        .enumerate()
        .find(|(_, (pivot, _))| pivot.is_nan() || *pivot <= tolerance)
    {
        Some((index, (pivot, coordinate))) => Err(DynamicsError::SingularMassMatrix {
            index,
            coordinate,
            pivot,
            null_motion: NullMotion::default(),
        }),
        None => Ok(()),
    }
}

/// A Cholesky pivot that is not safely positive.
pub(crate) struct Pivot {
    /// Its row and column.
    pub(crate) index: usize,
    /// Its value `Lⱼⱼ²`.
    pub(crate) value: f64,
}

/// Factorises a finite `M = L Lᵀ`, or reports its first pivot that is not
/// safely positive.
pub(crate) fn cholesky<const N: usize>(
    mass: SMatrix<f64, N, N>,
) -> Result<Cholesky<f64, Const<N>>, Pivot> {
    let tolerance = RELATIVE_PIVOT_TOLERANCE * mass.diagonal().max().max(0.0);
    // Never fails; a bad pivot leaves NaN behind it, but every row of L up to
    // it is exact before its diagonal, which is all the pivot scan reads.
    let factor = Cholesky::new_unchecked(mass);
    let l = factor.l_dirty();
    for j in 0..N {
        let pivot = mass[(j, j)] - l.row(j).columns(0, j).norm_squared();
        if pivot.is_nan() || pivot <= tolerance {
            return Err(Pivot {
                index: j,
                value: pivot,
            });
        }
    }
    Ok(factor)
}

/// The runtime's generic solver behind the provided
/// [`MultibodySystem::accelerations`]: nalgebra's Cholesky factorisation of
/// `M` on the stack, with the checks and errors of [`accelerations`](crate::accelerations).
/// Generated systems solve with their own unrolled factorisation; tests and
/// benchmarks compare it with this one.
pub fn cholesky_accelerations<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    t: f64,
    q: &[f64; NQ],
    v: &[f64; NV],
    u: &[f64; NU],
) -> Result<[f64; NV], DynamicsError>
where
    S: MultibodySystem<NQ, NV, NU> + ?Sized,
{
    if !(t.is_finite() && all_finite(q) && all_finite(v) && all_finite(u)) {
        return Err(DynamicsError::NonFiniteState);
    }
    let mass = system.mass_matrix_at(t, q);
    let forcing = system.forcing(t, q, v, u);
    if !(mass.iter().all(all_finite) && all_finite(&forcing)) {
        return Err(DynamicsError::NonFiniteEquations);
    }
    let factor = factor_mass_matrix(&mass, &pivot_names::<S, NQ, NV, NU>())?;
    let vdot: [f64; NV] = factor.solve(&SVector::from(forcing)).into();
    if !all_finite(&vdot) {
        return Err(DynamicsError::NonFiniteAccelerations);
    }
    Ok(vdot)
}

#[cfg(test)]
mod tests {
    use super::*;

    const NAMES: [&str; 3] = ["a", "b", "c"];

    #[test]
    fn pivots_well_above_the_tolerance_pass() {
        assert_eq!(check_pivots([2.0, 1e-10, 0.5], NAMES), Ok(()));
    }

    #[test]
    fn the_first_pivot_at_or_below_the_tolerance_is_named() {
        let tiny = 0.5 * RELATIVE_PIVOT_TOLERANCE * 2.0;
        assert_eq!(
            check_pivots([2.0, tiny, -1.0], NAMES),
            Err(DynamicsError::SingularMassMatrix {
                index: 1,
                coordinate: "b",
                pivot: tiny,
                null_motion: NullMotion::default(),
            })
        );
    }

    #[test]
    fn a_nan_pivot_is_singular() {
        let error = check_pivots([1.0, 1.0, f64::NAN], NAMES).unwrap_err();
        assert!(matches!(
            error,
            DynamicsError::SingularMassMatrix {
                index: 2,
                coordinate: "c",
                ..
            }
        ));
    }
}
