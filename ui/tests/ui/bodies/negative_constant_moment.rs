//! A constant principal moment is evaluated: `1 - sqrt(2)` is negative.

use dalembert_macros::dalembert;

dalembert! {
    pub Flywheel {
        parameters m;
        coordinates angle;
        frame Disc = N.rotate_y(angle);
        body disc { mass: m, center: O, frame: Disc, inertia: [1, 1 - sqrt(2), 1] };
    }
}

fn main() {}
