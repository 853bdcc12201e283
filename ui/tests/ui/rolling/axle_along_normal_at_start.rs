//! A wheel whose axle is along the plane's normal at the start (every coordinate zero) has no contact point there.

use dalembert_macros::dalembert;

dalembert! {
    pub Lying {
        parameters m, r;
        coordinates x, y, z, theta;
        frame B = N.rotate_x(theta);
        point G = O + x * N.x + y * N.y + z * N.z;
        body wheel { mass: m, center: G, frame: B, inertia: [1, 1, 1] };
        rolling contact { wheel: B, axle: B.z, center: G, radius: r, plane: N.z };
    }
}

fn main() {}
