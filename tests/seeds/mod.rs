//! The three seed examples, written exactly as DESIGN §3 writes them, for
//! the tests, examples and benchmarks that need them (each uses a subset),
//! and the chaotic reference trajectory of seed example 1
//! (`tests/reference/chaotic_double_pendulum.json`).

#![allow(dead_code)]

use dalembert::State;

dalembert::dalembert! {
    /// Seed example 1: double pendulum, absolute angles from the downward vertical.
    pub DoublePendulum {
        parameters m, L, g;
        coordinates theta1, theta2;
        frame B1 = N.rotate_z(theta1);
        frame B2 = N.rotate_z(theta2);
        point P1 = O - L * B1.y;
        point G1 = O - L/2 * B1.y;
        point G2 = P1 - L/2 * B2.y;
        body link1 { mass: m, center: G1, frame: B1, inertia: [0, 0, m*L^2/12] };
        body link2 { mass: m, center: G2, frame: B2, inertia: [0, 0, m*L^2/12] };
        gravity -g * N.y;
    }
}

dalembert::dalembert! {
    /// Seed example 2: a bar on a rotating massless frame, two motors.
    pub RotatingBar {
        parameters m, l, d;
        coordinates phi, theta;
        inputs M_phi, M_theta;
        frame F = N.rotate_z(phi);
        frame B = F.rotate_y(theta);
        point G = O + d * F.y;
        body bar { mass: m, center: G, frame: B, inertia: [0, m*l^2/12, m*l^2/12] };
        torque M_phi * N.z on F;
        torque M_theta * F.y on B reacting F;
    }
}

dalembert::dalembert! {
    /// Seed example 3: pendulum in dependent coordinates.
    pub ConstrainedPendulum {
        parameters m, l, g;
        coordinates x, y, theta;
        inputs M;
        frame B = N.rotate_z(theta);
        point G = O + x * N.x + y * N.y;
        body bar { mass: m, center: G, frame: B, inertia: [0, 0, m*l^2/12] };
        gravity -g * N.y;
        torque M * N.z on B;
        constraint x - l/2 * sin(theta) == 0;
        constraint y + l/2 * cos(theta) == 0;
    }
}

/// Seed example 1 with the parameters of the chaotic reference trajectory.
pub const CHAOTIC: DoublePendulum = DoublePendulum {
    m: 1.0,
    L: 1.0,
    g: 9.81,
};

/// Both links at 2 rad from the downward vertical, at rest: the start of the
/// chaotic reference trajectory.
pub const CHAOTIC_START: State<2, 2> = State {
    t: 0.0,
    q: [2.0, 2.0],
    v: [0.0, 0.0],
};

/// The end of the chaotic reference trajectory, in seconds.
pub const CHAOTIC_END: f64 = 10.0;
