//! A wheel's radius that is a number must be positive: a negative one puts the contact point on the wrong side of the centre.

use dalembert_macros::dalembert;

dalembert! {
    pub Disc {
        parameters m, g;
        coordinates x, y, z, psi, theta, phi;
        frame A = N.rotate_z(psi);
        frame L = A.rotate_x(theta);
        frame B = L.rotate_y(phi);
        point G = O + x * N.x + y * N.y + z * N.z;
        body disc { mass: m, center: G, frame: B, inertia: [1, 2, 1] };
        gravity -g * N.z;
        rolling contact { wheel: B, axle: B.y, center: G, radius: -0.5, plane: N.z };
    }
}

fn main() {}
