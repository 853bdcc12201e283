//! Closed loops as a user writes them, each against an independent
//! reference: a parallelogram with a third, redundant bar (its Jacobian
//! rank-deficient everywhere) against its one-degree-of-freedom closed form
//! through every integrator; a loop row written with its sides swapped; a
//! driven crank and a bead on a hoop turned by a constraint, whose bias
//! must carry the explicit time derivatives.

use dalembert::constrained::{ConstraintSolver, constrained_accelerations, constraint_drift};
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

/// The crank angle at `t_end` of the closed-form equation
/// `φ̈ = crank_acceleration(φ)` from `(phi, phi_dot)`, by RK4 at `1e-4 s`
/// (error about `1e-13`).
fn closed_form_angle(phi: f64, phi_dot: f64, t_end: f64) -> f64 {
    let p = PARALLELOGRAM;
    let rate = |[x, v]: [f64; 2]| [v, p.crank_acceleration(x)];
    let steps = (t_end / 1e-4).round() as usize;
    let h = t_end / steps as f64;
    let mut y = [phi, phi_dot];
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
    let expected = closed_form_angle(RELEASED_AT, 0.0, 10.0);
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
}

#[test]
fn redundant_parallelogram_unstabilised_drifts_until_its_rows_contradict() {
    // Along the redundant direction nothing holds the drift: it grows
    // exponentially (the middle crank leaves the others), until the rows
    // that depend on the others demand what they cannot give. The
    // integration then stops, naming the rows, as `Stabilisation::None`
    // documents.
    let p = PARALLELOGRAM;
    let start = p.assembled(RELEASED_AT, 0.0);
    let mut drift = Vec::new();
    let dynamics = Constrained::without_inputs(&p, Stabilisation::None);
    let error = rk4(&dynamics, start, 10.0, 10_000, |s| {
        drift.push(constraint_drift(&p, s))
    })
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
    assert!(error.t > 4.0, "{error}");
    let (early, late) = (drift[1_000], drift[4_000]);
    println!("unstabilised: max |φ| {early:.2e} at 1 s, {late:.2e} at 4 s, stopped: {error}");
    assert!(late > 1e4 * early.max(1e-16), "{early:e} {late:e}");
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
