//! `F.rotate_z(..)` makes a frame in a `frame` statement only; it is not a vector.

use dalembert_macros::dalembert;

dalembert! {
    pub Mass {
        parameters m;
        coordinates x;
        particle p { mass: m, at: O + x * N.x };
        force N.rotate_z(x) at O;
    }
}

fn main() {}
