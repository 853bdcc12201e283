//! An output asked for twice is an error at the second request (`in N` is
//! the default axes, so `position(G in N)` is `position(G)` again).

use dalembert_macros::dalembert;

dalembert! {
    Slider {
        parameters m;
        coordinates x;
        point G = O + x * N.x;
        particle block { mass: m, at: G };
        outputs position(G), jacobian(G);
        outputs position(G in N);
    }
}

fn main() {}
