//! A spherical joint has no axis and makes its own coordinates: only
//! `parent`, `child` and `at`.

use dalembert_macros::dalembert;

dalembert! {
    pub Top {
        parameters m, a;
        joint spherical ball { parent: N, child: B, axis: z, at: O };
        body b { mass: m, center: ball + a * B.z, frame: B, inertia: [m, m, m] };
    }
}

fn main() {}
