//! A point is placed from a point, not from a frame.

use dalembert_macros::dalembert;

dalembert! {
    pub Wheel {
        parameters r;
        coordinates a;
        frame Hub = N.rotate_z(a);
        point Rim = Hub + r * Hub.x;
        particle valve { mass: 1, at: Rim };
    }
}

fn main() {}
