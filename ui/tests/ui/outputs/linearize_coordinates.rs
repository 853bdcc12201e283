//! `linearize(..)` names the independent coordinates of a system with
//! constraints: as many as its degrees of freedom (an error at the first
//! name otherwise), each a coordinate or, for a spherical joint's tangent
//! directions, the joint's speeds (an error at the name), and none for a
//! system without constraints (an error at the first name). With
//! nonholonomic rows it names the independent speeds after `;` (an error
//! at its name without them), each `dt(q)` or a speed's name (an error at
//! a bare coordinate).

use dalembert_macros::dalembert;

dalembert! {
    pub TooMany {
        parameters m, l, g;
        coordinates x, y, theta;
        frame B = N.rotate_z(theta);
        point G = O + x * N.x + y * N.y;
        body bar { mass: m, center: G, frame: B, inertia: [0, 0, m*l^2/12] };
        gravity -g * N.y;
        constraint x - l/2 * sin(theta) == 0;
        constraint y + l/2 * cos(theta) == 0;
        outputs linearize(x, theta);
    }
}

dalembert! {
    pub NotACoordinate {
        parameters m, l, g;
        coordinates x, y, theta;
        frame B = N.rotate_z(theta);
        point G = O + x * N.x + y * N.y;
        body bar { mass: m, center: G, frame: B, inertia: [0, 0, m*l^2/12] };
        gravity -g * N.y;
        constraint x - l/2 * sin(theta) == 0;
        constraint y + l/2 * cos(theta) == 0;
        outputs linearize(l);
    }
}

dalembert! {
    pub Unconstrained {
        parameters m, l, g;
        coordinates theta;
        frame B = N.rotate_z(theta);
        body bar { mass: m, center: O - l/2 * B.y, frame: B, inertia: [0, 0, m*l^2/12] };
        gravity -g * N.y;
        outputs linearize(theta);
    }
}

dalembert! {
    pub SledWithoutSpeeds {
        parameters m, I;
        coordinates x, y, theta;
        frame B = N.rotate_z(theta);
        body sled { mass: m, center: O + x * N.x + y * N.y, frame: B, inertia: [0, 0, I] };
        constraint -sin(theta) * dt(x) + cos(theta) * dt(y) == 0;
        outputs linearize(x, y, theta);
    }
}

dalembert! {
    pub SledWithBareCoordinates {
        parameters m, I;
        coordinates x, y, theta;
        frame B = N.rotate_z(theta);
        body sled { mass: m, center: O + x * N.x + y * N.y, frame: B, inertia: [0, 0, I] };
        constraint -sin(theta) * dt(x) + cos(theta) * dt(y) == 0;
        outputs linearize(x, y, theta; x, dt(theta));
    }
}

dalembert! {
    pub QuaternionComponent {
        parameters m, d, g;
        joint spherical ball { parent: N, child: B, at: O };
        body bob { mass: m, center: ball - d * B.z, frame: B, inertia: [1, 1, 1] };
        gravity -g * N.z;
        constraint ball_qx == 0;
        constraint ball_qz == 0;
        outputs linearize(ball_qy);
    }
}

fn main() {}
