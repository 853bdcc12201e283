//! Vectors are scaled by scalars; there is no vector product here.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        gravity N.x * N.y;
    }
}

fn main() {}
