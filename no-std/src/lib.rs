//! Generated equations in a `#![no_std]` crate: the build script asks
//! `dalembert-codegen` for code that calls `libm` instead of `f64`'s
//! methods (`Builder::no_std(true)`), so it builds without `std` (for
//! embedded targets). The runtime's traits and solvers are not available
//! there; the equations are.

#![no_std]
#![warn(missing_docs)]

/// Seed example 1.
pub mod double_pendulum {
    include!(concat!(env!("OUT_DIR"), "/double_pendulum.rs"));
}

/// Seed example 2.
pub mod rotating_bar {
    include!(concat!(env!("OUT_DIR"), "/rotating_bar.rs"));
}

/// Seed example 3.
pub mod constrained_pendulum {
    include!(concat!(env!("OUT_DIR"), "/constrained_pendulum.rs"));
}

/// The spatial 6-link chain of the benchmarks.
pub mod spatial_chain_06 {
    include!(concat!(env!("OUT_DIR"), "/spatial_chain_06.rs"));
}
