//! A free joint `base` names its coordinates `base_x … base_qw` and its
//! speeds `base_vx … base_wz`: they must be new names.

use dalembert_macros::dalembert;

dalembert! {
    pub Floating {
        parameters m, base_qw;
        joint free base { parent: N, child: B, at: O };
        body b { mass: m, center: base, frame: B, inertia: [m, m, m] };
    }
}

fn main() {}
