//! A closure of two distinct points that no coordinate moves.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters L;
        coordinates a;
        frame A = N.rotate_z(a);
        point T = O + L * A.x;
        point H = O + L * N.y;
        closure ground { at: O, to: H };
    }
}

fn main() {}
