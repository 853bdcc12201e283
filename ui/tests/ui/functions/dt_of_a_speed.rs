//! `dt(..)` takes a coordinate or an expression of coordinates, parameters and `t`: not a speed.

use dalembert_macros::dalembert;

dalembert! {
    pub Mass {
        parameters m, c;
        coordinates x;
        particle p { mass: m, at: O + x * N.x };
        dissipation c * dt(dt(x))^2;
    }
}

fn main() {}
