//! `accelerations_jacobian` of a system with constraints and a spherical
//! joint is not generated yet: an error at its name.

use dalembert_macros::dalembert;

dalembert! {
    pub BallOnSlider {
        parameters m, g;
        coordinates s;
        point P = O + s * N.x;
        joint spherical ball { parent: N, child: B, at: P };
        body b { mass: m, center: ball, frame: B, inertia: [1, 1, 1] };
        gravity -g * N.z;
        constraint s == 0;
        outputs accelerations_jacobian;
    }
}

fn main() {}
