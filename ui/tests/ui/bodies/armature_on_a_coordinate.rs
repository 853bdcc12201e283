//! `armature a on v;` names a speed (`dt(q)` or a joint's speed), not a coordinate.

use dalembert_macros::dalembert;

dalembert! {
    pub Motor {
        parameters m, a;
        coordinates theta;
        frame B = N.rotate_z(theta);
        particle bob { mass: m, at: O + B.x };
        armature a on theta;
    }
}

fn main() {}
