//! The integration tests of `dalembert`, one module per subject, in one test
//! binary: each binary links the engine, the generated models and their
//! dependencies again, and one of them builds and links in a fraction of the
//! time of one per subject. Run one subject with
//! `cargo test --test suite <module>::` (e.g. `cargo test --test suite taylor::`).
//! `tests/allocation.rs` (a counting global allocator) and `tests/hygiene.rs`
//! (items at the crate root that shadow the prelude) stay binaries of their own.

mod ball_and_free_joints;
mod bicycle;
mod constrained_linearize;
mod constraint_watch;
mod constraints;
mod dal_sympy;
mod dense_output_and_events;
mod driven_constraints;
mod events;
mod extreme_values;
mod free_body;
mod free_body_and_stiff_chain_integration;
mod generated_api;
mod generated_names;
mod gimbal_lock;
mod iftomm_bricard_and_andrews;
mod iftomm_four_bars;
mod integration_errors;
mod knife_edge;
mod lie_group_output_checks;
mod lie_group_outputs;
mod loop_rows;
mod lqr_cartpole;
mod manifold;
mod massless_frames;
mod non_finite;
mod output_checks;
mod outputs_against_derivatives;
mod planar_arm_outputs;
mod platform_arm;
mod redundant_parallelogram;
mod rheonomic;
mod rolling_ball;
mod rolling_compositions;
mod rolling_disc;
mod rolling_vanishing_row;
mod rolling_wheels;
mod rotor_sled_linearisation;
mod seed_examples;
mod shaken_pendulum;
mod singular_top;
mod sled_with_a_driven_slider;
mod spinning_hoop;
mod spun_hoop_and_spherical_pendulum;
mod stability;
mod taylor;
mod taylor_constrained;
mod taylor_heavy_top;
mod urdf_outputs;
