//! Frames are made by `rotate_x`, `rotate_y` or `rotate_z`.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        frame C = B.rotate_w(theta);
    }
}

fn main() {}
