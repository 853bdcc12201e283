//! A constant mass is evaluated: `sqrt(2) - 2` is negative.

use dalembert_macros::dalembert;

dalembert! {
    pub Bob {
        coordinates x;
        point P = O + x * N.x;
        particle bob { mass: sqrt(2) - 2, at: P };
    }
}

fn main() {}
