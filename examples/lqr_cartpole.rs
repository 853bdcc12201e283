//! LQR balancing of a cart-pole from its exact linearisation: the model
//! asks for `outputs linearize;`, so the generated `linearize` gives the
//! state-space matrices `A`, `B` at the upright (exact derivatives, no
//! finite differences); the Riccati equation gives the gain `K`; and the
//! nonlinear model, released 0.3 rad off upright, is simulated under
//! `F = −K (x, θ, ẋ, θ̇)` beside the uncontrolled fall.
//!
//! ```text
//! cargo run --release --example lqr_cartpole [-- --out DIR]
//! ```
//!
//! The chart is written to `DIR` (default `target/charts`).

use dalembert::{State, Unconstrained, integrate};
use dalembert_fixtures::cart_pole::{
    CART_POLE, INPUT_WEIGHT, RELEASE_ANGLE, STATE_WEIGHTS, feedback,
};
use dalembert_lab::{Series, line_chart, lqr};
use std::path::PathBuf;

/// Simulated time (s) and RK4 steps.
const END: f64 = 6.0;
const STEPS: u64 = 6_000;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .skip_while(|arg| arg != "--out")
        .nth(1)
        .map_or_else(|| PathBuf::from("target/charts"), PathBuf::from);
    std::fs::create_dir_all(&out)?;

    let (a, b) = CART_POLE.linearize(0.0, &[0.0; 2], &[0.0; 2], &[0.0])?;
    println!("A at the upright (state x, θ, ẋ, θ̇):");
    for row in &a {
        println!("  {row:9.4?}");
    }
    println!("B: {:9.4?}", b.map(|row| row[0]));
    let (gain, _) = lqr(&a, &b, &STATE_WEIGHTS, &INPUT_WEIGHT)?;
    println!("LQR gain K: {:9.4?}", gain[0]);

    let start = State {
        t: 0.0,
        q: [0.0, RELEASE_ANGLE],
        v: [0.0; 2],
    };
    let controlled = Unconstrained::new(&CART_POLE, |_, q: &[f64; 2], v: &[f64; 2]| {
        feedback(&gain, q, v)
    });
    let (mut angle, mut position, mut force) = (Vec::new(), Vec::new(), Vec::new());
    let end = integrate::Integration::new(&controlled, start, END, integrate::Rk4 { steps: STEPS })
        .observe(|s| {
            angle.push((s.t, s.q[1]));
            position.push((s.t, s.q[0]));
            force.push((s.t, feedback(&gain, &s.q, &s.v)[0] / 10.0));
        })
        .run()?
        .end;
    println!(
        "controlled, after {END} s: x = {:.2e} m, θ = {:.2e} rad",
        end.q[0], end.q[1]
    );
    let uncontrolled = Unconstrained::new(&CART_POLE, |_, _: &[f64; 2], _: &[f64; 2]| [0.0]);
    let mut falling = Vec::new();
    integrate::Integration::new(&uncontrolled, start, 1.2, integrate::Rk4 { steps: 1_200 })
        .observe(|s| {
            falling.push((s.t, s.q[1]));
        })
        .run()?;

    let chart = out.join("lqr_cartpole.svg");
    line_chart(
        &chart,
        "Cart-pole released 0.3 rad off upright: LQR from the exact linearisation",
        "t (s)",
        "θ (rad), x (m), F/10 (N)",
        &[
            Series {
                name: "θ, LQR",
                points: &angle,
            },
            Series {
                name: "x, LQR",
                points: &position,
            },
            Series {
                name: "F/10, LQR",
                points: &force,
            },
            Series {
                name: "θ, no control (first 1.2 s)",
                points: &falling,
            },
        ],
    )?;
    println!("wrote {}", chart.display());
    Ok(())
}
