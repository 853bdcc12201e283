//! `angular_velocity` takes a frame.

use dalembert_macros::dalembert;

dalembert! {
    pub Spinner {
        parameters m, c;
        coordinates q;
        frame B = N.rotate_z(q);
        body b { mass: m, center: O, frame: B, inertia: [1, 1, 1] };
        torque -c * angular_velocity(O) on B;
    }
}

fn main() {}
