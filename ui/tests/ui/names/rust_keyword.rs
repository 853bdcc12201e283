//! A Rust keyword cannot name anything: the generated code binds every
//! name as a Rust variable or field.

use dalembert_macros::dalembert;

dalembert! {
    pub Cart {
        parameters m, type;
        coordinates self, x;
        inputs crate;
        point P = O + x * N.x + self * N.y;
        particle cart { mass: m + type, at: P };
        force crate * N.x at P;
    }
}

fn main() {}
