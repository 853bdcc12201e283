//! A constraint that is the identity `0 == 0`.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        particle bob { mass: m, at: G };
        constraint 0 == 0;
    }
}

fn main() {}
