//! A torque needs `on` and the frame it acts on.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        torque u * N.z at B;
    }
}

fn main() {}
