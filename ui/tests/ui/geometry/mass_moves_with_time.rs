//! The generated `potential_energy(q)` has no `t`: a mass whose motion in
//! time stays in the energies (here `V = m g l sin t`) is an error.

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
        gravity -g * N.y;
    }
}

fn main() {}
