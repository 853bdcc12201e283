//! A velocity depends on the speeds: it has no place in a point's position.

use dalembert_macros::dalembert;

dalembert! {
    pub Slider {
        parameters m;
        coordinates x;
        point P = O + x * N.x;
        point Q = O + velocity(P);
        particle p { mass: m, at: Q };
    }
}

fn main() {}
