//! Constants without a finite value: `ln(0)` and `sqrt` of a negative
//! number would make the forcing infinite or NaN at every state. Both are
//! reported.

use dalembert_macros::dalembert;

dalembert! {
    pub Slider {
        parameters k;
        coordinates x;
        point P = O + x * N.x;
        particle s { mass: 1, at: P };
        force ln(0) * N.x + sqrt(2 - 3) * N.y at P;
    }
}

fn main() {}
