//! Only `linearize` takes speeds after `;`.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, L;
        coordinates theta;
        frame B = N.rotate_z(theta);
        point P = O - L * B.y;
        particle bob { mass: m, at: P };
        outputs position(P; dt(theta));
    }
}

fn main() {}
