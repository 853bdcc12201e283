//! The Dzhanibekov effect: a brick spun about its intermediate axis flips
//! over, and back, again and again, while its energy and its angular
//! momentum in `N` stay what they were. The brick turns on a ball joint, its
//! attitude a unit quaternion (`dalembert_generated::Dzhanibekov`, from
//! `generated/models/dzhanibekov.dal`), so no attitude is singular; DOP853 at
//! tolerance 1e-12 carries it for 100 s.
//!
//! ```text
//! cargo run --release --example dzhanibekov [-- --out DIR]
//! ```
//!
//! Writes `dzhanibekov_spin.svg` (the angular velocity in the brick's axes),
//! `dzhanibekov_drift.svg` (the relative drift of the energy and of the
//! angular momentum in `N`) and `dzhanibekov.html` (the brick turning, to
//! open in a browser) into `DIR` (default `target/charts`).

use std::ops::ControlFlow;
use std::path::PathBuf;

use dalembert::integrate::{Adaptive, AdaptiveOptions, ExplicitPair, Integration};
use dalembert::{State, Unconstrained, energy};
use dalembert_codegen::testing::{mat_vec, quaternion_rotation};
use dalembert_generated::Dzhanibekov;
use dalembert_lab::{Recording, Scene, Series, line_chart, line_chart_log_y};

/// The model text, which the animation draws.
const MODEL: &str = include_str!("../generated/models/dzhanibekov.dal");

/// A uniform brick of 12 kg, 3 × 2 × 1 m: principal moments 5, 10, 13 kg m².
const BRICK: Dzhanibekov = Dzhanibekov {
    m: 12.0,
    a: 3.0,
    b: 2.0,
    c: 1.0,
};

/// How long the brick turns, and the sampling interval of the charts and
/// the animation, in seconds.
const END: f64 = 100.0;
const SAMPLE: f64 = 0.05;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = output_directory();
    std::fs::create_dir_all(&out)?;
    // Spun at 2 rad/s about the intermediate axis B.y, with a wobble of
    // 1e-3 rad/s about the others.
    let start = State {
        t: 0.0,
        q: [0.0, 0.0, 0.0, 1.0],
        v: [1e-3, 2.0, 1e-3],
    };
    let (e0, l0) = (energy(&BRICK, &start.q, &start.v), momentum(&start));
    let mut spin: [Vec<(f64, f64)>; 3] = Default::default();
    let (mut energy_drift, mut momentum_drift) = (Vec::new(), Vec::new());
    let mut recording = Recording::new();
    let options = AdaptiveOptions {
        max_steps: 10_000_000,
        ..AdaptiveOptions::with_tolerance(1e-12)
    };
    let dynamics = Unconstrained::without_inputs(&BRICK);
    // The drift at every step's end; the spin and the animation sampled
    // every SAMPLE seconds from DOP853's seventh-order dense output.
    let mut next = 0.0;
    let solution = Integration::new(
        &dynamics,
        start,
        END,
        Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .dense(|step| {
        let s = step.end();
        let l = momentum(s);
        let dl = (0..3).map(|i| (l[i] - l0[i]).powi(2)).sum::<f64>().sqrt();
        let scale = l0.iter().map(|x| x * x).sum::<f64>().sqrt();
        let e = energy(&BRICK, &s.q, &s.v);
        energy_drift.push((s.t, ((e - e0) / e0).abs()));
        momentum_drift.push((s.t, dl / scale));
        while next <= s.t {
            let sample = step.state_at(next);
            for (axis, w) in spin.iter_mut().zip(sample.v) {
                axis.push((next, w));
            }
            recording.push(next, &sample.q, energy(&BRICK, &sample.q, &sample.v));
            next += SAMPLE;
        }
        ControlFlow::Continue(())
    })
    .run()?;
    let flips = spin[1].windows(2).filter(|w| w[0].1 * w[1].1 < 0.0).count();
    let worst = |drift: &[(f64, f64)]| drift.iter().fold(0.0_f64, |m, p| m.max(p.1));
    // Exact zeros have no place on a log scale.
    let positive = |drift: &mut Vec<(f64, f64)>| drift.retain(|p| p.1 > 0.0);
    positive(&mut energy_drift);
    positive(&mut momentum_drift);
    println!(
        "{} steps, {flips} reversals of the spin about B.y in {END} s; \
         worst relative drift: energy {:.1e}, angular momentum {:.1e}",
        solution.statistics.accepted_steps,
        worst(&energy_drift),
        worst(&momentum_drift)
    );
    let spin_chart = out.join("dzhanibekov_spin.svg");
    line_chart(
        &spin_chart,
        "Dzhanibekov effect: angular velocity in the brick's axes (DOP853, tol 1e-12)",
        "t [s]",
        "ω [rad/s]",
        &[
            Series {
                name: "ω_x (smallest moment)",
                points: &spin[0],
            },
            Series {
                name: "ω_y (intermediate)",
                points: &spin[1],
            },
            Series {
                name: "ω_z (largest moment)",
                points: &spin[2],
            },
        ],
    )?;
    let drift_chart = out.join("dzhanibekov_drift.svg");
    line_chart_log_y(
        &drift_chart,
        "Dzhanibekov effect: what is conserved (relative drift)",
        "t [s]",
        "relative drift",
        &[
            Series {
                name: "|E − E₀| / E₀",
                points: &energy_drift,
            },
            Series {
                name: "|L − L₀| / |L₀| (in N)",
                points: &momentum_drift,
            },
        ],
    )?;
    let animation = Scene::new(MODEL, &[BRICK.m, BRICK.a, BRICK.b, BRICK.c])?
        .title("Dzhanibekov effect: a brick spun about its intermediate axis (DOP853, tol 1e-12)")
        .equations(Dzhanibekov::EQUATIONS)
        .write(out.join("dzhanibekov.html"), &recording)?;
    for path in [spin_chart, drift_chart, animation] {
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// The angular momentum `R I ω` in `N`'s axes.
fn momentum(s: &State<4, 3>) -> [f64; 3] {
    let (a2, b2, c2) = (BRICK.a.powi(2), BRICK.b.powi(2), BRICK.c.powi(2));
    let inertia = [b2 + c2, a2 + c2, a2 + b2].map(|x| BRICK.m * x / 12.0);
    let body = [0, 1, 2].map(|i| inertia[i] * s.v[i]);
    mat_vec(&quaternion_rotation(s.q), body)
}

/// `--out DIR`, else `target/charts`.
fn output_directory() -> PathBuf {
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--out"
            && let Some(dir) = args.next()
        {
            return PathBuf::from(dir);
        }
    }
    PathBuf::from("target/charts")
}
