//! A spherical joint with a bad name gives that error only: no "needs at least one coordinate" after it.

use dalembert_macros::dalembert;

dalembert! {
    pub Top {
        parameters m;
        joint spherical type { parent: N, child: B, at: O };
    }
}

fn main() {}
