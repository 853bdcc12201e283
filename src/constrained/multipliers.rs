//! The accelerations and Lagrange multipliers of a constrained system, from
//! the saddle-point (KKT) system `[[M, Aᵀ], [A, 0]] [v̇; −λ] = [f; b]`, by
//! one of two [`ConstraintSolver`]s.

use nalgebra::{Cholesky, Const, SMatrix, SVector};

use super::rank::SchurFactor;
use super::sparse::SparseMetric;
use crate::ConstrainedSystem;
use crate::DynamicsError;
use crate::dynamics::{RELATIVE_PIVOT_TOLERANCE, all_finite, factor_mass_matrix, pivot_names};

/// A pivot of the Schur complement at most this fraction of its largest
/// diagonal entry marks its row as dependent in the projections of
/// [`ConstraintSolver::RankRevealing`]: the row is then within about `1e-6`
/// (relative) of the span of the rows taken before it.
pub const RANK_TOLERANCE: f64 = 1e-12;

/// The rank tolerance of the accelerations: a pivot of the Schur complement
/// at most this fraction of its largest diagonal entry (a row within about
/// `1e-5`, relative, of the span of the rows before it) marks a dependent
/// row in the accelerations of [`ConstraintSolver::RankRevealing`].
///
/// Looser than the projections' [`RANK_TOLERANCE`]: near a singular
/// position a row whose gradient has shrunk to `ε` (relative) demands
/// accelerations of order `δ / ε` from a state off the motion by `δ` (an
/// integrator's stage), a Lipschitz constant of order `1 / ε` that an
/// adaptive method at a tight tolerance resolves with ever shorter steps
/// (A02 by DOP853 at `1e-10` stopped with "step size too small" at
/// `1e-12`). Taken as dependent, such a row is held by the projection after
/// the step instead. Not looser: at `1e-8` RK4 with projection at
/// `h = 2e-3 s` crossed A02's singular positions 800 times less
/// accurately (B0 off by 1.3e-6 m instead of 1.6e-9 m at 20 s, N = 2),
/// while at `1e-10` it ends where it did at `1e-12`, as do DOP853's runs at
/// `1e-6` and `1e-8`. The positions keep the tight tolerance: the
/// projections hold every row whose gradient is above `1e-6`.
pub const ACCELERATION_RANK_TOLERANCE: f64 = 1e-10;

/// A dependent row is consistent when `|Aᵢ x − cᵢ|` is at most this fraction
/// of the largest `Σⱼ |Aᵢⱼ xⱼ| + |cᵢ|` of any row; beyond it the constraints contradict each other
/// ([`DynamicsError::InconsistentConstraints`]). Loose enough for the rows
/// that [`RANK_TOLERANCE`] declares dependent near a singular configuration.
pub const CONSISTENCY_TOLERANCE: f64 = 1e-3;

/// A state is on the position manifold, for the purpose of forgiving
/// dependent rows that disagree at acceleration level, when its largest
/// holonomic residual `max |φᵢ|` is at most this fraction of
/// `max |Aᵢⱼ| (1 + max |qⱼ|)`: within about `1e-8` of the manifold relative
/// to its coordinates, to first order. At such a state near a singular
/// position (the stage of an integrator a few `1e-10` rad from where
/// A02's four-bars lie flat) the rows that [`ACCELERATION_RANK_TOLERANCE`]
/// declares dependent demand, by rounding and discretisation, accelerations
/// their tiny gradients cannot give; far off it (a point at the centre of
/// its circle) they contradict the others. The residual of a nonholonomic
/// row is zero by definition, so at a state on the manifold of the
/// holonomic rows a contradiction among nonholonomic rows is not reported
/// either.
pub const NEAR_MANIFOLD: f64 = 1e-8;

/// Whether rows found dependent must agree with the others.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Dependents {
    /// A dependent row whose demand the solution misses beyond
    /// [`CONSISTENCY_TOLERANCE`] is an error
    /// ([`DynamicsError::InconsistentConstraints`]).
    MustAgree,
    /// The solution that holds the independent rows exactly (the
    /// least-squares one where the rank is deficient), whatever the
    /// dependent rows demand; the multipliers the least-norm ones.
    LeastSquares,
}

/// How the saddle-point system `M v̇ = f + Aᵀ λ`, `A v̇ = b` is solved (and
/// the projections onto the constraints, which are the same problem).
///
/// # Which solver when
///
/// * [`RankRevealing`](Self::RankRevealing), the default: any mechanism whose
///   accelerations are determined, that is whose KKT matrix has `M` positive
///   definite on the null space of `A`. It survives redundant constraints
///   (Bricard's mechanism, a planar loop written with spatial joints, a
///   constraint written twice), singular positions where `A` loses rank for
///   an instant (the N-four-bar mechanism when it lies flat; an integration
///   crosses them with [`Stabilisation::Projection`](crate::Stabilisation),
///   not unstabilised nor with Baumgarte's terms), and
///   coordinates with no inertia of their own that the constraints tie to
///   others. It returns the exact `v̇` and the multipliers `λ` of least
///   Euclidean norm (redundant rows share the load equally), and still
///   reports truly contradictory rows: dependent rows whose demand
///   disagrees at a state on the manifold ([`NEAR_MANIFOLD`]) are the
///   rounding and discretisation near a singular position, and get the
///   least-squares solution instead.
/// * [`SchurComplement`](Self::SchurComplement): the fastest, about one
///   Cholesky factorisation cheaper; for mechanisms known to have a positive
///   definite `M` and independent rows everywhere on their path. It stops
///   with [`DependentConstraints`](DynamicsError::DependentConstraints) at
///   the first redundancy or singular position, which also makes it a
///   check that a model has none.
/// * [`Sparse`](Self::Sparse): large mechanisms whose rows and bodies each
///   couple a few coordinates (long closed chains, the N-four-bar mechanism
///   with N = 40): it handles what the rank-revealing solver handles at a
///   cost that grows with the nonzeros instead of the cube of the size (14
///   times faster at 81 coordinates and 80 rows), to about `1e-9` relative
///   instead of the rounding.
/// * For long runs through singular positions at a fixed step, or to match
///   the reference solutions of the IFToMM benchmarks, integrate with the
///   index-3 augmented Lagrangian method
///   ([`AugmentedLagrangian`](crate::integrate::AugmentedLagrangian)),
///   which needs neither `A` of full rank nor `M` invertible.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ConstraintSolver {
    /// `M = L Lᵀ`, then `S = A M⁻¹ Aᵀ` by Cholesky in declaration order:
    /// `λ = S⁻¹ (b − A M⁻¹ f)`, `v̇ = M⁻¹ (f + Aᵀ λ)`. Needs `M` positive
    /// definite and `A` of full row rank.
    SchurComplement,
    /// The mass matrix augmented by the constraints, `M̄ = M + ρ AᵀA`
    /// (`ρ` the ratio of the largest diagonal entries of `M` and `AᵀA`),
    /// which is positive definite whenever the KKT matrix determines `v̇`;
    /// then `S̄ = A M̄⁻¹ Aᵀ` by Cholesky with symmetric pivoting, which
    /// reveals the rank of `A` ([`ACCELERATION_RANK_TOLERANCE`] for the
    /// accelerations, [`RANK_TOLERANCE`] for the projections). The
    /// independent rows give `v̇` exactly (the dependent ones are checked
    /// against it, [`CONSISTENCY_TOLERANCE`], unless the state is on the
    /// manifold, [`NEAR_MANIFOLD`]), and `λ` is moved to the least-norm member
    /// of its family `λ + null(Aᵀ)`. Adding `ρ AᵀA` changes no solution:
    /// on the motions that satisfy `A x = c` it adds the constant `ρ |c|²`
    /// to the kinetic-energy norm that Gauss's principle minimises.
    #[default]
    RankRevealing,
    /// `M̄ = M + ρ AᵀA` with a stiff weight `ρ` ([`STIFFNESS`](super::STIFFNESS)),
    /// factorised by a sparse `L D Lᵀ` in a minimum-degree order, and the
    /// multipliers by the method of
    /// multipliers (`M̄ xₖ = f + Aᵀ μₖ`, `μₖ₊₁ = μₖ + ρ (b − A xₖ)`), which
    /// converges to the least-norm `λ` whatever the rank of `A`: no dense
    /// `A M̄⁻¹ Aᵀ` is formed. For large mechanisms whose rows and bodies
    /// each couple a few coordinates (the IFToMM N-four-bar mechanism with
    /// N = 40: 81 coordinates, 80 rows), where it is many times faster than
    /// [`RankRevealing`](Self::RankRevealing); its accelerations hold the
    /// rows to `1e-13` (relative) but carry the rounding of the stiff
    /// factorisation, about `1e-9` relative. The structure (where `M` and
    /// `A` have nonzeros, the order, the fill-in) is analysed at the first
    /// call for a mechanism and kept by the thread for the next ones, which
    /// only check that no nonzero falls outside it and factorise at the
    /// cost of the nonzeros; an entry that was zero by chance at the first
    /// call and is not later brings a new analysis. Its work arrays are on
    /// the heap (a few allocations per call).
    Sparse,
}

/// The constraint Jacobian `A` seen through the metric of the (augmented)
/// mass matrix, factorised once for several right-hand sides:
/// `Y = M̄⁻¹ Aᵀ` and the factor of the Schur complement `S̄ = A M̄⁻¹ Aᵀ`.
///
/// It solves every problem of the form "minimise `½ xᵀ M x − fᵀ x` subject to
/// `A x = c`": the accelerations (`f` the forcing, `c = b`) and the
/// M-orthogonal projections onto the constraints (`f = 0`, `c` the residual).
///
/// It is lent to a closure by [`with`](Self::with) rather than returned: the
/// dense metric of a mechanism of 80 coordinates weighs some 200 kB, which
/// every move would copy.
#[derive(Clone, Copy)]
pub(crate) enum ConstraintMetric<'a, const NV: usize, const NC: usize> {
    /// [`ConstraintSolver::SchurComplement`] and [`ConstraintSolver::RankRevealing`].
    Dense(&'a DenseMetric<NV, NC>),
    /// [`ConstraintSolver::Sparse`].
    Sparse(&'a SparseMetric<NV, NC>),
}

impl<const NV: usize, const NC: usize> ConstraintMetric<'_, NV, NC> {
    /// Factorises the metric of `mass` and `jacobian` for `solver` and lends
    /// it to `use_metric`; fails if an entry is not finite, if the
    /// (augmented) mass matrix is not positive definite (a coordinate named
    /// from `names` moves freely without inertia), or, for the Schur
    /// complement, if a row depends on the rows before it. The dense
    /// solvers leave out the rows `absent` (those that vanish identically,
    /// [`ConstrainedSystem::VANISHING_ROWS`]), whose multipliers are zero;
    /// the sparse one needs no telling (a zero row adds nothing to `M̄`).
    pub(crate) fn with<R>(
        solver: ConstraintSolver,
        rank_tolerance: f64,
        mass: &[[f64; NV]; NV],
        names: &[&'static str; NV],
        (jacobian, absent): (&[[f64; NV]; NC], &[bool; NC]),
        use_metric: impl FnOnce(ConstraintMetric<'_, NV, NC>) -> Result<R, DynamicsError>,
    ) -> Result<R, DynamicsError> {
        match solver {
            ConstraintSolver::Sparse => use_metric(ConstraintMetric::Sparse(&SparseMetric::new(
                mass, names, jacobian,
            )?)),
            _ => use_metric(ConstraintMetric::Dense(&DenseMetric::new(
                solver,
                rank_tolerance,
                mass,
                names,
                (jacobian, absent),
            )?)),
        }
    }

    /// The `x` and least-norm `λ` of `M x = f + Aᵀ λ`, `A x = c`, the rows
    /// found dependent checked or not as `dependents` says.
    pub(crate) fn solve(
        &self,
        f: &SVector<f64, NV>,
        c: &SVector<f64, NC>,
        dependents: Dependents,
    ) -> Result<(SVector<f64, NV>, SVector<f64, NC>), DynamicsError> {
        match self {
            Self::Dense(metric) => metric.solve(f, c, dependents),
            Self::Sparse(metric) => metric
                .solve(&(*f).into(), &(*c).into(), dependents)
                .map(|(x, lambda)| (SVector::from(x), SVector::from(lambda))),
        }
    }

    /// The smallest correction in the metric of `M` with `A x = c` (on the
    /// independent rows).
    pub(crate) fn least_norm(&self, c: &SVector<f64, NC>) -> SVector<f64, NV> {
        match self {
            Self::Dense(metric) => metric.least_norm(c),
            Self::Sparse(metric) => SVector::from(metric.least_norm(&(*c).into())),
        }
    }
}

/// The metric of the dense solvers.
pub(crate) struct DenseMetric<const NV: usize, const NC: usize> {
    mass: Cholesky<f64, Const<NV>>,
    penalty: f64,
    jacobian: SMatrix<f64, NC, NV>,
    mass_inverse_jacobian_t: SMatrix<f64, NV, NC>,
    schur: SchurFactor<NC>,
}

impl<const NV: usize, const NC: usize> DenseMetric<NV, NC> {
    /// Factorises the metric of the finite `mass` and `jacobian` for
    /// `solver` (see [`ConstraintMetric::with`]).
    pub(crate) fn new(
        solver: ConstraintSolver,
        rank_tolerance: f64,
        mass: &[[f64; NV]; NV],
        names: &[&'static str; NV],
        (jacobian, absent): (&[[f64; NV]; NC], &[bool; NC]),
    ) -> Result<Self, DynamicsError> {
        if !mass.iter().all(all_finite) {
            return Err(DynamicsError::NonFiniteEquations);
        }
        if !jacobian.iter().all(all_finite) {
            return Err(DynamicsError::NonFiniteConstraints);
        }
        let a = SMatrix::<f64, NC, NV>::from_fn(|i, j| jacobian[i][j]);
        let penalty = match solver {
            ConstraintSolver::SchurComplement => 0.0,
            _ => augmentation(mass, &a),
        };
        let normal = a.tr_mul(&a) * penalty;
        let augmented: [[f64; NV]; NV] =
            std::array::from_fn(|i| std::array::from_fn(|j| mass[i][j] + normal[(i, j)]));
        let mass = factor_mass_matrix(&augmented, names)?;
        let mass_inverse_jacobian_t = mass.solve(&a.transpose());
        let s = a * mass_inverse_jacobian_t;
        let s = std::array::from_fn(|i| std::array::from_fn(|j| s[(i, j)]));
        let schur = match solver {
            ConstraintSolver::SchurComplement => {
                SchurFactor::in_order(s, RELATIVE_PIVOT_TOLERANCE, absent).map_err(|dependent| {
                    DynamicsError::DependentConstraints {
                        row: dependent.row,
                        pivot: dependent.pivot,
                    }
                })?
            }
            _ => SchurFactor::pivoted(s, rank_tolerance, absent),
        };
        Ok(Self {
            mass,
            penalty,
            jacobian: a,
            mass_inverse_jacobian_t,
            schur,
        })
    }

    /// The `x` and least-norm `λ` of `M x = f + Aᵀ λ`, `A x = c`. With
    /// `M̄ = M + ρ AᵀA`: `M̄ x = f + Aᵀ μ` with `μ = λ + ρ c`, so
    /// `S̄ μ = c − A M̄⁻¹ f` and `x = M̄⁻¹ (f + Aᵀ μ)`.
    pub(crate) fn solve(
        &self,
        f: &SVector<f64, NV>,
        c: &SVector<f64, NC>,
        dependents: Dependents,
    ) -> Result<(SVector<f64, NV>, SVector<f64, NC>), DynamicsError> {
        let unconstrained = self.mass.solve(f);
        let r: [f64; NC] = (c - self.jacobian * unconstrained).into();
        let mu = SVector::from(self.schur.solve(&r));
        let x = unconstrained + self.mass_inverse_jacobian_t * mu;
        if dependents == Dependents::MustAgree {
            self.check_consistency(&x, c)?;
        }
        let lambda: [f64; NC] = (mu - self.penalty * c).into();
        Ok((x, SVector::from(self.schur.least_norm(&lambda))))
    }

    /// The factorised Schur complement `S̄ = A M̄⁻¹ Aᵀ`.
    pub(crate) fn schur(&self) -> &SchurFactor<NC> {
        &self.schur
    }

    /// The smallest correction in the M-norm, `x = M̄⁻¹ Aᵀ S̄⁺ c`, with
    /// `A x = c` on the independent rows (and on every row when `c` is
    /// consistent).
    pub(crate) fn least_norm(&self, c: &SVector<f64, NC>) -> SVector<f64, NV> {
        self.mass_inverse_jacobian_t * SVector::from(self.schur.solve(&(*c).into()))
    }

    /// Fails if a dependent row demands something `x` does not do, beyond
    /// [`CONSISTENCY_TOLERANCE`] times the largest `Σⱼ |Aᵢⱼ xⱼ| + |cᵢ|` of
    /// any row.
    fn check_consistency(
        &self,
        x: &SVector<f64, NV>,
        c: &SVector<f64, NC>,
    ) -> Result<(), DynamicsError> {
        let scale = (0..NC).fold(0.0f64, |m, i| {
            let terms: f64 = (0..NV).map(|j| (self.jacobian[(i, j)] * x[j]).abs()).sum();
            m.max(terms + c[i].abs())
        });
        for k in self.schur.rank()..NC {
            let row = self.schur.row_at(k);
            let mismatch = (self.jacobian.row(row).dot(&x.transpose()) - c[row]).abs();
            if mismatch > CONSISTENCY_TOLERANCE * scale {
                let z = self.schur.dependency(k);
                let with = (0..NC)
                    .filter(|&i| i != row)
                    .max_by(|&i, &j| z[i].abs().total_cmp(&z[j].abs()))
                    .unwrap_or(row);
                return Err(DynamicsError::InconsistentConstraints {
                    row,
                    with,
                    mismatch,
                });
            }
        }
        Ok(())
    }
}

/// The weight `ρ` of `AᵀA` in the augmented mass matrix: the ratio of the
/// largest diagonal entries of `M` and `AᵀA`, so that both terms weigh
/// alike (`1` if `M` has no positive diagonal, `0` if `A` is zero).
fn augmentation<const NV: usize, const NC: usize>(
    mass: &[[f64; NV]; NV],
    jacobian: &SMatrix<f64, NC, NV>,
) -> f64 {
    let largest_mass = (0..NV).fold(0.0f64, |m, i| m.max(mass[i][i]));
    let largest_row = (0..NV).fold(0.0f64, |m, j| m.max(jacobian.column(j).norm_squared()));
    match (largest_mass > 0.0, largest_row > 0.0) {
        (_, false) => 0.0,
        (true, true) => largest_mass / largest_row,
        (false, true) => 1.0 / largest_row,
    }
}

/// The accelerations `v̇` and the Lagrange multipliers `λ` that solve
/// `M(q) v̇ = f(t, q, v, u) + A(q)ᵀ λ` and `A(q) v̇ = b(t, q, v)`, by the
/// default [`ConstraintSolver::RankRevealing`] (see
/// [`ConstraintSolver::accelerations`] for the other).
///
/// Solved on the stack (nothing is allocated). `λᵢ` is the generalized
/// constraint force of row `i` per unit of its Jacobian row: `Aᵀ λ` is the
/// force that the constraints add to `f`; with redundant rows it is the
/// least-norm choice among the multipliers giving the same `Aᵀ λ`.
///
/// Never returns a non-finite value. Errors: a non-finite state
/// ([`NonFiniteState`](DynamicsError::NonFiniteState)), mass matrix or forcing
/// ([`NonFiniteEquations`](DynamicsError::NonFiniteEquations)) or constraint
/// ([`NonFiniteConstraints`](DynamicsError::NonFiniteConstraints)); a
/// coordinate free to move without inertia
/// ([`SingularMassMatrix`](DynamicsError::SingularMassMatrix)); constraint
/// rows that contradict each other
/// ([`InconsistentConstraints`](DynamicsError::InconsistentConstraints)).
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
    ConstraintSolver::default().accelerations(system, t, q, v, u)
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
/// (`tests/suite/constraints.rs`): max `|φ|` is `2e-10` unstabilised, `2e-12` with
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
    ConstraintSolver::default().baumgarte_accelerations(system, t, q, v, u, alpha, beta)
}

impl ConstraintSolver {
    /// [`constrained_accelerations`] by this solver. The errors are those
    /// of [`constrained_accelerations`]; [`SchurComplement`](Self::SchurComplement)
    /// also fails with
    /// [`DependentConstraints`](DynamicsError::DependentConstraints) where
    /// the rows are linearly dependent (redundant or contradictory
    /// constraints, or a singular configuration), and with
    /// [`SingularMassMatrix`](DynamicsError::SingularMassMatrix) for any
    /// coordinate without inertia of its own.
    pub fn accelerations<S, const NQ: usize, const NV: usize, const NU: usize, const NC: usize>(
        self,
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
        self.solve_with_bias(system, t, q, v, u, bias)
    }

    /// [`baumgarte_accelerations`] by this solver.
    #[allow(clippy::too_many_arguments)]
    pub fn baumgarte_accelerations<
        S,
        const NQ: usize,
        const NV: usize,
        const NU: usize,
        const NC: usize,
    >(
        self,
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
        let stabilised = std::array::from_fn(|i| {
            bias[i] - 2.0 * alpha * velocity[i] - beta * beta * residual[i]
        });
        self.solve_with_bias(system, t, q, v, u, stabilised)
    }

    /// `v̇` and `λ` of `M v̇ = f + Aᵀ λ`, `A v̇ = bias`, at a finite state.
    fn solve_with_bias<S, const NQ: usize, const NV: usize, const NU: usize, const NC: usize>(
        self,
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
        let equations = SaddlePoint {
            mass: &system.mass_matrix_at(t, q),
            forcing: system.forcing(t, q, v, u),
            jacobian: &system.constraint_jacobian_at(t, q),
            bias,
        };
        self.solve_saddle_point(system, t, q, equations, |solution, _| Ok(solution))
    }

    /// `v̇` and `λ` of `equations` at `(t, q)` (the residual there says
    /// whether dependent rows that disagree are forgiven), then `then` with
    /// them and the factorised metric, for more right-hand sides.
    pub(crate) fn solve_saddle_point<
        S,
        R,
        const NQ: usize,
        const NV: usize,
        const NU: usize,
        const NC: usize,
    >(
        self,
        system: &S,
        t: f64,
        q: &[f64; NQ],
        equations: SaddlePoint<'_, NV, NC>,
        then: impl FnOnce(
            ([f64; NV], [f64; NC]),
            ConstraintMetric<'_, NV, NC>,
        ) -> Result<R, DynamicsError>,
    ) -> Result<R, DynamicsError>
    where
        S: ConstrainedSystem<NQ, NV, NU, NC>,
    {
        let SaddlePoint {
            mass,
            forcing,
            jacobian,
            bias,
        } = equations;
        if !all_finite(&forcing) {
            return Err(DynamicsError::NonFiniteEquations);
        }
        if !all_finite(&bias) {
            return Err(DynamicsError::NonFiniteConstraints);
        }
        ConstraintMetric::with(
            self,
            ACCELERATION_RANK_TOLERANCE,
            mass,
            &pivot_names::<S, NQ, NV, NU>(),
            (jacobian, &S::VANISHING_ROWS),
            |metric| {
                let (f, b) = (SVector::from(forcing), SVector::from(bias));
                let (vdot, lambda) = match metric.solve(&f, &b, Dependents::MustAgree) {
                    Err(DynamicsError::InconsistentConstraints { .. })
                        if on_the_manifold(&system.constraint_residual(t, q), jacobian, q) =>
                    {
                        metric.solve(&f, &b, Dependents::LeastSquares)
                    }
                    solution => solution,
                }?;
                let (vdot, lambda): ([f64; NV], [f64; NC]) = (vdot.into(), lambda.into());
                if !(all_finite(&vdot) && all_finite(&lambda)) {
                    return Err(DynamicsError::NonFiniteAccelerations);
                }
                then((vdot, lambda), metric)
            },
        )
    }
}

/// The saddle-point system `M v̇ = f + Aᵀ λ`, `A v̇ = b` at one state.
#[derive(Clone, Copy, Debug)]
pub struct SaddlePoint<'a, const NV: usize, const NC: usize> {
    /// `M`.
    pub mass: &'a [[f64; NV]; NV],
    /// `f`.
    pub forcing: [f64; NV],
    /// `A`.
    pub jacobian: &'a [[f64; NV]; NC],
    /// `b`.
    pub bias: [f64; NC],
}

/// Whether the holonomic `residual` at `q` is within [`NEAR_MANIFOLD`] of
/// the manifold: `max |φᵢ| ≤ NEAR_MANIFOLD · max |Aᵢⱼ| · (1 + max |qⱼ|)`.
fn on_the_manifold<const NQ: usize, const NV: usize, const NC: usize>(
    residual: &[f64; NC],
    jacobian: &[[f64; NV]; NC],
    q: &[f64; NQ],
) -> bool {
    let largest = |values: &[f64]| values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let gradient = jacobian.iter().fold(0.0f64, |m, row| m.max(largest(row)));
    largest(residual) <= NEAR_MANIFOLD * gradient * (1.0 + largest(q))
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constrained::test_systems::{PointOnCircle, TiedMassless};

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
    fn constraint_written_twice_shares_its_multiplier_equally() {
        let PointOnCircle { m, l, g } = PENDULUM;
        let twice = PointOnCircle::<2> { m, l, g };
        let (theta, speed) = (0.4, 1.0);
        let (q, qd) = on_circle(l, theta, speed);
        let (qdd, [first, second]) = constrained_accelerations(&twice, 0.0, &q, &qd, &[]).unwrap();
        let (single, _) = constrained_accelerations(&PENDULUM, 0.0, &q, &qd, &[]).unwrap();
        assert!((qdd[0] - single[0]).abs() < 1e-13 && (qdd[1] - single[1]).abs() < 1e-13);
        // The rod tension of the single row, split equally: the least-norm λ.
        let expected = -(m * speed * speed / l + m * g * theta.cos()) / (2.0 * l);
        for half in [first, second] {
            assert!(
                (half - expected / 2.0).abs() < 1e-12 * expected.abs(),
                "{half}"
            );
        }
    }

    #[test]
    fn the_schur_complement_stops_at_a_dependent_row() {
        let twice = PointOnCircle::<2> {
            m: PENDULUM.m,
            l: PENDULUM.l,
            g: PENDULUM.g,
        };
        let (q, qd) = on_circle(twice.l, 0.4, 1.0);
        match ConstraintSolver::SchurComplement.accelerations(&twice, 0.0, &q, &qd, &[]) {
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
        // Without mass the point moves freely along the circle.
        let massless = PointOnCircle::<1> { m: 0.0, ..PENDULUM };
        let result = constrained_accelerations(&massless, 0.0, &q, &qd, &[]);
        assert!(matches!(
            result,
            Err(DynamicsError::SingularMassMatrix { .. })
        ));
        let result = ConstraintSolver::SchurComplement.accelerations(&massless, 0.0, &q, &qd, &[]);
        assert!(matches!(
            result,
            Err(DynamicsError::SingularMassMatrix { index: 0, .. })
        ));
    }

    #[test]
    fn constraint_at_its_singular_point_cannot_be_met() {
        // At the centre of the circle the Jacobian [2x, 2y] vanishes, yet
        // moving at unit speed the row demands A q̈ = −2 |q̇|².
        let (q, qd) = ([0.0; 2], [1.0, 0.0]);
        let result = constrained_accelerations(&PENDULUM, 0.0, &q, &qd, &[]);
        assert_eq!(
            result,
            Err(DynamicsError::InconsistentConstraints {
                row: 0,
                with: 0,
                mismatch: 2.0
            })
        );
        let result = ConstraintSolver::SchurComplement.accelerations(&PENDULUM, 0.0, &q, &qd, &[]);
        assert!(matches!(
            result,
            Err(DynamicsError::DependentConstraints { row: 0, .. })
        ));
    }

    #[test]
    fn a_state_is_on_the_manifold_to_first_order_relative_to_its_coordinates() {
        // A02's stage 2e-10 rad from the flat position: residuals of
        // rounding, unit gradients, angles near −π.
        let q = [-3.14159205, -3.14159205, 2.9e-10];
        let a = [[2.9e-10, -2.9e-10, 1.0], [1.0, -1.0, 2.9e-10]];
        assert!(on_the_manifold(&[2.2e-16, -2.2e-15], &a, &q));
        // Off by 1e-7 of the coordinates' size: not on it.
        assert!(!on_the_manifold(&[4.2e-7, 0.0], &a, &q));
        // The centre of the circle `x² + y² = l²`: `A = 0`, `φ = −l²`.
        assert!(!on_the_manifold(&[-0.25], &[[0.0, 0.0]], &[0.0, 0.0]));
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

    #[test]
    fn a_coordinate_without_inertia_tied_by_a_constraint_has_its_acceleration() {
        let system = TiedMassless {
            m: 2.0,
            g: 9.81,
            push: 5.0,
        };
        let (vdot, [lambda]) =
            constrained_accelerations(&system, 0.0, &[0.3, 0.3], &[1.0, 1.0], &[]).unwrap();
        let expected = system.push / system.m - system.g;
        assert!((vdot[0] - expected).abs() < 1e-14 && (vdot[1] - expected).abs() < 1e-14);
        assert!((lambda + system.push).abs() < 1e-13, "{lambda}");
        let schur = ConstraintSolver::SchurComplement.accelerations(
            &system,
            0.0,
            &[0.3; 2],
            &[1.0; 2],
            &[],
        );
        assert!(matches!(
            schur,
            Err(DynamicsError::SingularMassMatrix {
                index: 1,
                coordinate: "s",
                ..
            })
        ));
    }

    #[test]
    fn contradictory_rows_are_named() {
        // Rows x = 0 and 2x = 0 agree at position level but, moving, the
        // second demands a different acceleration: A = [[1, 0], [2, 0]],
        // b = [0, 1].
        let a = [[1.0, 0.0], [2.0, 0.0]];
        let error = ConstraintMetric::with(
            ConstraintSolver::RankRevealing,
            ACCELERATION_RANK_TOLERANCE,
            &[[1.0, 0.0], [0.0, 1.0]],
            &["x", "y"],
            (&a, &[false; 2]),
            |metric| {
                metric.solve(
                    &SVector::from([0.0, -9.81]),
                    &SVector::from([0.0, 1.0]),
                    Dependents::MustAgree,
                )
            },
        )
        .unwrap_err();
        // Row 1 is taken first (larger diagonal): row 0 is the one left over.
        match error {
            DynamicsError::InconsistentConstraints {
                row: 0,
                with: 1,
                mismatch,
            } => assert!((mismatch - 0.5).abs() < 1e-15, "{mismatch}"),
            other => panic!("expected rows 0 and 1 to contradict, got {other:?}"),
        }
        assert!(
            error
                .to_string()
                .starts_with("constraint rows 0 and 1 contradict")
        );
    }
}
