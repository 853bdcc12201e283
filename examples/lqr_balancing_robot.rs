//! LQR balancing of a two-wheeled self-balancing robot that rolls
//! (`dalembert_fixtures::balancing_robot`: one `rolling` wheel, whose three
//! rows start with its contact row, zero as the axle stays level, and the
//! other's forward row: three nonholonomic rows that act), from the exact
//! linearisation about upright motion at 1 m/s: the generated `linearize`
//! gives `A`, `B` on the constraint manifold; the pitch, the heading and
//! the three independent speeds (pitch rate, wheel rates) close a
//! subsystem (the positions and wheel angles are cyclic), whose Riccati
//! equation gives the gain `K`. The nonlinear model, released pitched
//! 0.2 rad forward and turning, is simulated under
//! `(TL, TR) = −K (θ, ψ, θ̇, φ̇L − V/r, φ̇R − V/r)` beside the uncontrolled
//! fall, charted and animated.
//!
//! ```text
//! cargo run --release --example lqr_balancing_robot [-- --out DIR]
//! ```
//!
//! The chart and the scene are written to `DIR` (default `target/charts`).

use dalembert::{Constrained, Stabilisation, State, energy, integrate};
use dalembert_fixtures::balancing_robot::{BALANCING_ROBOT, BalancingRobot, upright};
use dalembert_lab::{Recording, Scene, Series, input_power, line_chart, lqr};
use std::path::PathBuf;

/// Forward speed of the motion balanced about (m/s).
const SPEED: f64 = 1.0;
/// The controlled states' entries of `linearize`'s state `(q, v)`: the
/// pitch, the heading, the pitch rate and the wheels' rates.
const CONTROLLED: [usize; 5] = [3, 2, 9, 10, 11];
/// Simulated time (s) and RK4 steps.
const END: f64 = 6.0;
const STEPS: u64 = 6_000;

/// `(TL, TR) = −K (θ, ψ, θ̇, φ̇L − V/r, φ̇R − V/r)`.
fn feedback(gain: &[[f64; 5]; 2], q: &[f64; 6], v: &[f64; 6]) -> [f64; 2] {
    let spin = SPEED / BALANCING_ROBOT.r;
    let error = [q[3], q[2], v[3], v[4] - spin, v[5] - spin];
    gain.map(|row| -row.iter().zip(&error).map(|(k, e)| k * e).sum::<f64>())
}

/// Released pitched by `pitch` and turning at 0.3 rad/s, rolling forward at
/// `SPEED`: the wheels' rates satisfy the rows (the axle's midpoint moves
/// along the heading at the mean rim speed).
fn released(pitch: f64) -> State<6, 6> {
    let (mut q, mut v) = upright(SPEED);
    q[3] = pitch;
    let (turn, robot) = (0.3, BALANCING_ROBOT);
    v[2] = turn;
    v[4] = (SPEED - robot.d * turn) / robot.r;
    v[5] = (SPEED + robot.d * turn) / robot.r;
    State { t: 0.0, q, v }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .skip_while(|arg| arg != "--out")
        .nth(1)
        .map_or_else(|| PathBuf::from("target/charts"), PathBuf::from);
    std::fs::create_dir_all(&out)?;

    let (q, v) = upright(SPEED);
    let (a, b) = BALANCING_ROBOT.linearize(0.0, &q, &v, &[0.0; 2])?;
    let a = CONTROLLED.map(|i| CONTROLLED.map(|j| a[i][j]));
    let b = CONTROLLED.map(|i| b[i]);
    println!("A of (θ, ψ, θ̇, φ̇L, φ̇R) at upright motion, {SPEED} m/s:");
    for row in &a {
        println!("  {row:9.3?}");
    }
    let mut state_weights = [[0.0; 5]; 5];
    for (i, w) in [100.0, 10.0, 1.0, 0.1, 0.1].into_iter().enumerate() {
        state_weights[i][i] = w;
    }
    let (gain, _) = lqr(&a, &b, &state_weights, &[[1.0, 0.0], [0.0, 1.0]])?;
    println!("LQR gain K:\n  {:9.3?}\n  {:9.3?}", gain[0], gain[1]);

    let start = released(0.2);
    let controlled = Constrained::new(
        &BALANCING_ROBOT,
        |_, q: &[f64; 6], v: &[f64; 6]| feedback(&gain, q, v),
        Stabilisation::None,
    );
    let (mut pitch, mut heading, mut torque) = (Vec::new(), Vec::new(), Vec::new());
    let mut recording = Recording::new();
    let end = integrate::Integration::new(&controlled, start, END, integrate::Rk4 { steps: STEPS })
        .observe(|s| {
            pitch.push((s.t, s.q[3]));
            heading.push((s.t, s.q[2]));
            let u = feedback(&gain, &s.q, &s.v);
            torque.push((s.t, u[0] / 10.0));
            let e = energy(&BALANCING_ROBOT, &s.q, &s.v);
            let power = input_power(&BALANCING_ROBOT, s.t, &s.q, &s.v, &u);
            recording.push_driven(s.t, &s.q, e, power);
        })
        .run()?
        .end;
    println!(
        "controlled, after {END} s: θ = {:.2e} rad, θ̇ = {:.2e} rad/s, mean wheel rate {:.4} rad/s (V/r = {:.4})",
        end.q[3],
        end.v[3],
        (end.v[4] + end.v[5]) / 2.0,
        SPEED / BALANCING_ROBOT.r
    );
    let uncontrolled = Constrained::without_inputs(&BALANCING_ROBOT, Stabilisation::None);
    let mut falling = Vec::new();
    integrate::Integration::new(&uncontrolled, start, 0.6, integrate::Rk4 { steps: 600 })
        .observe(|s| {
            falling.push((s.t, s.q[3]));
        })
        .run()?;

    let chart = out.join("lqr_balancing_robot.svg");
    line_chart(
        &chart,
        "Self-balancing robot released 0.2 rad off upright at 1 m/s: LQR from the exact linearisation",
        "t (s)",
        "θ, ψ (rad), TL/10 (N m)",
        &[
            Series {
                name: "pitch θ, LQR",
                points: &pitch,
            },
            Series {
                name: "heading ψ, LQR",
                points: &heading,
            },
            Series {
                name: "TL/10, LQR",
                points: &torque,
            },
            Series {
                name: "θ, no control (first 0.6 s)",
                points: &falling,
            },
        ],
    )?;
    println!("wrote {}", chart.display());
    let scene = Scene::of(&BALANCING_ROBOT)?
        .title("Self-balancing robot balanced by LQR while it rolls and turns (RK4, h = 1 ms)")
        .equations(BalancingRobot::EQUATIONS);
    let page = scene.write(out.join("lqr_balancing_robot.html"), &recording)?;
    println!("wrote {}", page.display());
    Ok(())
}
