//! Constrained dynamics in dependent coordinates: `M v̇ = f + Aᵀ λ` with
//! `A v̇ = b`, solved for the accelerations `v̇` and the Lagrange multipliers
//! `λ`, with the constraint drift of a numerical solution held in check by
//! Baumgarte stabilisation or by coordinate projection.
//!
//! * [`constrained_accelerations`] and [`baumgarte_accelerations`] solve the
//!   saddle-point system on the stack by a [`ConstraintSolver`] (its docs
//!   say which solver when): rank-revealing by default, so redundant
//!   constraints, singular positions and coordinates without inertia of
//!   their own are handled;
//! * [`linearize_on_constraints`] linearises the equations on the
//!   constraint manifold with independent coordinates and speeds (what a generated
//!   `linearize` calls for a constrained system), and
//!   [`constrained_accelerations_jacobian`] gives the accelerations'
//!   derivatives (what its `accelerations_jacobian` calls);
//! * [`project_onto_constraints`] moves a state back onto the constraint
//!   manifold (positions, then speeds), and [`project_onto_energy_level`]
//!   the speeds of a conservative system onto its energy level;
//! * [`constrained_series`] solves the orders of a constrained motion's
//!   Taylor series with one factorisation (what a generated
//!   `taylor_coefficients` calls);
//! * a [`Stabilisation`] chooses how [`Constrained`](crate::Constrained)
//!   dynamics keep an integration on the manifold, and
//!   [`constraint_drift`] measures how far it is off;
//! * [`DriftLimits`] say how far off (and, through
//!   [`constraint_conditioning`], how near a singular position) an
//!   integration may go before it stops with an error naming the row and
//!   the time.

mod linearize;
mod multipliers;
mod projection;
mod rank;
mod series;
mod sparse;
mod stabilisation;
#[cfg(test)]
pub(crate) mod test_systems;
mod watch;

pub use linearize::{
    AccelerationPartials, AccelerationsJacobian, ConstrainedLinearization, ConstrainedPartials,
    DEPENDENT_PIVOT_TOLERANCE, ManifoldChart, constrained_accelerations_jacobian,
    linearize_on_constraints,
};
pub use multipliers::{
    ACCELERATION_RANK_TOLERANCE, CONSISTENCY_TOLERANCE, ConstraintSolver, NEAR_MANIFOLD,
    RANK_TOLERANCE, SaddlePoint, baumgarte_accelerations, constrained_accelerations,
};
pub(crate) use projection::checked;
pub use projection::{project_onto_constraints, project_onto_energy_level};
pub(crate) use rank::SchurFactor;
pub use series::{SeriesSolver, constrained_series};
pub use sparse::STIFFNESS;
pub use stabilisation::{Stabilisation, constraint_drift};
pub use watch::{
    BARELY_INDEPENDENT, Conditioning, DRIFT_LIMIT, DriftLimits, WeakestRow, constraint_conditioning,
};
