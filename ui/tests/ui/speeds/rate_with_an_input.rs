//! A coordinate's rate in a `speeds` statement depends on coordinates, parameters and the new speeds only.

use dalembert_macros::dalembert;

dalembert! {
    pub Spinner {
        parameters m;
        coordinates theta;
        inputs u;
        speeds w { theta: w + u };
        frame B = N.rotate_z(theta);
        particle p { mass: m, at: O + B.x };
    }
}

fn main() {}
