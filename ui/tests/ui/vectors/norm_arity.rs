//! `norm` takes one vector.

use dalembert_macros::dalembert;

dalembert! {
    pub Slider {
        parameters m, k;
        coordinates x;
        point P = O + x * N.x;
        particle p { mass: m, at: P };
        potential k * norm(P - O, N.x);
    }
}

fn main() {}
