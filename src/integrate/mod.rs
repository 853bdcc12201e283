//! Time integration of `M(q) v̇ = f(t, q, v, u)`, `q̇ = N(q) v` from a
//! [`State`] `(t, q, v)`.
//!
//! Every integrator steps a [`Dynamics`]: a system closed over its input law,
//! [`Unconstrained::new(&system, |t, q, v| u)`](Unconstrained::new) (or
//! [`Unconstrained::without_inputs`]), or a constrained one with its drift
//! [`Stabilisation`](crate::Stabilisation) ([`Constrained`]). Every one
//! allocates nothing, moves the configuration through the system's
//! `integrate_configuration` (`q ⊕ h v`), lets an observer see the initial
//! state and every step, and returns the final state with the work done
//! ([`Solution`]) or an [`IntegrationError`] naming where and why it stopped.
//!
//! | method | steps | use it for |
//! |---|---|---|
//! | [`rk4`] | fixed, `steps` to `t_end` | real-time loops, reproducible runs, a cheap default ([`rk4_step`]: one step at a time) |
//! | [`adaptive`] with [`ExplicitPair::DormandPrince54`] | adaptive | moderate tolerances (`1e-6`…`1e-9`) on non-stiff systems |
//! | [`adaptive`] with [`ExplicitPair::Dop853`] | adaptive | tight tolerances (`1e-10` and below): the least work per digit |
//! | [`gauss_legendre`] | fixed | long runs of conservative systems: the energy error stays bounded |
//! | [`sdirk`] | fixed | stiff springs and joints, whose fast modes an explicit method must resolve |
//! | [`augmented_lagrangian`] | fixed | closed loops with redundant constraints or singular positions at a fixed step: the index-3 formulation of the IFToMM benchmarks' reference solutions (constrained dynamics only) |

mod adaptive;
mod augmented_lagrangian;
mod dynamics;
mod gauss;
mod lu;
mod runge_kutta;
mod sdirk;
mod solution;

pub use adaptive::{
    AdaptiveOptions, Crossing, DenseStep, Event, ExplicitPair, adaptive, adaptive_dense,
    adaptive_with_events,
};
pub use augmented_lagrangian::{AugmentedLagrangian, augmented_lagrangian};
pub use dynamics::{Constrained, Dynamics, InputLaw, NoInputs, Unconstrained};
pub use gauss::{GaussLegendre, gauss_legendre};
pub use runge_kutta::{State, rk4, rk4_step};
pub use sdirk::sdirk;
pub use solution::{Failure, IntegrationError, Solution, Statistics};
