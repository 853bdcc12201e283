//! A force needs `at` and its point of application.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        force u * N.x G;
    }
}

fn main() {}
