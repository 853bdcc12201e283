//! A wheel turns about its axle, so the axle must be fixed in the wheel's frame; `N.y` turns in it.

use dalembert_macros::dalembert;

dalembert! {
    pub Disc {
        parameters m, r, g;
        coordinates x, y, psi, theta, phi;
        frame A = N.rotate_z(psi);
        frame L = A.rotate_x(theta);
        frame B = L.rotate_y(phi);
        point G = O + x * N.x + y * N.y + r * L.z;
        body disc { mass: m, center: G, frame: B, inertia: [m*r^2/4, m*r^2/2, m*r^2/4] };
        gravity -g * N.z;
        rolling contact { wheel: B, axle: N.y, center: G, radius: r, plane: N.z };
    }
}

fn main() {}
