//! Time integration of `M(q) v̇ = f(t, q, v, u)`, `q̇ = N(q) v` from a
//! [`State`] `(t, q, v)`.
//!
//! Every integrator steps a [`Dynamics`]: a system closed over its input law,
//! [`Unconstrained::new(&system, |t, q, v| u)`](Unconstrained::new) (or
//! [`Unconstrained::without_inputs`]), or a constrained one with its drift
//! [`Stabilisation`](crate::Stabilisation) ([`Constrained`]). Every one
//! allocates nothing, lets an observer see the initial state and every step,
//! and returns the final state with the work done ([`Solution`]) or an
//! [`IntegrationError`] naming where and why it stopped.
//!
//! # Configurations on a manifold
//!
//! When the speeds are not the coordinates' rates (a unit quaternion and an
//! angular velocity: `NQ = 4`, `NV = 3`), the Runge–Kutta methods integrate
//! the coordinates' rates `q̇ = N(q) v` of the system's `coordinate_rates`
//! beside `v̇`, so each keeps its full order, and put the configuration back
//! on its manifold after every step through the system's own update with no
//! motion, `q ⊕ 0` (`integrate_configuration(q, 0, 0)`), which renormalises
//! a quaternion when the system's exponential map returns a unit quaternion.
//! Measured on a torque-free rigid body in quaternions (`tests/suite/manifold.rs`):
//! RK4, Gauss 4, Gauss 6 and SDIRK reach their orders 4.00, 4.00, 6.00 and
//! 3.00; DOPRI5 and DOP853 need 9.4 and 7.1 times the steps for a tolerance
//! 10⁵ and 10⁸ times smaller (10 expected at their orders). Renormalising
//! costs nothing measurable: RK4 at `h = 5 ms` over 20 s leaves `|q|` 6e-13
//! off one without it and changes the final state by 5e-13. Stepping the
//! configuration by `q ⊕ h Σ aᵢⱼ vⱼ` instead would lose the commutators of
//! the exponential map's derivative and fall to order 2 on a non-abelian
//! group. The augmented Lagrangian method, second order, moves `q` by the
//! system's update `q ⊕ Δ`, which keeps its order.
//!
//! # What an integration refuses
//!
//! Before its first evaluation, every integrator checks its arguments and
//! returns [`Failure::InvalidArgument`] (at the initial state, saying what
//! is wrong) for a time that is NaN, a final time before the initial one
//! (integrations run forward only), an infinite final time with a fixed
//! number of steps, no steps, a tolerance that is zero, negative or NaN
//! (DOP853 and DOPRI5: finite relative and absolute tolerances, not both
//! zero), and a first step or an [`Rk4::step`] that is not positive and
//! finite. A final time equal to the initial one is no error: the start is
//! returned, no step taken. The adaptive methods and Taylor may run to
//! `t_end = f64::INFINITY`, until a stopping event or their step budget.
//!
//! # What an integration watches
//!
//! After every step, every integrator checks that the step's end is finite
//! (an overflow in the last step of a fixed-step run is an error, not an
//! `Ok` holding infinities) and lets the dynamics [`watch`](Dynamics::watch)
//! it: a [`Constrained`] system's drift at position and velocity level
//! against its [`DriftLimits`](crate::constrained::DriftLimits)
//! ([`Failure::ConstraintDrift`]), and, for the stabilisations that cannot
//! cross singular positions, how independent its rows still are
//! ([`Failure::SingularPosition`]). A start that the stabilisation would
//! not correct is checked the same way before the first step. The error's
//! time and configuration are then those of the last good state. An event
//! function's NaN or infinite value is [`Failure::NonFiniteEvent`].
//! `docs/reliability.md` lists every such failure mode and its test.
//!
//! # Between steps
//!
//! The adaptive pairs and Taylor give the state at any time inside a step
//! ([`Integration::dense`], [`DenseStep::state_at`]: DOPRI5's fourth-order
//! and DOP853's seventh-order continuous extensions, Taylor's polynomial)
//! and locate the zeros of a function `g(t, q, v)` on it to a few units in
//! the last place of the time, recording them or stopping there
//! ([`Integration::event`], [`Event`]).
//!
//! # Choosing a method
//!
//! An [`Integration`] runs one [`Method`], a value: switching method
//! changes that value, nothing else. `docs/simulating.md` is the guide.
//!
//! | method | steps | use it for |
//! |---|---|---|
//! | [`Rk4 { steps }`](Rk4) | fixed | real-time loops, reproducible runs, a cheap default ([`Rk4::step`]: one step at a time) |
//! | [`Adaptive::dopri5(tolerance)`](Adaptive::dopri5) | adaptive | moderate tolerances (`1e-6`…`1e-9`) on non-stiff systems |
//! | [`Adaptive::dop853(tolerance)`](Adaptive::dop853) | adaptive | tight tolerances (`1e-10` and below): the least work per digit |
//! | [`Gauss { rule, steps }`](Gauss) | fixed | long runs of conservative systems: the energy error stays bounded |
//! | [`Taylor::with_tolerance(tolerance)`](Taylor::with_tolerance) | variable order and step | tight tolerances (`1e-12`…`1e-16`) on systems whose model asks for `outputs taylor;`: the series of the motion, compiled from the model |
//! | [`Sdirk { steps }`](Sdirk) | fixed | stiff springs and joints, whose fast modes an explicit method must resolve |
//! | [`AugmentedLagrangian { steps, settings }`](AugmentedLagrangian) | fixed | closed loops with redundant constraints or singular positions at a fixed step: the index-3 formulation of the IFToMM benchmarks' reference solutions (constrained dynamics only) |
//!
//! Dense output and events need a method with a continuous extension
//! ([`DenseMethod`]: [`Adaptive`] and [`Taylor`]); Taylor needs a system
//! whose model asks for `outputs taylor;` ([`TaylorDynamics`]); the
//! augmented Lagrangian method needs [`Constrained`] dynamics. Each is a
//! bound of the method's [`Method`] implementation: asking for one where it
//! is missing does not compile.

mod adaptive;
mod arguments;
mod augmented_lagrangian;
mod dynamics;
mod gauss;
mod integration;
mod lu;
mod runge_kutta;
mod sdirk;
mod solution;
mod taylor;

pub use adaptive::{Adaptive, AdaptiveOptions, Crossing, DenseStep, Event, ExplicitPair};
pub use augmented_lagrangian::{AugmentedLagrangian, AugmentedLagrangianSettings};
pub use dynamics::{
    Closed, Constrained, Constraints, Dynamics, InputLaw, NoConstraints, NoInputs, Stabilised,
    Unconstrained,
};
pub use gauss::{Gauss, GaussLegendre};
pub use integration::{Dense, DenseMethod, Events, Integration, Method, Observer, Quiet, Watcher};
pub use runge_kutta::{Rk4, State};
pub use sdirk::Sdirk;
pub use solution::{DriftLevel, Failure, IntegrationError, Solution, Statistics};
pub use taylor::{MAX_ORDER, Taylor, TaylorDynamics};
