//! Joints are `revolute` or `prismatic`.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        joint spherical J { parent: B, child: C, axis: z, coordinate: theta, at: G };
    }
}

fn main() {}
