//! Only coordinates have speeds: `dt` of a parameter is an error.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, c;
        coordinates theta;
        frame B = N.rotate_z(theta);
        body b { mass: m, center: O - l * B.y, frame: B, inertia: [m, m, m] };
        dissipation c * dt(l)^2;
    }
}

fn main() {}
