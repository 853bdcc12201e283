//! Identification of a two-link arm's parameters from its motion: the arm
//! of `generated/models/two_link_arm.dal` is simulated with known
//! parameters, driven by motors that track an exciting trajectory; the
//! torques are "measured" with noise, and the base parameters `π` are found
//! by least squares on the emitted regressor, `Y(q, v, v̇) π = τ`. Prints
//! the estimated base parameters beside the true ones.
//!
//! ```text
//! cargo run --example identification
//! ```

use dalembert::integrate::{Integration, Rk4};
use dalembert::{State, Unconstrained};
use dalembert_codegen::testing::Random;
use dalembert_generated::two_link_arm::TwoLinkArm;
use nalgebra::{DMatrix, DVector};

/// The arm whose parameters are to be found.
const TRUE_ARM: TwoLinkArm = TwoLinkArm {
    m1: 2.0,
    m2: 1.5,
    l1: 0.6,
    l2: 0.5,
    c1: 0.3,
    c2: 0.25,
    I1: 0.06,
    I2: 0.03,
    g: 9.81,
};

/// Standard deviation of the torque sensors' noise, N·m.
const NOISE: f64 = 0.05;
/// Length of the experiment and the integration step, s.
const DURATION: f64 = 20.0;
const STEP: f64 = 1e-3;
/// One sample every this many steps (100 Hz).
const SAMPLE_EVERY: u64 = 10;

/// The exciting trajectory the motors track: two sines per joint.
fn reference(t: f64) -> [f64; 2] {
    [
        0.8 * (1.3 * t).sin() + 0.4 * (3.1 * t).sin(),
        1.0 * (1.7 * t + 0.5).sin() + 0.3 * (4.3 * t).sin(),
    ]
}

/// The motors: a PD law on the tracking error.
fn torques(t: f64, q: &[f64; 2], v: &[f64; 2]) -> [f64; 2] {
    let r = reference(t);
    [0, 1].map(|i| 60.0 * (r[i] - q[i]) - 8.0 * v[i])
}

/// A standard normal draw (Box–Muller).
fn normal(random: &mut Random) -> f64 {
    let (u1, u2) = (random.uniform(f64::EPSILON, 1.0), random.uniform(0.0, 1.0));
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let arm = TRUE_ARM;
    let dynamics = Unconstrained::new(&arm, torques);
    let start = State {
        t: 0.0,
        q: [0.0, 0.0],
        v: [0.0, 0.0],
    };
    // Record (q, v, v̇, τ) at 100 Hz; v̇ from the model, as a filtered
    // differentiation of encoder readings would estimate it.
    let mut samples = Vec::new();
    let mut step = 0_u64;
    let steps = (DURATION / STEP).round() as u64;
    Integration::new(&dynamics, start, DURATION, Rk4 { steps })
        .observe(|state| {
            if step % SAMPLE_EVERY == 0 {
                let tau = torques(state.t, &state.q, &state.v);
                if let Ok(vdot) = arm.accelerations(state.t, &state.q, &state.v, &tau) {
                    samples.push((state.q, state.v, vdot, tau));
                }
            }
            step += 1;
        })
        .run()?;
    // Noisy torques; stack Y π = τ over every sample.
    let mut random = Random::new(2026);
    let nb = TwoLinkArm::BASE_PARAMETERS.len();
    let rows = 2 * samples.len();
    let mut y = DMatrix::<f64>::zeros(rows, nb);
    let mut tau = DVector::<f64>::zeros(rows);
    for (k, (q, v, vdot, measured)) in samples.iter().enumerate() {
        let regressor = arm.regressor(q, v, vdot);
        for i in 0..2 {
            for j in 0..nb {
                y[(2 * k + i, j)] = regressor[i][j];
            }
            tau[2 * k + i] = measured[i] + NOISE * normal(&mut random);
        }
    }
    let svd = y.clone().svd(true, true);
    let estimate = svd.solve(&tau, 1e-12)?;
    let residual = (&y * &estimate - &tau).norm() / (rows as f64).sqrt();
    let truth = arm.base_parameters();
    println!(
        "{} samples at 100 Hz over {DURATION} s, torque noise σ = {NOISE} N·m, \
         condition number of Y: {:.0}, residual RMS {residual:.4} N·m\n",
        samples.len(),
        svd.singular_values.max() / svd.singular_values.min(),
    );
    println!("| base parameter | true | estimated | relative error |\n|---|---|---|---|");
    for (j, name) in TwoLinkArm::BASE_PARAMETERS.iter().enumerate() {
        println!(
            "| `{name}` | {:.5} | {:.5} | {:.1e} |",
            truth[j],
            estimate[j],
            (estimate[j] - truth[j]).abs() / truth[j].abs()
        );
    }
    Ok(())
}
