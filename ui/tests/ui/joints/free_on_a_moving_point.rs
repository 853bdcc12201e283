//! A free joint's origin is measured from a point fixed in `N`.

use dalembert_macros::dalembert;

dalembert! {
    pub Floating {
        parameters m, l;
        coordinates theta;
        frame A = N.rotate_z(theta);
        point P = O + l * A.x;
        body arm { mass: m, center: P, frame: A, inertia: [m, m, m] };
        joint free base { parent: N, child: B, at: P };
        body b { mass: m, center: base, frame: B, inertia: [m, m, m] };
    }
}

fn main() {}
