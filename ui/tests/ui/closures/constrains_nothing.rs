//! A closure of a point on itself.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters L;
        coordinates a;
        frame A = N.rotate_z(a);
        point T = O + L * A.x;
        closure tip { at: T, to: T };
    }
}

fn main() {}
