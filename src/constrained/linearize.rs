//! The linearisation of a constrained system on its constraint manifold,
//! with independent coordinates chosen by the model (the method of
//! Peterson, Gede and Hubbard, *Symbolic linearization of equations of
//! motion of constrained multibody systems*, 2014, which SymPy's
//! `Linearizer` implements).
//!
//! The accelerations of `M v̇ = f + Aᵀ λ`, `A v̇ = b` are a function
//! `v̇(t, q, v, u)`; differentiating the residuals `r = M v̇ − f − Aᵀ λ`
//! and `c = A v̇ − b` at the solved `(v̇, λ)` gives the saddle-point system
//! `M ∂v̇ − Aᵀ ∂λ = −∂r`, `A ∂v̇ = −∂c` for each variable, solved here with
//! the Schur complement `A M⁻¹ Aᵀ`. On the manifold (`φ(q) = 0` and the
//! velocity form `ψ = A v + ψ₀ = 0`) the coordinates split into the
//! independent ones `q_I` and `NC` dependent ones `q_D`, which the
//! constraints determine to first order: `δq_D = −A_D⁻¹ A_I δq_I` and
//! `δv_D = −A_D⁻¹ (A_I δv_I + ∂ψ/∂q δq)`. A perturbation of the state
//! that keeps the constraints is thus `δq = E δq`, `δv = E δv + F δq`,
//! where `E` and `F` read only the independent entries; the linearised
//! equations `δq̇ = δv`, `δv̇ = ∂v̇/∂q δq + ∂v̇/∂v δv + ∂v̇/∂u δu` become
//! `A = [[F, E], [∂v̇/∂q E + ∂v̇/∂v F, ∂v̇/∂v E]]`, `B = [[0], [∂v̇/∂u]]`,
//! whose columns of dependent entries are zero. The rows and columns of the
//! independent entries of `A` are the reduced matrix of SymPy's
//! `Linearizer` (its `A_and_B` form); about an equilibrium its eigenvalues
//! are the nonzero ones of `A`.

use nalgebra::{Cholesky, Const, SMatrix};

use crate::DynamicsError;
use crate::dynamics::{cholesky, factor_mass_matrix};

/// A pivot of the elimination of the dependent coordinates at most this
/// fraction of the largest entry of their block of `A` counts as zero.
pub const DEPENDENT_PIVOT_TOLERANCE: f64 = 1e-12;

/// The partial derivatives of the residuals of the constrained equations
/// at the solved accelerations `v̇` and multipliers `λ`; entry `[i][j]` is
/// the derivative of component `i` by variable `j`. They give the
/// accelerations' own derivatives
/// ([`constrained_accelerations_jacobian`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AccelerationPartials<const NV: usize, const NU: usize, const NC: usize> {
    /// `∂r/∂q` of `r = M v̇ − f − Aᵀ λ` (`v̇`, `λ` held).
    pub residual_by_q: [[f64; NV]; NV],
    /// `∂r/∂v`.
    pub residual_by_v: [[f64; NV]; NV],
    /// `∂r/∂u`.
    pub residual_by_u: [[f64; NU]; NV],
    /// `∂c/∂q` of `c = A v̇ − b` (`v̇` held).
    pub constraint_by_q: [[f64; NV]; NC],
    /// `∂c/∂v`.
    pub constraint_by_v: [[f64; NV]; NC],
}

/// What [`linearize_on_constraints`] takes: the [`AccelerationPartials`]
/// and `∂ψ/∂q` of the constraints' velocity form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstrainedPartials<const NV: usize, const NU: usize, const NC: usize> {
    /// The partials of the residuals.
    pub accelerations: AccelerationPartials<NV, NU, NC>,
    /// `∂ψ/∂q` of the velocity form `ψ = A v + ψ₀`.
    pub velocity_by_q: [[f64; NV]; NC],
}

/// `(∂v̇/∂q, ∂v̇/∂v, ∂v̇/∂u)` of the constrained accelerations, entry
/// `[i][j]` the derivative of `v̇ᵢ`.
pub type AccelerationsJacobian<const NV: usize, const NU: usize> =
    ([[f64; NV]; NV], [[f64; NV]; NV], [[f64; NU]; NV]);

/// The derivatives of the accelerations `v̇(t, q, v, u)` of
/// `M v̇ = f + Aᵀ λ`, `A v̇ = b` by `q`, `v` and `u`, from the `partials`
/// of the residuals at the solved `v̇` and `λ` (see the module's docs),
/// for a system with mass matrix `mass` and constraint Jacobian `jacobian`
/// at the state; `coordinates` names the speeds for the errors. They hold
/// off the constraint manifold too: `v̇` is a function of the whole state.
/// Errors: a mass matrix that is not positive definite, dependent
/// constraint rows ([`DynamicsError::DependentConstraints`]), a
/// non-finite derivative ([`DynamicsError::NonFiniteEquations`]).
pub fn constrained_accelerations_jacobian<const NV: usize, const NU: usize, const NC: usize>(
    mass: &[[f64; NV]; NV],
    jacobian: &[[f64; NV]; NC],
    partials: &AccelerationPartials<NV, NU, NC>,
    coordinates: &[&'static str; NV],
) -> Result<AccelerationsJacobian<NV, NU>, DynamicsError> {
    let (by_q, by_v, by_u) = solved_partials(mass, jacobian, partials, coordinates)?;
    let (by_q, by_v, by_u) = (array(&by_q), array(&by_v), array(&by_u));
    let finite = |rows: &[[f64; NV]]| rows.iter().flatten().all(|x| x.is_finite());
    let all_finite = finite(&by_q) && finite(&by_v) && by_u.iter().flatten().all(|x| x.is_finite());
    match all_finite {
        true => Ok((by_q, by_v, by_u)),
        false => Err(DynamicsError::NonFiniteEquations),
    }
}

/// The blocks of `A = [[F, E], [∂v̇/∂q E + ∂v̇/∂v F, ∂v̇/∂v E]]` and of the
/// lower half `∂v̇/∂u` of `B` (the upper half is zero).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstrainedLinearization<const NV: usize, const NU: usize> {
    /// `∂δq̇/∂δq = F`.
    pub kinematic_by_q: [[f64; NV]; NV],
    /// `∂δq̇/∂δv = E`.
    pub kinematic_by_v: [[f64; NV]; NV],
    /// `∂δv̇/∂δq = ∂v̇/∂q E + ∂v̇/∂v F`.
    pub dynamic_by_q: [[f64; NV]; NV],
    /// `∂δv̇/∂δv = ∂v̇/∂v E`.
    pub dynamic_by_v: [[f64; NV]; NV],
    /// `∂δv̇/∂δu = ∂v̇/∂u`.
    pub dynamic_by_u: [[f64; NU]; NV],
}

/// The linearisation on the constraint manifold (see the module's docs) of
/// a system with mass matrix `mass` and holonomic constraint Jacobian
/// `jacobian` at a state on the manifold, from the `partials` at its
/// solved accelerations; `independent[j]` says whether coordinate `j` is
/// independent (exactly `NV − NC` are), `coordinates` names them. Errors:
/// a mass matrix or Schur complement that is not positive definite, and
/// [`DynamicsError::SingularDependentCoordinates`] where the independent
/// coordinates do not determine the others.
pub fn linearize_on_constraints<const NV: usize, const NU: usize, const NC: usize>(
    mass: &[[f64; NV]; NV],
    jacobian: &[[f64; NV]; NC],
    partials: &ConstrainedPartials<NV, NU, NC>,
    independent: &[bool; NV],
    coordinates: &[&'static str; NV],
) -> Result<ConstrainedLinearization<NV, NU>, DynamicsError> {
    let (by_q, by_v, by_u) = solved_partials(mass, jacobian, &partials.accelerations, coordinates)?;
    let a = matrix(jacobian);
    let mut dependent = [0; NC];
    for (slot, j) in dependent
        .iter_mut()
        .zip((0..NV).filter(|&j| !independent[j]))
    {
        *slot = j;
    }
    let block_d = SMatrix::<f64, NC, NC>::from_fn(|i, d| a[(i, dependent[d])]);
    let solve_dependent =
        |rhs: SMatrix<f64, NC, NV>| solve_dependent(block_d, rhs, &dependent, coordinates);
    // E: the identity on the independent columns, −A_D⁻¹ A_I below them.
    let eliminated = solve_dependent(a)?;
    let mut e = SMatrix::<f64, NV, NV>::zeros();
    for j in (0..NV).filter(|&j| independent[j]) {
        e[(j, j)] = 1.0;
        for (d, &i) in dependent.iter().enumerate() {
            e[(i, j)] = -eliminated[(d, j)];
        }
    }
    // F: −A_D⁻¹ ∂ψ/∂q E in the dependent rows.
    let velocity = matrix(&partials.velocity_by_q) * e;
    let moved = solve_dependent(velocity)?;
    let mut f = SMatrix::<f64, NV, NV>::zeros();
    for (d, &i) in dependent.iter().enumerate() {
        for j in 0..NV {
            f[(i, j)] = -moved[(d, j)];
        }
    }
    let linearization = ConstrainedLinearization {
        kinematic_by_q: array(&f),
        kinematic_by_v: array(&e),
        dynamic_by_q: array(&(by_q * e + by_v * f)),
        dynamic_by_v: array(&(by_v * e)),
        dynamic_by_u: array(&by_u),
    };
    let finite = |m: &[[f64; NV]; NV]| m.iter().flatten().all(|x| x.is_finite());
    let all_finite = [
        &linearization.kinematic_by_q,
        &linearization.kinematic_by_v,
        &linearization.dynamic_by_q,
        &linearization.dynamic_by_v,
    ]
    .into_iter()
    .all(finite)
        && linearization
            .dynamic_by_u
            .iter()
            .flatten()
            .all(|x| x.is_finite());
    match all_finite {
        true => Ok(linearization),
        false => Err(DynamicsError::NonFiniteEquations),
    }
}

/// `∂v̇/∂q`, `∂v̇/∂v` and `∂v̇/∂u` through the saddle-point system (see
/// [`constrained_accelerations_jacobian`]).
#[allow(clippy::type_complexity)]
fn solved_partials<const NV: usize, const NU: usize, const NC: usize>(
    mass: &[[f64; NV]; NV],
    jacobian: &[[f64; NV]; NC],
    partials: &AccelerationPartials<NV, NU, NC>,
    coordinates: &[&'static str; NV],
) -> Result<
    (
        SMatrix<f64, NV, NV>,
        SMatrix<f64, NV, NV>,
        SMatrix<f64, NV, NU>,
    ),
    DynamicsError,
> {
    let saddle = SaddlePoint::new(mass, matrix(jacobian), coordinates)?;
    let by_q = saddle.solve(
        &matrix(&partials.residual_by_q),
        &matrix(&partials.constraint_by_q),
    );
    let by_v = saddle.solve(
        &matrix(&partials.residual_by_v),
        &matrix(&partials.constraint_by_v),
    );
    let by_u = saddle.solve(
        &matrix(&partials.residual_by_u),
        &SMatrix::<f64, NC, NU>::zeros(),
    );
    Ok((by_q, by_v, by_u))
}

/// Rows of an array as a matrix.
fn matrix<const R: usize, const C: usize>(rows: &[[f64; C]; R]) -> SMatrix<f64, R, C> {
    SMatrix::from_fn(|i, j| rows[i][j])
}

/// A matrix as rows of an array.
fn array<const R: usize, const C: usize>(m: &SMatrix<f64, R, C>) -> [[f64; C]; R] {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

/// `A_D⁻¹ rhs` by Gaussian elimination of the dependent block `A_D` with
/// partial pivoting, column by column (one column per dependent
/// coordinate): the first column whose pivot is not above
/// [`DEPENDENT_PIVOT_TOLERANCE`] times the block's largest entry is the
/// error, naming its coordinate.
fn solve_dependent<const NC: usize, const NV: usize>(
    mut block: SMatrix<f64, NC, NC>,
    mut rhs: SMatrix<f64, NC, NV>,
    dependent: &[usize; NC],
    coordinates: &[&'static str; NV],
) -> Result<SMatrix<f64, NC, NV>, DynamicsError> {
    let tolerance = DEPENDENT_PIVOT_TOLERANCE * block.amax();
    for column in 0..NC {
        let (offset, pivot) = (column..NC)
            .map(|row| (row, block[(row, column)]))
            .max_by(|x, y| x.1.abs().total_cmp(&y.1.abs()))
            .unwrap_or((column, 0.0));
        // NaN fails too.
        if pivot.abs().partial_cmp(&tolerance) != Some(std::cmp::Ordering::Greater) {
            return Err(DynamicsError::SingularDependentCoordinates {
                coordinate: coordinates[dependent[column]],
                pivot,
            });
        }
        block.swap_rows(column, offset);
        rhs.swap_rows(column, offset);
        for row in column + 1..NC {
            let factor = block[(row, column)] / pivot;
            for j in column..NC {
                block[(row, j)] -= factor * block[(column, j)];
            }
            for j in 0..NV {
                rhs[(row, j)] -= factor * rhs[(column, j)];
            }
        }
    }
    for column in (0..NC).rev() {
        for j in 0..NV {
            let known: f64 = (column + 1..NC)
                .map(|k| block[(column, k)] * rhs[(k, j)])
                .sum();
            rhs[(column, j)] = (rhs[(column, j)] - known) / block[(column, column)];
        }
    }
    Ok(rhs)
}

/// `[[M, −Aᵀ], [A, 0]]` factorised for several right-hand sides: the
/// Cholesky factors of `M` and of the Schur complement `A M⁻¹ Aᵀ`.
struct SaddlePoint<const NV: usize, const NC: usize> {
    mass: Cholesky<f64, Const<NV>>,
    /// `M⁻¹ Aᵀ`.
    spread: SMatrix<f64, NV, NC>,
    schur: Cholesky<f64, Const<NC>>,
    jacobian: SMatrix<f64, NC, NV>,
}

impl<const NV: usize, const NC: usize> SaddlePoint<NV, NC> {
    fn new(
        mass: &[[f64; NV]; NV],
        jacobian: SMatrix<f64, NC, NV>,
        coordinates: &[&'static str; NV],
    ) -> Result<Self, DynamicsError> {
        let mass = factor_mass_matrix(mass, coordinates)?;
        let spread = mass.solve(&jacobian.transpose());
        let schur =
            cholesky(jacobian * spread).map_err(|pivot| DynamicsError::DependentConstraints {
                row: pivot.index,
                pivot: pivot.value,
            })?;
        Ok(SaddlePoint {
            mass,
            spread,
            schur,
            jacobian,
        })
    }

    /// `∂v̇` of `M ∂v̇ − Aᵀ ∂λ = −∂r`, `A ∂v̇ = −∂c`, column by column:
    /// `∂λ = S⁻¹ (A M⁻¹ ∂r − ∂c)`, `∂v̇ = M⁻¹ Aᵀ ∂λ − M⁻¹ ∂r`.
    fn solve<const K: usize>(
        &self,
        residual: &SMatrix<f64, NV, K>,
        constraint: &SMatrix<f64, NC, K>,
    ) -> SMatrix<f64, NV, K> {
        let pushed = self.mass.solve(residual);
        let multipliers = self.schur.solve(&(self.jacobian * pushed - constraint));
        self.spread * multipliers - pushed
    }
}
