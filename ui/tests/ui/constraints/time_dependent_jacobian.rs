//! The generated `constraint_jacobian(q)` has no `t`.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        constraint sin(theta * t) == 0;
    }
}

fn main() {}
