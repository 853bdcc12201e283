//! A scalar added to a vector: the error points at the operator.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        gravity g * N.y + g;
    }
}

fn main() {}
