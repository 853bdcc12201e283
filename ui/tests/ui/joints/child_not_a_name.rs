//! A joint's child is the name of the new frame.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        joint revolute J { parent: B, child: B.x, axis: z, coordinate: theta, at: G };
    }
}

fn main() {}
