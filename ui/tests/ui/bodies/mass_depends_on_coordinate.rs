//! Masses and inertias depend on parameters only.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        body bar { mass: m * theta, center: G, frame: B, inertia: [0, 0, 1] };
    }
}

fn main() {}
