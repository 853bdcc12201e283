use dalembert::constrained::constraint_drift;
use dalembert::integrate::rk4;
use dalembert::{Constrained, Stabilisation, State, energy};
include!("/tmp/qa6/ex/model.rs");
fn main() {
    let l = CrankRocker {
        a: 0.3,
        b: 0.5,
        c: 0.3,
        d: 0.5,
        m1: 0.5,
        m2: 0.9,
        m3: 0.7,
        g: 9.81,
    };
    let start = State {
        t: 0.0,
        q: [0.7, 0.0, 0.7],
        v: [15.0, 0.0, 15.0],
    };
    let e0 = energy(&l, &start.q, &start.v);
    let dynamics = Constrained::without_inputs(&l, Stabilisation::None);
    let mut n = 0;
    let r = rk4(&dynamics, start, 3.0, 30_000, |s| {
        n += 1;
        let off = s.q[1].abs().max((s.q[2] - s.q[0]).abs());
        if n % 50 == 0 && s.t > 0.3 && s.t < 0.7 {
            println!(
                "t {:.4} drift {:.3e} off {:.3e} dE {:.3e} q {:?} v {:?}",
                s.t,
                constraint_drift(&l, s),
                off,
                energy(&l, &s.q, &s.v) - e0,
                s.q,
                s.v
            );
        }
    });
    println!("{:?}", r.map(|s| s.statistics));
}
