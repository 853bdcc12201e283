//! Numbers are plain decimals, without a type suffix.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        gravity -9.81f64 * N.y;
    }
}

fn main() {}
