//! `dt(theta)` is not a speed when a `speeds` statement gives `theta` a rate of its own: name that speed.

use dalembert_macros::dalembert;

dalembert! {
    pub Sled {
        parameters m;
        coordinates x, y, theta;
        speeds w { theta: 2 * w };
        frame B = N.rotate_z(theta);
        body sled { mass: m, center: O + x * N.x + y * N.y, frame: B, inertia: [0, 0, m] };
        constraint -sin(theta) * dt(x) + cos(theta) * dt(y) == 0;
        outputs linearize(x, y, theta; dt(x), dt(theta));
    }
}

fn main() {}
