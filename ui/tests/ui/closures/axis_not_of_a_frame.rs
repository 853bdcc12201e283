//! A hinge axis written as a joint axis instead of a frame's unit vector.

use dalembert_macros::dalembert;

dalembert! {
    pub FourBar {
        parameters L;
        coordinates a, b, c;
        frame A = N.rotate_z(a);
        frame B = N.rotate_z(b);
        frame C = N.rotate_z(c);
        point TA = O + L * A.x;
        point TB = O + L * N.x + L * B.x;
        point TC = TA + L * C.x;
        closure window { at: TC, to: TB, axis: z, along: B.z };
    }
}

fn main() {}
