//! A list `[..]` is a body's inertia or a constant axis (of a joint or of `F.rotate`), not a value.

use dalembert_macros::dalembert;

dalembert! {
    pub Mass {
        parameters m;
        coordinates x;
        particle p { mass: m, at: O + x * N.x };
        potential [x, x, x];
    }
}

fn main() {}
