//! The adjoint of the inverse dynamics is refused for a system with constraints, pointing to `accelerations_jacobian`.

use dalembert_macros::dalembert;

dalembert! {
    pub Bar {
        parameters m, l, g;
        coordinates x, y, theta;
        frame B = N.rotate_z(theta);
        point G = O + x * N.x + y * N.y;
        body bar { mass: m, center: G, frame: B, inertia: [0, 0, m*l^2/12] };
        gravity -g * N.y;
        constraint x - l/2 * sin(theta) == 0;
        constraint y + l/2 * cos(theta) == 0;
        outputs inverse_dynamics_adjoint;
    }
}

fn main() {}
