//! A joint axis is `x`, `y`, `z` or a constant direction `[ax, ay, az]`.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        joint revolute J { parent: B, child: C, axis: w, coordinate: theta, at: G };
    }
}

fn main() {}
