//! Task-space control of a URDF arm's end effector: the UR5's tool flange
//! `tool0`, a massless link on a fixed joint, tracks a circle.
//!
//! The arm is imported at build time by the `dalembert-generated` crate's
//! build script, asking for the tool's outputs on import:
//!
//! ```rust,ignore
//! Builder::new().urdf_with(
//!     "ur5_robot.urdf",
//!     ImportOptions::new().outputs("position(tool0_origin), jacobian(tool0_origin), rotation(tool0)"),
//! )
//! ```
//!
//! so `Ur5` has `position_tool0_origin`, `jacobian_tool0_origin` and
//! `rotation_tool0` beside `mass_matrix` and `forcing`. The controller is a
//! task-space PD with gravity compensation and joint damping (the arm has
//! six joints for a three-dimensional task: the damping settles the other
//! three):
//!
//! ```text
//! τ = g(q) + Jᵀ (Kp (x_d − x) + Kd (ẋ_d − J v)) − c v,   g(q) = −f(t, q, 0, 0)
//! ```
//!
//! with `x = position_tool0_origin(q)` and `J = jacobian_tool0_origin(q)`.
//! RK4 at 1 ms over `dalembert::accelerations` for 8 s. The example prints
//! the tracking error and writes a chart of it, a chart of the tool's path
//! against the target's, and an animation (`ur5_reach.html`).
//!
//! ```text
//! cargo run --release --example ur5_reach [-- --out DIR]
//! ```
//!
//! Files are written to `DIR` (default `target/charts`).

use std::error::Error;
use std::path::PathBuf;

use dalembert::{State, Unconstrained, energy, integrate};
use dalembert_generated::Ur5;
use dalembert_lab::{Recording, Scene, Series, input_power, line_chart};

/// The starting pose (rad), at rest.
const START: [f64; 6] = [0.0, -1.2, 1.5, -0.8, 1.0, 0.0];
/// The target circle: radius (m) and period (s), in the plane of `N.y` and
/// `N.z` through the tool's starting position; the target starts at the
/// tool and moves off along the circle.
const RADIUS: f64 = 0.1;
const PERIOD: f64 = 4.0;
/// Task-space stiffness (N/m) and damping (N s/m), joint damping (N m s).
const KP: f64 = 2000.0;
const KD: f64 = 150.0;
const JOINT_DAMPING: f64 = 2.0;
/// Simulated time (s) and RK4 step (s).
const END: f64 = 8.0;
const STEP: f64 = 1e-3;

/// The target's position and velocity at `t`, about `center`.
fn target(center: [f64; 3], t: f64) -> ([f64; 3], [f64; 3]) {
    let w = 2.0 * std::f64::consts::PI / PERIOD;
    let (s, c) = (w * t).sin_cos();
    (
        [
            center[0],
            center[1] + RADIUS * s,
            center[2] + RADIUS * (c - 1.0),
        ],
        [0.0, RADIUS * w * c, -RADIUS * w * s],
    )
}

/// The torques of the task-space PD tracking the target about `center`.
fn control(arm: &Ur5, center: [f64; 3], t: f64, q: &[f64; 6], v: &[f64; 6]) -> [f64; 6] {
    let (x_d, xdot_d) = target(center, t);
    let x = arm.position_tool0_origin(t, q);
    let jacobian = arm.jacobian_tool0_origin(t, q);
    let xdot: [f64; 3] =
        std::array::from_fn(|i| jacobian[i].iter().zip(v).map(|(j, v)| j * v).sum());
    let force: [f64; 3] =
        std::array::from_fn(|i| KP * (x_d[i] - x[i]) + KD * (xdot_d[i] - xdot[i]));
    let gravity = arm.forcing(t, q, &[0.0; 6], &[0.0; 6]);
    std::array::from_fn(|k| {
        let task: f64 = (0..3).map(|i| jacobian[i][k] * force[i]).sum();
        -gravity[k] + task - JOINT_DAMPING * v[k]
    })
}

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args().skip(1);
    let out = match (args.next().as_deref(), args.next()) {
        (Some("--out"), Some(dir)) => PathBuf::from(dir),
        (None, _) => PathBuf::from("target/charts"),
        _ => return Err("usage: ur5_reach [--out DIR]".into()),
    };
    std::fs::create_dir_all(&out)?;
    let arm = Ur5 {};
    let center = arm.position_tool0_origin(0.0, &START);
    let dynamics = Unconstrained::new(&arm, |t, q, v| control(&arm, center, t, q, v));
    let start = State {
        t: 0.0,
        q: START,
        v: [0.0; 6],
    };
    let (mut error, mut path, mut wanted) = (Vec::new(), Vec::new(), Vec::new());
    let mut recording = Recording::new();
    let mut last_q = START;
    let steps = (END / STEP).round() as u64;
    integrate::Integration::new(&dynamics, start, END, integrate::Rk4 { steps })
        .observe(|s| {
            let x = arm.position_tool0_origin(s.t, &s.q);
            let (x_d, _) = target(center, s.t);
            let distance = (0..3).map(|i| (x[i] - x_d[i]).powi(2)).sum::<f64>().sqrt();
            error.push((s.t, 1e3 * distance));
            path.push((x[1], x[2]));
            wanted.push((x_d[1], x_d[2]));
            let u = control(&arm, center, s.t, &s.q, &s.v);
            let power = input_power(&arm, s.t, &s.q, &s.v, &u);
            recording.push_driven(s.t, &s.q, energy(&arm, &s.q, &s.v), power);
            last_q = s.q;
        })
        .run()
        .map_err(|e| format!("the simulation stopped at t = {}: {:?}", e.t, e.cause))?;

    let settled = error
        .iter()
        .filter(|(t, _)| *t >= PERIOD / 4.0)
        .fold(0.0_f64, |m, (_, e)| m.max(*e));
    let last = error.last().map_or(f64::NAN, |(_, e)| *e);
    let tool = arm.rotation_tool0(END, &last_q);
    println!(
        "UR5 tool0 tracking a {RADIUS} m circle of period {PERIOD} s (Kp = {KP} N/m, Kd = {KD} N s/m):"
    );
    println!(
        "largest error after {} s: {settled:.2} mm; at t = {END} s: {last:.2} mm",
        PERIOD / 4.0
    );
    println!(
        "tool0's z axis at t = {END} s, in N's axes: [{:+.3}, {:+.3}, {:+.3}]",
        tool[0][2], tool[1][2], tool[2][2]
    );

    let chart = out.join("ur5_reach_error.svg");
    line_chart(
        &chart,
        "UR5 task-space PD: distance from tool0 to the target",
        "t (s)",
        "error (mm)",
        &[Series {
            name: "|x − x_d|",
            points: &error,
        }],
    )?;
    println!("wrote {}", chart.display());
    let chart = out.join("ur5_reach_path.svg");
    line_chart(
        &chart,
        "UR5 tool0's path in the y-z plane of N",
        "y (m)",
        "z (m)",
        &[
            Series {
                name: "target",
                points: &wanted,
            },
            Series {
                name: "tool0",
                points: &path,
            },
        ],
    )?;
    println!("wrote {}", chart.display());

    // The arm is drawn link by link between its joint origins.
    let scene = Scene::of(&arm)?
        .title("UR5 (URDF): tool0 tracking a circle, task-space PD through jacobian(tool0_origin)")
        .equations(Ur5::EQUATIONS);
    let page = scene.write(out.join("ur5_reach.html"), &recording)?;
    println!("wrote {}", page.display());
    Ok(())
}
