//! A wheel whose axle is the plane's normal in every configuration has no contact point.

use dalembert_macros::dalembert;

dalembert! {
    pub Spinning {
        parameters m, r;
        coordinates x, y, z, psi;
        frame B = N.rotate_z(psi);
        point G = O + x * N.x + y * N.y + z * N.z;
        body wheel { mass: m, center: G, frame: B, inertia: [1, 1, 1] };
        rolling contact { wheel: B, axle: B.z, center: G, radius: r, plane: N.z };
    }
}

fn main() {}
