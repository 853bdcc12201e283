//! Exact multibody equations of motion, derived at compile time with
//! d'Alembert's principle.
//!
//! The `dalembert!` macro turns a declarative description of a mechanical
//! system into a struct whose functions evaluate the mass matrix `M(q)`, the
//! forcing `f(t, q, v, u)` of `M(q) v̇ = f`, the energies and the constraints
//! as flat, allocation-free code. The struct implements [`MultibodySystem`]
//! (and [`ConstrainedSystem`] when it has constraints), so this crate's
//! solvers and integrators work on it:
//!
//! ```
//! use dalembert::{State, Unconstrained, integrate};
//!
//! dalembert::dalembert! {
//!     /// A simple pendulum, angle from the downward vertical.
//!     pub Pendulum {
//!         parameters m, l, g;
//!         coordinates theta;
//!         frame B = N.rotate_z(theta);
//!         point P = O - l * B.y;
//!         particle bob { mass: m, at: P };
//!         gravity -g * N.y;
//!     }
//! }
//!
//! let pendulum = Pendulum { m: 1.0, l: 1.0, g: 9.81 };
//! assert_eq!(pendulum.mass_matrix(&[0.3]), [[1.0]]); // m l²
//! let start = State { t: 0.0, q: [1.0], v: [0.0] };
//! let dynamics = Unconstrained::without_inputs(&pendulum);
//! let end = integrate::rk4(&dynamics, start, 10.0, 10_000, |_| {})?.end;
//! assert_eq!(end.t, 10.0);
//! let energy = |s: &State<1, 1>| dalembert::energy(&pendulum, &s.q, &s.v);
//! assert!((energy(&end) - energy(&start)).abs() < 1e-9);
//! # Ok::<(), dalembert::IntegrationError<1>>(())
//! ```
//!
//! * [`MultibodySystem`] and [`ConstrainedSystem`]: the traits every
//!   generated system implements;
//! * [`dynamics`]: the accelerations `v̇` of `M v̇ = f` and their errors;
//! * [`constrained`]: accelerations and multipliers of constrained systems,
//!   projection onto the constraints, drift stabilisation;
//! * [`integrate`]: the integrators, and which one to use for which job;
//! * [`control`]: the exact jacobian of one integration step and its
//!   adjoint, for trajectory optimisation;
//! * [`math`]: the elementary functions the generated code calls;
//! * [`series`]: the Taylor-coefficient recurrences that the code of
//!   `outputs taylor;` calls ([`TaylorSystem`], [`integrate::taylor`]).
//!
//! The language, the generated API and the build-script route are described
//! in the project's README and `docs/language.md`; `Pendulum::EQUATIONS` and
//! the struct's docs show the derived equations.

#![deny(missing_docs)]
#![warn(rust_2018_idioms, unused_qualifications)]

pub use dalembert_macros::dalembert;

pub mod constrained;
pub mod control;
pub mod dynamics;
pub mod integrate;
pub mod math;
pub mod series;
mod system;
#[cfg(test)]
mod test_systems;

pub use constrained::Stabilisation;
pub use dynamics::{DynamicsError, accelerations, energy, energy_at, jacobi_integral};
pub use integrate::{Constrained, IntegrationError, Solution, State, Unconstrained};
pub use system::{ConstrainedSystem, MultibodySystem, TaylorSystem};

/// The README's Rust examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
