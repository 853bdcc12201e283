//! `N` is the built-in Newtonian frame.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        frame N = B.rotate_x(theta);
    }
}

fn main() {}
