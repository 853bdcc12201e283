//! The only attribute allowed is a `///` doc comment.

use dalembert_macros::dalembert;

dalembert! {
    #[derive(Debug)]
    pub Pendulum {
        coordinates theta;
    }
}

fn main() {}
