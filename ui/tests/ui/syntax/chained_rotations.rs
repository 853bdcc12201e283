//! A rotation is called on a frame's name: chained rotations take one
//! `frame` statement each.

use dalembert_macros::dalembert;

dalembert! {
    pub Gimbal {
        coordinates yaw, pitch;
        frame Inner = N.rotate_z(yaw).rotate_y(pitch);
        particle sensor { mass: 1, at: O + Inner.x };
    }
}

fn main() {}
