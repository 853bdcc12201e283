//! A free joint joins a floating body to `N`: its parent must be `N`.

use dalembert_macros::dalembert;

dalembert! {
    pub Floating {
        parameters m;
        coordinates theta;
        frame A = N.rotate_z(theta);
        joint free base { parent: A, child: B, at: O };
        body b { mass: m, center: base, frame: B, inertia: [m, m, m] };
    }
}

fn main() {}
