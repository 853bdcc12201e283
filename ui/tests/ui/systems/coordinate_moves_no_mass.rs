//! A coordinate that moves no mass makes the mass matrix singular in every configuration.

use dalembert_macros::dalembert;

dalembert! {
    pub Idle {
        parameters m, L;
        coordinates theta, spare;
        frame B = N.rotate_z(theta);
        particle bob { mass: m, at: O - L * B.y };
        potential spare^2 / 2;
    }
}

fn main() {}
