//! A joint's coordinate is the name of a declared coordinate, not an expression of one.

use dalembert_macros::dalembert;

dalembert! {
    pub Leg {
        coordinates q1, q2;
        frame Thigh = N.rotate_z(q1);
        joint revolute Knee { parent: Thigh, child: Shin, axis: y, coordinate: 2 * q2, at: O };
    }
}

fn main() {}
