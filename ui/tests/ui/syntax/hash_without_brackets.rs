//! A `#` that does not start an attribute: only `///` doc comments may precede the system.

use dalembert_macros::dalembert;

dalembert! {
    # pub Mass {
        parameters m;
        coordinates x;
        particle p { mass: m, at: O + x * N.x };
    }
}

fn main() {}
