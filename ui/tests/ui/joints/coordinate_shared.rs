//! Each joint has a coordinate of its own: the second use of one is an error.

use dalembert_macros::dalembert;

dalembert! {
    pub Arm {
        parameters L;
        coordinates q1, q2;
        joint revolute J1 { parent: N, child: A, axis: z, coordinate: q1, at: O };
        joint revolute J2 { parent: A, child: C, axis: z, coordinate: q1, at: J1 + L * A.x };
    }
}

fn main() {}
