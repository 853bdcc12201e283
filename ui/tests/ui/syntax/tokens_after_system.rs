//! Nothing may follow the system's closing brace.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        coordinates theta;
    }
    pub Other {}
}

fn main() {}
