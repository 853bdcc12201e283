//! `rotate` takes an axis and an angle.

use dalembert_macros::dalembert;

dalembert! {
    pub Tilted {
        parameters m, l;
        coordinates theta;
        frame B = N.rotate_z(theta);
        frame C = B.rotate(0.3);
        body b { mass: m, center: O - l * B.y, frame: C, inertia: [m, m, m] };
    }
}

fn main() {}
