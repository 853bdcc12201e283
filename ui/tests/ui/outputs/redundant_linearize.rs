//! `linearize` of a system whose holonomic constraints are redundant (a
//! row written twice: three rows for three coordinates, one degree of
//! freedom): not supported, and said so at the independent coordinate.

use dalembert_macros::dalembert;

dalembert! {
    pub RedundantPendulum {
        parameters m, l, g;
        coordinates x, y, theta;
        frame B = N.rotate_z(theta);
        point G = O + x * N.x + y * N.y;
        body bar { mass: m, center: G, frame: B, inertia: [0, 0, m*l^2/12] };
        gravity -g * N.y;
        constraint x - l/2 * sin(theta) == 0;
        constraint y + l/2 * cos(theta) == 0;
        constraint x - l/2 * sin(theta) == 0;
        outputs linearize(theta);
    }
}

fn main() {}
