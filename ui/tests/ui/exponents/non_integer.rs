//! `^` takes integer exponents: `sqrt` is the square root.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        potential m * theta^0.5;
    }
}

fn main() {}
