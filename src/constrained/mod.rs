//! Constrained dynamics in dependent coordinates: `M q̈ = f + Aᵀ λ` with
//! `A q̈ = b`, solved for the accelerations `q̈` and the Lagrange multipliers
//! `λ`, with the constraint drift of a numerical solution held in check by
//! Baumgarte stabilisation or by coordinate projection.
//!
//! * [`constrained_accelerations`] and [`baumgarte_accelerations`] solve the
//!   saddle-point system by its Schur complement `A M⁻¹ Aᵀ` on the stack;
//! * [`project_onto_constraints`] moves a state back onto the constraint
//!   manifold (positions, then speeds);
//! * [`constrained_rk4_step`] and [`simulate_constrained`] integrate with a
//!   chosen [`Stabilisation`], mirroring [`rk4_step`](crate::rk4_step) and
//!   [`simulate`](crate::simulate).

mod multipliers;
mod projection;
mod stepper;
#[cfg(test)]
mod test_systems;

pub use multipliers::{baumgarte_accelerations, constrained_accelerations};
pub use projection::project_onto_constraints;
pub use stepper::{Stabilisation, constrained_rk4_step, constraint_drift, simulate_constrained};
