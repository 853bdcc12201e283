//! Two operands without an operator between them.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        point P = O + (l theta) * B.x;
    }
}

fn main() {}
