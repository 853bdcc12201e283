//! Every syntax error is reported, not only the first.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        body bar { mass m, center G };
        frame C = ;
        constraint theta = 0;
    }
}

fn main() {}
