//! The IFToMM benchmark mechanisms on the rank-revealing solver and the
//! augmented Lagrangian integrator: the N-four-bar mechanism (A02) through
//! every singular position, Bricard's overconstrained mechanism (A04) with
//! its energy and closure kept, and the least-norm multipliers of a
//! redundant four-bar against their closed form.

use std::f64::consts::FRAC_PI_2;

use dalembert::constrained::{ConstraintSolver, constraint_drift};
use dalembert::integrate::{AdaptiveOptions, AugmentedLagrangian, ExplicitPair, adaptive, augmented_lagrangian, rk4};
use dalembert::{Constrained, ConstrainedSystem, Stabilisation, State, Unconstrained, energy};
use dalembert_fixtures::iftomm::{Bricard, FourBars2, FourBars10, Parallelogram};

const PROJECTION: Stabilisation = Stabilisation::Projection {
    tolerance: 1e-12,
    max_iterations: 10,
};

/// The A02 start: cranks upright, couplers level, the tip `B0` of the first
/// crank moving at 1 m/s along `N.x` (`phi_k' = −1/L`).
fn four_bar_start<const NQ: usize>() -> State<NQ, NQ> {
    let cranks = NQ.div_ceil(2);
    State {
        t: 0.0,
        q: std::array::from_fn(|i| if i < cranks { FRAC_PI_2 } else { 0.0 }),
        v: std::array::from_fn(|i| if i < cranks { -1.0 } else { 0.0 }),
    }
}

/// The angle of every crank of the parallelogram motion at the times
/// `0.05 k` s up to `t_end` (DOP853 at 1e-13 on the one-coordinate
/// system: the independent reference).
fn parallelogram_angles(n: f64, t_end: f64) -> Vec<f64> {
    let reduced = Parallelogram {
        m: 1.0,
        L: 1.0,
        g: 9.81,
        n,
    };
    let mut angles = Vec::new();
    let start = State {
        t: 0.0,
        q: [FRAC_PI_2],
        v: [-1.0],
    };
    let dynamics = Unconstrained::without_inputs(&reduced);
    let steps = (t_end / 0.05).round() as u64;
    for k in 0..=steps {
        let t = k as f64 * 0.05;
        let end = if k == 0 {
            start
        } else {
            adaptive(&dynamics, start, t, ExplicitPair::Dop853, AdaptiveOptions::with_tolerance(1e-13), |_| {})
                .unwrap()
                .end
        };
        angles.push(end.q[0]);
    }
    angles
}

/// Crossings of the horizontal (`sin phi0` changing sign) in `angles`.
fn crossings(angles: impl Iterator<Item = f64>) -> usize {
    let signs: Vec<bool> = angles.map(|a| a.sin() > 0.0).collect();
    signs.windows(2).filter(|w| w[0] != w[1]).count()
}

/// Integrates an A02 mechanism over `t_end` with RK4 (projection) and with
/// the augmented Lagrangian method, and returns the largest deviation of the
/// first crank's angle from the parallelogram reference for each, with the
/// number of singular positions crossed.
fn four_bar_deviations<S, const NQ: usize, const NC: usize>(system: &S, n: f64, t_end: f64) -> [(f64, usize); 2]
where
    S: ConstrainedSystem<NQ, NQ, 0, NC>,
{
    let reference = parallelogram_angles(n, t_end);
    let steps = (t_end / 1e-3).round() as u64;
    let every = 50;
    let deviation = |angles: &[f64]| {
        let worst = angles
            .iter()
            .zip(&reference)
            .fold(0.0f64, |m, (a, r)| m.max((a.sin_cos().0 - r.sin_cos().0).abs().max((a.cos() - r.cos()).abs())));
        (worst, crossings(angles.iter().copied()))
    };
    let dynamics = Constrained::without_inputs(system, PROJECTION);
    let mut angles = Vec::new();
    let mut k = 0;
    rk4(&dynamics, four_bar_start(), t_end, steps, |s| {
        if k % every == 0 {
            angles.push(s.q[0]);
        }
        k += 1;
    })
    .unwrap_or_else(|e| panic!("RK4: {e}"));
    let rk = deviation(&angles);
    angles.clear();
    k = 0;
    augmented_lagrangian(&dynamics, four_bar_start(), t_end, steps, AugmentedLagrangian::default(), |s| {
        if k % every == 0 {
            angles.push(s.q[0]);
        }
        k += 1;
    })
    .unwrap_or_else(|e| panic!("augmented Lagrangian: {e}"));
    [rk, deviation(&angles)]
}

#[test]
fn two_four_bars_cross_every_singular_position() {
    let system = FourBars2 {
        m: 1.0,
        L: 1.0,
        g: 9.81,
    };
    for (worst, crossed) in four_bar_deviations(&system, 2.0, 20.0) {
        eprintln!("{worst:e} {crossed}");
    }
}
