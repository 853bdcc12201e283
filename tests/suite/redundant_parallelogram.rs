//! A closed loop as a user writes it, against its closed form: a
//! parallelogram with a third, redundant bar (its Jacobian rank-deficient
//! everywhere) against its one-degree-of-freedom closed form through every
//! integrator, and stopped by its drift when unstabilised.

use dalembert::constrained::{
    ConstraintSolver, DRIFT_LIMIT, DriftLimits, constrained_accelerations, constraint_drift,
};
use dalembert::integrate::{
    Adaptive, AugmentedLagrangian, AugmentedLagrangianSettings, Failure, Gauss, GaussLegendre,
    Integration, Rk4, Sdirk,
};
use dalembert::{Constrained, DynamicsError, Stabilisation, State, energy};
use dalembert_fixtures::reference::assert_close;

dalembert::dalembert! {
    /// Three equal cranks, `d` apart on the ground, carrying one coupler:
    /// the classic redundant parallelogram. The coupler hangs from the
    /// first crank's tip; the other two tips are closed on it, so four rows
    /// hold four coordinates that keep one degree of freedom.
    pub TripleParallelogram {
        parameters m, mc, L, d, g;
        coordinates phi1, phi2, phi3, psi;
        joint revolute P1 { parent: N, child: C1, axis: z, coordinate: phi1, at: O };
        joint revolute P2 { parent: N, child: C2, axis: z, coordinate: phi2, at: O + d * N.x };
        joint revolute P3 { parent: N, child: C3, axis: z, coordinate: phi3, at: O + 2 * d * N.x };
        joint revolute K { parent: C1, child: D, axis: z, coordinate: psi, at: P1 + L * C1.x };
        body crank1 { mass: m, center: P1 + L/2 * C1.x, frame: C1, inertia: [0, 0, m*L^2/12] };
        body crank2 { mass: m, center: P2 + L/2 * C2.x, frame: C2, inertia: [0, 0, m*L^2/12] };
        body crank3 { mass: m, center: P3 + L/2 * C3.x, frame: C3, inertia: [0, 0, m*L^2/12] };
        body coupler { mass: mc, center: K + d * D.x, frame: D, inertia: [0, 0, mc*d^2/3] };
        gravity -g * N.y;
        closure middle { at: P2 + L * C2.x, to: K + d * D.x };
        closure right { at: P3 + L * C3.x, to: K + 2 * d * D.x };
        outputs accelerations_jacobian;
    }
}

const PARALLELOGRAM: TripleParallelogram = TripleParallelogram {
    m: 0.7,
    mc: 1.3,
    L: 0.4,
    d: 0.5,
    g: 9.81,
};

impl TripleParallelogram {
    /// The state with every crank at `phi` turning at `phi_dot` and the
    /// coupler level.
    fn assembled(&self, phi: f64, phi_dot: f64) -> State<4, 4> {
        State {
            t: 0.0,
            q: [phi, phi, phi, -phi],
            v: [phi_dot, phi_dot, phi_dot, -phi_dot],
        }
    }

    /// The crank's angular acceleration in closed form: the cranks turn
    /// about their pivots (`m L²/3` each), the coupler translates with
    /// their tips, so `(m + mc) L² φ̈ = −(3m/2 + mc) g L cos φ`.
    fn crank_acceleration(&self, phi: f64) -> f64 {
        let (m, mc) = (self.m, self.mc);
        -(1.5 * m + mc) * self.g * phi.cos() / ((m + mc) * self.L)
    }
}

/// The rank of `rows` by their singular values, those below `1e-12` of the
/// largest taken as zero.
fn rank<const N: usize, const C: usize>(rows: [[f64; N]; C]) -> usize {
    let a = nalgebra::DMatrix::from_fn(C, N, |i, j| rows[i][j]);
    let largest = a.singular_values().max();
    a.rank(1e-12 * largest)
}

#[test]
fn redundant_parallelogram_has_rank_three_and_the_closed_form_accelerations() {
    let p = PARALLELOGRAM;
    for (phi, phi_dot) in [(0.3, 0.0), (1.2, -2.0), (2.9, 4.0), (-1.0, 0.5)] {
        let State { q, v, .. } = p.assembled(phi, phi_dot);
        assert!(
            p.constraint_residual(0.0, &q)
                .iter()
                .all(|r| r.abs() < 1e-15)
        );
        assert_eq!(rank(p.constraint_jacobian(&q)), 3, "at {phi}");
        let (vdot, lambda) = constrained_accelerations(&p, 0.0, &q, &v, &[]).unwrap();
        let expected = p.crank_acceleration(phi);
        for (k, want) in [expected, expected, expected, -expected].iter().enumerate() {
            assert!(
                (vdot[k] - want).abs() < 1e-12 * (1.0 + want.abs()),
                "at {phi}: {vdot:?}, expected {expected}"
            );
        }
        assert!(lambda.iter().all(|l| l.is_finite()));
        // The Schur complement names the first row that depends on the
        // ones before it.
        let error = ConstraintSolver::SchurComplement
            .accelerations(&p, 0.0, &q, &v, &[])
            .unwrap_err();
        assert!(
            matches!(
                error,
                DynamicsError::DependentConstraints { row: 2 | 3, .. }
            ),
            "{error:?}"
        );
    }
}

#[test]
fn redundant_parallelogram_accelerations_jacobian_along_its_motion() {
    // Along the mechanism's one direction (every crank alike, the coupler
    // against them) the accelerations change as the closed form's:
    // ∂φ̈/∂φ = k sin φ, ∂φ̈/∂φ̇ = 0; the rows' dependence costs no error.
    let p = PARALLELOGRAM;
    let k = (1.5 * p.m + p.mc) * p.g / ((p.m + p.mc) * p.L);
    let along = [1.0, 1.0, 1.0, -1.0];
    for (phi, phi_dot) in [(-std::f64::consts::FRAC_PI_2, 0.0), (-0.8, 2.5)] {
        let State { q, v, .. } = p.assembled(phi, phi_dot);
        let (by_q, by_v, _) = p.accelerations_jacobian(0.0, &q, &v, &[]).unwrap();
        let times_along = |jacobian: [[f64; 4]; 4]| {
            jacobian.map(|row| row.iter().zip(&along).map(|(a, b)| a * b).sum::<f64>())
        };
        let expected = along.map(|a| a * k * phi.sin());
        assert_close("∂v̇/∂q along", &times_along(by_q), &expected, 1e-12);
        let by_speed = times_along(by_v);
        assert!(by_speed.iter().all(|x| x.abs() < 1e-12 * k), "{by_speed:?}");
    }
}

/// What an integration of the parallelogram did: the largest drift
/// `max |φ|`, the largest relative change of energy, and the crank angle at
/// the end.
#[derive(Debug, Default)]
struct Run {
    drift: f64,
    energy_change: f64,
    angle: f64,
}

impl Run {
    /// Takes `state` into account; energies are measured against the
    /// swing's scale, the potential energy between level and hanging.
    fn see(&mut self, state: &State<4, 4>, initial_energy: f64) {
        let p = PARALLELOGRAM;
        self.drift = self.drift.max(constraint_drift(&p, state));
        let scale = (1.5 * p.m + p.mc) * p.g * p.L;
        let change = (energy(&p, &state.q, &state.v) - initial_energy) / scale;
        self.energy_change = self.energy_change.max(change.abs());
        self.angle = state.q[0];
    }
}

/// The coordinate at `t_end` of the one-degree-of-freedom equation
/// `ẍ = acceleration(x)` from `(x, v)`, by RK4 at `1e-4 s` (error about
/// `1e-13` on the motions here).
pub(crate) fn scalar_motion(acceleration: impl Fn(f64) -> f64, x: f64, v: f64, t_end: f64) -> f64 {
    let rate = |[x, v]: [f64; 2]| [v, acceleration(x)];
    let steps = (t_end / 1e-4).round() as usize;
    let h = t_end / steps as f64;
    let mut y = [x, v];
    for _ in 0..steps {
        let k1 = rate(y);
        let k2 = rate([y[0] + h / 2.0 * k1[0], y[1] + h / 2.0 * k1[1]]);
        let k3 = rate([y[0] + h / 2.0 * k2[0], y[1] + h / 2.0 * k2[1]]);
        let k4 = rate([y[0] + h * k3[0], y[1] + h * k3[1]]);
        y = std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
    y[0]
}

/// The parallelogram released from rest 0.3 rad below level: it swings to
/// 0.3 rad below level on the other side and back, short of the flat
/// (singular) positions.
const RELEASED_AT: f64 = -0.3;

/// Checks `run` against the closed form's angle at 10 s (`expected`) and
/// the bounds on its drift and energy change.
fn check(name: &str, run: Run, expected: f64, bounds: [f64; 3]) {
    let [angle, drift, energy] = bounds;
    let off = (run.angle - expected).abs();
    println!(
        "{name}: angle off by {off:.2e}, max |φ| {:.2e}, max |ΔE| {:.2e}",
        run.drift, run.energy_change
    );
    assert!(off < angle, "{name}: {run:?} vs {expected}");
    assert!(run.drift < drift, "{name}: {run:?}");
    assert!(run.energy_change < energy, "{name}: {run:?}");
}

/// Tens of seconds in a debug build (thirteen runs over 10 s): CI runs it in
/// its release step (`cargo test --release -p dalembert --test suite -- --ignored`).
#[test]
#[ignore = "long: run in release"]
fn redundant_parallelogram_through_every_integrator_with_stabilisation() {
    let p = PARALLELOGRAM;
    let start = p.assembled(RELEASED_AT, 0.0);
    let e0 = energy(&p, &start.q, &start.v);
    let expected = scalar_motion(|phi| p.crank_acceleration(phi), RELEASED_AT, 0.0, 10.0);
    let projection = Stabilisation::Projection {
        tolerance: 1e-12,
        max_iterations: 5,
    };
    let baumgarte = Stabilisation::Baumgarte {
        alpha: 10.0,
        beta: 10.0,
    };
    for (name, stabilisation) in [("Baumgarte", baumgarte), ("projection", projection)] {
        let dynamics = Constrained::without_inputs(&p, stabilisation);
        let mut run = Run::default();
        Integration::new(&dynamics, start, 10.0, Rk4 { steps: 10_000 })
            .observe(|s| run.see(s, e0))
            .run()
            .unwrap();
        check(&format!("RK4, {name}"), run, expected, [2e-9, 1e-13, 1e-10]);
        let mut run = Run::default();
        let dop853 = Adaptive::dop853(1e-10);
        Integration::new(&dynamics, start, 10.0, dop853)
            .observe(|s| run.see(s, e0))
            .run()
            .unwrap();
        check(
            &format!("DOP853, {name}"),
            run,
            expected,
            [1e-8, 1e-13, 2e-9],
        );
        let mut run = Run::default();
        Integration::new(&dynamics, start, 10.0, Adaptive::dopri5(1e-8))
            .observe(|s| run.see(s, e0))
            .run()
            .unwrap();
        check(
            &format!("DOPRI5, {name}"),
            run,
            expected,
            [3e-5, 1e-13, 5e-6],
        );
        let mut run = Run::default();
        Integration::new(
            &dynamics,
            start,
            10.0,
            Gauss {
                rule: GaussLegendre::Order4,
                steps: 2_000,
            },
        )
        .observe(|s| run.see(s, e0))
        .run()
        .unwrap();
        check(
            &format!("Gauss 4, {name}"),
            run,
            expected,
            [2e-7, 1e-13, 5e-9],
        );
        let mut run = Run::default();
        Integration::new(&dynamics, start, 10.0, Sdirk { steps: 10_000 })
            .observe(|s| run.see(s, e0))
            .run()
            .unwrap();
        check(
            &format!("SDIRK, {name}"),
            run,
            expected,
            [1e-5, 1e-13, 1e-6],
        );
    }
    let dynamics = Constrained::without_inputs(&p, Stabilisation::None);
    let mut run = Run::default();
    let settings = AugmentedLagrangianSettings::for_step(1e-3);
    Integration::new(
        &dynamics,
        start,
        10.0,
        AugmentedLagrangian {
            steps: 10_000,
            settings,
        },
    )
    .observe(|s| run.see(s, e0))
    .run()
    .unwrap();
    check("augmented Lagrangian", run, expected, [1e-3, 1e-10, 1e-5]);
    // Holding the energy too, and on the sparse solver.
    let held = Stabilisation::EnergyProjection {
        tolerance: 1e-12,
        max_iterations: 5,
        energy: e0,
    };
    let dynamics = Constrained::without_inputs(&p, held);
    let mut run = Run::default();
    Integration::new(&dynamics, start, 10.0, Rk4 { steps: 10_000 })
        .observe(|s| run.see(s, e0))
        .run()
        .unwrap();
    check(
        "RK4, energy projection",
        run,
        expected,
        [2e-9, 1e-13, 1e-13],
    );
    let dynamics =
        Constrained::without_inputs(&p, projection).with_solver(ConstraintSolver::Sparse);
    let mut run = Run::default();
    Integration::new(&dynamics, start, 10.0, Rk4 { steps: 10_000 })
        .observe(|s| run.see(s, e0))
        .run()
        .unwrap();
    check(
        "RK4, projection, sparse",
        run,
        expected,
        [1e-8, 1e-12, 1e-9],
    );
}

/// Over ten seconds in a debug build: CI runs it in its release step
/// (`cargo test --release -p dalembert --test suite -- --ignored`).
#[test]
#[ignore = "long: run in release"]
fn redundant_parallelogram_unstabilised_stops_at_its_drift_limit() {
    // Along the redundant direction nothing holds the drift: it grows
    // exponentially (the middle crank leaves the others). Unwatched, the
    // rows that depend on the others end by demanding what they cannot
    // give (RK4: `InconsistentConstraints` at 5.5 s), or, by DOP853 at
    // 1e-10, the run goes on with the drifted mechanism's motion and ends
    // "successfully" 29 % of the swing's energy off. Watched (the default
    // `DriftLimits`), both stop where the drift passes 1e-6, with the last
    // good state.
    let p = PARALLELOGRAM;
    let start = p.assembled(RELEASED_AT, 0.0);
    let e0 = energy(&p, &start.q, &start.v);
    let unwatched = Constrained::without_inputs(&p, Stabilisation::None)
        .with_drift_limits(DriftLimits::UNWATCHED);
    let error = Integration::new(&unwatched, start, 10.0, Rk4 { steps: 10_000 })
        .run()
        .unwrap_err();
    assert!(
        matches!(
            error.cause,
            Failure::Dynamics(DynamicsError::InconsistentConstraints {
                row: 1,
                with: 3,
                ..
            })
        ),
        "{error}"
    );
    let dop853 = Adaptive::dop853(1e-10);
    let mut run = Run::default();
    Integration::new(&unwatched, start, 10.0, dop853)
        .observe(|s| run.see(s, e0))
        .run()
        .unwrap();
    println!("unwatched DOP853 at 1e-10: {run:?}");
    assert!(run.energy_change > 0.2, "{run:?}");

    let watched = Constrained::without_inputs(&p, Stabilisation::None);
    let mut last = start;
    let error = Integration::new(&watched, start, 10.0, Rk4 { steps: 10_000 })
        .observe(|s| last = *s)
        .run()
        .unwrap_err();
    println!("unstabilised RK4: {error}");
    let Failure::ConstraintDrift {
        row,
        level,
        residual,
        t,
        ..
    } = error.cause
    else {
        panic!("{error}")
    };
    assert!(residual.abs() > DRIFT_LIMIT && row < 4, "{error}");
    assert!(
        t > 4.0 && t < 5.5 && (t - error.t - 1e-3).abs() < 1e-12,
        "{error}"
    );
    assert_eq!((error.t, error.q), (last.t, last.q));
    assert!(constraint_drift(&p, &last) <= DRIFT_LIMIT);
    let mut last = start;
    let error = Integration::new(&watched, start, 10.0, dop853)
        .observe(|s| last = *s)
        .run()
        .unwrap_err();
    println!("unstabilised DOP853 at 1e-10: {error} ({level:?} for RK4)");
    let at = match error.cause {
        Failure::ConstraintDrift { t, .. } => t,
        _ => panic!("{error}"),
    };
    assert!(at > 4.0 && at < 5.2, "{error}");
    assert_eq!((error.t, error.q), (last.t, last.q));
    let change = (energy(&p, &last.q, &last.v) - e0) / ((1.5 * p.m + p.mc) * p.g * p.L);
    assert!(change.abs() < 1e-6, "{change:e}");
}
