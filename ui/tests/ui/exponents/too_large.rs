//! An exponent beyond `i32` is reported, not wrapped.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        potential m * theta^4294967296;
    }
}

fn main() {}
