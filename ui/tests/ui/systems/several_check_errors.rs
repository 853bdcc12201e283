//! Every error of the checker is reported, not only the first.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        inputs u;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        point P = O + k * N.x;
        body bar { mass: m, center: G, frame: B };
        potential theta^l;
        gravity g;
    }
}

fn main() {}
