//! The systems of the work-precision example, shared with
//! `tests/stability.rs`: the chaotic double pendulum of the reference data
//! (seed example 1, `tests/reference/chaotic_double_pendulum.json`), the
//! same pendulum with a stiff spring across its middle joint, and seed
//! example 2 at its singular mass matrix.

use std::error::Error;
use std::path::Path;

use dalembert::State;

#[path = "../../tests/seeds/mod.rs"]
mod seeds;
pub use seeds::{CHAOTIC, CHAOTIC_END, CHAOTIC_START, RotatingBar};

/// The reference final state at [`CHAOTIC_END`], its 25 digits rounded to
/// the nearest doubles.
pub fn chaotic_reference() -> Result<State<2, 2>, Box<dyn Error>> {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/chaotic_double_pendulum.json");
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(path)?)?;
    let digits = json["final_state_25_digits"]
        .as_array()
        .ok_or("final_state_25_digits is not an array")?;
    let mut values = [0.0; 4];
    for (value, text) in values.iter_mut().zip(digits) {
        *value = text
            .as_str()
            .ok_or("a final-state entry is not a string")?
            .parse()?;
    }
    let [theta1, theta2, theta1_dot, theta2_dot] = values;
    Ok(State {
        t: json["t_final"].as_f64().ok_or("t_final is not a number")?,
        q: [theta1, theta2],
        v: [theta1_dot, theta2_dot],
    })
}

dalembert::dalembert! {
    /// Seed example 1 with a torsional spring of stiffness `k` between the
    /// links: a stiff joint when `k` is large.
    pub StiffDoublePendulum {
        parameters m, L, g, k;
        coordinates theta1, theta2;
        frame B1 = N.rotate_z(theta1);
        frame B2 = N.rotate_z(theta2);
        point P1 = O - L * B1.y;
        point G1 = O - L/2 * B1.y;
        point G2 = P1 - L/2 * B2.y;
        body link1 { mass: m, center: G1, frame: B1, inertia: [0, 0, m*L^2/12] };
        body link2 { mass: m, center: G2, frame: B2, inertia: [0, 0, m*L^2/12] };
        gravity -g * N.y;
        potential k * (theta2 - theta1)^2 / 2;
    }
}

/// The stiff joint: `k = 10⁶ N·m/rad` on unit links.
pub const STIFF: StiffDoublePendulum = StiffDoublePendulum {
    m: 1.0,
    L: 1.0,
    g: 9.81,
    k: 1e6,
};

/// The stiff pendulum released at rest with its spring relaxed, both links
/// at 1 rad.
pub const STIFF_START: State<2, 2> = State {
    t: 0.0,
    q: [1.0, 1.0],
    v: [0.0, 0.0],
};

/// Seed example 2 with its bar on the rotation axis (`d = 0`): the mass
/// matrix `diag(m l²/12 cos²θ, m l²/12)` is singular at `θ = π/2`.
pub const ON_AXIS: RotatingBar = RotatingBar {
    m: 1.0,
    l: 1.0,
    d: 0.0,
};

/// The bar 0.5 rad below the vertical, tilting towards it at 1 rad/s
/// without spin: `θ` grows linearly and reaches `π/2` at `t = 0.5`.
pub const TOWARDS_AXIS: State<2, 2> = State {
    t: 0.0,
    q: [0.0, std::f64::consts::FRAC_PI_2 - 0.5],
    v: [0.0, 1.0],
};
