//! The Taylor method against DOP853 at a tight tolerance: on a heavy top
//! (keeping its energy) and with a constant input.

use crate::dense_output_and_events::G;
use crate::free_body_and_stiff_chain_integration::{distance, dop853};
use crate::integration_errors::PushedPendulum;

use dalembert::energy;
use dalembert::integrate::{self, State, Unconstrained};

dalembert::dalembert! {
    /// A heavy top on a ball joint, its centre on its symmetry axis.
    pub HeavyTop {
        parameters m, a, I1, I3, g;
        joint spherical ball { parent: N, child: B, at: O };
        body top { mass: m, center: ball + a * B.z, frame: B, inertia: [I1, I1, I3] };
        gravity -g * N.z;
        outputs taylor;
    }
}

const TOP: HeavyTop = HeavyTop {
    m: 1.5,
    a: 0.2,
    I1: 0.05,
    I3: 0.02,
    g: G,
};

fn top_start() -> State<4, 3> {
    let (s, c) = 0.15f64.sin_cos();
    State {
        t: 0.0,
        q: [s, 0.0, 0.0, c],
        v: [0.0, 0.1, 40.0],
    }
}

#[test]
fn taylor_follows_dop853_on_a_heavy_top_and_keeps_its_energy() {
    let dynamics = Unconstrained::without_inputs(&TOP);
    let start = top_start();
    let t_end = 5.0;
    let reference = dop853(&dynamics, start, t_end, 1e-14).end;
    let e0 = energy(&TOP, &start.q, &start.v);
    let mut drift: f64 = 0.0;
    let taylor = integrate::Integration::new(
        &dynamics,
        start,
        t_end,
        integrate::Taylor::with_tolerance(1e-16),
    )
    .observe(|s| drift = drift.max((energy(&TOP, &s.q, &s.v) - e0).abs() / e0.abs()))
    .run()
    .unwrap();
    let error = distance(&taylor.end, &reference);
    assert!(error < 1e-9, "{error:e}");
    assert!(drift < 1e-13, "{drift:e}");
}

#[test]
fn taylor_holds_a_constant_input_as_dop853_does() {
    let pendulum = PushedPendulum {
        m: 1.0,
        L: 0.8,
        g: G,
    };
    let dynamics = Unconstrained::new(&pendulum, |_, _, _| [0.7]);
    let start = State {
        t: 0.0,
        q: [0.3],
        v: [0.0],
    };
    let reference = dop853(&dynamics, start, 10.0, 1e-14).end;
    let taylor = integrate::Integration::new(
        &dynamics,
        start,
        10.0,
        integrate::Taylor::with_tolerance(1e-15),
    )
    .run()
    .unwrap()
    .end;
    assert!(
        distance(&taylor, &reference) < 1e-11,
        "{taylor:?} vs {reference:?}"
    );
    assert_eq!(PushedPendulum::NU, 1);
}
