//! Constraint drift and energy of two systems in dependent coordinates, seed
//! example 3 (a pendulum in `(x, y, θ)`) and a slider-crank
//! `(θ, φ, s)`, integrated with RK4 without stabilisation, with Baumgarte's
//! and with coordinate projection; writes a chart of the drift of each and
//! an animation of the slider-crank's projected run.
//!
//! ```text
//! cargo run --release --example slider_crank [-- --out DIR]
//! ```
//!
//! The charts and the animation go to `DIR` (default `target/charts` in the package).

use std::error::Error;
use std::path::PathBuf;

use dalembert::constrained::{DriftLimits, constraint_drift};
use dalembert::{Constrained, ConstrainedSystem, Stabilisation, State, energy, integrate};
use dalembert_fixtures::slider_crank::{CRANK_SPEED, SEED_3, SLIDER_CRANK, SliderCrank};
use dalembert_lab::{Recording, Scene, Series, line_chart_log_y};

/// The RK4 step, in seconds.
const STEP: f64 = 1e-3;
/// Every this many steps a point goes into the charts.
const CHART_STRIDE: usize = 20;
/// Projection after every step: residual bound and iteration budget.
const PROJECTION: Stabilisation = Stabilisation::Projection {
    tolerance: 1e-12,
    max_iterations: 5,
};

/// What one integration measured.
struct Run {
    /// `(t, max |φ|)` every [`CHART_STRIDE`] steps.
    drift: Vec<(f64, f64)>,
    /// Largest `|φ|` in the first second.
    first_second_drift: f64,
    /// Largest `|φ|` of the run.
    worst_drift: f64,
    /// Largest `|E(t) − E(0)| / |E(0)|`.
    worst_energy_error: f64,
    /// The final state.
    end: State<3, 3>,
    /// Every step's configuration and energy.
    recording: Recording,
}

/// Integrates `system` unforced from `start` for `steps` steps of [`STEP`]
/// and measures its drift and energy.
fn run<S: ConstrainedSystem<3, 3, 1, 2>>(
    system: &S,
    start: State<3, 3>,
    steps: usize,
    stabilisation: Stabilisation,
) -> Result<Run, Box<dyn Error>> {
    let initial_energy = energy(system, &start.q, &start.v);
    let mut run = Run {
        drift: Vec::with_capacity(steps / CHART_STRIDE + 1),
        first_second_drift: 0.0,
        worst_drift: 0.0,
        worst_energy_error: 0.0,
        end: start,
        recording: Recording::new(),
    };
    let mut step = 0;
    let observe = |s: &State<3, 3>| {
        let drift = constraint_drift(system, s);
        let energy_now = energy(system, &s.q, &s.v);
        let energy_error = (energy_now - initial_energy) / initial_energy;
        run.recording.push(s.t, &s.q, energy_now);
        run.worst_drift = run.worst_drift.max(drift);
        run.worst_energy_error = run.worst_energy_error.max(energy_error.abs());
        if s.t <= 1.0 + STEP / 2.0 {
            run.first_second_drift = run.first_second_drift.max(drift);
        }
        if step % CHART_STRIDE == 0 {
            run.drift.push((s.t, drift));
        }
        step += 1;
    };
    let end = integrate::Integration::new(
        // Unwatched: the drift is what this example charts.
        &Constrained::without_inputs(system, stabilisation)
            .with_drift_limits(DriftLimits::UNWATCHED),
        start,
        start.t + steps as f64 * STEP,
        integrate::Rk4 {
            steps: steps as u64,
        },
    )
    .observe(observe)
    .run()
    .map(|solution| solution.end)?;
    run.end = end;
    Ok(run)
}

/// Runs `system` three ways, prints the figures and charts the drift to
/// `chart`.
fn compare<S: ConstrainedSystem<3, 3, 1, 2>>(
    name: &str,
    system: &S,
    start: State<3, 3>,
    steps: usize,
    baumgarte_gain: f64,
    chart: PathBuf,
) -> Result<[Run; 3], Box<dyn Error>> {
    let modes = [
        ("none", Stabilisation::None),
        (
            "Baumgarte",
            Stabilisation::Baumgarte {
                alpha: baumgarte_gain,
                beta: baumgarte_gain,
            },
        ),
        ("projection", PROJECTION),
    ];
    let mut runs = Vec::with_capacity(modes.len());
    for (label, mode) in modes {
        let run = run(system, start, steps, mode)?;
        println!(
            "{name}, {label:>10}: max |φ| {:.3e} over 1 s, {:.3e} over {:.0} s; max |ΔE|/E {:.3e}",
            run.first_second_drift, run.worst_drift, run.end.t, run.worst_energy_error
        );
        runs.push(run);
    }
    let labels = [
        "no stabilisation".to_owned(),
        format!("Baumgarte α = β = {baumgarte_gain:.2}/s"),
        "projection (tolerance 1e-12)".to_owned(),
    ];
    let series: Vec<Series<'_>> = labels
        .iter()
        .zip(&runs)
        .map(|(label, run)| Series {
            name: label,
            points: &run.drift,
        })
        .collect();
    let title = format!("{name}: constraint drift, RK4, h = {STEP} s");
    line_chart_log_y(&chart, &title, "time [s]", "max |φ|", &series)?;
    println!("chart: {}", chart.display());
    runs.try_into().map_err(|_| "three runs expected".into())
}

/// The chart directory: `--out DIR`, or `target/charts` in the package.
fn output_directory() -> Result<PathBuf, Box<dyn Error>> {
    let mut arguments = std::env::args().skip(1);
    match (arguments.next().as_deref(), arguments.next()) {
        (None, _) => Ok(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/charts")),
        (Some("--out"), Some(directory)) => Ok(PathBuf::from(directory)),
        _ => Err("usage: slider_crank [--out DIR]".into()),
    }
}

fn main() -> Result<(), Box<dyn Error>> {
    let out = output_directory()?;
    std::fs::create_dir_all(&out)?;

    let pendulum = SEED_3;
    // Critical damping at the bar's natural frequency √(3g/2l).
    let pendulum_frequency = (1.5 * pendulum.g / pendulum.l).sqrt();
    compare(
        "seed example 3",
        &pendulum,
        pendulum.assembled(1.0, 2.0),
        10_000,
        pendulum_frequency,
        out.join("constraint_drift_seed_3.svg"),
    )?;

    let crank = SLIDER_CRANK;
    let [_, _, projected] = compare(
        "slider-crank",
        &crank,
        crank.assembled(0.0, CRANK_SPEED),
        25_000,
        10.0,
        out.join("constraint_drift_slider_crank.svg"),
    )?;
    let animation = Scene::of(&crank)?
        .title("Slider-crank at 4 rev/s, unforced (RK4, h = 1 ms, projection)")
        .equations(SliderCrank::EQUATIONS)
        .write(out.join("slider_crank.html"), &projected.recording)?;
    println!("animation: {}", animation.display());
    let revolutions = projected.end.q[0] / std::f64::consts::TAU;
    println!(
        "slider-crank with projection: {revolutions:.1} crank revolutions in {:.0} s, \
         max |φ| {:.3e}, max |ΔE|/E {:.3e}",
        projected.end.t, projected.worst_drift, projected.worst_energy_error
    );
    Ok(())
}
