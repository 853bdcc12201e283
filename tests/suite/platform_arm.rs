//! A two-link arm on a platform turned at the prescribed rate `Ω`, written
//! twice: with the platform's angle `Ω t` in its geometry
//! (`frame P = N.rotate_z(Omega * t)`), and with a coordinate `phi` held by
//! the rheonomic constraint `phi == Omega * t`. The two are one mechanism:
//! the arm's accelerations, mass matrix and energies agree to 1e-12, and
//! so do their motions.
//!
//! The constrained spelling also shows the start check: without
//! stabilisation, a start whose platform speed is not `Ω` (off the
//! constraint's velocity form) is refused rather than left to drift.

use dalembert::constrained::ConstraintSolver;
use dalembert::integrate::{Adaptive, DriftLevel, Integration};
use dalembert::{Constrained, MultibodySystem, Stabilisation, State, Unconstrained};

dalembert::dalembert! {
    /// A two-link arm pitching on a platform that turns at the rate `Omega`.
    pub DrivenPlatformArm {
        parameters mp, m1, m2, l1, l2, r, Omega, g;
        coordinates q1, q2;
        frame P = N.rotate_z(Omega * t);
        point S = O + r * P.x + l1/4 * P.z;
        frame B1 = P.rotate_y(q1);
        frame B2 = B1.rotate_x(q2);
        point E = S + l1 * B1.x;
        body platform { mass: mp, center: O, frame: P, inertia: [mp*r^2/4, mp*r^2/3, mp*r^2/2] };
        body link1 { mass: m1, center: S + l1/2 * B1.x, frame: B1, inertia: [m1*l1^2/50, m1*l1^2/12, m1*l1^2/11] };
        body link2 { mass: m2, center: E + l2/2 * B2.y, frame: B2, inertia: [m2*l2^2/12, m2*l2^2/40, m2*l2^2/13] };
        gravity -g * N.z;
    }
}

dalembert::dalembert! {
    /// The same arm, the platform's angle a coordinate held at `Omega t`.
    pub ConstrainedPlatformArm {
        parameters mp, m1, m2, l1, l2, r, Omega, g;
        coordinates phi, q1, q2;
        frame P = N.rotate_z(phi);
        point S = O + r * P.x + l1/4 * P.z;
        frame B1 = P.rotate_y(q1);
        frame B2 = B1.rotate_x(q2);
        point E = S + l1 * B1.x;
        body platform { mass: mp, center: O, frame: P, inertia: [mp*r^2/4, mp*r^2/3, mp*r^2/2] };
        body link1 { mass: m1, center: S + l1/2 * B1.x, frame: B1, inertia: [m1*l1^2/50, m1*l1^2/12, m1*l1^2/11] };
        body link2 { mass: m2, center: E + l2/2 * B2.y, frame: B2, inertia: [m2*l2^2/12, m2*l2^2/40, m2*l2^2/13] };
        gravity -g * N.z;
        constraint phi == Omega * t;
    }
}

const DRIVEN: DrivenPlatformArm = DrivenPlatformArm {
    mp: 3.0,
    m1: 1.2,
    m2: 0.7,
    l1: 0.6,
    l2: 0.45,
    r: 0.3,
    Omega: 2.5,
    g: 9.81,
};

const CONSTRAINED: ConstrainedPlatformArm = ConstrainedPlatformArm {
    mp: 3.0,
    m1: 1.2,
    m2: 0.7,
    l1: 0.6,
    l2: 0.45,
    r: 0.3,
    Omega: 2.5,
    g: 9.81,
};

/// The constrained spelling's state for the driven one's.
fn on_constraint(t: f64, q: [f64; 2], v: [f64; 2]) -> ([f64; 3], [f64; 3]) {
    let omega = CONSTRAINED.Omega;
    ([omega * t, q[0], q[1]], [omega, v[0], v[1]])
}

fn states() -> Vec<(f64, [f64; 2], [f64; 2])> {
    vec![
        (0.0, [0.3, -0.2], [0.0, 0.0]),
        (0.7, [-1.1, 0.9], [1.5, -2.0]),
        (2.3, [2.4, 2.8], [-0.4, 3.1]),
        (11.9, [0.01, -1.5], [4.0, 0.2]),
    ]
}

fn close(what: &str, a: f64, b: f64, scale: f64) {
    assert!(
        (a - b).abs() <= 1e-12 * scale.max(1.0),
        "{what}: {a} vs {b} (off by {:e})",
        (a - b).abs()
    );
}

#[test]
fn both_spellings_have_the_same_accelerations_and_energies() {
    let mut checked = 0;
    for (t, q, v) in states() {
        let (qc, vc) = on_constraint(t, q, v);
        let driven = dalembert::accelerations(&DRIVEN, t, &q, &v, &[]).expect("regular");
        let held = dalembert::accelerations(&CONSTRAINED, t, &qc, &vc, &[]).expect("regular");
        let scale = driven.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
        close("platform", held[0], 0.0, scale);
        for i in 0..2 {
            close(
                &format!("q̈{} at t = {t}", i + 1),
                driven[i],
                held[i + 1],
                scale,
            );
        }
        let mass = DRIVEN.mass_matrix_at(t, &q);
        let full = CONSTRAINED.mass_matrix(&qc);
        for i in 0..2 {
            for j in 0..2 {
                close(&format!("M[{i}][{j}]"), mass[i][j], full[i + 1][j + 1], 1.0);
            }
        }
        let kinetic = DRIVEN.kinetic_energy_at(t, &q, &v);
        close("T", kinetic, CONSTRAINED.kinetic_energy(&qc, &vc), kinetic);
        let potential = DRIVEN.potential_energy_at(t, &q);
        close("V", potential, CONSTRAINED.potential_energy(&qc), potential);
        checked += 1;
    }
    assert_eq!(checked, 4);
}

#[test]
fn both_spellings_move_alike() {
    let (t0, q0, v0) = (0.2, [0.4, -0.3], [0.5, 1.0]);
    let dop853 = Adaptive::dop853(1e-12);
    let driven = Unconstrained::without_inputs(&DRIVEN);
    let start = State {
        t: t0,
        q: q0,
        v: v0,
    };
    let end = Integration::new(&driven, start, 3.0, dop853)
        .run()
        .expect("integrates")
        .end;
    let (qc, vc) = on_constraint(t0, q0, v0);
    let held = Constrained::without_inputs(&CONSTRAINED, Stabilisation::None);
    let start = State {
        t: t0,
        q: qc,
        v: vc,
    };
    let held_end = Integration::new(&held, start, 3.0, dop853)
        .run()
        .expect("integrates")
        .end;
    let (qe, ve) = on_constraint(3.0, end.q, end.v);
    for i in 0..3 {
        assert!(
            (held_end.q[i] - qe[i]).abs() < 1e-8,
            "q[{i}]: {:?} vs {qe:?}",
            held_end.q
        );
        assert!(
            (held_end.v[i] - ve[i]).abs() < 1e-8,
            "v[{i}]: {:?} vs {ve:?}",
            held_end.v
        );
    }
}

#[test]
fn the_arm_on_the_driven_platform_keeps_its_jacobi_integral() {
    let start = State {
        t: 0.0,
        q: [0.4, -0.3],
        v: [0.5, 1.0],
    };
    let jacobi = |s: &State<2, 2>| dalembert::jacobi_integral(&DRIVEN, s.t, &s.q, &s.v);
    let h0 = jacobi(&start);
    let mut worst: f64 = 0.0;
    let dop853 = Adaptive::dop853(1e-13);
    let dynamics = Unconstrained::without_inputs(&DRIVEN);
    Integration::new(&dynamics, start, 4.0, dop853)
        .observe(|s| {
            worst = worst.max((jacobi(s) - h0).abs());
        })
        .run()
        .expect("integrates");
    assert!(worst < 1e-11 * h0.abs().max(1.0), "{worst:e}");
}

#[test]
fn a_start_off_the_driven_speed_is_refused_unless_projected() {
    let (qc, mut vc) = on_constraint(0.5, [0.4, -0.3], [0.5, 1.0]);
    vc[0] = 0.0;
    let start = State {
        t: 0.5,
        q: qc,
        v: vc,
    };
    let held = Constrained::without_inputs(&CONSTRAINED, Stabilisation::None);
    let dop853 = Adaptive::dop853(1e-10);
    let error = Integration::new(&held, start, 3.0, dop853)
        .run()
        .expect_err("refused");
    assert_eq!(error.t, 0.5);
    let message = error.to_string();
    assert!(message.contains("constraint row 0"), "{message}");
    match error.cause {
        dalembert::integrate::Failure::ConstraintDrift {
            row: 0,
            level: DriftLevel::Velocity,
            residual,
            t,
            ..
        } => {
            assert_eq!(t, 0.5);
            assert!((residual + CONSTRAINED.Omega).abs() < 1e-14, "{residual}");
        }
        other => panic!("expected the drift of row 0's velocity form, got {other:?}"),
    }
    let rk4 = dalembert::integrate::Integration::new(
        &held,
        start,
        3.0,
        dalembert::integrate::Rk4 { steps: 100 },
    )
    .run();
    assert!(rk4.is_err(), "RK4 refuses it too");
    // Projected onto the constraints first, it starts, and moves as the
    // driven spelling does.
    let projected = ConstraintSolver::default()
        .project_onto_constraints(&CONSTRAINED, &start, 1e-14, 5)
        .expect("projects");
    assert!((projected.v[0] - CONSTRAINED.Omega).abs() < 1e-14);
    Integration::new(&held, projected, 1.0, dop853)
        .run()
        .expect("starts");
    // So does an integration that projects, whose first step moves it
    // onto the constraints; Baumgarte's terms would pull the speed in only
    // over time, off the constraints meanwhile, and are refused too.
    let projecting = Stabilisation::Projection {
        tolerance: 1e-12,
        max_iterations: 5,
    };
    let stabilised = Constrained::without_inputs(&CONSTRAINED, projecting);
    Integration::new(&stabilised, start, 1.0, dop853)
        .run()
        .expect("starts");
    let baumgarte = Stabilisation::Baumgarte {
        alpha: 10.0,
        beta: 10.0,
    };
    let pulled = Constrained::without_inputs(&CONSTRAINED, baumgarte);
    assert!(Integration::new(&pulled, start, 1.0, dop853).run().is_err());
}

#[test]
fn the_driven_spelling_is_time_free_where_time_cancels() {
    // The platform turns steadily about an axis, so `t` cancels from the
    // arm's M, T and V: the time-free functions hold.
    const { assert!(!<DrivenPlatformArm as MultibodySystem<2, 2, 0>>::TIME_DEPENDENT) };
    let q = [0.4, -0.3];
    assert_eq!(DRIVEN.mass_matrix(&q), DRIVEN.mass_matrix_at(7.0, &q));
}
