//! A dissipation function depends on coordinates, speeds and parameters, not on inputs.

use dalembert_macros::dalembert;

dalembert! {
    pub Damped {
        parameters m, c;
        coordinates x;
        inputs u;
        particle p { mass: m, at: O + x * N.x };
        dissipation c * u * dt(x)^2 / 2;
    }
}

fn main() {}
