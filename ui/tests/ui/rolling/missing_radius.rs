//! A rolling contact needs its wheel, axle, center, radius and plane.

use dalembert_macros::dalembert;

dalembert! {
    pub Wheel {
        parameters m;
        coordinates x, z, phi;
        frame B = N.rotate_y(phi);
        point G = O + x * N.x + z * N.z;
        body wheel { mass: m, center: G, frame: B, inertia: [1, 1, 1] };
        rolling contact { wheel: B, axle: B.y, center: G, plane: N.z };
    }
}

fn main() {}
