//! The integration tests of `dalembert-generated`, one module per subject,
//! in one test binary: every binary links the generated models (tens of
//! thousands of lines of code) and the engine again, and one of them builds
//! and links in a fraction of the time of one per subject. Run one subject
//! with `cargo test -p dalembert-generated --test suite <module>::`.

mod adjoints;
mod batched_rk4;
mod chains;
mod common;
mod derivatives;
#[cfg(feature = "humanoids")]
mod humanoids;
mod lanes;
mod looped;
mod macro_equivalence;
mod mjcf;
mod model_source;
mod outputs;
mod panic_free;
mod snapshots;
mod spellings;
mod step_derivatives;
mod trees;
mod urdf;
