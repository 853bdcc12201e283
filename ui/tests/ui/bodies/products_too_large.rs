//! With products of inertia the principal moments are the tensor's
//! eigenvalues: `Ixy = 2` between moments of 1 gives one of −1.

use dalembert_macros::dalembert;

dalembert! {
    pub Plate {
        parameters m;
        coordinates a, b;
        frame A = N.rotate_x(a);
        frame B = A.rotate_y(b);
        body plate { mass: m, center: O, frame: B, inertia: [1, 1, 1, 2, 0, 0] };
    }
}

fn main() {}
