//! A literal beyond the range of `f64` would be infinite in the generated
//! code (and the mass matrix NaN).

use dalembert_macros::dalembert;

dalembert! {
    pub Slider {
        coordinates x;
        particle s { mass: 1e400, at: O + x * N.x };
    }
}

fn main() {}
