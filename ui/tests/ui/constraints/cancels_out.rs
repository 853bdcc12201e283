//! A constraint whose coordinates cancel: `lhs − rhs` simplifies to zero.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l, g;
        coordinates theta;
        frame B = N.rotate_z(theta);
        point G = O - l * B.y;
        particle bob { mass: m, at: G };
        constraint 2 * theta == theta + theta;
    }
}

fn main() {}
