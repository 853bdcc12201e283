//! A quadrotor on a free joint: four rotor thrusts as inputs, each rotor's
//! drag torque proportional to its thrust (alternating spin directions). It
//! hovers at exactly the thrust that carries its weight, then flips: a burst
//! of climb, a roll torque from the thrust difference of the rotors on
//! `±B.y` for half the turn, the opposite torque for the other half, hover
//! again. The attitude is a unit quaternion, so turning upside down meets no
//! singularity (Euler angles would lock at 90° of pitch).
//!
//! Writes `docs/charts/quadrotor.svg` (altitude, the cosine of the tilt and
//! the roll in turns against time). Run with
//! `cargo run --example quadrotor`.

use std::error::Error;
use std::path::Path;

use dalembert::integrate::{Integration, Rk4};
use dalembert::{State, Unconstrained};
use dalembert_lab::{Series, line_chart};

dalembert::dalembert! {
    /// A quadrotor: rotors at `±l B.x` and `±l B.y`, thrusts along `B.z`.
    pub Quadrotor {
        parameters m, l, Ixx, Iyy, Izz, k, g;
        inputs f1, f2, f3, f4;
        joint free drone { parent: N, child: B, at: O };
        body airframe { mass: m, center: drone, frame: B, inertia: [Ixx, Iyy, Izz] };
        gravity -g * N.z;
        force f1 * B.z at drone + l * B.x;
        force f2 * B.z at drone + l * B.y;
        force f3 * B.z at drone - l * B.x;
        force f4 * B.z at drone - l * B.y;
        torque k * (f1 - f2 + f3 - f4) * B.z on B;
    }
}

const DRONE: Quadrotor = Quadrotor {
    m: 1.0,
    l: 0.2,
    Ixx: 0.01,
    Iyy: 0.01,
    Izz: 0.02,
    k: 0.01,
    g: 9.81,
};

/// Hover until `HOVER`, climb until `CLIMB`, then roll.
const HOVER: f64 = 1.0;
const CLIMB: f64 = 1.4;
/// The thrust difference between the rotors on `+B.y` and `−B.y` (N).
const ROLL_THRUST: f64 = 2.0;

/// Half the time of a full roll: accelerating at `l Δ / Ixx` for `T` and
/// decelerating for `T` turns by `α T² = 2π`.
fn half_roll() -> f64 {
    let alpha = DRONE.l * ROLL_THRUST / DRONE.Ixx;
    (2.0 * std::f64::consts::PI / alpha).sqrt()
}

/// The open-loop thrusts at time `t`.
fn thrusts(t: f64) -> [f64; 4] {
    let weight = DRONE.m * DRONE.g / 4.0;
    let half = half_roll();
    let roll = match t - CLIMB {
        s if (0.0..half).contains(&s) => ROLL_THRUST / 2.0,
        s if (half..2.0 * half).contains(&s) => -ROLL_THRUST / 2.0,
        _ => 0.0,
    };
    let climb = if (HOVER..CLIMB).contains(&t) {
        3.0
    } else {
        0.0
    };
    [
        weight + climb,
        weight + climb + roll,
        weight + climb,
        weight + climb - roll,
    ]
}

fn main() -> Result<(), Box<dyn Error>> {
    let start = State {
        t: 0.0,
        q: [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        v: [0.0; 6],
    };
    let dynamics = Unconstrained::new(&DRONE, |t, _: &[f64; 7], _: &[f64; 6]| thrusts(t));
    let (mut altitude, mut upright, mut roll) = (Vec::new(), Vec::new(), Vec::new());
    let (mut turned, mut last_t) = (0.0, 0.0);
    let mut hover_drift = 0.0_f64;
    let end = Integration::new(&dynamics, start, 3.0, Rk4 { steps: 3000 })
        .observe(|s| {
            let [_, _, z, qx, qy, _, _] = s.q;
            // N.z · B.z: 1 upright, −1 upside down.
            let cos_tilt = 1.0 - 2.0 * (qx * qx + qy * qy);
            turned += s.v[3] * (s.t - last_t) / (2.0 * std::f64::consts::PI);
            last_t = s.t;
            if s.t <= HOVER {
                hover_drift = hover_drift.max((z - 1.0).abs());
            }
            altitude.push((s.t, z));
            upright.push((s.t, cos_tilt));
            roll.push((s.t, turned));
        })
        .run()?
        .end;
    println!("hover: altitude held to {hover_drift:.1e} m for {HOVER} s");
    println!(
        "flip: {turned:.3} turns about B.x in {:.3} s, ending at altitude {:.3} m, \
         quaternion norm {:.15}",
        2.0 * half_roll(),
        end.q[2],
        end.q[3..].iter().map(|c| c * c).sum::<f64>().sqrt()
    );
    let path = Path::new("docs/charts/quadrotor.svg");
    line_chart(
        path,
        "Quadrotor: hover, climb and a flip (open loop)",
        "time t (s)",
        "altitude (m), cos tilt, roll (turns)",
        &[
            Series {
                name: "altitude z (m)",
                points: &altitude,
            },
            Series {
                name: "cos tilt = N.z · B.z",
                points: &upright,
            },
            Series {
                name: "roll (turns)",
                points: &roll,
            },
        ],
    )?;
    println!("wrote {}", path.display());
    Ok(())
}
