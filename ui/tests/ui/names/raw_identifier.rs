//! A raw identifier cannot name a coordinate: the generated code makes
//! `q_dot` and `q_ddot` from its name (this one used to panic the macro).

use dalembert_macros::dalembert;

dalembert! {
    pub Cart {
        parameters m;
        coordinates r#q;
        point P = O + r#q * N.x;
        particle cart { mass: m, at: P };
    }
}

fn main() {}
