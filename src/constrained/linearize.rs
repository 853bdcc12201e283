//! The linearisation of a constrained system on its constraint manifold,
//! with independent coordinates and speeds chosen by the model (the method
//! of Peterson, Gede and Hubbard, *Symbolic linearization of equations of
//! motion of constrained multibody systems*, 2014, which SymPy's
//! `Linearizer` implements, holonomic and nonholonomic rows alike).
//!
//! The accelerations of `M v̇ = f + Aᵀ λ`, `A v̇ = b` are a function
//! `v̇(t, q, v, u)`; differentiating the residuals `r = M v̇ − f − Aᵀ λ`
//! and `c = A v̇ − b` at the solved `(v̇, λ)` gives the saddle-point system
//! `M ∂v̇ − Aᵀ ∂λ = −∂r`, `A ∂v̇ = −∂c` for each variable, solved here with
//! the Schur complement `A M⁻¹ Aᵀ`, or, where the rows are dependent
//! (redundant rows, a singular position), by the rank-revealing solver of
//! the accelerations. A perturbation of the coordinates is
//! taken in the tangent space, `q = q̄ ⊕ δ` with one entry per speed (a
//! plain coordinate moves by its entry, a free or spherical joint along
//! its speeds), and `v = v̄ + δv`. On the manifold (`φ(q) = 0` for the
//! holonomic rows, and the velocity form `ψ = A v + ψ₀ = 0` for all rows)
//! the holonomic rows determine as many dependent entries `δ_D` of `δ` as
//! they are, to first order, and all rows as many dependent speeds:
//! `δ_D = −Φ_D⁻¹ Φ_I δ_I` (`Φ = ∂φ/∂δ` of the holonomic rows) and
//! `δv_D = −A_D⁻¹ (A_I δv_I + ∂ψ/∂δ δ)`. A perturbation that keeps the
//! constraints is thus `δ = E_q δ`, `δv = E_v δv + F δ`, where `E_q`,
//! `E_v` and `F` read only the independent entries; the linearised
//! equations `δ̇ = K_δ δ + K_v δv` (`(0, I)` where the speeds are the
//! coordinates' rates), `δv̇ = ∂v̇/∂q δ + ∂v̇/∂v δv + ∂v̇/∂u δu` become
//! `A = [[K_δ E_q + K_v F, K_v E_v], [∂v̇/∂q E_q + ∂v̇/∂v F, ∂v̇/∂v E_v]]`,
//! `B = [[0], [∂v̇/∂u]]`, whose columns of dependent entries are zero. The
//! rows and columns of the independent entries of `A` are the reduced
//! matrix of SymPy's `Linearizer` (its `A_and_B` form); about an
//! equilibrium its eigenvalues are the nonzero ones of `A`.

use nalgebra::{Cholesky, Const, SMatrix};

use super::multipliers::{
    ACCELERATION_RANK_TOLERANCE, ConstraintMetric, ConstraintSolver, Dependents,
};
use crate::DynamicsError;
use crate::dynamics::{cholesky, factor_mass_matrix};

/// A pivot of the elimination of the dependent coordinates or speeds at
/// most this fraction of the largest entry of the rows eliminating them
/// counts as zero.
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
/// (by `q` in the tangent space `q ⊕ δ`, one column per speed), the
/// constraints' derivatives by the state and the kinematic rows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstrainedPartials<const NV: usize, const NU: usize, const NC: usize> {
    /// The partials of the residuals.
    pub accelerations: AccelerationPartials<NV, NU, NC>,
    /// `∂ψ/∂δ` of the velocity form `ψ = A v + ψ₀`.
    pub velocity_by_q: [[f64; NV]; NC],
    /// `∂φ/∂δ` of the holonomic rows (the rows of the nonholonomic ones
    /// are not read).
    pub position_by_q: [[f64; NV]; NC],
    /// `K_δ` of the kinematic rows `δ̇ = K_δ δ + K_v δv` (zero where the
    /// speeds are the coordinates' rates).
    pub kinematic_by_q: [[f64; NV]; NV],
    /// `K_v` (the identity where the speeds are the coordinates' rates).
    pub kinematic_by_v: [[f64; NV]; NV],
}

/// The independent entries of a linearisation on the constraint manifold,
/// as the model names them: which rows are holonomic, which tangent
/// directions of the coordinates (one per speed) and which speeds are
/// independent, and the names of both for the errors.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ManifoldChart<const NV: usize, const NC: usize> {
    /// Whether each constraint row is holonomic.
    pub holonomic: [bool; NC],
    /// Whether each tangent direction of the coordinates is independent
    /// (as many are as the speeds less the holonomic rows).
    pub coordinates: [bool; NV],
    /// Whether each speed is independent (as many are as the speeds less
    /// the rows).
    pub speeds: [bool; NV],
    /// The tangent directions' names: a plain coordinate's, or the speed's
    /// along which a free or spherical joint's coordinates move.
    pub coordinate_names: [&'static str; NV],
    /// The speeds' names.
    pub speed_names: [&'static str; NV],
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
/// Dependent rows (redundant ones, a singular position) are solved as the
/// accelerations are, by [`ConstraintSolver::RankRevealing`]: exact along
/// the motions the rows allow. Errors: a mass matrix that is not positive
/// definite, a non-finite derivative
/// ([`DynamicsError::NonFiniteEquations`]).
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

/// The blocks of `A = [[K_δ E_q + K_v F, K_v E_v], [∂v̇/∂q E_q + ∂v̇/∂v F,
/// ∂v̇/∂v E_v]]` and of the lower half `∂v̇/∂u` of `B` (the upper half is
/// zero).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstrainedLinearization<const NV: usize, const NU: usize> {
    /// `∂δ̇/∂δ = K_δ E_q + K_v F`.
    pub kinematic_by_q: [[f64; NV]; NV],
    /// `∂δ̇/∂δv = K_v E_v`.
    pub kinematic_by_v: [[f64; NV]; NV],
    /// `∂δv̇/∂δ = ∂v̇/∂q E_q + ∂v̇/∂v F`.
    pub dynamic_by_q: [[f64; NV]; NV],
    /// `∂δv̇/∂δv = ∂v̇/∂v E_v`.
    pub dynamic_by_v: [[f64; NV]; NV],
    /// `∂δv̇/∂δu = ∂v̇/∂u`.
    pub dynamic_by_u: [[f64; NU]; NV],
}

/// The linearisation on the constraint manifold (see the module's docs) of
/// a system with mass matrix `mass` and constraint Jacobian `jacobian` (by
/// the speeds) at a state on the manifold, from the `partials` at its
/// solved accelerations, with the independent entries of `chart`. Errors:
/// a mass matrix or Schur complement that is not positive definite,
/// [`DynamicsError::SingularDependentCoordinates`] where the independent
/// coordinates do not determine the others, and
/// [`DynamicsError::SingularDependentSpeeds`] where the independent speeds
/// do not determine the others. The rows are those that constrain: a
/// generated system passes its own without those that vanish identically
/// ([`VANISHING_ROWS`](crate::ConstrainedSystem::VANISHING_ROWS)), which
/// would leave a dependent entry without a row.
pub fn linearize_on_constraints<const NV: usize, const NU: usize, const NC: usize>(
    mass: &[[f64; NV]; NV],
    jacobian: &[[f64; NV]; NC],
    partials: &ConstrainedPartials<NV, NU, NC>,
    chart: &ManifoldChart<NV, NC>,
) -> Result<ConstrainedLinearization<NV, NU>, DynamicsError> {
    let (by_q, by_v, by_u) = solved_partials(
        mass,
        jacobian,
        &partials.accelerations,
        &chart.coordinate_names,
    )?;
    let positions = Elimination::new(
        &partials.position_by_q,
        &chart.holonomic,
        &chart.coordinates,
    );
    let singular_coordinate = |column: usize, pivot| DynamicsError::SingularDependentCoordinates {
        coordinate: entry_name(&chart.coordinate_names, column),
        pivot,
    };
    let e_q = positions.basis(singular_coordinate)?;
    let velocities = Elimination::new(jacobian, &[true; NC], &chart.speeds);
    let singular_speed = |column: usize, pivot| DynamicsError::SingularDependentSpeeds {
        speed: entry_name(&chart.speed_names, column),
        pivot,
    };
    let e_v = velocities.basis(singular_speed)?;
    // F: −A_D⁻¹ ∂ψ/∂δ E_q in the rows of the dependent speeds.
    let moved = velocities.solve(&(matrix(&partials.velocity_by_q) * e_q), singular_speed)?;
    let f = velocities.spread(&(-moved));
    let (k_q, k_v) = (
        matrix(&partials.kinematic_by_q),
        matrix(&partials.kinematic_by_v),
    );
    let linearization = ConstrainedLinearization {
        kinematic_by_q: array(&(k_q * e_q + k_v * f)),
        kinematic_by_v: array(&(k_v * e_v)),
        dynamic_by_q: array(&(by_q * e_q + by_v * f)),
        dynamic_by_v: array(&(by_v * e_v)),
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

/// `∂v̇/∂q`, `∂v̇/∂v` and `∂v̇/∂u`.
type SolvedPartials<const NV: usize, const NU: usize> = (
    SMatrix<f64, NV, NV>,
    SMatrix<f64, NV, NV>,
    SMatrix<f64, NV, NU>,
);

/// `∂v̇/∂q`, `∂v̇/∂v` and `∂v̇/∂u` through the saddle-point system (see
/// [`constrained_accelerations_jacobian`]): by the Schur complement, or,
/// where the rows are dependent (redundant rows, a singular position), by
/// the rank-revealing solver, which holds the independent rows and gives
/// the dependent ones the least-squares solution, as for the
/// accelerations themselves.
fn solved_partials<const NV: usize, const NU: usize, const NC: usize>(
    mass: &[[f64; NV]; NV],
    jacobian: &[[f64; NV]; NC],
    partials: &AccelerationPartials<NV, NU, NC>,
    coordinates: &[&'static str; NV],
) -> Result<SolvedPartials<NV, NU>, DynamicsError> {
    match SaddlePoint::new(mass, matrix(jacobian), coordinates) {
        Err(DynamicsError::DependentConstraints { .. }) => ConstraintMetric::with(
            ConstraintSolver::RankRevealing,
            ACCELERATION_RANK_TOLERANCE,
            mass,
            coordinates,
            (jacobian, &[false; NC]),
            |metric| partials_through(&metric, partials),
        ),
        saddle => partials_through(&saddle?, partials),
    }
}

/// A solver of `M ∂v̇ − Aᵀ ∂λ = −∂r`, `A ∂v̇ = −∂c` for `∂v̇`, column by
/// column.
trait SaddleSolve<const NV: usize, const NC: usize> {
    /// `∂v̇` for the columns of `residual` (`∂r`) and `constraint` (`∂c`).
    fn columns<const K: usize>(
        &self,
        residual: &SMatrix<f64, NV, K>,
        constraint: &SMatrix<f64, NC, K>,
    ) -> Result<SMatrix<f64, NV, K>, DynamicsError>;
}

/// `∂v̇/∂q`, `∂v̇/∂v` and `∂v̇/∂u` of `partials` through `solver`.
fn partials_through<const NV: usize, const NU: usize, const NC: usize>(
    solver: &impl SaddleSolve<NV, NC>,
    partials: &AccelerationPartials<NV, NU, NC>,
) -> Result<SolvedPartials<NV, NU>, DynamicsError> {
    Ok((
        solver.columns(
            &matrix(&partials.residual_by_q),
            &matrix(&partials.constraint_by_q),
        )?,
        solver.columns(
            &matrix(&partials.residual_by_v),
            &matrix(&partials.constraint_by_v),
        )?,
        solver.columns(
            &matrix(&partials.residual_by_u),
            &SMatrix::<f64, NC, NU>::zeros(),
        )?,
    ))
}

/// Through the rank-revealing solver, the dependent rows by least squares.
impl<const NV: usize, const NC: usize> SaddleSolve<NV, NC> for ConstraintMetric<'_, NV, NC> {
    fn columns<const K: usize>(
        &self,
        residual: &SMatrix<f64, NV, K>,
        constraint: &SMatrix<f64, NC, K>,
    ) -> Result<SMatrix<f64, NV, K>, DynamicsError> {
        let mut solved = SMatrix::<f64, NV, K>::zeros();
        for j in 0..K {
            let (column, _) = self.solve(
                &(-residual.column(j)),
                &(-constraint.column(j)),
                Dependents::LeastSquares,
            )?;
            solved.set_column(j, &column);
        }
        Ok(solved)
    }
}

/// The name of entry `j` (`j = NV` where the chart names too few
/// dependent entries for its rows).
fn entry_name<const NV: usize>(names: &[&'static str; NV], j: usize) -> &'static str {
    names.get(j).copied().unwrap_or("(none)")
}

/// Rows of an array as a matrix.
fn matrix<const R: usize, const C: usize>(rows: &[[f64; C]; R]) -> SMatrix<f64, R, C> {
    SMatrix::from_fn(|i, j| rows[i][j])
}

/// A matrix as rows of an array.
fn array<const R: usize, const C: usize>(m: &SMatrix<f64, R, C>) -> [[f64; C]; R] {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

/// The elimination of the dependent entries by some rows of a matrix
/// `A` (`NC × NV`): `δ_D = −A_D⁻¹ A_I δ_I` over the rows taken, `A_D` and
/// `A_I` their columns of the dependent and independent entries. The rows
/// taken are the first `count` of `rows`, the dependent entries the first
/// `count` of `dependent` (where fewer entries than rows are dependent,
/// the block has an empty column and the elimination fails at it).
struct Elimination<const NV: usize, const NC: usize> {
    a: SMatrix<f64, NC, NV>,
    rows: [usize; NC],
    dependent: [usize; NC],
    count: usize,
    independent: [bool; NV],
}

impl<const NV: usize, const NC: usize> Elimination<NV, NC> {
    /// The rows of `a` `taken`, and its entries not `independent`.
    fn new(a: &[[f64; NV]; NC], taken: &[bool; NC], independent: &[bool; NV]) -> Self {
        let (mut rows, mut dependent) = ([0; NC], [NV; NC]);
        let taken_rows = (0..NC).filter(|&i| taken[i]);
        let count = taken_rows.clone().count();
        for (slot, i) in rows.iter_mut().zip(taken_rows) {
            *slot = i;
        }
        for (slot, j) in dependent
            .iter_mut()
            .zip((0..NV).filter(|&j| !independent[j]))
        {
            *slot = j;
        }
        Elimination {
            a: matrix(a),
            rows,
            dependent,
            count,
            independent: *independent,
        }
    }

    /// `E`: the identity on the independent columns, `−A_D⁻¹ A_I` in the
    /// rows of the dependent entries.
    fn basis(
        &self,
        singular: impl Fn(usize, f64) -> DynamicsError,
    ) -> Result<SMatrix<f64, NV, NV>, DynamicsError> {
        let mut independent_part = self.a;
        for j in (0..NV).filter(|&j| !self.independent[j]) {
            independent_part.column_mut(j).fill(0.0);
        }
        let eliminated = self.solve(&independent_part, singular)?;
        let mut e = self.spread(&(-eliminated));
        for j in (0..NV).filter(|&j| self.independent[j]) {
            e[(j, j)] = 1.0;
        }
        Ok(e)
    }

    /// Row `d < count` of `solved` (one per dependent entry) as the row of
    /// its entry, the other rows zero.
    fn spread(&self, solved: &SMatrix<f64, NC, NV>) -> SMatrix<f64, NV, NV> {
        let mut spread = SMatrix::<f64, NV, NV>::zeros();
        for (d, &i) in self.dependent.iter().enumerate().take(self.count) {
            if i < NV {
                spread.set_row(i, &solved.row(d));
            }
        }
        spread
    }

    /// `A_D⁻¹ rhs` over the rows taken, by Gaussian elimination of `A_D`
    /// with partial pivoting, column by column (one per dependent entry):
    /// the first column whose pivot is not above
    /// [`DEPENDENT_PIVOT_TOLERANCE`] times the largest entry of the rows
    /// taken is the error `singular` gives for its entry. Row `d` of the result is the
    /// `d`-th dependent entry's; rows from `count` on are zero.
    fn solve(
        &self,
        rhs: &SMatrix<f64, NC, NV>,
        singular: impl Fn(usize, f64) -> DynamicsError,
    ) -> Result<SMatrix<f64, NC, NV>, DynamicsError> {
        let n = self.count;
        let column_of = |d: usize| self.dependent[d];
        let mut block = SMatrix::<f64, NC, NC>::zeros();
        let mut solved = SMatrix::<f64, NC, NV>::zeros();
        for (r, &i) in self.rows.iter().enumerate().take(n) {
            for d in (0..n).filter(|&d| column_of(d) < NV) {
                block[(r, d)] = self.a[(i, column_of(d))];
            }
            solved.set_row(r, &rhs.row(i));
        }
        let largest = self.rows[..n]
            .iter()
            .fold(0.0_f64, |m, &i| m.max(self.a.row(i).amax()));
        let tolerance = DEPENDENT_PIVOT_TOLERANCE * largest;
        for column in 0..n {
            let (offset, pivot) = (column..n)
                .map(|row| (row, block[(row, column)]))
                .max_by(|x, y| x.1.abs().total_cmp(&y.1.abs()))
                .unwrap_or((column, 0.0));
            // NaN fails too.
            if pivot.abs().partial_cmp(&tolerance) != Some(std::cmp::Ordering::Greater) {
                return Err(singular(column_of(column), pivot));
            }
            block.swap_rows(column, offset);
            solved.swap_rows(column, offset);
            for row in column + 1..n {
                let factor = block[(row, column)] / pivot;
                for j in column..n {
                    block[(row, j)] -= factor * block[(column, j)];
                }
                for j in 0..NV {
                    solved[(row, j)] -= factor * solved[(column, j)];
                }
            }
        }
        for column in (0..n).rev() {
            for j in 0..NV {
                let known: f64 = (column + 1..n)
                    .map(|k| block[(column, k)] * solved[(k, j)])
                    .sum();
                solved[(column, j)] = (solved[(column, j)] - known) / block[(column, column)];
            }
        }
        Ok(solved)
    }
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
}

/// Through the Schur complement: `∂λ = S⁻¹ (A M⁻¹ ∂r − ∂c)`,
/// `∂v̇ = M⁻¹ Aᵀ ∂λ − M⁻¹ ∂r`.
impl<const NV: usize, const NC: usize> SaddleSolve<NV, NC> for SaddlePoint<NV, NC> {
    fn columns<const K: usize>(
        &self,
        residual: &SMatrix<f64, NV, K>,
        constraint: &SMatrix<f64, NC, K>,
    ) -> Result<SMatrix<f64, NV, K>, DynamicsError> {
        let pushed = self.mass.solve(residual);
        let multipliers = self.schur.solve(&(self.jacobian * pushed - constraint));
        Ok(self.spread * multipliers - pushed)
    }
}
