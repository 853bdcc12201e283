//! A system needs at least one generalized coordinate.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m;
    }
}

fn main() {}
