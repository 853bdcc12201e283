//! A potential depends on the positions only, not on a velocity.

use dalembert_macros::dalembert;

dalembert! {
    pub Slider {
        parameters m, c;
        coordinates x;
        point P = O + x * N.x;
        particle p { mass: m, at: P };
        potential c * dot(velocity(P), N.x);
    }
}

fn main() {}
