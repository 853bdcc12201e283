//! Nothing may follow the system's closing brace, not even a `;`.

use dalembert_macros::dalembert;

dalembert! {
    pub Mass {
        parameters m;
        coordinates x;
        particle p { mass: m, at: O + x * N.x };
    };
}

fn main() {}
