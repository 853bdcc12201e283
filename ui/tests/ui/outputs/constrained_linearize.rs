//! `linearize` of a system with constraints needs the independent
//! coordinates: an error at its name (its `taylor`, beside it, is
//! generated).

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
