//! A potential depends on coordinates and parameters only.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        potential m * dt(theta)^2;
    }
}

fn main() {}
