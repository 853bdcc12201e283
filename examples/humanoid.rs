//! dm_control's humanoid, imported from its MJCF file at build time
//! (`dalembert_generated::Humanoid`, `Builder::mjcf` on
//! `tests/reference/mjcf/dm_control/humanoid.xml`), released slightly
//! tilted and spinning with no joint torques: it falls under gravity (there
//! is no floor: contacts are left out), its limbs swinging on their joint
//! springs and dampers. 2 s of RK4 at 1 ms, animated from the same import's
//! model text.
//!
//! ```text
//! cargo run --release --example humanoid [-- DIR]
//! ```
//!
//! Writes `humanoid.html` (to open in a browser) into `DIR` (default
//! `target/charts`) and prints the energy balance: with dampers, the total
//! energy can only fall.

use std::path::PathBuf;

use dalembert::{State, Unconstrained, energy, integrate};
use dalembert_generated::Humanoid;
use dalembert_lab::{Recording, Scene};

/// The MJCF file `dalembert_generated::Humanoid` is imported from.
const MJCF: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/reference/mjcf/dm_control/humanoid.xml"
);

/// How long it falls, and the step, in seconds.
const END: f64 = 2.0;
const STEP: f64 = 1e-3;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .map_or_else(|| PathBuf::from("target/charts"), PathBuf::from);
    std::fs::create_dir_all(&out)?;
    let humanoid = Humanoid {};
    // Standing 1.5 m up, tilted by 0.2 rad about x (the quaternion
    // (sin 0.1, 0, 0, cos 0.1)), turning at 1 rad/s about its own z axis;
    // the joints straight and at rest.
    let mut q = [0.0; Humanoid::NQ];
    q[2] = 1.5;
    q[3] = 0.1_f64.sin();
    q[6] = 0.1_f64.cos();
    let mut v = [0.0; Humanoid::NV];
    v[5] = 1.0;
    let start = State { t: 0.0, q, v };
    let initial = energy(&humanoid, &start.q, &start.v);
    let mut recording = Recording::new();
    let mut last = initial;
    let steps = (END / STEP).round() as u64;
    integrate::Integration::new(
        &Unconstrained::without_inputs(&humanoid),
        start,
        END,
        integrate::Rk4 { steps },
    )
    .observe(|s| {
        last = energy(&humanoid, &s.q, &s.v);
        recording.push(s.t, &s.q, last);
    })
    .run()?;
    println!(
        "humanoid: {} steps of RK4, energy {initial:.6} J at the start, {last:.6} J after {END} s \
         (the dampers took {:.6} J)",
        steps,
        initial - last
    );
    let model = dalembert_codegen::Mjcf::read(MJCF)?.model()?;
    let page = Scene::new(&model, &[])?
        .title("dm_control's humanoid (MJCF) falling without joint torques (RK4, h = 1 ms)")
        .equations(Humanoid::EQUATIONS)
        .write(out.join("humanoid.html"), &recording)?;
    println!("wrote {}", page.display());
    Ok(())
}
