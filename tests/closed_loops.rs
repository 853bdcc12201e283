//! Closed loops as a user writes them, each against an independent
//! reference: a parallelogram with a third, redundant bar (its Jacobian
//! rank-deficient everywhere) against its one-degree-of-freedom closed form
//! through every integrator, and stopped by its drift when unstabilised; a
//! parallelogram four-bar crossing its flat positions on its branch, or
//! refusing them with an error; a loop row written with its sides swapped; a
//! driven crank and a bead on a hoop turned by a constraint, whose bias
//! must carry the explicit time derivatives.

use dalembert::constrained::{
    BARELY_INDEPENDENT, ConstraintSolver, DRIFT_LIMIT, DriftLimits, constrained_accelerations,
    constraint_drift,
};
use dalembert::integrate::{
    AdaptiveOptions, AugmentedLagrangian, ExplicitPair, Failure, GaussLegendre, adaptive,
    augmented_lagrangian, gauss_legendre, rk4, sdirk,
};
use dalembert::{Constrained, DynamicsError, Stabilisation, State, energy};
use dalembert_fixtures::reference::{array, assert_close, assert_near, reference};

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
fn scalar_motion(acceleration: impl Fn(f64) -> f64, x: f64, v: f64, t_end: f64) -> f64 {
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

#[test]
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
        rk4(&dynamics, start, 10.0, 10_000, |s| run.see(s, e0)).unwrap();
        check(&format!("RK4, {name}"), run, expected, [2e-9, 1e-13, 1e-10]);
        let mut run = Run::default();
        let options = AdaptiveOptions::with_tolerance(1e-10);
        adaptive(&dynamics, start, 10.0, ExplicitPair::Dop853, options, |s| {
            run.see(s, e0)
        })
        .unwrap();
        check(
            &format!("DOP853, {name}"),
            run,
            expected,
            [1e-8, 1e-13, 2e-9],
        );
        let mut run = Run::default();
        let options = AdaptiveOptions::with_tolerance(1e-8);
        adaptive(
            &dynamics,
            start,
            10.0,
            ExplicitPair::DormandPrince54,
            options,
            |s| run.see(s, e0),
        )
        .unwrap();
        check(
            &format!("DOPRI5, {name}"),
            run,
            expected,
            [3e-5, 1e-13, 5e-6],
        );
        let mut run = Run::default();
        gauss_legendre(&dynamics, start, 10.0, 2_000, GaussLegendre::Order4, |s| {
            run.see(s, e0)
        })
        .unwrap();
        check(
            &format!("Gauss 4, {name}"),
            run,
            expected,
            [2e-7, 1e-13, 5e-9],
        );
        let mut run = Run::default();
        sdirk(&dynamics, start, 10.0, 10_000, |s| run.see(s, e0)).unwrap();
        check(
            &format!("SDIRK, {name}"),
            run,
            expected,
            [1e-5, 1e-13, 1e-6],
        );
    }
    let dynamics = Constrained::without_inputs(&p, Stabilisation::None);
    let mut run = Run::default();
    let settings = AugmentedLagrangian::for_step(1e-3);
    augmented_lagrangian(&dynamics, start, 10.0, 10_000, settings, |s| run.see(s, e0)).unwrap();
    check("augmented Lagrangian", run, expected, [1e-3, 1e-10, 1e-5]);
    // Holding the energy too, and on the sparse solver.
    let held = Stabilisation::EnergyProjection {
        tolerance: 1e-12,
        max_iterations: 5,
        energy: e0,
    };
    let dynamics = Constrained::without_inputs(&p, held);
    let mut run = Run::default();
    rk4(&dynamics, start, 10.0, 10_000, |s| run.see(s, e0)).unwrap();
    check(
        "RK4, energy projection",
        run,
        expected,
        [2e-9, 1e-13, 1e-13],
    );
    let dynamics =
        Constrained::without_inputs(&p, projection).with_solver(ConstraintSolver::Sparse);
    let mut run = Run::default();
    rk4(&dynamics, start, 10.0, 10_000, |s| run.see(s, e0)).unwrap();
    check(
        "RK4, projection, sparse",
        run,
        expected,
        [1e-8, 1e-12, 1e-9],
    );
}

#[test]
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
    let error = rk4(&unwatched, start, 10.0, 10_000, |_| {}).unwrap_err();
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
    let options = AdaptiveOptions::with_tolerance(1e-10);
    let mut run = Run::default();
    adaptive(
        &unwatched,
        start,
        10.0,
        ExplicitPair::Dop853,
        options,
        |s| run.see(s, e0),
    )
    .unwrap();
    println!("unwatched DOP853 at 1e-10: {run:?}");
    assert!(run.energy_change > 0.2, "{run:?}");

    let watched = Constrained::without_inputs(&p, Stabilisation::None);
    let mut last = start;
    let error = rk4(&watched, start, 10.0, 10_000, |s| last = *s).unwrap_err();
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
    let error = adaptive(&watched, start, 10.0, ExplicitPair::Dop853, options, |s| {
        last = *s
    })
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

dalembert::dalembert! {
    /// A crank-rocker four-bar in dependent coordinates: the crank (`a`)
    /// turns by `phi` about `O`, the coupler (`b`) hangs from its tip at
    /// `psi` from `N.x`, the rocker (`c`) turns by `chi` about the pivot
    /// `d` along `N.x`; two loop-closure rows join the coupler's far end
    /// to the rocker's tip. Uniform rods in the vertical plane.
    pub CrankRocker {
        parameters a, b, c, d, m1, m2, m3, g;
        coordinates phi, psi, chi;
        frame C = N.rotate_z(phi);
        frame D = N.rotate_z(psi);
        frame R = N.rotate_z(chi);
        point A = O + a * C.x;
        body crank { mass: m1, center: O + a/2 * C.x, frame: C, inertia: [0, 0, m1*a^2/12] };
        body coupler { mass: m2, center: A + b/2 * D.x, frame: D, inertia: [0, 0, m2*b^2/12] };
        body rocker { mass: m3, center: O + d * N.x + c/2 * R.x, frame: R, inertia: [0, 0, m3*c^2/12] };
        gravity -g * N.y;
        constraint a*cos(phi) + b*cos(psi) == d + c*cos(chi);
        constraint a*sin(phi) + b*sin(psi) == c*sin(chi);
    }
}

#[test]
fn crank_rocker_turns_its_crank_and_traces_the_coupler_curve_of_the_reference() {
    let reference = reference("four_bar.json");
    let parameter = |name: &str| reference["parameters"][name].as_f64().unwrap();
    let linkage = CrankRocker {
        a: parameter("a"),
        b: parameter("b"),
        c: parameter("c"),
        d: parameter("d"),
        m1: parameter("m1"),
        m2: parameter("m2"),
        m3: parameter("m3"),
        g: parameter("g"),
    };
    let (p, e) = (parameter("p"), parameter("e"));
    // The coupler point `p` along the coupler and `e` across it.
    let coupler_point = |q: &[f64; 3]| {
        let ([phi, psi, _], a) = (*q, linkage.a);
        [
            a * phi.cos() + p * psi.cos() - e * psi.sin(),
            a * phi.sin() + p * psi.sin() + e * psi.cos(),
        ]
    };
    let start = State {
        t: 0.0,
        q: array(&reference["initial"]["q"]),
        v: array(&reference["initial"]["v"]),
    };
    let initial_energy = reference["energy"].as_f64().unwrap();
    assert_near(
        "E(0)",
        energy(&linkage, &start.q, &start.v),
        initial_energy,
        1e-14,
    );
    let states = reference["states"].as_array().unwrap();
    let projection = Stabilisation::Projection {
        tolerance: 1e-12,
        max_iterations: 5,
    };
    let dynamics = Constrained::without_inputs(&linkage, projection);
    let (mut drift, mut energy_change, mut seen) = (0.0f64, 0.0f64, 0);
    rk4(&dynamics, start, 1.0, 10_000, |s| {
        drift = drift.max(constraint_drift(&linkage, s));
        let change = energy(&linkage, &s.q, &s.v) - initial_energy;
        energy_change = energy_change.max(change.abs() / initial_energy);
        for expected in states {
            if (s.t - expected["t"].as_f64().unwrap()).abs() < 1e-9 {
                seen += 1;
                let at = format!("t = {:.2}", s.t);
                assert_near(&at, s.q[0], expected["phi"].as_f64().unwrap(), 1e-9);
                assert_near(&at, s.v[0], expected["phi_dot"].as_f64().unwrap(), 1e-8);
                let point: [f64; 2] = array(&expected["coupler_point"]);
                assert_close(&at, &coupler_point(&s.q), &point, 1e-9);
            }
        }
    })
    .unwrap();
    println!("crank-rocker, 1 s: max |φ| {drift:.2e}, max |ΔE|/E {energy_change:.2e}");
    assert_eq!(seen, states.len());
    let last = states.last().unwrap()["phi"].as_f64().unwrap();
    assert!(
        last - 0.5 > std::f64::consts::TAU,
        "a full turn of the crank"
    );
    assert!(drift < 1e-12, "{drift:e}");
    assert!(energy_change < 1e-10, "{energy_change:e}");
}

dalembert::dalembert! {
    /// A slider-crank whose crank a motor drives through a prescribed
    /// angle, `theta = w t + k sin(w t)`: three rows, three coordinates,
    /// the driving row's multiplier the motor's torque.
    pub DrivenSliderCrank {
        parameters r, L, m, g, w, k;
        coordinates theta, phi, s;
        frame C = N.rotate_z(theta);
        frame R = N.rotate_z(phi);
        point A = O + r * C.x;
        body crank { mass: m, center: O + r/2 * C.x, frame: C, inertia: [0, 0, m*r^2/12] };
        body rod { mass: m, center: A + L/2 * R.x, frame: R, inertia: [0, 0, m*L^2/12] };
        particle slider { mass: m, at: O + s * N.x };
        gravity -g * N.y;
        constraint r*cos(theta) + L*cos(phi) - s == 0;
        constraint r*sin(theta) + L*sin(phi) == 0;
        constraint theta == w*t + k*sin(w*t);
    }
}

const DRIVEN: DrivenSliderCrank = DrivenSliderCrank {
    r: 0.1,
    L: 0.3,
    m: 0.6,
    g: 9.81,
    w: 7.0,
    k: 0.4,
};

/// The prescribed motion of [`DRIVEN`] at `t`, in closed form.
fn driven_motion(t: f64) -> [f64; 3] {
    let DrivenSliderCrank { r, L, w, k, .. } = DRIVEN;
    let theta = w * t + k * (w * t).sin();
    let phi = -(r * theta.sin() / L).asin();
    [theta, phi, r * theta.cos() + L * phi.cos()]
}

/// The rate and acceleration of `motion` at `t` by central differences
/// (steps `1e-5` and `1e-4`: errors about `1e-9` and `1e-7` relative for
/// [`DRIVEN`]).
fn differentiated(motion: impl Fn(f64) -> [f64; 3], t: f64) -> ([f64; 3], [f64; 3]) {
    let (h, h2) = (1e-5, 1e-4);
    let (ahead, behind) = (motion(t + h), motion(t - h));
    let (far_ahead, here, far_behind) = (motion(t + h2), motion(t), motion(t - h2));
    (
        std::array::from_fn(|i| (ahead[i] - behind[i]) / (2.0 * h)),
        std::array::from_fn(|i| (far_ahead[i] - 2.0 * here[i] + far_behind[i]) / (h2 * h2)),
    )
}

#[test]
fn driven_crank_bias_carries_the_explicit_time_derivative() {
    for t in [0.0, 0.13, 0.61, 1.4] {
        let q = driven_motion(t);
        let (qd, qdd) = differentiated(driven_motion, t);
        assert!(
            DRIVEN
                .constraint_residual(t, &q)
                .iter()
                .all(|r| r.abs() < 1e-15)
        );
        let velocity = DRIVEN.constraint_velocity(t, &q, &qd);
        assert!(velocity.iter().all(|v| v.abs() < 1e-8), "{velocity:?}");
        // On the motion, A q̈ = b, the driving row's b being θ̈ itself.
        let a = DRIVEN.constraint_jacobian(&q);
        let b = DRIVEN.constraint_bias(t, &q, &qd);
        for (row, bias) in a.iter().zip(b) {
            let achieved: f64 = row.iter().zip(&qdd).map(|(a, x)| a * x).sum();
            assert!(
                (achieved - bias).abs() < 1e-5 * (1.0 + bias.abs()),
                "t = {t}: {achieved} vs {bias}"
            );
        }
        let DrivenSliderCrank { w, k, .. } = DRIVEN;
        assert_near("θ̈", b[2], -k * w * w * (w * t).sin(), 1e-13);
    }
}

#[test]
fn driven_crank_follows_its_drive_and_the_motor_does_the_work() {
    // No degree of freedom is left: the integration must follow the
    // prescribed motion, and the work of the driving row's multiplier (the
    // motor torque, `λ θ̇`) is the change of energy.
    let (qd, _) = differentiated(driven_motion, 0.0);
    let start = State {
        t: 0.0,
        q: driven_motion(0.0),
        v: qd,
    };
    let start = State {
        v: dalembert::constrained::project_onto_constraints(&DRIVEN, &start, 1e-14, 5)
            .unwrap()
            .v,
        ..start
    };
    let initial_energy = energy(&DRIVEN, &start.q, &start.v);
    let projection = Stabilisation::Projection {
        tolerance: 1e-12,
        max_iterations: 5,
    };
    let dynamics = Constrained::without_inputs(&DRIVEN, projection);
    let (mut worst, mut work, mut last_power) = (0.0f64, 0.0, None::<(f64, f64)>);
    let end = rk4(&dynamics, start, 2.0, 20_000, |s| {
        let exact = driven_motion(s.t);
        worst = (0..3).fold(worst, |m, i| m.max((s.q[i] - exact[i]).abs()));
        let (_, lambda) = constrained_accelerations(&DRIVEN, s.t, &s.q, &s.v, &[]).unwrap();
        let power = lambda[2] * s.v[0];
        if let Some((t, p)) = last_power {
            work += (s.t - t) * (p + power) / 2.0;
        }
        last_power = Some((s.t, power));
    })
    .unwrap()
    .end;
    let change = energy(&DRIVEN, &end.q, &end.v) - initial_energy;
    println!(
        "driven crank, 2 s: max |q − q(t)| {worst:.2e}, ΔE {change:.6e}, motor work {work:.6e}"
    );
    assert!(worst < 1e-10, "{worst:e}");
    assert!(
        (change - work).abs() < 1e-6 * work.abs().max(1.0),
        "{change} vs {work}"
    );
}

dalembert::dalembert! {
    /// A bead on a hoop that a motor turns about the vertical at the
    /// prescribed rate `w`: the bead at `theta` from the bottom, the hoop at
    /// `phi`, held by the rheonomic row `phi == w t`.
    pub BeadOnHoop {
        parameters m, R, J, w, g;
        coordinates theta, phi;
        frame H = N.rotate_z(phi);
        particle bead { mass: m, at: O + R * sin(theta) * H.x - R * cos(theta) * N.z };
        body hoop { mass: m, center: O, frame: H, inertia: [J, J, 2*J] };
        gravity -g * N.z;
        constraint phi == w*t;
    }
}

#[test]
fn bead_on_a_driven_hoop_follows_the_closed_form_equation_and_torque() {
    let hoop = BeadOnHoop {
        m: 0.2,
        R: 0.5,
        J: 0.05,
        w: 6.0,
        g: 9.81,
    };
    let BeadOnHoop { m, R, w, g, .. } = hoop;
    // θ̈ = sin θ (w² cos θ − g/R); the motor's torque is the rate of the
    // angular momentum about the axis, 2 m R² w sin θ cos θ θ̇.
    let bead = |theta: f64| theta.sin() * (w * w * theta.cos() - g / R);
    for (t, theta, theta_dot) in [(0.0, 0.5, 0.0), (0.3, 1.1, -2.0), (2.0, 2.5, 3.0)] {
        let (q, v) = ([theta, w * t], [theta_dot, w]);
        assert_eq!(hoop.constraint_residual(t, &q), [0.0]);
        let (vdot, [torque]) = constrained_accelerations(&hoop, t, &q, &v, &[]).unwrap();
        assert_near("θ̈", vdot[0], bead(theta), 1e-13);
        assert_near("φ̈", vdot[1], 0.0, 1e-13);
        let expected = 2.0 * m * R * R * w * theta.sin() * theta.cos() * theta_dot;
        assert_near("motor torque", torque, expected, 1e-13);
    }
    let start = State {
        t: 0.0,
        q: [0.5, 0.0],
        v: [0.0, w],
    };
    let expected = scalar_motion(bead, 0.5, 0.0, 10.0);
    let projection = Stabilisation::Projection {
        tolerance: 1e-12,
        max_iterations: 5,
    };
    let mut drift = 0.0f64;
    let end = rk4(
        &Constrained::without_inputs(&hoop, projection),
        start,
        10.0,
        10_000,
        |s| {
            drift = drift.max(constraint_drift(&hoop, s));
        },
    )
    .unwrap()
    .end;
    println!(
        "bead on a hoop, 10 s: θ off by {:.2e}, max |φ| {drift:.2e}",
        end.q[0] - expected
    );
    assert_near("θ(10 s)", end.q[0], expected, 1e-9);
    assert_near("φ(10 s)", end.q[1], 10.0 * w, 1e-12);
}

dalembert::dalembert! {
    /// A bead on the parabola `y = c x²` in the vertical plane, its row
    /// written with the sides swapped.
    pub ParabolaBead {
        parameters m, c, g;
        coordinates x, y;
        particle bead { mass: m, at: O + x * N.x + y * N.y };
        gravity -g * N.y;
        constraint 0 == y - c * x^2;
    }
}

#[test]
fn a_row_written_with_its_sides_swapped_has_the_sign_of_lhs_minus_rhs() {
    let bead = ParabolaBead {
        m: 0.3,
        c: 0.8,
        g: 9.81,
    };
    let ParabolaBead { m, c, g } = bead;
    for (x, y, xd, yd) in [(0.4, 0.1, 1.0, -0.5), (-1.2, 2.0, 0.3, 2.5)] {
        // docs/architecture.md §4: A is the Jacobian of lhs − rhs = c x² − y, and
        // A q̈ = b differentiates it twice: 2c x ẍ − ÿ = −2c ẋ².
        let (q, v) = ([x, y], [xd, yd]);
        assert_close(
            "A",
            &bead.constraint_jacobian(&q)[0],
            &[2.0 * c * x, -1.0],
            1e-15,
        );
        assert_close(
            "b",
            &bead.constraint_bias(0.0, &q, &v),
            &[-2.0 * c * xd * xd],
            1e-15,
        );
        assert_close(
            "φ",
            &bead.constraint_residual(0.0, &q),
            &[c * x * x - y],
            1e-15,
        );
        // On the parabola: ẍ = −2c x (g + 2c ẋ²)/(1 + 4c² x²), and
        // m ÿ = −m g + Aᵀλ's y entry = −m g − λ, so λ = −m (ÿ + g): the
        // multiplier of the row as written (the bead pressing down on the
        // curve makes it negative).
        let (q, v) = ([x, c * x * x], [xd, 2.0 * c * x * xd]);
        let (vdot, [lambda]) = constrained_accelerations(&bead, 0.0, &q, &v, &[]).unwrap();
        let xdd = -2.0 * c * x * (g + 2.0 * c * xd * xd) / (1.0 + 4.0 * c * c * x * x);
        let ydd = 2.0 * c * (xd * xd + x * xdd);
        assert_close("v̇", &vdot, &[xdd, ydd], 1e-14);
        assert_near("λ", lambda, -m * (ydd + g), 1e-14);
    }
}

dalembert::dalembert! {
    /// A sleigh whose blade may not slip sideways (a nonholonomic row) and
    /// whose blade point is held on a circle of radius `R` (a holonomic
    /// row), driven by a torque `u` and a push `F` along its blade.
    pub CircleSleigh {
        parameters m, I, R;
        coordinates x, y, theta;
        inputs u, F;
        frame B = N.rotate_z(theta);
        point G = O + x * N.x + y * N.y;
        body sleigh { mass: m, center: G, frame: B, inertia: [0, 0, I] };
        torque u * N.z on B;
        force F * B.x at G;
        constraint x^2 + y^2 == R^2;
        constraint -sin(theta) * dt(x) + cos(theta) * dt(y) == 0;
    }
}

#[test]
fn sleigh_on_a_circle_mixes_holonomic_and_nonholonomic_rows_with_inputs() {
    let sleigh = CircleSleigh {
        m: 2.0,
        I: 0.3,
        R: 1.5,
    };
    let CircleSleigh { m, I, R } = sleigh;
    let (u, push) = (0.2, 0.5);
    // Both rows' forces act at G across the blade and along the radius:
    // nothing turns the sleigh but u, nothing pushes it along the circle
    // but F. With the blade along the circle (θ = α + π/2, the rows
    // dependent there) it may move: α̈ = F/(m R), θ̈ = u/I, and the
    // centripetal acceleration R α̇².
    for (alpha, alpha_dot) in [(0.0f64, 1.0), (2.0, -0.7)] {
        let (sin, cos) = alpha.sin_cos();
        let q = [R * cos, R * sin, alpha + std::f64::consts::FRAC_PI_2];
        let v = [-R * sin * alpha_dot, R * cos * alpha_dot, alpha_dot];
        assert_eq!(
            sleigh.constraint_residual(0.0, &q)[1],
            0.0,
            "a nonholonomic row has none"
        );
        let (vdot, _) = constrained_accelerations(&sleigh, 0.0, &q, &v, &[u, push]).unwrap();
        let alpha_ddot = push / (m * R);
        let expected = [
            -R * cos * alpha_dot * alpha_dot - R * sin * alpha_ddot,
            -R * sin * alpha_dot * alpha_dot + R * cos * alpha_ddot,
            u / I,
        ];
        assert_close("v̇", &vdot, &expected, 1e-13);
    }
    // Across the circle, the blade can only turn on the spot: from a
    // heading 0.3 rad off the circle, turned by u = 0.4 sin t for 10 s, it
    // passes the headings along the circle (where the rows lose rank)
    // again and again, and θ(t) = θ₀ + ω₀ t + 0.4 (t − sin t)/I.
    let (u0, theta0, w0) = (0.4, 0.3, 2.0);
    let start = State {
        t: 0.0,
        q: [R, 0.0, theta0],
        v: [0.0, 0.0, w0],
    };
    let projection = Stabilisation::Projection {
        tolerance: 1e-12,
        max_iterations: 5,
    };
    let inputs = |t: f64, _: &[f64; 3], _: &[f64; 3]| [u0 * t.sin(), 0.0];
    let dynamics = Constrained::new(&sleigh, inputs, projection);
    let (mut drift, mut slip) = (0.0f64, 0.0f64);
    let end = rk4(&dynamics, start, 10.0, 10_000, |s| {
        drift = drift.max(constraint_drift(&sleigh, s));
        slip = slip.max(sleigh.constraint_velocity(s.t, &s.q, &s.v)[1].abs());
    })
    .unwrap()
    .end;
    let t = 10.0f64;
    let theta = theta0 + w0 * t + u0 * (t - t.sin()) / I;
    println!(
        "sleigh on a circle, 10 s: θ off by {:.2e}, moved {:.2e}, max |φ| {drift:.2e}, max slip {slip:.2e}",
        end.q[2] - theta,
        (end.q[0] - R).hypot(end.q[1])
    );
    assert_near("θ(10 s)", end.q[2], theta, 1e-10);
    assert_close("position", &end.q[..2], &[R, 0.0], 1e-12);
    assert!(drift < 1e-12 && slip < 1e-12, "{drift:e} {slip:e}");
}

#[test]
fn parallelogram_four_bar_crosses_its_flat_positions_on_its_branch() {
    // The crank-rocker's model with crank = rocker and coupler = ground: at
    // φ = 0 and π the three rods lie on the ground line and the two rows
    // lose rank, where the antiparallelogram branch meets this one. On
    // this branch the coupler stays level (ψ = 0, χ = φ) and the crank
    // moves as one rod: (m₁/3 + m₂ + m₃/3) a² φ̈ = −(m₁/2 + m₂ + m₃/2) g a cos φ.
    let linkage = CrankRocker {
        a: 0.3,
        b: 0.5,
        c: 0.3,
        d: 0.5,
        m1: 0.5,
        m2: 0.9,
        m3: 0.7,
        g: 9.81,
    };
    let CrankRocker {
        a, m1, m2, m3, g, ..
    } = linkage;
    let crank =
        |phi: f64| -(m1 / 2.0 + m2 + m3 / 2.0) * g * phi.cos() / ((m1 / 3.0 + m2 + m3 / 3.0) * a);
    let (phi0, w0) = (0.7, 15.0);
    let start = State {
        t: 0.0,
        q: [phi0, 0.0, phi0],
        v: [w0, 0.0, w0],
    };
    let expected = scalar_motion(crank, phi0, w0, 3.0);
    // The largest distance from the branch over 3 s, and the end.
    let run = |stabilisation| {
        let dynamics = Constrained::without_inputs(&linkage, stabilisation);
        let mut off_branch = 0.0f64;
        rk4(&dynamics, start, 3.0, 30_000, |s| {
            off_branch = off_branch.max(s.q[1].abs()).max((s.q[2] - s.q[0]).abs());
        })
        .map(|solution| (off_branch, solution.end))
    };
    let projection = Stabilisation::Projection {
        tolerance: 1e-12,
        max_iterations: 5,
    };
    let (off_branch, end) = run(projection).unwrap();
    let crossings = ((end.q[0] - phi0) / std::f64::consts::PI).floor();
    println!(
        "parallelogram four-bar, projection: {crossings} flat positions crossed, off the branch by {off_branch:.2e}, φ off by {:.2e}",
        end.q[0] - expected
    );
    assert!(crossings >= 6.0, "{crossings}");
    assert!(off_branch < 1e-9, "{off_branch:e}");
    assert_near("φ(3 s)", end.q[0], expected, 1e-8);
    // Neither of the other stabilisations crosses, as `Stabilisation`
    // documents: unwatched, the unstabilised run's speeds' drift left by one
    // crossing meets the vanishing gradient of the next (a jump of 12 % of
    // its energy at 0.341 s, off the branch, with no error); Baumgarte's
    // terms, divided by that gradient, diverge. Watched, both stop as they
    // reach the first flat position (φ = π, at 0.1655 s), naming its rows.
    let unwatched = |stabilisation| {
        let dynamics = Constrained::without_inputs(&linkage, stabilisation)
            .with_drift_limits(DriftLimits::UNWATCHED);
        let mut off_branch = 0.0f64;
        rk4(&dynamics, start, 3.0, 30_000, |s| {
            off_branch = off_branch.max(s.q[1].abs()).max((s.q[2] - s.q[0]).abs());
        })
        .map(|_| off_branch)
    };
    let jumped = unwatched(Stabilisation::None).unwrap();
    assert!(jumped > 1e-3, "{jumped:e}");
    let baumgarte = Stabilisation::Baumgarte {
        alpha: 20.0,
        beta: 20.0,
    };
    let diverged = unwatched(baumgarte);
    assert!(
        matches!(diverged, Err(ref e) if matches!(e.cause, Failure::Dynamics(DynamicsError::NonFiniteEquations))),
        "{diverged:?}"
    );
    for stabilisation in [Stabilisation::None, baumgarte] {
        let error = run(stabilisation).unwrap_err();
        println!("{stabilisation:?}: {error}");
        match error.cause {
            Failure::SingularPosition {
                row,
                with,
                singular_value,
                t,
            } => {
                assert_eq!(row + with, 1, "rows 0 and 1: {error}");
                assert!(singular_value < BARELY_INDEPENDENT);
                assert!(t > 0.16 && t < 0.17, "{error}");
            }
            other => panic!("{stabilisation:?}: {other:?}"),
        }
        assert!(error.q[0] < std::f64::consts::PI, "{error}");
    }
    // The augmented Lagrangian crosses, like the projections.
    let dynamics = Constrained::without_inputs(&linkage, Stabilisation::None);
    let mut off_branch = 0.0f64;
    let settings = AugmentedLagrangian::for_step(1e-4);
    let end = augmented_lagrangian(&dynamics, start, 3.0, 30_000, settings, |s| {
        off_branch = off_branch.max(s.q[1].abs()).max((s.q[2] - s.q[0]).abs());
    })
    .unwrap()
    .end;
    println!(
        "parallelogram four-bar, augmented Lagrangian: off the branch by {off_branch:.2e}, φ off by {:.2e}",
        end.q[0] - expected
    );
    assert!(off_branch < 1e-6, "{off_branch:e}");
    assert_near("φ(3 s)", end.q[0], expected, 1e-3);
}

dalembert::dalembert! {
    /// A particle held by a rheonomic holonomic row and an affine,
    /// time-dependent nonholonomic row: the two ways `t` enters `b`.
    pub TimedRows {
        parameters m, l;
        coordinates x, y, z;
        particle p { mass: m, at: O + x * N.x + y * N.y + z * N.z };
        constraint x^2 + l * y == l^2 * sin(t);
        constraint dt(z) + y * dt(x) == cos(2 * t) + x * z;
    }
}

#[test]
fn bias_is_a_times_the_acceleration_less_the_rate_of_each_row_along_any_motion() {
    // Along any motion q(t), on the manifold or not, a holonomic row's
    // φ(t, q(t)) has φ̈ = A q̈ − b and a nonholonomic row's ψ(t, q, q̇) has
    // ψ̇ = A q̈ − b: the rows written out by hand here, differentiated by
    // central differences.
    let rows = TimedRows { m: 0.4, l: 0.7 };
    let l = rows.l;
    let motion = |t: f64| {
        let q = [(1.3 * t).sin(), (0.7 * t).cos(), t * t / 3.0 + 0.1];
        let v = [1.3 * (1.3 * t).cos(), -0.7 * (0.7 * t).sin(), 2.0 * t / 3.0];
        let a = [-1.69 * (1.3 * t).sin(), -0.49 * (0.7 * t).cos(), 2.0 / 3.0];
        (q, v, a)
    };
    let holonomic = |t: f64| {
        let ([x, y, _], _, _) = motion(t);
        x * x + l * y - l * l * t.sin()
    };
    let nonholonomic = |t: f64| {
        let ([x, y, z], [xd, _, zd], _) = motion(t);
        zd + y * xd - (2.0 * t).cos() - x * z
    };
    let h = 1e-4;
    for t in [0.0, 0.4, 1.7, 3.0] {
        let (q, v, a) = motion(t);
        let jacobian = rows.constraint_jacobian(&q);
        let b = rows.constraint_bias(t, &q, &v);
        let achieved = jacobian.map(|row| row.iter().zip(&a).map(|(x, y)| x * y).sum::<f64>());
        let phi_ddot = (holonomic(t + h) - 2.0 * holonomic(t) + holonomic(t - h)) / (h * h);
        let psi_dot = (nonholonomic(t + h) - nonholonomic(t - h)) / (2.0 * h);
        assert_near("holonomic b", b[0], achieved[0] - phi_ddot, 1e-6);
        assert_near("nonholonomic b", b[1], achieved[1] - psi_dot, 1e-7);
        let residual = rows.constraint_residual(t, &q);
        assert_near("φ", residual[0], holonomic(t), 1e-15);
        assert_eq!(residual[1], 0.0, "a nonholonomic row has no residual");
    }
}
