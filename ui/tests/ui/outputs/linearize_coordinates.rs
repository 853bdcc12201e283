//! `linearize(..)` names the independent coordinates of a system with
//! constraints: as many as its degrees of freedom (an error at the first
//! name otherwise), each a coordinate (an error at the name), and none for
//! a system without constraints (an error at the first name).

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

fn main() {}
