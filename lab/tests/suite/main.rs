//! The integration tests of `dalembert-lab`, one module per subject, in one
//! test binary: every binary links the lab, the runtime and the engine
//! again. Run one subject with `cargo test -p dalembert-lab --test suite
//! scene::`.

mod ddp;
mod scene;
mod scene_model;
