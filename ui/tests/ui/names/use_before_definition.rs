//! Statements are read in order: a name must be defined above its use.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        point Q = R + l * B.x;
        point R = O;
    }
}

fn main() {}
