//! Systems generated at build time from the `.dal` models in `models/`, one
//! module each: `build.rs` runs [`dalembert_codegen::Builder`] on every
//! `models/NAME.dal` and writes `NAME.rs` into `OUT_DIR`, included here.
//!
//! The generated source is reviewed through the insta snapshots in
//! `tests/snapshots/`: a change to a model or to the derivation shows up as
//! a snapshot diff (`cargo insta test`).
//!
//! [`dalembert_codegen::Builder`]: https://docs.rs/dalembert-codegen

#![warn(missing_docs, rust_2018_idioms, unused_qualifications)]

/// Includes the file generated from `models/$name.dal` as module `$name`.
macro_rules! model {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        pub mod $name {
            include!(concat!(env!("OUT_DIR"), "/", stringify!($name), ".rs"));
        }
    };
}

// Seed examples (DESIGN §3).
model!(
    /// Seed example 1: double pendulum, absolute angles.
    double_pendulum
);
model!(
    /// Seed example 2: a bar on a rotating massless frame, two motors.
    rotating_bar
);
model!(
    /// Seed example 3: pendulum in dependent coordinates (Lagrange multipliers).
    constrained_pendulum
);

// Benchmark chains (issue 5): add `models/NAME.dal` and `model!(NAME);` here.

pub use constrained_pendulum::ConstrainedPendulum;
pub use double_pendulum::DoublePendulum;
pub use rotating_bar::RotatingBar;
