//! The engine of `dalembert`: parse and check the system-description
//! language, derive the equations of motion with d'Alembert's principle on a
//! symbolic DAG, and emit flat Rust.
//!
//! Data flows one way: [`language`] → model → [`expr`] → kinematics →
//! equations → emission.

#![warn(missing_docs, rust_2018_idioms, unused_qualifications)]

mod expr;
mod language;
