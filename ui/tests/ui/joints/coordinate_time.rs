//! A joint's coordinate is one of the declared coordinates, not time `t`.

use dalembert_macros::dalembert;

dalembert! {
    pub Slider {
        parameters l;
        coordinates s;
        joint prismatic Rail { parent: N, child: C, axis: x, coordinate: t, at: O + l * N.y };
    }
}

fn main() {}
