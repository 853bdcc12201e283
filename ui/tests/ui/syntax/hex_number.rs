//! Numbers are plain decimals, without a base prefix.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        potential 0x10 * theta;
    }
}

fn main() {}
