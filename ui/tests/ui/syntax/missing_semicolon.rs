//! A statement without its `;`: the error points at the next token and parsing goes on.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        frame C = B.rotate_x(theta)
        particle p { mass: m, at: G };
    }
}

fn main() {}
