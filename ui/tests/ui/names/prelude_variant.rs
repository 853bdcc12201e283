//! `Some`, `None`, `Ok` and `Err` cannot name anything: in the generated
//! code's `let` they would be patterns of the prelude's variants, not new
//! variables.

use dalembert_macros::dalembert;

dalembert! {
    pub Cart {
        parameters m, Some;
        coordinates None, x;
        inputs Ok;
        point P = O + x * N.x;
        particle Err { mass: m, at: P };
        force Ok * N.x at P;
    }
}

fn main() {}
