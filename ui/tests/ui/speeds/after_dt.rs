//! A `speeds` statement comes before every `dt(..)`: it changes what the
//! speeds of its coordinates are.

use dalembert_macros::dalembert;

dalembert! {
    pub Spinner {
        parameters I, c;
        coordinates theta;
        dissipation c * dt(theta)^2 / 2;
        speeds w { theta: 2 * w };
        frame B = N.rotate_z(theta);
        body b { mass: 1, center: O, frame: B, inertia: [I, I, I] };
    }
}

fn main() {}
