//! Why forward dynamics fails: [`DynamicsError`], with the time, state or
//! equation entry that made the accelerations impossible to compute.

use std::fmt;

use super::NullMotion;

/// Why the accelerations could not be computed.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum DynamicsError {
    /// The time, a coordinate, a speed or an input is NaN or infinite.
    NonFiniteState,
    /// The mass matrix or the forcing has a NaN or infinite entry.
    NonFiniteEquations,
    /// The mass matrix is not safely positive definite: the Cholesky
    /// factorisation `M = L Lᵀ` met a pivot `Lⱼⱼ²` that is not larger than
    /// `1e-14` times the largest diagonal entry of `M`. `null_motion` says
    /// why: the combination of speeds that moves no mass there. One speed
    /// alone moves no mass of its own (a body without inertia about some
    /// axis); several have dependent columns, a coordinate singularity
    /// (Euler angles whose axes line up: a top released upright, a gimbal
    /// lock), which a quaternion joint or another start avoids.
    SingularMassMatrix {
        /// Index of the first failing pivot, which is the index of its
        /// coordinate.
        index: usize,
        /// Name of that coordinate.
        coordinate: &'static str,
        /// The pivot: zero, negative or tiny.
        pivot: f64,
        /// The speeds whose columns of `M` are dependent, with the weights
        /// of the motion that moves no mass (empty where the solver had no
        /// `M` at hand to analyse).
        null_motion: NullMotion,
    },
    /// The accelerations overflowed although the equations were finite and
    /// the mass matrix passed the pivot test.
    NonFiniteAccelerations,
    /// The coordinate rates `q̇ = N(q) v` of a `speeds` statement are
    /// undefined at this configuration: the rate of `coordinate` divides by
    /// `divisor`, which is within
    /// [`SINGULAR_RATES_TOLERANCE`](crate::dynamics::SINGULAR_RATES_TOLERANCE)
    /// of zero (a gimbal lock of Euler angles with body-axis rates, where
    /// `cos θ = 0`). Reported by
    /// [`MultibodySystem::check_coordinate_rates`](crate::MultibodySystem::check_coordinate_rates),
    /// which every integrator calls at every state it evaluates.
    SingularCoordinateRates {
        /// Name of the coordinate whose rate divides by `divisor`.
        coordinate: &'static str,
        /// The divisor, as the equations render it (`cos θ`).
        divisor: &'static str,
        /// Its value.
        value: f64,
    },
    /// The constraint Jacobian `A`, the bias `b`, the residual `φ` or the
    /// velocity form `ψ` has a NaN or infinite entry.
    NonFiniteConstraints,
    /// The constraint rows are linearly dependent to working precision: the
    /// Cholesky factorisation of the Schur complement `S = A M⁻¹ Aᵀ` met a
    /// pivot not larger than `1e-14` times the largest diagonal entry of `S`.
    /// Constraint `row` is then a combination of the rows before it: a
    /// redundant or contradictory constraint, or a singular configuration of
    /// the mechanism (a slider-crank whose rod equals its crank, at the
    /// position where both are vertical).
    DependentConstraints {
        /// Index of the first failing pivot, which is the index of its
        /// constraint row (declaration order).
        row: usize,
        /// The pivot: zero, negative or tiny.
        pivot: f64,
    },
    /// The constraints contradict each other: constraint `row` depends on the
    /// rows taken before it by the rank-revealing solver (among them `with`,
    /// the one weighing most in the dependency), but demands a different
    /// acceleration (`A v̇ = b`). Found by
    /// [`ConstraintSolver::RankRevealing`](crate::constrained::ConstraintSolver)
    /// when `|Aᵢ x − cᵢ|` exceeds
    /// [`CONSISTENCY_TOLERANCE`](crate::constrained::CONSISTENCY_TOLERANCE)
    /// times the largest `Σⱼ |Aᵢⱼ xⱼ| + |cᵢ|` of any row.
    InconsistentConstraints {
        /// The contradicting row (declaration order).
        row: usize,
        /// The independent row weighing most in its dependency.
        with: usize,
        /// `|Aᵢ x − cᵢ|`, the part of the demand that no motion can meet.
        mismatch: f64,
    },
    /// Coordinate projection did not bring the largest constraint residual
    /// `|φᵢ|` below its tolerance within its iteration budget.
    ProjectionNotConverged {
        /// Gauss–Newton iterations made.
        iterations: usize,
        /// The largest `|φᵢ|` left.
        residual: f64,
    },
    /// The independent coordinates chosen for the linearisation of a
    /// constrained system do not determine the others here: the
    /// constraints' Jacobian by the dependent coordinates is singular (its
    /// elimination met a pivot not larger than `1e-12` times the largest
    /// entry of the holonomic rows), at the column of `coordinate`. Choose other independent
    /// coordinates near this configuration.
    SingularDependentCoordinates {
        /// The dependent coordinate whose column failed.
        coordinate: &'static str,
        /// The pivot.
        pivot: f64,
    },
    /// The independent speeds chosen for the linearisation of a
    /// constrained system do not determine the others here: the
    /// constraints' Jacobian by the dependent speeds is singular (its
    /// elimination met a pivot not larger than `1e-12` times the largest
    /// entry of the rows), at the column of `speed`. Choose other independent speeds
    /// near this state.
    SingularDependentSpeeds {
        /// The dependent speed whose column failed.
        speed: &'static str,
        /// The pivot.
        pivot: f64,
    },
}

impl fmt::Display for DynamicsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFiniteState => f.write_str("non-finite time, coordinate, speed or input"),
            Self::NonFiniteEquations => {
                f.write_str("non-finite entry in the mass matrix or the forcing")
            }
            Self::SingularMassMatrix {
                index,
                coordinate,
                pivot,
                null_motion,
            } => match null_motion.names() {
                [_, _, ..] => {
                    let (names, weights) = (null_motion.names(), null_motion.weights());
                    let listed = names.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>();
                    let combination: String = names
                        .iter()
                        .zip(weights)
                        .map(|(n, w)| format!(" {w:+.3} {n}"))
                        .collect();
                    write!(
                        f,
                        "singular mass matrix: the columns of {} are dependent at this \
                         configuration (the speeds{combination} move no mass): a coordinate \
                         singularity, where angles such as Euler angles turn about the same axis; \
                         use a quaternion joint (`joint spherical` or `joint free`) or start \
                         elsewhere (pivot of `{coordinate}`, index {index}: {pivot:.3e})",
                        listed.join(" and ")
                    )
                }
                _ => write!(
                    f,
                    "singular mass matrix: coordinate `{coordinate}` (index {index}) has no \
                     inertia of its own (Cholesky pivot {pivot:.3e})"
                ),
            },
            Self::NonFiniteAccelerations => f.write_str("the accelerations overflowed"),
            Self::SingularCoordinateRates {
                coordinate,
                divisor,
                value,
            } => write!(
                f,
                "singular coordinate rates q̇ = N(q) v: the rate of `{coordinate}` divides by \
                 {divisor} = {value:.3e}, which is (nearly) zero here"
            ),
            Self::NonFiniteConstraints => {
                f.write_str("non-finite entry in the constraint Jacobian, bias or residual")
            }
            Self::DependentConstraints { row, pivot } => write!(
                f,
                "constraint row {row} depends on the rows before it: redundant, contradictory \
                 or at a singular configuration (Schur pivot {pivot:.3e})"
            ),
            Self::InconsistentConstraints {
                row,
                with,
                mismatch,
            } => write!(
                f,
                "constraint rows {row} and {with} contradict each other: row {row} depends on \
                 rows including {with} but demands a value off by {mismatch:.3e}"
            ),
            Self::ProjectionNotConverged {
                iterations,
                residual,
            } => write!(
                f,
                "projection onto the constraints did not converge: max |φ| = {residual:.3e} \
                 after {iterations} iterations"
            ),
            Self::SingularDependentCoordinates { coordinate, pivot } => write!(
                f,
                "the independent coordinates do not determine `{coordinate}` here: the \
                 constraints' Jacobian by the dependent coordinates is singular (pivot \
                 {pivot:.3e}); choose other independent coordinates"
            ),
            Self::SingularDependentSpeeds { speed, pivot } => write!(
                f,
                "the independent speeds do not determine `{speed}` here: the constraints' \
                 Jacobian by the dependent speeds is singular (pivot {pivot:.3e}); choose \
                 other independent speeds"
            ),
        }
    }
}

impl std::error::Error for DynamicsError {}
