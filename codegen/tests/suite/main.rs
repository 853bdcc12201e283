//! The integration tests of `dalembert-codegen`, one module per subject, in
//! one test binary: every binary links the engine (optimised, and the
//! largest library of the workspace) again, and one of them builds and links
//! in a fraction of the time of one per subject. Run one subject with
//! `cargo test -p dalembert-codegen --test suite <module>::`.

mod armature;
mod build_api;
mod cli;
mod fuzz;
mod lanes;
mod long_input;
mod mjcf_defaults;
mod mjcf_doors;
mod mjcf_errors;
mod mjcf_fuzz;
mod mjcf_geom_rules;
mod mjcf_import;
mod mjcf_passive;
mod mjcf_refusals;
mod model_size;
mod outputs;
mod pinocchio;
mod report_equations;
mod robots;
mod robustness;
mod rolling_axle;
mod rolling_planes;
mod rolling_radii;
mod rolling_rows;
mod urdf;
mod urdf_branching;
mod urdf_cli;
mod urdf_errors;
mod urdf_frames;
mod urdf_fuzz;
mod urdf_jacobians;
mod urdf_picker;
