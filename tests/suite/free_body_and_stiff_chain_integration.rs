//! The simulation API as a user meets it, on models written here in the
//! macro: every integrator on a free body in quaternions, and a stiff
//! spring-mass chain that collapses explicit steps or fails with an error.
//! Expected values come from closed forms or another method at a tight
//! tolerance, never from the code under test.

use dalembert::integrate::{
    self, AdaptiveOptions, ExplicitPair, Failure, GaussLegendre, State, Unconstrained,
};

dalembert::dalembert! {
    /// A brick floating freely, its attitude a unit quaternion.
    pub FreeBrick {
        parameters m, I1, I2, I3;
        joint free base { parent: N, child: B, at: O };
        body brick { mass: m, center: base, frame: B, inertia: [I1, I2, I3] };
        outputs taylor;
    }
}

dalembert::dalembert! {
    /// Three masses in a row on soft springs `k` from a wall, the first two
    /// tied by a stiff spring `K`.
    pub SpringChain {
        parameters m, k, K;
        coordinates x1, x2, x3;
        particle a { mass: m, at: O + x1 * N.x };
        particle b { mass: m, at: O + x2 * N.x };
        particle c { mass: m, at: O + x3 * N.x };
        potential k / 2 * x1^2 + K / 2 * (x2 - x1)^2 + k / 2 * (x3 - x2)^2;
    }
}

const BRICK: FreeBrick = FreeBrick {
    m: 2.0,
    I1: 1.0,
    I2: 2.0,
    I3: 3.0,
};

/// The brick thrown spinning near its intermediate axis, tilted.
fn brick_start() -> State<7, 6> {
    let (s, c) = 0.35f64.sin_cos();
    State {
        t: 0.0,
        q: [0.1, -0.2, 0.3, s * 0.6, s * 0.8, 0.0, c],
        v: [1.0, 0.5, -0.3, 0.01, 2.0, 0.02],
    }
}

/// DOP853 at `tolerance` from `start` to `t_end`: the reference runs.
pub(crate) fn dop853<D, const NQ: usize, const NV: usize>(
    dynamics: &D,
    start: State<NQ, NV>,
    t_end: f64,
    tolerance: f64,
) -> integrate::Solution<NQ, NV>
where
    D: integrate::Dynamics<NQ, NV>,
{
    let options = AdaptiveOptions::with_tolerance(tolerance);
    integrate::Integration::new(
        dynamics,
        start,
        t_end,
        integrate::Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .run()
    .unwrap()
}

fn quaternion_norm(q: &[f64; 7]) -> f64 {
    q[3..].iter().map(|x| x * x).sum::<f64>().sqrt()
}

pub(crate) fn distance<const NQ: usize, const NV: usize>(
    a: &State<NQ, NV>,
    b: &State<NQ, NV>,
) -> f64 {
    a.q.iter()
        .zip(&b.q)
        .chain(a.v.iter().zip(&b.v))
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn every_integrator_keeps_a_free_bodys_quaternion_unit_over_ten_thousand_steps() {
    let dynamics = Unconstrained::without_inputs(&BRICK);
    let start = brick_start();
    let steps = 10_000;
    let t_end = 20.0;
    let mut worst: f64 = 0.0;
    let mut unit = |s: &State<7, 6>| worst = worst.max((quaternion_norm(&s.q) - 1.0).abs());
    let reference =
        integrate::Integration::new(&dynamics, start, t_end, integrate::Adaptive::dop853(1e-13))
            .observe(&mut unit)
            .run()
            .unwrap()
            .end;
    let rk4 = integrate::Integration::new(&dynamics, start, t_end, integrate::Rk4 { steps })
        .observe(&mut unit)
        .run()
        .unwrap();
    let gauss = integrate::Integration::new(
        &dynamics,
        start,
        t_end,
        integrate::Gauss {
            rule: GaussLegendre::Order4,
            steps,
        },
    )
    .observe(&mut unit)
    .run()
    .unwrap();
    let sdirk = integrate::Integration::new(&dynamics, start, t_end, integrate::Sdirk { steps })
        .observe(&mut unit)
        .run()
        .unwrap();
    let dopri =
        integrate::Integration::new(&dynamics, start, t_end, integrate::Adaptive::dopri5(1e-10))
            .observe(&mut unit)
            .run()
            .unwrap();
    let taylor = integrate::Integration::new(
        &dynamics,
        start,
        t_end,
        integrate::Taylor::with_tolerance(1e-15),
    )
    .observe(&mut unit)
    .run()
    .unwrap();
    assert!(worst < 4.0 * f64::EPSILON, "|q| off one by {worst:e}");
    // Each follows the tight DOP853 run: the centre moves on a line, the
    // attitude tumbles (h = 2 ms; SDIRK, third order, is the loosest).
    for (name, end, tolerance) in [
        ("RK4", rk4.end, 1e-8),
        ("Gauss 4", gauss.end, 1e-8),
        ("SDIRK", sdirk.end, 1e-3),
        ("DOPRI5", dopri.end, 1e-7),
        ("Taylor", taylor.end, 1e-10),
    ] {
        let error = distance(&end, &reference);
        assert!(error < tolerance, "{name}: {error:e}");
    }
    // No force: the centre moves on a straight line in N, at the velocity
    // the body-axis speeds give at the start.
    let velocity = rotated(&start.q, [start.v[0], start.v[1], start.v[2]]);
    for (i, speed) in velocity.iter().enumerate() {
        let line = start.q[i] + speed * t_end;
        assert!((reference.q[i] - line).abs() < 1e-10, "{reference:?}");
    }
}

/// `x` in the body's axes turned into N's by the attitude `q[3..]` of a
/// free joint, `(qx, qy, qz, qw)`: `x + 2w (u × x) + 2 u × (u × x)`.
fn rotated(q: &[f64; 7], x: [f64; 3]) -> [f64; 3] {
    let (u, w) = ([q[3], q[4], q[5]], q[6]);
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let ux = cross(u, x);
    let uux = cross(u, ux);
    std::array::from_fn(|i| x[i] + 2.0 * w * ux[i] + 2.0 * uux[i])
}

const CHAIN: SpringChain = SpringChain {
    m: 1.0,
    k: 1.0,
    K: 1e6,
};

fn chain_start() -> State<3, 3> {
    State {
        t: 0.0,
        q: [0.1, 0.1001, 0.3],
        v: [0.0, 0.0, 0.0],
    }
}

#[test]
fn a_stiff_spring_chain_collapses_explicit_steps_or_fails_with_an_error_never_a_panic() {
    let dynamics = Unconstrained::without_inputs(&CHAIN);
    let start = chain_start();
    let t_end = 1.0;
    // The fast mode, ω = √(2K/m) ≈ 1414 rad/s, bounds explicit steps.
    let tight = dop853(&dynamics, start, t_end, 1e-12);
    let loose =
        integrate::Integration::new(&dynamics, start, t_end, integrate::Adaptive::dopri5(1e-3))
            .run()
            .unwrap();
    // Even at 1e-3, stability alone keeps DOPRI5 below h ≈ 3.3 / ω.
    assert!(
        loose.statistics.accepted_steps > 300,
        "{:?}",
        loose.statistics
    );
    // RK4 beyond its stability limit 2.8 / ω ≈ 2e-3 s blows up into an
    // error naming where, never a NaN state returned as a success.
    let unstable =
        integrate::Integration::new(&dynamics, start, t_end, integrate::Rk4 { steps: 200 })
            .observe(|s| {
                assert!(s.q.iter().chain(&s.v).all(|x| x.is_finite()), "{s:?}");
            })
            .run()
            .unwrap_err();
    assert!(matches!(unstable.cause, Failure::Dynamics(_)), "{unstable}");
    // Gauss 4 is A-stable, but its fixed-point stage iteration does not
    // converge at a step this long against the fast mode: an error.
    let gauss = integrate::Integration::new(
        &dynamics,
        start,
        t_end,
        integrate::Gauss {
            rule: GaussLegendre::Order4,
            steps: 200,
        },
    )
    .run()
    .unwrap_err();
    assert!(
        matches!(gauss.cause, Failure::NotConverged { .. }),
        "{gauss}"
    );
    // SDIRK (L-stable) damps the fast mode and follows the slow masses.
    let sdirk =
        integrate::Integration::new(&dynamics, start, t_end, integrate::Sdirk { steps: 200 })
            .run()
            .unwrap();
    assert!(
        (sdirk.end.q[2] - tight.end.q[2]).abs() < 1e-3,
        "{:?} vs {:?}",
        sdirk.end,
        tight.end
    );
}
