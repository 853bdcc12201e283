//! Exact multibody equations of motion, derived at compile time with
//! d'Alembert's principle.
//!
//! The `dalembert!` macro turns a declarative description of a mechanical
//! system into a struct whose functions evaluate the mass matrix `M(q)`, the
//! forcing `f(t, q, q̇, u)` of `M(q) q̈ = f`, the energies and the constraints
//! as flat, allocation-free code. The struct implements [`MultibodySystem`]
//! (and [`ConstrainedSystem`] when it has constraints), so this crate's
//! solvers, integrators and charts work on it:
//!
//! ```
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
//! let start = dalembert::State { t: 0.0, q: [1.0], qd: [0.0] };
//! let end = dalembert::simulate(&pendulum, start, |_, _, _| [], 1e-3, 10_000, |_| {})?;
//! let energy = |s: &dalembert::State<1>| dalembert::energy(&pendulum, &s.q, &s.qd);
//! assert!((energy(&end) - energy(&start)).abs() < 1e-9);
//! # Ok::<(), dalembert::IntegrationError<1>>(())
//! ```
//!
//! The language, the generated API and the build-script route are described
//! in the project's README; `Pendulum::EQUATIONS` and the struct's docs show
//! the derived equations.

#![warn(missing_docs, rust_2018_idioms, unused_qualifications)]

pub use dalembert_macros::dalembert;

mod adaptive;
#[cfg(feature = "charts")]
mod chart;
mod constrained;
mod dynamics;
mod equations;
mod gauss;
mod integrate;
mod sdirk;
mod solution;
mod system;
#[cfg(test)]
mod test_systems;
mod work_precision;

pub use adaptive::{AdaptiveOptions, ExplicitPair, simulate_adaptive};
#[cfg(feature = "charts")]
pub use chart::{ChartError, Series, line_chart, line_chart_log_log, line_chart_log_y};
pub use constrained::{
    Stabilisation, baumgarte_accelerations, constrained_accelerations, constrained_rk4_step,
    constraint_drift, project_onto_constraints, simulate_constrained,
};
pub use dynamics::{DynamicsError, accelerations, energy};
pub use equations::{Constrained, Equations, Unconstrained};
pub use gauss::{GaussLegendre, simulate_gauss};
pub use integrate::{IntegrationError, State, rk4_step, simulate, simulate_rk4};
pub use sdirk::simulate_sdirk;
pub use solution::{Solution, SolverError, SolverFailure, Statistics};
pub use system::{ConstrainedSystem, MultibodySystem};
#[cfg(feature = "charts")]
pub use work_precision::work_precision_chart;
pub use work_precision::{
    Accuracy, WorkPoint, measure, seconds_at_error, state_error, to_csv, work_line,
};
