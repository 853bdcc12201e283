//! A constraint written above the statement that declares its coordinates.

use dalembert_macros::dalembert;

dalembert! {
    pub Slider {
        parameters m, l;
        constraint x == l;
        coordinates x;
        particle block { mass: m, at: O + x * N.x };
    }
}

fn main() {}
