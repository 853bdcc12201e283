//! Outputs that name what the model does not have, or name it where it
//! does not fit, are errors at the name: an unknown point, an unknown frame
//! after `in`, a parameter after `in`, a point defined only below the
//! request, a speed among `linearize`'s coordinates, a coordinate named
//! twice, and a regressor of a model whose `M v̇ − f` moves with time.

use dalembert_macros::dalembert;

dalembert! {
    pub Pendulum {
        parameters m, l;
        coordinates theta;
        frame B = N.rotate_z(theta);
        point P = O - l * B.y;
        particle bob { mass: m, at: P };
        outputs position(tip), velocity(P in C), jacobian(P in l);
        outputs acceleration(Q);
        point Q = P - l * B.y;
    }
}

dalembert! {
    pub SpeedAsCoordinate {
        parameters m, k;
        coordinates a, b;
        particle p { mass: m, at: O + a * N.x + b * N.y };
        potential k / 2 * (a^2 + b^2);
        constraint a == 2 * b;
        outputs linearize(dt(a));
    }
}

dalembert! {
    pub CoordinateTwice {
        parameters m;
        coordinates a, b, c;
        particle p { mass: m, at: O + a * N.x + b * N.y + c * N.z };
        constraint a + b + c == 1;
        outputs linearize(b, b);
    }
}

dalembert! {
    pub ShakenRegressor {
        parameters m, l, a, w;
        coordinates theta;
        frame B = N.rotate_z(theta);
        particle bob { mass: m, at: O - l * B.y };
        force a * sin(w * t) * N.x at O - l * B.y;
        outputs regressor;
    }
}

fn main() {}
