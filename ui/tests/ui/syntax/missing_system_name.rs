//! The system needs a name, which becomes the struct's.

use dalembert_macros::dalembert;

dalembert! {
    pub {
        coordinates theta;
    }
}

fn main() {}
