//! A wheel's radius is made of parameters only.

use dalembert_macros::dalembert;

dalembert! {
    pub Wheel {
        parameters m, r;
        coordinates x, phi;
        frame B = N.rotate_y(phi);
        point G = O + x * N.x + r * N.z;
        body wheel { mass: m, center: G, frame: B, inertia: [1, 2, 1] };
        rolling contact { wheel: B, axle: B.y, center: G, radius: r + x, plane: N.z };
    }
}

fn main() {}
