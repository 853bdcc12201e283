//! A mass must be positive.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        body bar { mass: 0, center: G, frame: B, inertia: [0, 0, 1] };
    }
}

fn main() {}
