//! A real robot, one line from its URDF: the Franka Emika Panda arm
//! (`tests/reference/urdf/panda.urdf`, imported by `Builder::urdf` in the
//! `dalembert-generated` crate's build script), simulated twice from the
//! same pose at rest:
//!
//! * **falling**: every joint torque zero, the arm collapses under gravity;
//! * **held**: gravity compensation, the inputs `τ = −f(q, 0, 0)` (the
//!   forcing at zero speed and zero torque is minus the gravity torques), so
//!   `M q̈ = τ − g(q) − (velocity terms)` stays at rest.
//!
//! Both runs use the classical RK4 over `dalembert::accelerations` (the
//! system's emitted solver). The example prints the final joint angles and
//! the held arm's largest drift, and writes one SVG chart per run.
//!
//! ```text
//! cargo run --release --example panda [-- --out DIR]
//! ```
//!
//! Charts are written to `DIR` (default `target/charts`).

use std::error::Error;
use std::path::PathBuf;

use dalembert::{MultibodySystem, State, Unconstrained, integrate};
use dalembert_generated::Panda;
use dalembert_lab::{Series, line_chart};

/// The arm's "ready" pose: the seven arm joints (rad), then the two
/// fingers' openings (m).
const READY: [f64; 9] = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785, 0.02, 0.02];
/// Simulated time (s) and RK4 step (s).
const END: f64 = 2.0;
const STEP: f64 = 1e-3;

/// The torques that hold the arm still at `q`: `τ = −f(t, q, 0, 0)`.
fn gravity_compensation(arm: &Panda, t: f64, q: &[f64; 9]) -> [f64; 9] {
    let f = arm.forcing(t, q, &[0.0; 9], &[0.0; 9]);
    f.map(|x| -x)
}

/// One `(t, angle)` series per arm joint.
type Trajectories = Vec<Vec<(f64, f64)>>;

/// Simulates `arm` from `READY` at rest under the input law `inputs`, and
/// returns the seven arm joints' trajectories `(t, angle)`.
fn simulate(
    arm: &Panda,
    inputs: impl Fn(f64, &[f64; 9], &[f64; 9]) -> [f64; 9],
) -> Result<Trajectories, Box<dyn Error>> {
    let dynamics = Unconstrained::new(arm, inputs);
    let start = State {
        t: 0.0,
        q: READY,
        v: [0.0; 9],
    };
    let mut joints = vec![Vec::new(); 7];
    let steps = (END / STEP).round() as u64;
    integrate::Integration::new(&dynamics, start, END, integrate::Rk4 { steps })
        .observe(|state| {
            for (joint, &angle) in joints.iter_mut().zip(&state.q) {
                joint.push((state.t, angle));
            }
        })
        .run()
        .map_err(|e| format!("the simulation stopped at t = {}: {:?}", e.t, e.cause))?;
    Ok(joints)
}

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args().skip(1);
    let out = match (args.next().as_deref(), args.next()) {
        (Some("--out"), Some(dir)) => PathBuf::from(dir),
        (None, _) => PathBuf::from("target/charts"),
        _ => return Err("usage: panda [--out DIR]".into()),
    };
    std::fs::create_dir_all(&out)?;
    let arm = Panda {};
    println!(
        "{} coordinates: {}",
        Panda::NQ,
        <Panda as MultibodySystem<9, 9, 9>>::COORDINATES.join(", ")
    );
    let falling = simulate(&arm, |_, _, _| [0.0; 9])?;
    let held = simulate(&arm, |t, q, _| gravity_compensation(&arm, t, q))?;
    let names: Vec<String> = (1..=7).map(|j| format!("joint {j}")).collect();
    for (title, joints, file) in [
        (
            "Panda falling under gravity (τ = 0)",
            &falling,
            "panda_falling.svg",
        ),
        (
            "Panda held by gravity compensation (τ = −f(q, 0, 0))",
            &held,
            "panda_held.svg",
        ),
    ] {
        let series: Vec<Series<'_>> = names
            .iter()
            .zip(joints)
            .map(|(name, points)| Series { name, points })
            .collect();
        let path = out.join(file);
        line_chart(&path, title, "t (s)", "joint angle (rad)", &series)?;
        println!("wrote {}", path.display());
    }
    let last = |joints: &[Vec<(f64, f64)>]| -> Vec<String> {
        joints
            .iter()
            .map(|j| format!("{:+.3}", j[j.len() - 1].1))
            .collect()
    };
    println!(
        "falling, angles at t = {END} s: {}",
        last(&falling).join(" ")
    );
    println!("held,    angles at t = {END} s: {}", last(&held).join(" "));
    let drift = held
        .iter()
        .zip(READY)
        .flat_map(|(joint, start)| joint.iter().map(move |&(_, a)| (a - start).abs()))
        .fold(0.0, f64::max);
    println!("held arm: largest joint drift over {END} s = {drift:.1e} rad");
    Ok(())
}
