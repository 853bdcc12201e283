//! A wheel rolls on a fixed plane: its normal is a unit vector of a frame that does not turn.

use dalembert_macros::dalembert;

dalembert! {
    pub Turntable {
        parameters m, r;
        coordinates x, y, z, psi, phi;
        frame T = N.rotate_z(psi);
        frame B = N.rotate_y(phi);
        point G = O + x * N.x + y * N.y + z * N.z;
        body wheel { mass: m, center: G, frame: B, inertia: [1, 1, 1] };
        rolling contact { wheel: B, axle: B.y, center: G, radius: r, plane: T.x };
    }
}

fn main() {}
