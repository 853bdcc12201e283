//! Joints are `revolute`, `prismatic`, `spherical` or `free`.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        joint planar J { parent: B, child: C, axis: z, coordinate: theta, at: G };
    }
}

fn main() {}
