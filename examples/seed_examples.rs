//! The main job: derive the three seed examples at compile time, print the
//! derived equations beside the seed document's, simulate the double
//! pendulum and chart its trajectory and energy, and write an animation of
//! each seed example and of a URDF robot falling under gravity (pages to
//! open in a browser).
//!
//! ```text
//! cargo run --release --example seed_examples [-- --out DIR]
//! ```
//!
//! Charts and animations are written to `DIR` (default `target/charts`).

use dalembert::{
    Constrained, IntegrationError, Stabilisation, State, Unconstrained, energy, integrate,
    integrate::Dynamics,
};
use dalembert_lab::{Recording, Scene, Series, line_chart, line_chart_log_y};
use std::path::{Path, PathBuf};

use dalembert_fixtures::seeds::{
    CHAOTIC, CHAOTIC_END, CHAOTIC_START, ConstrainedPendulum, DoublePendulum, RotatingBar,
};
use dalembert_fixtures::slider_crank::SEED_3 as REFERENCE_SEED_3;
use dalembert_generated::Ur5;

/// The animations' length, in seconds, and step.
const ANIMATION_END: f64 = 10.0;
const ANIMATION_STEP: f64 = 1e-3;

/// The seed document's boxed results, transcribed.
const SEED_1: &str = "\
(4/3 m L²) θ̈₁ + (½ m L² C₂₋₁) θ̈₂ − (½ m L² S₂₋₁) θ̇₂² + (3/2 m g L) S₁ = 0
(½ m L² C₂₋₁) θ̈₁ + (⅓ m L²) θ̈₂ + (½ m L² S₂₋₁) θ̇₁² + (½ m g L) S₂ = 0";
const SEED_2: &str = "\
(m d² + 1/12 m ℓ² C²θ) φ̈ − (⅙ m ℓ² Sθ Cθ) θ̇ φ̇ = M_φ
(1/12 m ℓ²) θ̈ + (1/12 m ℓ² Sθ Cθ) φ̇² = M_θ";
const SEED_3: &str = "\
m ẍ = λ₁
m ÿ = −m g + λ₂
(1/12 m ℓ²) θ̈ = M − (ℓ/2 Cθ) λ₁ − (ℓ/2 Sθ) λ₂
ẍ − (ℓ/2 Cθ) θ̈ + (ℓ/2 Sθ) θ̇² = 0
ÿ − (ℓ/2 Sθ) θ̈ − (ℓ/2 Cθ) θ̇² = 0";

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = output_directory();
    std::fs::create_dir_all(&out)?;
    for (title, seed, derived) in [
        (
            "Seed example 1: double pendulum",
            SEED_1,
            DoublePendulum::EQUATIONS,
        ),
        (
            "Seed example 2: rotating bar",
            SEED_2,
            RotatingBar::EQUATIONS,
        ),
        (
            "Seed example 3: constrained pendulum",
            SEED_3,
            ConstrainedPendulum::EQUATIONS,
        ),
    ] {
        println!(
            "== {title}\n-- the seed document:\n{seed}\n-- derived by dalembert:\n{derived}\n"
        );
    }
    let mut written = simulate_double_pendulum(&out)?;
    written.push(animate_rotating_bar(&out)?);
    written.push(animate_constrained_pendulum(&out)?);
    written.push(animate_ur5(&out)?);
    for file in written {
        println!("wrote {}", file.display());
    }
    Ok(())
}

/// `--out DIR`, or `target/charts`.
fn output_directory() -> PathBuf {
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--out" {
            if let Some(dir) = args.next() {
                return PathBuf::from(dir);
            }
        }
    }
    PathBuf::from("target/charts")
}

/// Releases the double pendulum (m = L = 1) from θ₁ = θ₂ = 2 rad at rest,
/// integrates 10 s with RK4 at two step sizes and charts the angles and the
/// energy error.
fn simulate_double_pendulum(
    out: &std::path::Path,
) -> Result<Vec<PathBuf>, Box<dyn std::error::Error>> {
    let (pendulum, initial) = (CHAOTIC, CHAOTIC_START);
    let energy =
        |s: &State<2, 2>| pendulum.kinetic_energy(&s.q, &s.v) + pendulum.potential_energy(&s.q);
    let e0 = energy(&initial);
    let mut angles = [Vec::new(), Vec::new()];
    let mut drift = Vec::new();
    let mut recording = Recording::new();
    for (h, keep_angles) in [(1e-3, true), (1e-2, false)] {
        let mut errors = Vec::new();
        let steps = (CHAOTIC_END / h).round() as u64;
        let dynamics = Unconstrained::without_inputs(&pendulum);
        integrate::Integration::new(&dynamics, initial, CHAOTIC_END, integrate::Rk4 { steps })
            .observe(|s| {
                if keep_angles {
                    angles[0].push((s.t, s.q[0]));
                    angles[1].push((s.t, s.q[1]));
                    recording.push(s.t, &s.q, energy(s));
                }
                errors.push((s.t, (energy(s) - e0).abs()));
            })
            .run()?;
        let worst = errors.iter().map(|p| p.1).fold(0.0, f64::max);
        println!("double pendulum, RK4 h = {h}: max |E − E₀| = {worst:.3e} J over 10 s");
        drift.push((format!("RK4, h = {h} s"), errors));
    }
    let trajectory = out.join("double_pendulum_angles.svg");
    line_chart(
        &trajectory,
        "Double pendulum released at θ₁ = θ₂ = 2 rad (RK4, h = 1 ms)",
        "t [s]",
        "angle [rad]",
        &[
            Series {
                name: "θ₁",
                points: &angles[0],
            },
            Series {
                name: "θ₂",
                points: &angles[1],
            },
        ],
    )?;
    let energy_chart = out.join("double_pendulum_energy.svg");
    let series: Vec<Series<'_>> = drift
        .iter()
        .map(|(name, points)| Series { name, points })
        .collect();
    line_chart_log_y(
        &energy_chart,
        "Double pendulum: energy error |E − E₀|",
        "t [s]",
        "|E − E₀| [J]",
        &series,
    )?;
    let animation = Scene::of(&pendulum)?
        .title("Seed example 1: double pendulum released at θ₁ = θ₂ = 2 rad (RK4, h = 1 ms)")
        .equations(DoublePendulum::EQUATIONS)
        .write(out.join("double_pendulum.html"), &recording)?;
    Ok(vec![trajectory, energy_chart, animation])
}

/// Seed example 2 (m = l = 1, d = 0.5) coasting without motor torques from
/// θ = 0.3 rad, φ̇ = 1.5 rad/s, θ̇ = 2 rad/s: 10 s of RK4 at 1 ms, animated.
fn animate_rotating_bar(out: &Path) -> Result<PathBuf, Box<dyn std::error::Error>> {
    let bar = RotatingBar {
        m: 1.0,
        l: 1.0,
        d: 0.5,
    };
    let start = State {
        t: 0.0,
        q: [0.0, 0.3],
        v: [1.5, 2.0],
    };
    let recording = record(&Unconstrained::without_inputs(&bar), start, |s| {
        energy(&bar, &s.q, &s.v)
    })?;
    let scene = Scene::of(&bar)?
        .title("Seed example 2: a bar on a rotating massless frame, coasting (RK4, h = 1 ms)")
        .equations(RotatingBar::EQUATIONS);
    Ok(scene.write(out.join("rotating_bar.html"), &recording)?)
}

/// Seed example 3 with the reference parameters, released at θ = 1 rad
/// turning at 2 rad/s on its constraints: 10 s of RK4 at 1 ms with
/// coordinate projection, animated.
fn animate_constrained_pendulum(out: &Path) -> Result<PathBuf, Box<dyn std::error::Error>> {
    let pendulum = REFERENCE_SEED_3;
    let projection = Stabilisation::Projection {
        tolerance: 1e-12,
        max_iterations: 5,
    };
    let dynamics = Constrained::without_inputs(&pendulum, projection);
    let recording = record(&dynamics, pendulum.assembled(1.0, 2.0), |s| {
        energy(&pendulum, &s.q, &s.v)
    })?;
    let scene = Scene::of(&pendulum)?
        .title("Seed example 3: pendulum in dependent coordinates (RK4, h = 1 ms, projection)")
        .equations(ConstrainedPendulum::EQUATIONS);
    Ok(scene.write(out.join("constrained_pendulum.html"), &recording)?)
}

/// The UR5 arm (imported from its URDF at build time) released from a bent
/// pose at rest with no joint torque, falling under gravity: 10 s of RK4 at
/// 1 ms, animated from the same import's model text.
fn animate_ur5(out: &Path) -> Result<PathBuf, Box<dyn std::error::Error>> {
    let robot = Ur5 {};
    let start = State {
        t: 0.0,
        q: [0.0, -1.2, 1.5, -0.8, 1.0, 0.0],
        v: [0.0; 6],
    };
    let recording = record(&Unconstrained::without_inputs(&robot), start, |s| {
        energy(&robot, &s.q, &s.v)
    })?;
    // The arm is drawn link by link between its joint origins.
    let scene = Scene::of(&robot)?
        .title("UR5 (URDF) falling under gravity without joint torques (RK4, h = 1 ms)")
        .equations(Ur5::EQUATIONS);
    Ok(scene.write(out.join("ur5.html"), &recording)?)
}

/// Every state and energy of [`ANIMATION_END`] seconds of RK4 at
/// [`ANIMATION_STEP`] from `start`.
fn record<const NQ: usize, const NV: usize>(
    dynamics: &impl Dynamics<NQ, NV>,
    start: State<NQ, NV>,
    energy: impl Fn(&State<NQ, NV>) -> f64,
) -> Result<Recording, IntegrationError<NQ>> {
    let mut recording = Recording::new();
    let steps = (ANIMATION_END / ANIMATION_STEP).round() as u64;
    integrate::Integration::new(dynamics, start, ANIMATION_END, integrate::Rk4 { steps })
        .observe(|s| {
            recording.push(s.t, &s.q, energy(s));
        })
        .run()?;
    Ok(recording)
}
