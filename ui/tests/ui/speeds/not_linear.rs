//! A coordinate's rate must be linear in the new speeds.

use dalembert_macros::dalembert;

dalembert! {
    pub Spinner {
        parameters I;
        coordinates theta;
        speeds w { theta: w^2 };
        frame B = N.rotate_z(theta);
        body b { mass: 1, center: O, frame: B, inertia: [I, I, I] };
    }
}

fn main() {}
