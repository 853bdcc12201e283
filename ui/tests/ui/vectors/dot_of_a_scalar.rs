//! `dot` takes two vectors.

use dalembert_macros::dalembert;

dalembert! {
    pub Slider {
        parameters m;
        coordinates x;
        point P = O + x * N.x;
        particle p { mass: m, at: P };
        constraint dot(x, N.x) == 0;
    }
}

fn main() {}
