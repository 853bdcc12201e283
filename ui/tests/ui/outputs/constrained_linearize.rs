//! `taylor` of a system with constraints is not generated,
//! and its `linearize` needs the independent coordinates: each is an error
//! at its name.

use dalembert_macros::dalembert;

dalembert! {
    pub ConstrainedPendulum {
        parameters m, l, g;
        coordinates x, y, theta;
        frame B = N.rotate_z(theta);
        point G = O + x * N.x + y * N.y;
        body bar { mass: m, center: G, frame: B, inertia: [0, 0, m*l^2/12] };
        gravity -g * N.y;
        outputs linearize, taylor;
        constraint x - l/2 * sin(theta) == 0;
        constraint y + l/2 * cos(theta) == 0;
    }
}

fn main() {}
