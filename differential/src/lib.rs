//! Differential testing on random valid models.
//!
//! [`random_model`] is a proptest strategy for random kinematic trees of
//! one to six links (bodies with random positive inertias, some with
//! products of inertia, and particles; random rotation axes and angles
//! built from coordinates; constant rotations of both signs about
//! coordinate axes and other directions; slides; offsets; gravity; forces, some velocity
//! or time dependent; torques, some reacting; potentials; dissipation),
//! written out as `.dal` text. Every coordinate carries inertia, so `M` is symmetric
//! positive definite. Two test suites use it:
//!
//! * `tests/interpreter.rs`: the interpreter's d'Alembert route against its
//!   Lagrange route on many models ([`RANDOM_MODELS`] proptest cases),
//!   which checks the d'Alembert assembly;
//! * `tests/emitted.rs`: the code that `build.rs` generated and compiled
//!   (the optimised equations) for [`EMITTED_MODELS`] fixed-seed models
//!   against both routes of the interpreter (the equations as derived,
//!   before optimisation), which checks the optimiser and the emitter.

#![warn(missing_docs, rust_2018_idioms, unused_qualifications)]

mod compare;
mod random_model;

pub use compare::{Evaluation, assert_positive_definite};
pub use random_model::{
    EMITTED_MODELS, Link, Load, Mass, RandomModel, Rotation, Tilt, random_model,
};

/// How many random models the interpreter test checks in CI.
pub const RANDOM_MODELS: u32 = 500;
