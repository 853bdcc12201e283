//! A body's name has no value: its frame or its center point does.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        body bar { mass: m, center: G, frame: B, inertia: [0, 0, m*l^2/12] };
        force u * N.x at bar;
    }
}

fn main() {}
