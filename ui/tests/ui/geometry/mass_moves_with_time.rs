//! The generated `mass_matrix(q)` has no `t`: a mass may not move with time.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        frame R = N.rotate_z(t);
        particle p { mass: m, at: O + l * R.x };
    }
}

fn main() {}
