//! A misspelled free joint gives that error only: its names stay silent, and no "needs at least one coordinate" follows.

use dalembert_macros::dalembert;

dalembert! {
    pub Drone {
        parameters m, I;
        joint fre base { parent: N, child: Frame, at: O };
        body hull { mass: m, center: base, frame: Frame, inertia: [I, I, 2 * I] };
    }
}

fn main() {}
