//! The laboratory around `dalembert`: SVG charts of trajectories and error
//! histories, animated scenes of any model in the browser, and the
//! work-precision harness that measures what accuracy
//! each integrator buys per unit of time, linear-quadratic regulators
//! from a system's linearisation, and differential dynamic programming over
//! the exact step jacobians ([`ddp`]). The examples of the repository use
//! it, together with its re-exports of the command-line and progress-bar
//! crates they need; the `dalembert` crate itself pulls no plotting library.

#![warn(missing_docs, rust_2018_idioms, unused_qualifications)]

mod chart;
pub mod ddp;
mod lqr;
mod scene;
mod work_precision;

pub use chart::{ChartError, Series, line_chart, line_chart_log_log, line_chart_log_y};
pub use lqr::{RiccatiError, lqr};
pub use scene::{Pose, Recording, Scene, SceneError, decimate};
pub use work_precision::{
    Accuracy, WorkPoint, measure, seconds_at_error, state_error, to_csv, work_line,
    work_precision_chart,
};
pub use {clap, indicatif};
