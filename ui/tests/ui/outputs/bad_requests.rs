//! Every bad output request is reported, together, at its token: an unknown
//! output, a frame where a point is expected and the reverse, an output
//! without the point it needs or with one it does not take.

use dalembert_macros::dalembert;

dalembert! {
    pub Crank {
        parameters mass, radius;
        coordinates phi;
        frame B = N.rotate_z(phi);
        point P = O + radius * B.x;
        particle pin { mass: mass, at: P };
        outputs speed(P), velocity(B), rotation(P), position(P in P);
        outputs position, inverse_dynamics(P);
    }
}

fn main() {}
