//! A joint's coordinate is one of the declared coordinates, not a parameter (which would make a fixed joint).

use dalembert_macros::dalembert;

dalembert! {
    pub Hinge {
        parameters m;
        coordinates q;
        joint revolute J { parent: N, child: B, axis: z, coordinate: m, at: O };
    }
}

fn main() {}
