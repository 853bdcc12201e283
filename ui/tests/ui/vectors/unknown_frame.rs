//! `angular_velocity` of a name that is not defined.

use dalembert_macros::dalembert;

dalembert! {
    pub Spinner {
        parameters m, c;
        coordinates q;
        frame B = N.rotate_z(q);
        body b { mass: m, center: O, frame: B, inertia: [1, 1, 1] };
        torque -c * angular_velocity(K) on B;
    }
}

fn main() {}
