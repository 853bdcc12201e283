//! A nonholonomic constraint with a product of two speeds.

use dalembert_macros::dalembert;

dalembert! {
    pub Cart {
        parameters m;
        coordinates x, y;
        particle block { mass: m, at: O + x * N.x + y * N.y };
        constraint dt(x) * dt(y) == 0;
    }
}

fn main() {}
