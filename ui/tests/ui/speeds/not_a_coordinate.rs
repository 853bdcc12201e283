//! A `speeds` statement gives the rates of declared coordinates.

use dalembert_macros::dalembert;

dalembert! {
    pub Spinner {
        parameters I;
        coordinates theta;
        speeds w { I: w };
        frame B = N.rotate_z(theta);
        body b { mass: 1, center: O, frame: B, inertia: [I, I, I] };
    }
}

fn main() {}
