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
//! * a generated `linearize` of a constrained system linearises the
//!   equations on the constraint manifold with independent coordinates and
//!   speeds ([`ConstrainedLinearization`]), and its `accelerations_jacobian`
//!   gives the accelerations' derivatives ([`AccelerationsJacobian`]);
//! * [`project_onto_constraints`] moves a state back onto the constraint
//!   manifold (positions, then speeds), and [`project_onto_energy_level`]
//!   the speeds of a conservative system onto its energy level;
//! * a [`Stabilisation`] chooses how [`Constrained`](crate::Constrained)
//!   dynamics keep an integration on the manifold, and
//!   [`constraint_drift`] measures how far it is off;
//! * [`DriftLimits`] say how far off (and, through
//!   [`constraint_conditioning`], how near a singular position) an
//!   integration may go before it stops with an error naming the row and
//!   the time.

pub(crate) mod linearize;
pub(crate) mod multipliers;
mod projection;
mod rank;
pub(crate) mod series;
mod sparse;
mod stabilisation;
#[cfg(test)]
pub(crate) mod test_systems;
mod watch;

pub use linearize::{AccelerationsJacobian, ConstrainedLinearization, DEPENDENT_PIVOT_TOLERANCE};
pub use multipliers::{
    ACCELERATION_RANK_TOLERANCE, CONSISTENCY_TOLERANCE, ConstraintSolver, NEAR_MANIFOLD,
    RANK_TOLERANCE, baumgarte_accelerations, constrained_accelerations,
};
pub(crate) use projection::checked;
pub use projection::{project_onto_constraints, project_onto_energy_level};
pub(crate) use rank::SchurFactor;
pub use sparse::STIFFNESS;
pub use stabilisation::{Stabilisation, constraint_drift};
pub use watch::{
    BARELY_INDEPENDENT, Conditioning, DRIFT_LIMIT, DriftLimits, WeakestRow, constraint_conditioning,
};
