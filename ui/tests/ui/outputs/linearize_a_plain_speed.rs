//! `linearize(..)` names plain coordinates, or a free or spherical joint's tangent directions by its speeds: not a speed of a `speeds` statement.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, L;
        coordinates x, theta;
        speeds w { theta: w };
        frame B = N.rotate_z(theta);
        point P = O + x * N.x;
        particle slider { mass: m, at: P };
        particle bob { mass: m, at: P - L * B.y };
        constraint x == 0;
        outputs linearize(w);
    }
}

fn main() {}
