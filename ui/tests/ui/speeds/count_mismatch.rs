//! As many new speeds as coordinates whose rates are given.

use dalembert_macros::dalembert;

dalembert! {
    pub Spinner {
        parameters I;
        coordinates theta, phi;
        speeds w1, w2 { theta: w1 + w2 };
        frame A = N.rotate_z(theta);
        frame B = A.rotate_x(phi);
        body b { mass: 1, center: O, frame: B, inertia: [I, I, I] };
    }
}

fn main() {}
