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
//! use dalembert::integrate::{Integration, Rk4};
//! use dalembert::{State, Unconstrained};
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
//! let end = Integration::new(&dynamics, start, 10.0, Rk4 { steps: 10_000 }).run()?.end;
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
//! * [`TaylorSystem`]: the Taylor coefficients of the motion that a model
//!   asking for `outputs taylor;` gives, which [`integrate::Taylor`] sums.
//!
//! What only the generated code calls (elementary functions, Taylor
//! recurrences, the tree loops) lives in a hidden module and is no part
//! of this API.
//!
//! The language, the generated API and the build-script route are described
//! in the project's guide (`docs/README.md`, from getting started to the
//! language reference `docs/language.md`); `Pendulum::EQUATIONS` and the
//! struct's docs show the derived equations.

#![deny(missing_docs)]
#![warn(rust_2018_idioms, unused_qualifications)]

pub use dalembert_macros::dalembert;

#[doc(hidden)]
#[path = "private/mod.rs"]
pub mod __private;
pub mod constrained;
pub mod control;
pub mod dynamics;
pub mod integrate;
mod system;
#[cfg(test)]
mod test_systems;

pub use constrained::Stabilisation;
pub use dynamics::{
    DynamicsError, accelerations, accelerations_x4, energy, energy_at, jacobi_integral,
};
pub use integrate::{Constrained, IntegrationError, Solution, State, Unconstrained};
pub use system::{ConstrainedSystem, Model, MultibodySystem, TaylorSystem};

/// The README's Rust examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

/// The guide's chapters (`docs/`), their Rust examples compiled and run as
/// doctests.
#[cfg(doctest)]
mod guide {
    #[doc = include_str!("../docs/getting-started.md")]
    struct GettingStarted;
    #[doc = include_str!("../docs/language.md")]
    struct Language;
    #[doc = include_str!("../docs/simulating.md")]
    struct Simulating;
    #[doc = include_str!("../docs/constraints.md")]
    struct Constraints;
    #[doc = include_str!("../docs/outputs.md")]
    struct Outputs;
    #[doc = include_str!("../docs/control.md")]
    struct Control;
    #[doc = include_str!("../docs/urdf.md")]
    struct Urdf;
    #[doc = include_str!("../docs/mjcf.md")]
    struct Mjcf;
    #[doc = include_str!("../docs/scene.md")]
    struct Scene;
    #[doc = include_str!("../docs/prescribed_motion.md")]
    struct PrescribedMotion;
}
