//! A nonholonomic constraint must be linear in the speeds.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        constraint dt(theta)^2 == l;
    }
}

fn main() {}
