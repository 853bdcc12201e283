//! The axis of `F.rotate(axis, angle)` is a constant list `[ax, ay, az]` of components in `F`'s axes, not a unit vector.

use dalembert_macros::dalembert;

dalembert! {
    pub Arm {
        parameters m;
        coordinates q;
        frame B = N.rotate(N.z, q);
        particle tip { mass: m, at: O + B.x };
    }
}

fn main() {}
