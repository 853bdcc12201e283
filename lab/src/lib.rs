//! The laboratory around `dalembert`: SVG charts of trajectories and error
//! histories, animated scenes of any model in the browser, and the
//! work-precision harness that measures what accuracy
//! each integrator buys per unit of time, linear-quadratic regulators
//! from a system's linearisation, and differential dynamic programming over
//! the exact step jacobians ([`ddp`]), with costs on a frame's pose
//! ([`pose`]). The `dalembert` crate itself pulls
//! no plotting library; this one pulls no command-line one.
//!
//! A scene of a generated system needs nothing but the system: it carries
//! its model ([`dalembert::Model`]).
//!
//! ```ignore
//! let scene = dalembert_lab::Scene::of(&pendulum)?;
//! let mut recording = dalembert_lab::Recording::new();
//! for s in &solution.states {
//!     recording.push(s.t, &s.q, dalembert::energy(&pendulum, &s.q, &s.v));
//! }
//! scene.write("pendulum.html", &recording)?;
//! ```

#![deny(missing_docs)]
#![warn(rust_2018_idioms, unused_qualifications)]

mod chart;
pub mod ddp;
mod lqr;
pub mod pose;
mod scene;
mod work_precision;

pub use chart::{ChartError, Series, line_chart, line_chart_log_log, line_chart_log_y};
pub use lqr::{RiccatiError, lqr};
pub use scene::{Pose, Recording, Scene, SceneError, decimate, input_power};
pub use work_precision::{
    Accuracy, WorkPoint, measure, seconds_at_error, state_error, to_csv, work_line,
    work_precision_chart,
};
